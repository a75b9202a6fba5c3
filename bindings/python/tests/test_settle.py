"""move(wait=True) understands a servo held short of its target (a gripper
closed on an object): the wait ends when it stops, with a MoveResult saying
where; strict=True raises lsc.Stalled. The servo is held by lsc-sim --block
(the virtual controller's block, as an object in a gripper's way)."""
import time

import pytest

import lsc
from conftest import test_s


def test_held_servo_ends_the_wait(lsc_sim):
    s = lsc_sim("--fast", "--block", "1:600")
    with lsc.open(s.path) as c:
        r = c.move({1: 700, 2: 1000}, time_ms=500, wait=True)
        assert isinstance(r, lsc.MoveResult) and not r and r.reads
        assert r.stopped == [lsc.StoppedServo(1, 1, 600, 700, 100)]
        assert r.message == "servo 1 stopped at 600, 100 short of its target 700"
        assert c.read([1, 2]) == {1: 600, 2: 1000}
        ok = c.move({1: 300}, time_ms=100, wait=True)
        assert ok and ok.stopped == [] and ok.message == ""
        assert c.move({1: 500}, time_ms=0) is None


def test_strict_raises_stalled(lsc_sim):
    s = lsc_sim("--fast", "--block", "2:400:below")
    with lsc.open(s.path) as c:
        with pytest.raises(lsc.Stalled) as e:
            c.move({2: 300}, time_ms=100, wait=True, strict=True)
        assert isinstance(e.value, lsc.Timeout)
        assert str(e.value) == "servo 2 stopped at 400, 100 short of its target 300"
        assert e.value.stopped == [lsc.StoppedServo(2, 2, 400, 300, 100)]


def test_on_a_pty(lsc_sim):
    s = lsc_sim("--fast", "--block", "1:600")
    with lsc.open(s.path) as c:
        t = time.monotonic()
        r = c.move({1: 700}, time_ms=500, wait=True)
        assert time.monotonic() - t < test_s(3)
        assert r.stopped == [lsc.StoppedServo(1, 1, 600, 700, 100)]


def test_settle_on_its_own(lsc_sim):
    """settle(): the wait of move(wait=True) for a move sent otherwise."""
    s = lsc_sim("--fast", "--block", "1:600")
    with lsc.open(s.path) as c:
        c.send(3, bytes([2, 0xF4, 0x01, 1, 0xBC, 0x02, 2, 0x20, 0x03]))  # 1:700 2:800, 500 ms
        r = c.settle({1: 700, 2: 800}, time_ms=500)
        assert r.stopped == [lsc.StoppedServo(1, 1, 600, 700, 100)]
        assert c.settle({2: 800})
        with pytest.raises(lsc.InvalidArgument):
            c.settle({})
        with pytest.raises(lsc.Stalled):
            c.settle({1: 700}, strict=True)
