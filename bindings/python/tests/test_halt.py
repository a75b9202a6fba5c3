"""halt(), hold(), id lists in one string ("all", "1-6") and a group that
never starts (lsc.NeverStarted): on "sim" (virtual clock) and against
lsc-sim on a pseudo-terminal (real time)."""
import time

import pytest

import lsc
from conftest import test_s

XARM_LIKE = "gripper 1 bus limits=0..700\nbase 6 bus\n"


def test_halt_during_a_move_on_sim():
    with lsc.open("sim") as c:
        c.move({1: 2500}, time_ms=6000)
        c.poll(3)
        assert c.halt() == ""
        first = c.read(1)[1]
        c.poll(0.6)
        assert c.read(1)[1] == first
        assert 1500 < first < 2500


def test_halt_during_a_looping_group_on_sim():
    with lsc.open("sim") as c:
        c.run(8, times=0)
        c.poll(1.5)
        assert c.notification(0).kind == "action_group_run"
        c.halt()
        assert c.notification(0).kind == "action_group_stop"
        before = c.read([1, 2, 3])
        c.poll(3)
        assert c.read([1, 2, 3]) == before


def test_hold_beyond_a_limit(tmp_path):
    path = tmp_path / "arm.conf"
    path.write_text(XARM_LIKE)
    with lsc.open("sim", arm=str(path)) as c:
        c.send(3, bytes([1, 0, 0, 1, 0x84, 0x03]))  # servo 1 to 900, "by hand"
        c.unload("gripper")
        res = c.hold()
        assert not res
        assert res.held == {1: 900, 6: 500}
        assert res.beyond == [1]
        assert "joint gripper (servo 1)" in res.message
        res = c.hold(["base", "gripper"])
        assert res.beyond == ["gripper"]
        assert res.held == {"base": 500, "gripper": 900}
        with pytest.raises(lsc.InvalidArgument):
            c.move({"gripper": 950}, 100)
        assert "joint gripper (servo 1)" in c.halt()
        assert c.hold("base") and c.hold("base").message == ""


def test_id_lists():
    with lsc.open("sim") as c:
        assert c.read("1-3") == {1: 1500, 2: 1500, 3: 1500}
        assert list(c.read(["1,3-4", 7])) == [1, 3, 4, 7]
        assert len(c.read("all")) == 32  # sim: every id of a serial board
        c.unload("all")
        c.unload("1-6")
        assert len(c.hold("1-6").held) == 6
        with pytest.raises(lsc.InvalidArgument, match="the range 5-3 is empty"):
            c.unload("5-3")
        with pytest.raises(lsc.InvalidArgument, match="servo 2 appears twice"):
            c.read(["1-3", 2])
        with pytest.raises(lsc.InvalidArgument):
            c.hold([])
        a = c.record("1-3", every_ms=100, count=1)
        assert a.ids == (1, 2, 3)


def test_never_started_on_sim():
    with lsc.open("sim") as c:
        with pytest.raises(lsc.NeverStarted, match="has no group 9"):
            c.run(9, wait=True)


def test_never_started_on_a_serial_port(lsc_sim, groups_file):
    s = lsc_sim("--fast", "--groups", groups_file)
    with lsc.open(s.path) as c:
        start = time.monotonic()
        with pytest.raises(lsc.NeverStarted, match="group 9 never started") as e:
            c.run(9, wait=True, timeout=test_s(60))
        assert isinstance(e.value, lsc.Timeout)
        assert time.monotonic() - start < test_s(30)
        assert c.run(1, wait=True, timeout=test_s(30)).kind == "action_group_complete"
        # halt on a real link: the servo stops between start and target
        c.move({1: 2500}, time_ms=6000)
        time.sleep(0.3)
        assert c.halt() == ""
        first = c.read(1)[1]
        time.sleep(0.6)
        assert c.read(1)[1] == first
        assert 1500 < first < 2500


def test_xarm_drop_in_halts():
    from lsc.compat import xarm
    with xarm.Controller("sim") as arm:
        arm.setPosition(1, 900, duration=6000)
        arm.lsc.poll(3)
        assert arm.halt() == ""
        first = arm.getPosition(1)
        arm.lsc.poll(1)
        assert arm.getPosition(1) == first
        assert 900 < first < 1500  # from 1500, where "sim" starts a servo
