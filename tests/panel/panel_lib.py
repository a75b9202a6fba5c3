"""Helpers for lsc-panel's tests: lsc-sim on a pseudo-terminal, lscd on it,
lsc-panel on a free port, and waits that poll a condition until a deadline
scaled by LSC_TEST_TIME_SCALE (tests/test_time.h). Standard library only.

Environment: LSC_PANEL, LSC_SIM, LSCD, LSCCTL (the built programs)."""
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time


def scale():
    s = os.environ.get("LSC_TEST_TIME_SCALE", "1")
    return int(s) if s.isdigit() and 1 <= int(s) <= 1000 else 1


def wait_for(what, cond, seconds=10.0):
    """Polls cond() until it is true; fails naming what after seconds (scaled)."""
    deadline = time.monotonic() + seconds * scale()
    while True:
        v = cond()
        if v:
            return v
        if time.monotonic() > deadline:
            raise AssertionError("timed out waiting for " + what)
        time.sleep(0.02)


class Rig:
    """lsc-sim (a board, or with sim_args a bus), optionally lscd on it, and
    lsc-panel, in a temporary directory."""

    def __init__(self, groups=None, tty="a", sim_args=()):
        self.tmp = tempfile.mkdtemp(prefix="lsc-panel-test.")
        self.procs = []
        self.files = os.path.join(self.tmp, "files")
        os.mkdir(self.files)
        self.sim_log = os.path.join(self.tmp, "sim.log")
        self.tty = os.path.join(self.tmp, tty)
        cmd = [os.environ["LSC_SIM"], "--link", self.tty, "--log"]
        if groups:
            cmd += ["--groups", groups]
        cmd += list(sim_args)  # ("--lx", "1-3": a bus of servos)
        self.sim = self.start(cmd, stdout=subprocess.DEVNULL, stderr=open(self.sim_log, "w"))
        wait_for("lsc-sim's link", lambda: os.path.exists(self.tty))
        self.sock = None

    def start(self, cmd, **kw):
        p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, **kw)
        self.procs.append(p)
        return p

    def lscctl(self, *args, check=True):
        r = subprocess.run([os.environ["LSCCTL"], *args], stdin=subprocess.DEVNULL,
                           capture_output=True, text=True, timeout=60 * scale())
        if check and r.returncode != 0:
            raise AssertionError("lscctl %s: exit %d: %s" % (" ".join(args), r.returncode,
                                                             r.stderr.strip()))
        return r

    def start_lscd(self):
        run = self.run = os.path.join(self.tmp, "run")
        os.makedirs(run, exist_ok=True)
        env = dict(os.environ, LSC_LSCD_DIR=run)
        self.lscd = self.start([os.environ["LSCD"], "--port", self.tty], env=env,
                               stderr=open(os.path.join(self.tmp, "lscd.log"), "a"))
        self.sock = os.path.join(run, os.path.basename(self.tty) + ".sock")
        wait_for("lscd to answer", lambda: self.lscctl("--port", "lscd:" + self.sock,
                                                       "status", check=False).returncode == 0)
        return "lscd:" + self.sock

    def stop_lscd(self):
        """Stops lscd (SIGTERM) and waits for its end."""
        self.lscd.send_signal(signal.SIGTERM)
        self.lscd.wait(timeout=20 * scale())

    def restart_lscd(self):
        """lscd again, on the same socket."""
        return self.start_lscd()

    def start_panel(self, port, *extra, dir="", env=None, cwd=None):
        """Starts lsc-panel on port (with --dir the rig's files, or dir, or
        with dir None none: the default); returns the URL it printed."""
        d = self.files if dir == "" else dir
        self.panel = self.start([os.environ["LSC_PANEL"], "--port", port, "--listen",
                                 "127.0.0.1:0", *(["--dir", d] if d else []), *extra],
                                stdout=subprocess.PIPE, text=True, env=env, cwd=cwd,
                                stderr=open(os.path.join(self.tmp, "panel.log"), "a"))
        ready, _, _ = select.select([self.panel.stdout], [], [], 20 * scale())
        line = self.panel.stdout.readline().strip() if ready else ""
        m = re.fullmatch(r"http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]{32})", line)
        if not m:
            raise AssertionError("lsc-panel printed %r; its log: %s" % (line, self.log("panel")))
        self.url, self.port, self.token = line, int(m.group(1)), m.group(2)
        self.base = "http://127.0.0.1:%d" % self.port
        return line

    def log(self, name):
        with open(os.path.join(self.tmp, name + ".log"), errors="replace") as f:
            return f.read()

    def moves(self, since=0):
        """The servo_move frames lsc-sim received (after byte offset since of its
        log): a list of {id: position}."""
        out = []
        for m in re.finditer(r" rx 55 55 ([0-9A-F]{2}) 03 ((?:[0-9A-F]{2} ?)*)",
                             self.log("sim")[since:]):
            b = [int(x, 16) for x in m.group(2).split()]
            n = b[0]
            out.append({b[3 + 3 * i]: b[4 + 3 * i] | b[5 + 3 * i] << 8 for i in range(n)
                        if len(b) >= 6 + 3 * i})
        return out

    def close(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        codes = []
        for p in reversed(self.procs):
            try:
                codes.append(p.wait(timeout=20 * scale()))
            except subprocess.TimeoutExpired:
                p.kill()
                codes.append("hung")
        self.panel_log = self.log("panel") if os.path.exists(
            os.path.join(self.tmp, "panel.log")) else ""
        if os.environ.get("LSC_KEEP_TMP"):
            print("kept", self.tmp)
        else:
            shutil.rmtree(self.tmp, ignore_errors=True)
        return codes


def browser(size="1100,1000"):
    """Headless Chromium (chromedriver, selenium) with the console's and the
    network's logs, a window of size ("WIDTH,HEIGHT")."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    o = webdriver.ChromeOptions()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=" + size,
              "--disable-dev-shm-usage", "--no-first-run", "--disable-extensions",
              "--disable-background-networking", "--disable-component-update",
              "--disable-sync", "--disable-default-apps"):
        o.add_argument(a)
    o.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def skip(why):
    print("SKIP: " + why)
    sys.exit(77)


# ---- checks: each test counts its checks and lists its failures ------------------------

failures = []
_checks = [0]


def check(what, cond):
    """One check: a failure is listed (and printed) and the test goes on.
    Returns cond."""
    _checks[0] += 1
    if not cond:
        failures.append(what)
        print("FAIL: " + what, file=sys.stderr)
    return cond


def report():
    """Prints the count; the exit status: 1 if any check failed."""
    print("%d checks, %d failures" % (_checks[0], len(failures)))
    return 1 if failures else 0
