#!/usr/bin/env python3
"""lscctl calibrate's walk, on a pseudo-terminal as an owner runs it: lsc-sim
stands in for an xArm assembled with zeros off and the elbow's servo
reversed, lscd shares it, and "the owner's hands" are another lscctl moving
the servos through the arm's true profile between the walk's prompts. A
joint leaned too little is asked again; q quits without writing; the whole
walk writes the profile and leaves the servos holding.

Environment: LSCCTL, LSCD, LSC_SIM (the built programs), LSC_TEST_TIME_SCALE.
Waits are deadlines on what the walk prints; nothing sleeps to synchronise.
"""

import os
import pty
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import arm_as_built  # noqa: E402

XARM = os.path.join(HERE, "..", "..", "examples", "arms", "xarm.conf")
SCALE = int(os.environ.get("LSC_TEST_TIME_SCALE", "1") or "1")
DEADLINE_S = 30.0 * SCALE
LSCCTL = os.environ["LSCCTL"]


def wait_for(what, cond):
    end = time.monotonic() + DEADLINE_S
    while not cond():
        if time.monotonic() > end:
            sys.exit("FAIL: %s" % what)
        time.sleep(0.01)


class Walk:
    """lscctl calibrate on a pty: its output read as it comes."""

    def __init__(self, port, out):
        master, slave = pty.openpty()
        self.proc = subprocess.Popen(
            [LSCCTL, "--port", port, "--timeout", str(10000 * SCALE), "calibrate", "--arm", XARM,
             "--out", out],
            stdin=slave, stdout=slave, stderr=slave, close_fds=True)
        os.close(slave)
        self.master = master
        self.text = ""

    def expect(self, words):
        """Reads until the output (since the last expect) holds words."""
        end = time.monotonic() + DEADLINE_S
        while words not in self.text:
            left = end - time.monotonic()
            if left <= 0:
                sys.exit("FAIL: the walk did not say %r; it said:\n%s" % (words, self.text))
            r, _, _ = select.select([self.master], [], [], left)
            if r:
                try:
                    data = os.read(self.master, 4096)
                except OSError:
                    data = b""
                if not data:
                    sys.exit("FAIL: the walk ended before %r:\n%s" % (words, self.text))
                self.text += data.decode(errors="replace")
        seen = self.text
        self.text = self.text[self.text.index(words) + len(words):]
        return seen

    def key(self, line):
        os.write(self.master, line.encode() + b"\r")

    def end(self):
        rc = self.proc.wait(timeout=DEADLINE_S)
        try:
            while True:
                data = os.read(self.master, 4096)
                if not data:
                    break
                self.text += data.decode(errors="replace")
        except OSError:
            pass
        os.close(self.master)
        return rc


def main():
    tmp = tempfile.mkdtemp()
    true_conf = arm_as_built.write_profile(XARM, os.path.join(tmp, "true.conf"))

    link = os.path.join(tmp, "x")
    run_dir = os.path.join(tmp, "run")
    env = dict(os.environ, LSC_LSCD_DIR=run_dir)
    os.environ["LSC_LSCD_DIR"] = run_dir
    sim = subprocess.Popen([os.environ["LSC_SIM"], "--link", link, "--fast", "--arm", XARM],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    procs = [sim]
    try:
        wait_for("lsc-sim made no link", lambda: os.path.exists(link))
        lscd = subprocess.Popen([os.environ["LSCD"], "--port", link], env=env,
                                stderr=subprocess.DEVNULL)
        procs.append(lscd)
        port = "lscd:x"

        def answers():
            return subprocess.run([LSCCTL, "--port", port, "status"], stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL).returncode == 0
        wait_for("lscd did not answer", answers)

        def hands(*targets):
            r = subprocess.run([LSCCTL, "--port", port, "--arm", true_conf, "--timeout",
                                str(10000 * SCALE), "move", "--time", "0"] + list(targets),
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit("FAIL: the hands' move %s: %s" % (targets, r.stderr))

        def read(*joints):
            r = subprocess.run([LSCCTL, "--port", port, "--timeout", str(10000 * SCALE),
                                "read"] + list(joints), capture_output=True, text=True)
            return r.stdout.split()

        out = os.path.join(tmp, "walk.conf")
        # q at the first prompt: nothing written, exit 2
        w = Walk(port, out)
        w.expect("servos are limp")
        w.expect("Press Enter")
        w.key("q")
        rc = w.end()
        if rc != 2 or "Nothing was written" not in w.text or os.path.exists(out):
            sys.exit("FAIL: q: exit %d, %r, file %s" % (rc, w.text, os.path.exists(out)))

        # Ctrl-C at a prompt: as q (the servos hold, nothing written)
        w = Walk(port, out)
        w.expect("straight up")
        w.expect("Press Enter")
        hands("base:10deg")
        w.proc.send_signal(signal.SIGINT)
        rc = w.end()
        if rc != 2 or "Nothing was written" not in w.text or os.path.exists(out):
            sys.exit("FAIL: Ctrl-C: exit %d, %r, file %s" % (rc, w.text, os.path.exists(out)))

        # the whole walk
        w = Walk(port, out)
        w.expect("straight up")
        w.expect("Press Enter")
        hands("base:0deg", "shoulder:0deg", "elbow:0deg", "wrist:0deg", "wrist-rotate:0deg")
        w.key("")
        w.expect("home: base offset=+23 shoulder offset=-17 elbow offset=+30 wrist offset=-12 "
                 "wrist-rotate offset=+5")
        w.expect("Press Enter")
        hands("base:20deg", "shoulder:20deg", "elbow:2deg", "wrist:20deg", "wrist-rotate:20deg")
        w.key("")
        w.expect("lean further, then take this step again: elbow")
        w.expect("Press Enter")  # asked again
        hands("elbow:25deg")
        w.key("")
        w.expect("lean: base dir=+1 shoulder dir=+1 elbow dir=-1 wrist dir=+1 wrist-rotate dir=+1")
        w.expect("Close the gripper")
        hands("gripper:650")
        w.key("")
        w.expect("gripper-closed: gripper closed=650")
        w.expect("Open the gripper")
        hands("gripper:120")
        w.key("")
        w.expect("gripper-open: gripper open=120")
        w.expect("Written to " + out)
        rc = w.end()
        if rc != 0:
            sys.exit("FAIL: the walk exited %d: %s" % (rc, w.text))
        text = open(out).read()
        for want in ("offset=+23", "dir=-1 offset=+30", "limits=120..650 open=120 closed=650",
                     "# calibrate gripper-open: "):
            if want not in text:
                sys.exit("FAIL: the profile lacks %r:\n%s" % (want, text))
        # the servos hold where the hands left them
        got = read("1", "2", "3", "4", "5", "6")
        if got != ["1:120", "2:588", "3:571", "4:426", "5:566", "6:606"]:
            sys.exit("FAIL: after the walk the servos are at %s" % got)
        print("calibrate walk: ok")
    finally:
        for p in reversed(procs):
            p.terminate()
            p.wait()
        shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
