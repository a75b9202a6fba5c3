"""The stand-in bus of servos for the bus tests (test_servo*.py): the
source tree's tests/lxbus/lxbus_peer.py (a bus written from the vendor's
protocol document alone, not by lsc) on a pseudo-terminal, with its control
socket. $LSC_LXBUS_PEER names another copy; none found: the tests skip."""
import os
import select
import socket
import subprocess
import sys

import pytest

from conftest import HERE, test_s

PEER = os.environ.get("LSC_LXBUS_PEER", "") or os.path.normpath(
    os.path.join(HERE, "..", "..", "..", "tests", "lxbus", "lxbus_peer.py"))

# the protocol's command numbers the tests count
ID_WRITE = 13
ANGLE_OFFSET_ADJUST = 17
ANGLE_LIMIT_WRITE = 20
VIN_LIMIT_WRITE = 22
TEMP_MAX_LIMIT_WRITE = 24
OR_MOTOR_MODE_WRITE = 29
LOAD_OR_UNLOAD_WRITE = 31
LED_CTRL_WRITE = 33
LED_ERROR_WRITE = 35
WRITES = (1, 7, 11, 12, ID_WRITE, ANGLE_OFFSET_ADJUST, 18, ANGLE_LIMIT_WRITE, VIN_LIMIT_WRITE,
          TEMP_MAX_LIMIT_WRITE, OR_MOTOR_MODE_WRITE, LOAD_OR_UNLOAD_WRITE, LED_CTRL_WRITE,
          LED_ERROR_WRITE)


class Peer:
    """lxbus_peer.py serving servos `ids` at self.path (lx:self.path opens it)."""

    def __init__(self, tmp, ids, *args):
        self.path = str(tmp / "bus")
        self.ctl_path = str(tmp / "bus.ctl")
        self.proc = subprocess.Popen(
            [sys.executable, PEER, "--link", self.path, "--ids", ids, "--control",
             self.ctl_path, "--watch-stdin", *args],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        ready, _, _ = select.select([self.proc.stdout], [], [], test_s(30))
        line = self.proc.stdout.readline().decode().strip() if ready else ""
        if line != "ready " + self.path:
            self.proc.kill()
            err = self.proc.communicate()[1].decode(errors="replace")
            raise AssertionError("the peer did not start: %r %s" % (line, err))

    @property
    def port(self):
        return "lx:" + self.path

    def ctl(self, command):
        """The peer's answer to a control command, without its "ok"."""
        with socket.socket(socket.AF_UNIX) as s:
            s.settimeout(test_s(30))
            s.connect(self.ctl_path)
            s.sendall((command + "\n").encode())
            answer = s.makefile().readline().strip()
        assert answer.startswith("ok"), "%s: %s" % (command, answer)
        return answer[3:]

    def count(self, cmd):
        """How many frames of command cmd the bus received."""
        return int(self.ctl("count %d" % cmd))

    def writes(self):
        """How many frames that write anything the bus received."""
        return sum(self.count(c) for c in WRITES)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=test_s(30))
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        for f in (self.proc.stdin, self.proc.stdout, self.proc.stderr):
            f.close()


@pytest.fixture
def lx_peer(tmp_path):
    """A function starting the stand-in bus with servos ids ("1,2,3"), and
    the peer's options (stopped at the end)."""
    if not os.path.exists(PEER):
        pytest.skip("the stand-in bus (tests/lxbus/lxbus_peer.py) is not here: set "
                    "LSC_LXBUS_PEER")
    peers = []

    def start(ids, *args):
        d = tmp_path / ("peer%d" % len(peers))
        d.mkdir()
        p = Peer(d, ids, *args)
        peers.append(p)
        return p
    yield start
    for p in peers:
        p.stop()
