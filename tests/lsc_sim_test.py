#!/usr/bin/env python3
"""Tests of lsc-sim over its pseudo-terminal, with a raw peer (stdlib only).

Usage: lsc_sim_test.py PATH/TO/lsc-sim [unittest arguments]

Waits that bound how long a test may take scale with LSC_TEST_TIME_SCALE (a
positive integer, default 1), as tests/test_time.h does for the C tests;
figures the test asserts lsc-sim keeps (a lower bound on pacing) do not.
"""
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tty
import unittest

LSC_SIM = None


def time_scale():
    """LSC_TEST_TIME_SCALE: a positive integer up to 1000, else 1."""
    s = os.environ.get("LSC_TEST_TIME_SCALE", "")
    return int(s) if s.isdigit() and 1 <= int(s) <= 1000 else 1


def test_s(seconds):
    """A wall-clock wait of the test, scaled for a slow or busy machine."""
    return seconds * time_scale()

BATTERY_REQ = bytes([0x55, 0x55, 0x02, 0x0F])
BATTERY_7500 = bytes([0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D])


def pos_request(ids):
    return bytes([0x55, 0x55, len(ids) + 3, 0x15, len(ids)] + list(ids))


class Sim:
    """One lsc-sim process and a raw peer on its pseudo-terminal."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([LSC_SIM, *args], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE)
        ready, _, _ = select.select([self.proc.stdout], [], [], test_s(30))
        if not ready:
            self.proc.kill()
            raise AssertionError("lsc-sim printed no path within %d s" % test_s(30))
        self.path = self.proc.stdout.readline().decode().strip()
        self.fd = os.open(self.path, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd)

    def send(self, data):
        os.write(self.fd, data)

    def recv(self, n, timeout=10.0):
        """Reads exactly n bytes, or fewer if timeout (scaled) passes."""
        out = b""
        end = time.monotonic() + test_s(timeout)
        while len(out) < n:
            left = end - time.monotonic()
            if left <= 0:
                break
            ready, _, _ = select.select([self.fd], [], [], left)
            if ready:
                out += os.read(self.fd, n - len(out))
        return out

    def silent(self, seconds):
        ready, _, _ = select.select([self.fd], [], [], seconds)
        return not ready

    def stop(self, sig=signal.SIGTERM):
        os.close(self.fd)
        self.proc.send_signal(sig)
        try:
            _, err = self.proc.communicate(timeout=test_s(30))
        except subprocess.TimeoutExpired:
            self.proc.kill()
            raise
        self.stderr = err.decode()
        return self.proc.returncode


class LscSimTest(unittest.TestCase):
    def run_sim(self, *args):
        sim = Sim(*args)
        self.addCleanup(lambda: sim.proc.poll() is None and sim.proc.kill())
        return sim

    def test_defaults(self):
        sim = self.run_sim("--fast")
        self.assertTrue(sim.path.startswith("/dev/pts/"), sim.path)
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), BATTERY_7500)
        sim.send(pos_request([1, 255, 0]))
        self.assertEqual(sim.recv(14), bytes([0x55, 0x55, 0x0C, 0x15, 3, 1, 0xDC, 0x05,
                                              255, 0xDC, 0x05, 0, 0xDC, 0x05]))
        self.assertEqual(sim.stop(), 0)
        self.assertEqual(sim.stderr, "")

    def test_move_then_read(self):
        sim = self.run_sim("--fast")
        sim.send(bytes([0x55, 0x55, 0x08, 0x03, 0x01, 0x64, 0x00, 0x07, 0xD0, 0x07]))  # 100 ms
        # servo 7 moves from 1500 to 2000 over 100 ms: read until it is there
        # (the positions on the way are checked by the model's own tests)
        end = time.monotonic() + test_s(10)
        reply = b""
        while time.monotonic() < end:
            sim.send(pos_request([7]))
            reply = sim.recv(8)
            if reply == bytes([0x55, 0x55, 0x06, 0x15, 1, 7, 0xD0, 0x07]):
                break
            self.assertEqual(reply[:6], bytes([0x55, 0x55, 0x06, 0x15, 1, 7]))
            pos = reply[6] | reply[7] << 8
            self.assertTrue(1500 <= pos < 2000, pos)
        self.assertEqual(reply, bytes([0x55, 0x55, 0x06, 0x15, 1, 7, 0xD0, 0x07]))
        self.assertEqual(sim.stop(), 0)

    def timed_read_of_32(self, *args):
        sim = self.run_sim(*args)
        sim.send(pos_request(range(32)))
        start = time.monotonic()
        reply = sim.recv(101)
        took = time.monotonic() - start
        self.assertEqual(len(reply), 101)
        self.assertEqual(reply[:5], bytes([0x55, 0x55, 0x63, 0x15, 32]))
        self.assertEqual(sim.stop(), 0)
        return took

    def test_pacing_default_9600(self):
        took = self.timed_read_of_32()
        self.assertGreaterEqual(took, 0.100)
        self.assertLess(took, test_s(1.0))

    def test_pacing_baud(self):
        took = self.timed_read_of_32("--baud", "2400")  # 101 bytes: 421 ms
        self.assertGreaterEqual(took, 0.400)

    def test_fast(self):
        # Not paced: the whole 101-byte reply is written at once, so the
        # first read gets all of it (paced, it comes a byte per ~1 ms). A
        # bound on the time taken would fail on a busy machine.
        sim = self.run_sim("--fast")
        sim.send(pos_request(range(32)))
        ready, _, _ = select.select([sim.fd], [], [], test_s(10))
        self.assertTrue(ready)
        reply = os.read(sim.fd, 200)
        self.assertEqual(len(reply), 101)
        self.assertEqual(reply[:5], bytes([0x55, 0x55, 0x63, 0x15, 32]))
        self.assertEqual(sim.stop(), 0)

    def test_link_and_sigterm(self):
        d = tempfile.mkdtemp()
        link = os.path.join(d, "lsc")
        sim = self.run_sim("--fast", "--link", link)
        self.assertEqual(os.readlink(link), sim.path)
        fd = os.open(link, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(fd)
        os.write(fd, BATTERY_REQ)
        got = b""
        end = time.monotonic() + test_s(10)
        while len(got) < len(BATTERY_7500) and time.monotonic() < end:
            if select.select([fd], [], [], end - time.monotonic())[0]:
                got += os.read(fd, 64)
        self.assertEqual(got, BATTERY_7500)
        os.close(fd)
        self.assertEqual(sim.stop(signal.SIGTERM), 0)
        self.assertFalse(os.path.lexists(link))
        os.rmdir(d)

    def test_link_replaces_stale_symlink_sigint(self):
        d = tempfile.mkdtemp()
        link = os.path.join(d, "lsc")
        os.symlink("/nonexistent", link)
        sim = self.run_sim("--fast", "--link", link)
        self.assertEqual(os.readlink(link), sim.path)
        self.assertEqual(sim.stop(signal.SIGINT), 0)
        self.assertFalse(os.path.lexists(link))
        os.rmdir(d)

    def test_link_removed_on_sighup_and_sigquit(self):
        for sig in (signal.SIGHUP, signal.SIGQUIT):
            d = tempfile.mkdtemp()
            link = os.path.join(d, "lsc")
            sim = self.run_sim("--fast", "--link", link)
            self.assertEqual(os.readlink(link), sim.path)
            self.assertEqual(sim.stop(sig), 0, sig)
            self.assertFalse(os.path.lexists(link), sig)
            os.rmdir(d)

    def test_link_refuses_a_file(self):
        with tempfile.NamedTemporaryFile() as f:
            r = subprocess.run([LSC_SIM, "--link", f.name], capture_output=True,
                               timeout=test_s(30))
            self.assertEqual(r.returncode, 1)
            self.assertIn(b"not a symlink", r.stderr)
            self.assertEqual(r.stdout, b"")

    def test_battery(self):
        sim = self.run_sim("--fast", "--battery", "6123")
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), bytes([0x55, 0x55, 0x04, 0x0F, 0xEB, 0x17]))
        self.assertEqual(sim.stop(), 0)

    def test_numbers_decimal_or_hex(self):
        # lscctl's number grammar: a leading 0 is decimal, never octal
        for value, mv in [("010", 10), ("0x1F40", 8000), ("0X1f40", 8000), ("00065535", 65535)]:
            sim = self.run_sim("--fast", "--battery", value)
            sim.send(BATTERY_REQ)
            self.assertEqual(sim.recv(6), bytes([0x55, 0x55, 0x04, 0x0F, mv & 0xFF, mv >> 8]),
                             value)
            self.assertEqual(sim.stop(), 0)
        sim = self.run_sim("--fast", "--corrupt", "010:03:0x01")  # 10 replies, offset 3
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), bytes([0x55, 0x55, 0x04, 0x0E, 0x4C, 0x1D]))
        self.assertEqual(sim.stop(), 0)

    def test_groups_file(self):
        with tempfile.NamedTemporaryFile("w", suffix=".txt") as f:
            f.write("# test\ngroup 5\nstep 100 1:2000\nstep 100 1:1000\n")
            f.flush()
            sim = self.run_sim("--fast", "--groups", f.name)
            sim.send(bytes([0x55, 0x55, 0x05, 0x06, 0x05, 0x01, 0x00]))
            start = time.monotonic()
            self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x06, 0x05, 0x01, 0x00]))
            self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x08, 0x05, 0x01, 0x00]))
            self.assertGreaterEqual(time.monotonic() - start, 0.190)
            # forever, then stop
            sim.send(bytes([0x55, 0x55, 0x05, 0x06, 0x05, 0x00, 0x00]))
            self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x06, 0x05, 0x00, 0x00]))
            self.assertTrue(sim.silent(0.3))
            sim.send(bytes([0x55, 0x55, 0x02, 0x07]))
            self.assertEqual(sim.recv(4), bytes([0x55, 0x55, 0x02, 0x07]))
            self.assertEqual(sim.stop(), 0)

    def run_group(self, sim, group):
        """Runs group once and waits for its start and end notifications."""
        sim.send(bytes([0x55, 0x55, 0x05, 0x06, group, 0x01, 0x00]))
        self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x06, group, 0x01, 0x00]))
        self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x08, group, 0x01, 0x00]))

    def test_groups_several_files(self):
        """--groups FILE... and --groups repeated: every file's groups served together."""
        d = tempfile.mkdtemp()
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", d]))
        paths = []
        for g in (5, 6, 7):
            paths.append(os.path.join(d, "g%d.txt" % g))
            with open(paths[-1], "w") as f:
                f.write("group %d\nstep 50 1:%d\n" % (g, 1000 + g))
        for args in (["--groups", *paths], ["--groups", paths[0], "--groups", paths[1], paths[2]],
                     ["--groups", paths[0], "--fast", "--groups", paths[1], paths[2]]):
            if "--fast" not in args:
                args = ["--fast", *args]
            sim = self.run_sim(*args)
            for g in (5, 6, 7):
                self.run_group(sim, g)
            self.assertEqual(sim.stop(), 0, args)

    @staticmethod
    def rob(times_positions):
        """A .rob file's bytes: SOBARM, the count, 8 zero bytes, 14-byte records."""
        out = b"SOBARM" + len(times_positions).to_bytes(2, "little") + bytes(8)
        for t, pos in times_positions:
            out += b"".join(v.to_bytes(2, "little") for v in [t, *pos])
        return out

    def test_groups_numbered_action_files(self):
        """N.rob, N.csv, N-name.d6a: group N, as the vendors' software numbers its
        files; served together."""
        d = tempfile.mkdtemp()
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", d]))
        with open(os.path.join(d, "10.rob"), "wb") as f:
            f.write(self.rob([(60, [100, 200, 300, 400, 500, 600])]))
        with open(os.path.join(d, "11.rob"), "wb") as f:
            f.write(self.rob([(60, [600, 500, 400, 300, 200, 100])]))
        with open(os.path.join(d, "3-wave.csv"), "w") as f:
            f.write("time_ms,9\n60,1234\n")
        files = [os.path.join(d, n) for n in ("10.rob", "11.rob", "3-wave.csv")]
        sim = self.run_sim("--fast", "--groups", *files)
        for g, (servo, pos) in ((10, (1, 100)), (11, (1, 600)), (3, (9, 1234))):
            self.run_group(sim, g)
            sim.send(pos_request([servo]))
            self.assertEqual(sim.recv(8), bytes([0x55, 0x55, 0x06, 0x15, 1, servo,
                                                 pos & 0xFF, pos >> 8]), g)
        self.assertEqual(sim.stop(), 0)
        self.assertEqual(sim.stderr.splitlines(), ["lsc-sim: %s: group %d" % (f, g) for f, g in
                                                   zip(files, (10, 11, 3))])

    def test_groups_clash(self):
        """A group number two files define: exit 2, naming both files."""
        d = tempfile.mkdtemp()
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", d]))
        txt = os.path.join(d, "g.txt")
        with open(txt, "w") as f:
            f.write("group 4\nstep 50 1:1000\ngroup 10\nstep 50 1:1000\n")
        rob10 = os.path.join(d, "10.rob")
        with open(rob10, "wb") as f:
            f.write(self.rob([(60, [100, 200, 300, 400, 500, 600])]))
        one = os.path.join(d, "wave.csv")  # no number: group 1
        with open(one, "w") as f:
            f.write("time_ms,1\n60,1000\n")
        other = os.path.join(d, "other.csv")
        with open(other, "w") as f:
            f.write("time_ms,1\n60,1000\n")
        bad = os.path.join(d, "300.csv")
        with open(bad, "w") as f:
            f.write("time_ms,1\n60,1000\n")
        for args, message in [
            ([txt, rob10], "group 10 is in both %s and %s" % (txt, rob10)),
            ([one, "--groups", other], "group 1 is in both %s and %s" % (one, other)),
            ([one, one], "group 1 is in both %s and %s" % (one, one)),
            ([bad], "%s: the number the name starts with is not a group (0..254)" % bad),
        ]:
            r = subprocess.run([LSC_SIM, "--groups", *args], capture_output=True,
                               timeout=test_s(30))
            self.assertEqual(r.returncode, 2, args)
            self.assertIn("lsc-sim: " + message, r.stderr.decode(), args)
            self.assertEqual(r.stdout, b"", args)
        # a word after another option is not a group file
        r = subprocess.run([LSC_SIM, "--groups", one, "--fast", other], capture_output=True,
                           timeout=test_s(30))
        self.assertEqual(r.returncode, 2)
        self.assertIn("unexpected argument '%s'" % other, r.stderr.decode())

    def test_button(self):
        """--button G: SIGUSR1 runs group G once, as the board's button would;
        other signals still end lsc-sim."""
        with tempfile.NamedTemporaryFile("w", suffix=".txt") as f:
            f.write("group 5\nstep 100 1:2000\n")
            f.flush()
            sim = self.run_sim("--fast", "--groups", f.name, "--button", "5")
            for _ in range(2):
                sim.proc.send_signal(signal.SIGUSR1)
                self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x06, 0x05, 0x01, 0x00]))
                self.assertEqual(sim.recv(7), bytes([0x55, 0x55, 0x05, 0x08, 0x05, 0x01, 0x00]))
            self.assertEqual(sim.stop(), 0)
            for args, message in [
                (["--button", "3"], "--button 3: no group 3 is loaded (load it with --groups FILE)"),
                (["--button", "255"], "invalid --button '255': group 255 is out of range: use 0..254"),
                (["--button", "x"], "invalid --button 'x'"),
            ]:
                r = subprocess.run([LSC_SIM, "--groups", f.name, *args], capture_output=True,
                                   timeout=test_s(30))
                self.assertEqual(r.returncode, 2, args)
                self.assertIn("lsc-sim: " + message, r.stderr.decode(), args)
                self.assertEqual(r.stdout, b"", args)
        r = subprocess.run([LSC_SIM, "--button", "1"], capture_output=True, timeout=test_s(30))
        self.assertEqual(r.returncode, 2)
        self.assertIn("no group 1 is loaded", r.stderr.decode())

    def test_groups_file_errors(self):
        with tempfile.NamedTemporaryFile("w", suffix=".txt") as f:
            f.write("group 1\nstep 100 1:2000 1:3\n")
            f.flush()
            r = subprocess.run([LSC_SIM, "--groups", f.name], capture_output=True,
                               timeout=test_s(30))
            self.assertEqual(r.returncode, 2)
            self.assertEqual(r.stderr.decode(),
                             "lsc-sim: %s:2:17: servo listed twice in one step\n" % f.name)
            self.assertEqual(r.stdout, b"")
        r = subprocess.run([LSC_SIM, "--groups", "/nonexistent/groups"], capture_output=True,
                           timeout=test_s(30))
        self.assertEqual(r.returncode, 2)
        self.assertIn(b"/nonexistent/groups: No such file", r.stderr)

    def test_example_groups_load(self):
        examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples",
                                "groups")
        for name in sorted(os.listdir(examples)):
            sim = self.run_sim("--fast", "--groups", os.path.join(examples, name))
            self.assertEqual(sim.stop(), 0, name)

    def test_log(self):
        sim = self.run_sim("--fast", "--log")
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), BATTERY_7500)
        sim.send(bytes([0x55, 0x55, 0x05, 0x08, 0x01, 0x01, 0x00]))  # command 8: beep
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), BATTERY_7500)  # no reply came before this one
        self.assertEqual(sim.stop(), 0)
        lines = sim.stderr.splitlines()
        self.assertRegex(lines[0], r"^lsc-sim: \d+\.\d{6} rx 55 55 02 0F$")
        self.assertRegex(lines[1], r"^lsc-sim: \d+\.\d{6} tx 55 55 04 0F 4C 1D$")
        self.assertRegex(lines[2], r"^lsc-sim: \d+\.\d{6} rx 55 55 05 08 01 01 00$")
        self.assertRegex(lines[3], r"^lsc-sim: \d+\.\d{6} beep \(two beeps\) command 8")
        self.assertEqual(len(lines), 6)

    def test_drop_replies(self):
        sim = self.run_sim("--fast", "--drop-replies", "2")
        sim.send(BATTERY_REQ)
        sim.send(BATTERY_REQ)
        self.assertTrue(sim.silent(0.2))
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), BATTERY_7500)
        self.assertEqual(sim.stop(), 0)

    def test_delay(self):
        sim = self.run_sim("--fast", "--delay-ms", "200")
        sim.send(BATTERY_REQ)
        start = time.monotonic()
        self.assertEqual(sim.recv(6), BATTERY_7500)
        self.assertGreaterEqual(time.monotonic() - start, 0.195)
        self.assertEqual(sim.stop(), 0)

    def test_corrupt(self):
        sim = self.run_sim("--fast", "--corrupt", "1")
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), bytes([0x55, 0x55, 0xFB, 0x0F, 0x4C, 0x1D]))
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), BATTERY_7500)
        self.assertEqual(sim.stop(), 0)
        sim = self.run_sim("--fast", "--corrupt", "1:5:0x01")
        sim.send(BATTERY_REQ)
        self.assertEqual(sim.recv(6), bytes([0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1C]))
        self.assertEqual(sim.stop(), 0)

    def test_bad_options(self):
        cases = [
            (["--bogus"], "unknown option '--bogus'"),
            (["--baud"], "option '--baud' needs an argument"),
            (["--baud", "0"], "invalid --baud '0': baud rate 0 is out of range: use 1..4000000"),
            (["--baud", "96x"], "invalid --baud '96x': baud rate '96x' is not a number"),
            (["--baud", "-5"], "invalid --baud '-5': baud rate '-5' is negative: use 1..4000000"),
            (["--baud", "4000001"], "invalid --baud '4000001': baud rate 4000001 is out of "
                                    "range: use 1..4000000"),
            (["--baud", "1e3"], "invalid --baud '1e3'"),
            (["--baud", "+9600"], "invalid --baud '+9600'"),
            (["--baud", " 9600"], "invalid --baud ' 9600'"),
            (["--battery", "65536"], "invalid --battery '65536': millivolts 65536 is out of "
                                     "range: use 0..65535"),
            (["--battery", "0x"], "invalid --battery '0x'"),
            (["--battery", "0o17"], "invalid --battery '0o17'"),
            (["--battery", "9" * 23], "invalid --battery '%s'" % ("9" * 23)),
            (["--drop-replies", "x"], "invalid --drop-replies 'x'"),
            (["--drop-replies", "4294967296"], "invalid --drop-replies '4294967296'"),
            (["--delay-ms", "3600001"], "invalid --delay-ms '3600001'"),
            (["--corrupt", "1:256"], "invalid --corrupt '1:256': offset 256 is out of range"),
            (["--corrupt", "1:2:0x100"], "invalid --corrupt '1:2:0x100': XOR mask 0x100 is out "
                                         "of range"),
            (["--corrupt", "1:2:3:4"], "invalid --corrupt '1:2:3:4'"),
            (["--corrupt", "1:"], "invalid --corrupt '1:'"),
            (["--corrupt", ""], "invalid --corrupt ''"),
            (["--link", ""], "--link needs a path"),
            (["--fast", "--baud", "9600"], "--fast and --baud exclude each other"),
            (["extra"], "unexpected argument 'extra'"),
        ]
        for args, message in cases:
            r = subprocess.run([LSC_SIM, *args], capture_output=True, timeout=test_s(30))
            self.assertEqual(r.returncode, 2, args)
            self.assertIn("lsc-sim: " + message, r.stderr.decode(), args)
            self.assertIn("--help", r.stderr.decode(), args)
            self.assertEqual(r.stdout, b"", args)

    def test_help(self):
        r = subprocess.run([LSC_SIM, "--help"], capture_output=True, timeout=test_s(30))
        self.assertEqual(r.returncode, 0)
        out = r.stdout.decode()
        for opt in ["--link", "--baud", "--fast", "--battery", "--groups", "--log",
                    "--drop-replies", "--delay-ms", "--corrupt", "--help", "--version"]:
            self.assertIn(opt, out)
        r = subprocess.run([LSC_SIM, "--version"], capture_output=True, timeout=test_s(30))
        self.assertEqual(r.returncode, 0)
        self.assertRegex(r.stdout.decode(), r"^lsc-sim \d+\.\d+\.\d+\n$")

    def test_man_page_groups_indent(self):
        """lsc-sim.1: the paragraphs under --groups render at one indentation."""
        nroff = shutil.which("nroff")
        if nroff is None:
            self.skipTest("nroff is not installed")
        page = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli", "lsc-sim.1")
        r = subprocess.run([nroff, "-man", "-rLL=80n", page], capture_output=True,
                           timeout=test_s(30), env=dict(os.environ, LC_ALL="C"))
        self.assertEqual(r.returncode, 0, r.stderr)
        text = r.stdout.decode(errors="replace")
        text = re.sub(".\b", "", text)  # bold and underline
        lines = text.splitlines()
        def indent(prefix):
            for line in lines:
                if " ".join(line.split()).startswith(prefix):
                    return len(line) - len(line.lstrip())
            self.fail("no line starts with %r" % prefix)
        self.assertEqual(indent("group N starts group N"), indent("A .csv,"))
        self.assertEqual(indent("group N starts group N"), indent("A group file is line based"))


if __name__ == "__main__":
    LSC_SIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
