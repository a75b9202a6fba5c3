#!/usr/bin/env python3
"""The stand-in bus of servos (lxbus_peer.py) against frames written by hand
from the vendor's bus-servo protocol document.

Run: python3 tests/lxbus/test_lxbus_peer.py (ctest: lxbus_peer). Waits are
deadlines on replies, scaled by LSC_TEST_TIME_SCALE; nothing sleeps to
synchronise.
"""

import json
import os
import select
import socket
import subprocess
import sys
import tempfile
import termios
import time
import tty
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
PEER = os.path.join(HERE, "lxbus_peer.py")
SCALE = int(os.environ.get("LSC_TEST_TIME_SCALE", "1") or "1")
REPLY_S = 2.0 * SCALE  # a reply's deadline: the peer answers at once


def chk(body):
    return (~sum(body)) & 0xFF


def fr(servo_id, cmd, *params):
    body = bytes([servo_id, len(params) + 3, cmd]) + bytes(params)
    return b"\x55\x55" + body + bytes([chk(body)])


class Bus:
    def __init__(self, tmp, ids="1", *extra):
        self.link = os.path.join(tmp, "bus")
        self.ctl_path = os.path.join(tmp, "ctl")
        self.proc = subprocess.Popen(
            [sys.executable, PEER, "--link", self.link, "--ids", ids, "--control", self.ctl_path,
             "--watch-stdin"] + list(extra),
            stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        line = self.proc.stdout.readline().decode()
        assert line.startswith("ready "), line
        self.fd = os.open(self.link, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd)
        self.ctl = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.ctl.connect(self.ctl_path)
        self.ctl_file = self.ctl.makefile("r")

    def close(self):
        os.close(self.fd)
        self.ctl.close()
        self.proc.stdin.close()
        self.proc.wait(timeout=10 * SCALE)
        self.proc.stdout.close()

    def send(self, data):
        os.write(self.fd, data)

    def read(self, n):
        out = b""
        deadline = time.monotonic() + REPLY_S
        while len(out) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                break
            r, _, _ = select.select([self.fd], [], [], left)
            if r:
                out += os.read(self.fd, n - len(out))
        return out

    def ask(self, data, n):
        self.send(data)
        return self.read(n)

    def command(self, line):
        self.ctl.sendall(line.encode() + b"\n")
        reply = self.ctl_file.readline().strip()
        assert reply.startswith("ok"), reply
        return reply[3:]

    def dump(self):
        return {s["id"]: s for s in json.loads(self.command("dump"))["servos"]}

    def pos(self, servo_id):
        r = self.ask(fr(servo_id, 28), 8)
        assert r[:5] == bytes([0x55, 0x55, servo_id, 5, 28]), r
        v = r[5] | (r[6] << 8)
        return v - 0x10000 if v & 0x8000 else v

    def nothing_before(self, servo_id):
        """No answer was pending: the next request's reply comes first."""
        assert self.ask(fr(servo_id, 14), 7) == fr(servo_id, 14, servo_id)


class PeerTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.buses = []

    def tearDown(self):
        for b in self.buses:
            b.close()
        self.tmp.cleanup()

    def bus(self, ids="1", *extra):
        b = Bus(self.tmp.name, ids, *extra)
        self.buses.append(b)
        return b

    def test_frame_and_checksum(self):
        # the document's checksum: ~(ID + LEN + CMD + params), low byte
        self.assertEqual(fr(1, 1, 0xF4, 0x01, 0xE8, 0x03), bytes.fromhex("55 55 01 07 01 F4 01 E8 03 16"))
        b = self.bus("1")
        self.assertEqual(b.ask(fr(1, 14), 7), bytes.fromhex("55 55 01 04 0E 01 EB"))
        # LEN is n + 3, not "command + parameters" (a transcription's error)
        bad = bytes.fromhex("55 55 01 01 0E")
        b.send(bad + bytes([chk(bad[2:])]))
        b.nothing_before(1)
        # a flipped checksum is never believed
        good = fr(1, 1, 0x20, 0x03, 0x00, 0x00)
        b.send(good[:-1] + bytes([good[-1] ^ 0x01]))
        b.nothing_before(1)
        self.assertEqual(b.pos(1), 500)

    def test_move_and_read(self):
        b = self.bus("1-3")
        b.send(fr(2, 1, 0xBC, 0x02, 0x2C, 0x01))  # 700 in 300 ms
        deadline = time.monotonic() + 10 * SCALE
        while b.pos(2) != 700:
            self.assertLess(time.monotonic(), deadline)
        self.assertEqual(b.ask(fr(2, 2), 10), fr(2, 2, 0xBC, 0x02, 0x2C, 0x01))
        self.assertEqual(b.pos(1), 500)

    def test_wait_write_then_broadcast_start(self):
        b = self.bus("1,2")
        b.send(fr(1, 7, 0xC8, 0x00, 0x00, 0x00))  # 200, at once, when started
        b.send(fr(2, 7, 0x20, 0x03, 0x00, 0x00))  # 800
        self.assertEqual(b.ask(fr(1, 8), 10), fr(1, 8, 0xC8, 0x00, 0x00, 0x00))
        self.assertEqual(b.pos(1), 500)
        b.send(fr(254, 11))
        b.nothing_before(1)
        self.assertEqual((b.pos(1), b.pos(2)), (200, 800))

    def test_broadcast_is_unanswered_except_id_read(self):
        b = self.bus("5")
        b.send(fr(254, 28))
        b.nothing_before(5)
        self.assertEqual(b.ask(fr(254, 14), 7), fr(5, 14, 5))

    def test_answers_collide(self):
        b = self.bus("1,2")
        got = b.ask(fr(254, 14), 7)
        a, c = fr(1, 14, 1), fr(2, 14, 2)
        self.assertEqual(got, bytes(x & y for x, y in zip(a, c)))
        # the checksum of the ANDed bytes fails: 55 55 00 04 0E 00 EA
        self.assertNotEqual(chk(got[2:-1]), got[-1])

    def test_id_write_is_kept(self):
        state = os.path.join(self.tmp.name, "state.json")
        b = self.bus("1", "--state", state)
        b.send(fr(1, 13, 9))
        self.assertEqual(b.ask(fr(254, 14), 7), fr(9, 14, 9))
        b.command("power-cycle")
        self.assertEqual(b.ask(fr(254, 14), 7), fr(9, 14, 9))
        b.close()
        self.buses.remove(b)
        b = self.bus("1", "--state", state)
        self.assertEqual(b.ask(fr(254, 14), 7), fr(9, 14, 9))

    def test_offset_adjust_is_lost_write_is_kept(self):
        b = self.bus("1,3")
        b.send(fr(3, 1, 0xF4, 0x01, 0, 0))  # held at 500
        b.send(fr(1, 17, 15))
        b.send(fr(1, 18))
        b.send(fr(3, 17, (-20) & 0xFF))
        self.assertEqual(b.ask(fr(3, 19), 7), fr(3, 19, 0xEC))  # int8 -20
        # the shaft turned by the offset, the position reads the same
        self.assertEqual(b.dump()[3]["shaft"], 480)
        self.assertEqual(b.pos(3), 500)
        b.command("power-cycle")
        self.assertEqual(b.ask(fr(1, 19), 7), fr(1, 19, 15))
        self.assertEqual(b.ask(fr(3, 19), 7), fr(3, 19, 0))
        # out of the document's range (-125..125): ignored
        b.send(fr(1, 17, (-126) & 0xFF))
        self.assertEqual(b.ask(fr(1, 19), 7), fr(1, 19, 15))

    def test_position_is_int16(self):
        b = self.bus("1")
        b.send(fr(1, 17, (-100) & 0xFF))
        b.send(fr(1, 31, 0))  # limp
        b.command("set 1 pos 20")
        self.assertEqual(b.pos(1), 120)
        b.send(fr(1, 17, 100))
        self.assertEqual(b.pos(1), -80)

    def test_limits(self):
        b = self.bus("1")
        b.send(fr(1, 20, 0x64, 0x00, 0x84, 0x03))  # 100..900
        self.assertEqual(b.ask(fr(1, 21), 10), fr(1, 21, 0x64, 0x00, 0x84, 0x03))
        b.send(fr(1, 20, 0x84, 0x03, 0x64, 0x00))  # min > max: ignored
        self.assertEqual(b.ask(fr(1, 21), 10), fr(1, 21, 0x64, 0x00, 0x84, 0x03))
        b.send(fr(1, 1, 0xE8, 0x03, 0, 0))  # 1000, clamped to 900
        b.nothing_before(1)
        self.assertEqual(b.pos(1), 900)
        # input voltage limits: 4500..12000 (not the reply text's 6500..10000)
        self.assertEqual(b.ask(fr(1, 23), 10), fr(1, 23, 0x94, 0x11, 0xE0, 0x2E))
        b.send(fr(1, 22, 0x94, 0x11, 0xE0, 0x2E))
        b.send(fr(1, 22, 0x93, 0x11, 0xE0, 0x2E))  # 4499: ignored
        self.assertEqual(b.ask(fr(1, 23), 10), fr(1, 23, 0x94, 0x11, 0xE0, 0x2E))
        self.assertEqual(b.ask(fr(1, 25), 7), fr(1, 25, 85))
        b.send(fr(1, 24, 101))
        b.send(fr(1, 24, 70))
        self.assertEqual(b.ask(fr(1, 25), 7), fr(1, 25, 70))

    def test_readings_and_protection(self):
        b = self.bus("1", "--temp", "41", "--vin", "7600")
        self.assertEqual(b.ask(fr(1, 26), 7), fr(1, 26, 41))
        self.assertEqual(b.ask(fr(1, 27), 8), fr(1, 27, 0xB0, 0x1D))
        b.send(fr(1, 31, 1))
        self.assertEqual(b.ask(fr(1, 32), 7), fr(1, 32, 1))
        b.command("set 1 temp 90")
        self.assertEqual(b.ask(fr(1, 32), 7), fr(1, 32, 0))
        self.assertEqual(b.dump()[1]["alarms"], 1)

    def test_motor_mode_led_alarm_mask(self):
        b = self.bus("1")
        b.send(fr(1, 29, 1, 0, 0x18, 0xFC))  # motor, speed -1000
        self.assertEqual(b.ask(fr(1, 30), 10), fr(1, 30, 1, 0, 0x18, 0xFC))
        b.command("power-cycle")
        self.assertEqual(b.ask(fr(1, 30), 10), fr(1, 30, 0, 0, 0, 0))
        b.send(fr(1, 33, 1))
        self.assertEqual(b.ask(fr(1, 34), 7), fr(1, 34, 1))
        b.send(fr(1, 35, 3))
        self.assertEqual(b.ask(fr(1, 36), 7), fr(1, 36, 3))
        b.send(fr(1, 35, 8))
        self.assertEqual(b.ask(fr(1, 36), 7), fr(1, 36, 3))

    def test_echo_and_flip(self):
        b = self.bus("2", "--echo")
        req = fr(2, 28)
        self.assertEqual(b.ask(req, 6 + 8), req + fr(2, 28, 0xF4, 0x01))
        b.command("flip")
        r = b.ask(req, 6 + 8)[6:]
        self.assertNotEqual(chk(r[2:-1]), r[-1])
        self.assertEqual(b.command("count 28"), "2")

    def test_stop(self):
        b = self.bus("1")
        b.send(fr(1, 1, 0xE8, 0x03, 0x30, 0x75))  # 1000 in 30 s
        b.send(fr(1, 12))
        first = b.pos(1)
        self.assertEqual(b.dump()[1]["moving"], False)
        self.assertEqual(b.pos(1), first)
        self.assertLess(first, 1000)


if __name__ == "__main__":
    unittest.main(verbosity=1)
