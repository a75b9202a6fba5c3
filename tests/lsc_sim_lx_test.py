#!/usr/bin/env python3
"""Tests of lsc-sim --lx (a virtual bus of serial bus servos) over its
pseudo-terminal, with a raw peer speaking the bus-servo protocol (standard
library only).

Usage: lsc_sim_lx_test.py PATH/TO/lsc-sim [unittest arguments]

Waits that bound how long a test may take scale with LSC_TEST_TIME_SCALE (a
positive integer, default 1), as tests/test_time.h does for the C tests.
"""
import os
import select
import signal
import subprocess
import sys
import tempfile
import time
import tty
import unittest

LSC_SIM = None


def time_scale():
    s = os.environ.get("LSC_TEST_TIME_SCALE", "")
    return int(s) if s.isdigit() and 1 <= int(s) <= 1000 else 1


def test_s(seconds):
    return seconds * time_scale()


def frame(servo, cmd, params=()):
    """A frame as the document defines it: 55 55 ID LEN CMD P... CHK."""
    params = list(params)
    length = len(params) + 3
    chk = ~(servo + length + cmd + sum(params)) & 0xFF
    return bytes([0x55, 0x55, servo, length, cmd] + params + [chk])


def u16(v):
    v &= 0xFFFF
    return [v & 0xFF, v >> 8]


POS_READ, ID_READ, OFFSET_READ, OFFSET_ADJUST, OFFSET_WRITE = 28, 14, 19, 17, 18
MOVE_WAIT, MOVE_START, ID_WRITE, VIN_READ, TEMP_READ = 7, 11, 13, 27, 26
REPLY_LEN = {POS_READ: 8, ID_READ: 7, OFFSET_READ: 7, VIN_READ: 8, TEMP_READ: 7}


class Sim:
    """One lsc-sim --lx process and a raw peer on its pseudo-terminal."""

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

    def ask(self, servo, cmd):
        """A read's reply (its whole frame)."""
        self.send(frame(servo, cmd))
        return self.recv(REPLY_LEN[cmd])

    def position(self, servo):
        r = self.ask(servo, POS_READ)
        assert len(r) == 8 and r == frame(servo, POS_READ, r[5:7]), r.hex()
        return int.from_bytes(r[5:7], "little", signed=True)

    def offset(self, servo):
        r = self.ask(servo, OFFSET_READ)
        assert r == frame(servo, OFFSET_READ, r[5:6]), r.hex()
        return int.from_bytes(r[5:6], "little", signed=True)

    def try_offset(self, servo):
        """The offset, or None when the reply did not come whole (a power
        cycle drops what was on its way); what came is drained."""
        self.send(frame(servo, OFFSET_READ))
        r = self.recv(7, timeout=1.0)
        while not self.silent(0.05):
            os.read(self.fd, 64)
        if r != frame(servo, OFFSET_READ, r[5:6]) or len(r) != 7:
            return None
        return int.from_bytes(r[5:6], "little", signed=True)

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


class LscSimLxTest(unittest.TestCase):
    def run_sim(self, *args):
        sim = Sim(*args)
        self.addCleanup(lambda: sim.proc.poll() is None and sim.proc.kill())
        return sim

    def test_scan_finds_exactly_the_servos(self):
        sim = self.run_sim("--lx", "1-6")
        found = []
        for servo in range(254):
            sim.send(frame(servo, ID_READ))
            # the reply of a servo that is there comes at once; nothing comes
            # from an id that is not, and the next request goes out meanwhile
        replies = sim.recv(6 * 7)
        self.assertTrue(sim.silent(0.2))
        for k in range(0, len(replies), 7):
            r = replies[k:k + 7]
            self.assertEqual(r, frame(r[2], ID_READ, [r[2]]))
            found.append(r[2])
        self.assertEqual(found, [1, 2, 3, 4, 5, 6])
        self.assertEqual(sim.stop(), 0)

    def test_move_together_then_read(self):
        sim = self.run_sim("--lx", "1-3")
        sim.send(frame(2, MOVE_WAIT, u16(700) + u16(300)))
        sim.send(frame(3, MOVE_WAIT, u16(250) + u16(300)))
        sim.send(frame(254, MOVE_START))
        end = time.monotonic() + test_s(10)
        while time.monotonic() < end and (sim.position(2), sim.position(3)) != (700, 250):
            time.sleep(0.02)
        self.assertEqual([sim.position(i) for i in (1, 2, 3)], [500, 700, 250])
        self.assertEqual(sim.stop(), 0)

    def test_readings(self):
        sim = self.run_sim("--lx", "2", "--battery", "7400")
        self.assertEqual(sim.ask(2, VIN_READ), frame(2, VIN_READ, u16(7400)))
        self.assertEqual(sim.ask(2, TEMP_READ), frame(2, TEMP_READ, [30]))
        self.assertEqual(sim.stop(), 0)

    def test_broadcast_id_read_collides(self):
        sim = self.run_sim("--lx", "1,2,3")
        sim.send(frame(254, ID_READ))
        r = sim.recv(7)
        want = bytes(a & b & c for a, b, c in zip(frame(1, ID_READ, [1]), frame(2, ID_READ, [2]),
                                                  frame(3, ID_READ, [3])))
        self.assertEqual(r, want)
        self.assertNotEqual(r[6], ~sum(r[2:6]) & 0xFF)  # its checksum fails
        self.assertEqual(sim.stop(), 0)

    def test_bad_checksum_unanswered(self):
        sim = self.run_sim("--lx", "1", "--log")
        bad = bytearray(frame(1, POS_READ))
        bad[-1] ^= 1
        sim.send(bytes(bad))
        self.assertTrue(sim.silent(0.3))
        self.assertEqual(sim.position(1), 500)
        self.assertEqual(sim.stop(), 0)
        self.assertIn("discarded checksum failed", sim.stderr)
        self.assertNotIn("beep", sim.stderr)

    def test_corrupt_reply_has_a_bad_checksum(self):
        sim = self.run_sim("--lx", "1", "--corrupt", "1:5:0x01")
        r = sim.ask(1, POS_READ)
        self.assertEqual(r[5], 0xF4 ^ 0x01)
        self.assertNotEqual(r, frame(1, POS_READ, r[5:7]))
        self.assertEqual(sim.position(1), 500)
        self.assertEqual(sim.stop(), 0)

    def test_echo(self):
        sim = self.run_sim("--lx", "1", "--echo")
        req = frame(1, POS_READ)
        sim.send(req)
        self.assertEqual(sim.recv(6 + 8), req + frame(1, POS_READ, u16(500)))
        self.assertEqual(sim.stop(), 0)

    def test_offsets_and_power_cycle_and_state(self):
        with tempfile.TemporaryDirectory() as tmp:
            state = os.path.join(tmp, "bus.txt")
            sim = self.run_sim("--lx", "1-3", "--state", state)
            self.assertTrue(os.path.exists(state))  # written at once
            sim.send(frame(1, OFFSET_ADJUST, [15]))
            sim.send(frame(1, OFFSET_WRITE))
            sim.send(frame(3, OFFSET_ADJUST, [(-20) & 0xFF]))
            sim.send(frame(2, ID_WRITE, [9]))
            self.assertEqual(sim.offset(1), 15)
            self.assertEqual(sim.offset(3), -20)
            self.assertEqual(sim.position(1), 515)  # the offset moves the servo
            self.assertEqual(sim.position(3), 480)
            sim.proc.send_signal(signal.SIGUSR2)  # power cycle
            end = time.monotonic() + test_s(10)
            while time.monotonic() < end and sim.try_offset(3) != 0:
                time.sleep(0.02)
            self.assertEqual(sim.offset(3), 0)
            self.assertEqual(sim.offset(1), 15)
            self.assertEqual(sim.position(9), 500)
            self.assertEqual(sim.stop(), 0)
            with open(state) as f:
                text = f.read()
            self.assertIn("servo id=1 offset=15 ", text)
            self.assertIn("servo id=9 offset=0 ", text)
            self.assertEqual([n for n in os.listdir(tmp)], ["bus.txt"])  # no temporary left
            # a new run: the same bus, servo 2 still 9
            sim = self.run_sim("--lx", "1-3", "--state", state)
            self.assertEqual(sim.offset(1), 15)
            self.assertEqual(sim.position(9), 500)
            sim.send(frame(2, POS_READ))
            self.assertTrue(sim.silent(0.2))
            self.assertEqual(sim.stop(), 0)
            # a list of another length is refused
            r = subprocess.run([LSC_SIM, "--lx", "1-2", "--state", state], capture_output=True,
                               timeout=test_s(30))
            self.assertEqual(r.returncode, 2)
            self.assertIn(b"keeps 3 servos but --lx '1-2' names 2", r.stderr)
            with open(state, "w") as f:
                f.write("servo id=300\n")
            r = subprocess.run([LSC_SIM, "--lx", "1", "--state", state], capture_output=True,
                               timeout=test_s(30))
            self.assertEqual(r.returncode, 2)
            self.assertIn(b"bus.txt:1:10: id: use 0..253", r.stderr)

    def test_link(self):
        with tempfile.TemporaryDirectory() as tmp:
            link = os.path.join(tmp, "bus")
            sim = self.run_sim("--lx", "4", "--link", link)
            self.assertEqual(os.readlink(link), sim.path)
            self.assertEqual(sim.position(4), 500)
            self.assertEqual(sim.stop(), 0)
            self.assertFalse(os.path.lexists(link))

    def test_pacing_115200(self):
        sim = self.run_sim("--lx", "1-6")
        start = time.monotonic()
        for servo in range(1, 7):
            sim.send(frame(servo, POS_READ))
        r = sim.recv(48)
        took = time.monotonic() - start
        self.assertEqual(len(r), 48)
        self.assertGreaterEqual(took, 48 * 10 / 115200)
        self.assertEqual(sim.stop(), 0)

    def test_usage_errors(self):
        for args, words in [
            (["--state", "x"], b"--state is for a bus of servos: give --lx IDS"),
            (["--echo"], b"--echo is for a bus of servos"),
            (["--lx", "1,254"], b"id 254 is not a servo's: use 0..253"),
            (["--lx", "1,1"], b"invalid --lx '1,1'"),
            (["--lx", "0-40"], b"more than 32"),
            (["--lx", "1", "--groups", "g.txt"], b"--groups is for the virtual controller"),
            (["--lx", "1", "--arm", "x.conf"], b"--arm is for the virtual controller"),
        ]:
            r = subprocess.run([LSC_SIM, *args], capture_output=True, timeout=test_s(30))
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(words, r.stderr, args)
            self.assertEqual(r.stdout, b"", args)

    def test_help(self):
        r = subprocess.run([LSC_SIM, "--help"], capture_output=True, timeout=test_s(30))
        self.assertEqual(r.returncode, 0)
        for words in (b"--lx IDS", b"--state FILE", b"--echo", b"SIGUSR2"):
            self.assertIn(words, r.stdout)


if __name__ == "__main__":
    LSC_SIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
