"""Action files of several groups, arm-to-arm conversion, moves back to the
angles read, the virtual controller standing in for an arm, and what only lscd
does (status, a lease)."""
import os
import subprocess

import pytest

import lsc
from conftest import DATA, program, test_s, wait_until

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
# the shipped profiles: the source tree's, or $LSC_TEST_ARMS (the packages'
# test runs the tests from a copy outside the tree)
ARMS = os.environ.get("LSC_TEST_ARMS") or os.path.join(TOP, "examples", "arms")
XARM = os.path.join(ARMS, "xarm.conf")
LEARM = os.path.join(ARMS, "learm.conf")
GROUPS = os.path.join(DATA, "groups.txt")


def test_load_one_group_of_several():
    with pytest.raises(lsc.InvalidArgument, match="read one of them by its number"):
        lsc.Action.load(GROUPS)
    a = lsc.Action.load(GROUPS, group=1)
    b = lsc.Action.load(GROUPS, group=3)
    assert len(a) > 0 and len(b) > 0 and a != b
    with pytest.raises(lsc.InvalidArgument, match="no group 99"):
        lsc.Action.load(GROUPS, group=99)
    for bad in (-1, 255, True, "1", 1.0):
        with pytest.raises(lsc.InvalidArgument, match="a group is an int"):
            lsc.Action.load(GROUPS, group=bad)


def test_load_group_of_a_one_group_file(tmp_path):
    path = tmp_path / "7-wave.csv"
    lsc.Action([1], [(0, (500,)), (100, (700,))]).save(path)
    assert lsc.Action.load(path, group=7) == lsc.Action.load(path)
    with pytest.raises(lsc.InvalidArgument):
        lsc.Action.load(path, group=1)


def test_to_arm_as_lscctl_convert():
    # the LeArm's PWM middle (1500) is the xArm's bus-servo middle (500)
    a = lsc.Action([1, 2, 3, 4, 5, 6], [(200, (1500, 1500, 1500, 1500, 1500, 1500))])
    b = a.to_arm(LEARM, lsc.Arm(XARM))
    assert b.ids == a.ids
    assert b.keyframes[0].time_ms == 200
    # the same answer as the C library's convert gives lscctl (joint by joint)
    x = lsc.Arm(XARM)
    le = lsc.Arm(LEARM)
    for sid, pos in zip(b.ids, b.keyframes[0].positions):
        assert x.degrees(sid, pos) == pytest.approx(le.degrees(sid, 1500), abs=0.25)
    # a pose outside the target's limits: refused, naming keyframe and joint
    wide = lsc.Action([6], [(100, (500,)), (100, (979,))])  # the xArm's base at 115 degrees
    with pytest.raises(lsc.InvalidArgument, match="keyframe 2") as e:
        wide.to_arm(XARM, LEARM)  # the LeArm's base stops at 85
    assert "base" in str(e.value)


def test_move_takes_what_read_degrees_gives():
    with lsc.open("sim", arm=XARM) as c:
        c.move({"base": "30deg", "elbow": -20.0, "gripper": 700}, time_ms=0)
        pose = c.read(["base", "elbow", "gripper"], degrees=True)
        assert pose == {"base": 30.0, "elbow": -19.92, "gripper": 48.0}  # the nearest position's
        c.move({"base": 0.0, "elbow": 0.0, "gripper": 0.0}, time_ms=0)
        c.move(pose, time_ms=0)
        assert c.read(["base", "elbow", "gripper"], degrees=True) == pose
        assert c.read(["base", "gripper"]) == {"base": 625, "gripper": 700}
        with pytest.raises(lsc.InvalidArgument, match="None is no target"):
            c.move({"base": None}, time_ms=0)
        with pytest.raises(lsc.InvalidArgument, match="finite"):
            c.move({"base": float("nan")}, time_ms=0)
        with pytest.raises(lsc.InvalidArgument, match="base"):
            c.move({"base": 200.0}, time_ms=0)  # beyond its limits: nothing sent
    with lsc.open("sim") as c:
        with pytest.raises(lsc.InvalidArgument, match="needs an arm profile"):
            c.move({1: 30.0}, time_ms=0)


def test_sim_stands_in_for_the_arm():
    with lsc.open("sim", arm=XARM) as c:
        assert c.read([1, 2, 3, 4, 5, 6]) == {i: 500 for i in range(1, 7)}
        assert c.read([7]) == {7: 1500}  # on no joint
        c.arm = None
        c.send(3, bytes([1, 0, 0, 6, 0xD0, 0x07]))  # servo 6 to 2000: a bus servo stops at 1000
        assert c.read([6]) == {6: 1000}
    with lsc.open("sim", arm=LEARM) as c:
        arm = c.arm
        assert c.read([6]) == {6: 1500}
        assert c.read(["shoulder"])["shoulder"] == arm.joint("shoulder").zero


def test_lsc_sim_arm(lsc_sim):
    s = lsc_sim("--fast", "--arm", XARM)
    with lsc.open(s.path) as c:
        assert c.read([1, 2, 3, 4, 5, 6]) == {i: 500 for i in range(1, 7)}


def test_status_and_lease_need_lscd(sim):
    with pytest.raises(lsc.InvalidArgument, match="does not go through lscd"):
        sim.status()
    with pytest.raises(lsc.InvalidArgument, match="does not go through lscd"):
        with sim.lease(1):
            pass


@pytest.fixture
def lscd(tmp_path):
    """lscd serving the built-in virtual controller on a socket in tmp_path."""
    exe = program("LSCD", "lscd")
    if not exe:
        pytest.skip("lscd not found (set LSCD, or install the lscd package)")
    sock = str(tmp_path / "sim.sock")
    proc = subprocess.Popen([exe, "--port", "sim", "--socket", sock],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            env=dict(os.environ, LSC_LSCD_DIR=str(tmp_path)))

    def answers():
        try:
            lsc.open("lscd:" + sock).close()
            return True
        except lsc.Error:
            return proc.poll() is not None
    wait_until(answers, 30, "lscd answering on " + sock)
    assert proc.poll() is None, proc.stderr.read().decode()
    yield "lscd:" + sock
    proc.terminate()
    proc.wait(timeout=test_s(30))
    proc.stderr.close()


def test_status_through_lscd(lscd):
    with lsc.open(lscd) as c:
        assert c.kind == "lscd"
        st = c.status()
    assert st["port"] == "sim"
    assert isinstance(st["client"], list) and len(st["client"]) >= 1
    assert all(isinstance(k, str) for k in st)


def test_lease_through_lscd(lscd):
    with lsc.open(lscd) as a, lsc.open(lscd) as b:  # (wait=0: Busy at once, no timeout waited)
        with a.lease(5) as granted:
            assert 0 < granted <= 5
            assert a.battery() == 7500
            with pytest.raises(lsc.Busy):
                with b.lease(5):
                    pass
            assert "lease" in "".join(str(k) for k in a.status())
        with b.lease(None) as granted:  # lscd's longest
            assert granted > 0
            assert b.battery() == 7500
        with pytest.raises(lsc.InvalidArgument, match="more than 0"):
            with a.lease(0):
                pass
