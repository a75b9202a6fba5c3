"""Controller.move(..., speed=DEG_PER_S): the library's move at a speed
(lsc_device_move_speed, the call lscctl move --speed makes): the time of the
servo_move frame sent, the virtual controller's clock, the wait after it, and
what is refused before anything is sent."""
import pytest

import lsc

XARM_TEXT = """
gripper 1 bus limits=0..700
wrist-rotate 2 bus limits=-115deg..115deg
wrist 3 bus limits=-115deg..115deg
elbow 4 bus limits=-115deg..115deg
shoulder 5 bus limits=-115deg..115deg
base 6 bus limits=-115deg..115deg
"""


def xarm():
    return lsc.Arm.parse(XARM_TEXT, "xarm.conf")


def moves(frames):
    """The servo_move frames (command 3) among frames: [(time_ms, {id: position})]."""
    out = []
    for f in frames:
        if f[3] == 3:
            n = f[4]
            out.append((f[5] | f[6] << 8,
                        {f[7 + 3 * i]: f[8 + 3 * i] | f[9 + 3 * i] << 8 for i in range(n)}))
    return out


@pytest.fixture
def arm_sim():
    """"sim" standing in for the xArm (every joint at 0 degrees), frames sent in c.sent."""
    c = lsc.open("sim", arm=xarm())
    c.sent = []
    c.trace(lambda d, frame: c.sent.append(frame) if d == "tx" else None)
    yield c
    c.close()


def test_move_at_a_speed(arm_sim):
    c = arm_sim
    start = c.now_ms()
    r = c.move({"base": 30.0}, speed=60, wait=True)
    took = c.now_ms() - start
    assert r and r.reads  # a MoveResult: arrived
    # 30 degrees at 60 degrees a second: the move's frame says 500 ms, and
    # that much passed on the virtual controller's clock before it settled
    (time_ms, servos), = moves(c.sent)
    assert time_ms == 500 and servos == {6: 625}  # bus servo: 0.24 degree a position
    assert took >= 500
    assert c.read(["base"], degrees=True) == {"base": 30.0}
    # the joint that turns the most sets the time: base back 30, shoulder 45
    c.sent.clear()
    assert c.move({"base": 0.0, "shoulder": "45deg"}, speed=90) is None  # no wait: None
    (time_ms, servos), = moves(c.sent)
    assert time_ms == 502 and servos == {6: 500, 5: 688}  # 45deg: position 688, 45.12
    # positions (ints) are fine too: their joints' degrees
    c.poll(1)
    c.sent.clear()
    c.move({5: 500}, speed=45.12)
    assert moves(c.sent)[0][0] == 1000


def test_move_default_time(arm_sim):
    """Neither time_ms nor speed: 1000 ms, as lscctl move."""
    arm_sim.move({"base": 10.0})
    assert moves(arm_sim.sent)[0][0] == 1000


def test_move_speed_stopped_short(lsc_sim):
    """The base held at 600 on its way up (lsc-sim --block, as an obstacle)."""
    sim = lsc_sim("--fast", "--block", "6:600")
    with lsc.open(sim.path, arm=xarm()) as c:
        r = c.move({"base": 30.0}, speed=60, wait=True)
        assert not r and [(s.servo, s.position) for s in r.stopped] == [("base", 600)]
        c.move({"base": 0.0}, time_ms=0, wait=True)
        with pytest.raises(lsc.Stalled):
            c.move({"base": 30.0}, speed=60, wait=True, strict=True)


def test_move_speed_refused(arm_sim):
    c = arm_sim
    for bad in (0, -5, 0.001, 200000, float("nan"), float("inf"), 10**400):
        with pytest.raises(lsc.InvalidArgument) as e:
            c.move({"base": 30.0}, speed=bad)
        assert not isinstance(e.value, TypeError), bad
    for bad in ("60", True, b"60", [60]):
        with pytest.raises(lsc.InvalidArgument) as e:
            c.move({"base": 30.0}, speed=bad)
        assert isinstance(e.value, TypeError), bad
    # the library's message, as lscctl's
    with pytest.raises(lsc.InvalidArgument, match="a speed of 0 degrees a second: give "
                       "0.01..100000; nothing was sent"):
        c.move({"base": 30.0}, speed=0)
    with pytest.raises(lsc.InvalidArgument, match="give time_ms or speed, not both"):
        c.move({"base": 30.0}, time_ms=500, speed=60)
    # a servo on no joint: no degrees to turn (the library's message)
    with pytest.raises(lsc.InvalidArgument, match="servo 9 is no joint of the arm profile"):
        c.move({9: 500}, speed=60)
    # too slow for one frame's time
    with pytest.raises(lsc.InvalidArgument, match="raise the speed"):
        c.move({"base": 100.0}, speed=0.01)
    assert moves(c.sent) == []  # nothing was sent


def test_move_speed_needs_a_profile(sim):
    with pytest.raises(lsc.InvalidArgument, match="no joint of any arm profile"):
        sim.move({6: 625}, speed=60)


def test_move_speed_on_a_serial_port(lsc_sim):
    """Over a link (lsc-sim on a pseudo-terminal): the same frame; the wait
    polls in steps (Ctrl-C gets in) and ends when the servo is there."""
    s = lsc_sim("--fast")
    with lsc.open(s.path, arm=xarm()) as c:
        sent = []
        c.trace(lambda d, frame: sent.append(frame) if d == "tx" else None)
        c.move({"base": 0.0}, time_ms=0, wait=True)  # lsc-sim's servos start at 1500
        sent.clear()
        r = c.move({"base": -30.0}, speed=120, wait=True)
        assert r
        assert moves(sent)[0] == (250, {6: 375})
        assert c.read(["base"]) == {"base": 375}
