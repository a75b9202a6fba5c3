"""The hand (docs/kinematics.md): Arm.forward and Arm.inverse, and
Controller.where and Controller.reach on the built-in virtual controller
"sim", with the xArm's figures; lsc.Unreachable carrying the distance or the
joint."""
import math

import pytest

import lsc
from conftest import XARM_PROFILE

XARM = XARM_PROFILE
CHAIN = ("base", "shoulder", "elbow", "wrist", "wrist-rotate")


def fk(q):
    """The chain in the plane of the base, written out here (independently of
    the library): (x, y, z, pitch)."""
    b, s, e, w = (math.radians(v) for v in q[:4])
    a1, a2, a3 = s, s + e, s + e + w
    r = 98.8 * math.sin(a1) + 94.7 * math.sin(a2) + 158.8 * math.sin(a3)
    z = 64.7 + 98.8 * math.cos(a1) + 94.7 * math.cos(a2) + 158.8 * math.cos(a3)
    return r * math.cos(b), r * math.sin(b), z, 90 - math.degrees(a3)


@pytest.fixture
def arm():
    return lsc.Arm.parse(XARM, "xarm.conf")


def test_forward(arm):
    for q in ([0, 0, 0, 0, 0], [30, 20, 40, -30, 10], [-100, -60, 90, 45, -90]):
        p = arm.forward(q)
        x, y, z, pitch = fk(q)
        assert abs(p.x_mm - x) < 0.01 and abs(p.y_mm - y) < 0.01 and abs(p.z_mm - z) < 0.01
        assert abs((p.pitch_deg - pitch + 180) % 360 - 180) < 0.001
        assert list(p.angles) == list(CHAIN)
    p = arm.forward({"shoulder": 90})
    assert abs(p.x_mm - 352.3) < 0.01 and abs(p.z_mm - 64.7) < 0.01 and abs(p.pitch_deg) < 1e-3
    for bad in ([0, 0, 0], {"hand": 3}, [0, 0, 0, 0, float("nan")], [0, 0, 0, 0, "1"],
                [0, 0, 0, 0, 5000]):
        with pytest.raises(lsc.InvalidArgument):
            arm.forward(bad)


def test_inverse(arm):
    q = [20, 30, 40, 20, 0]
    x, y, z, pitch = fk(q)
    got = arm.inverse((x, y, z), pitch=pitch, near=q)
    assert all(abs(got[n] - v) < 0.01 for n, v in zip(CHAIN, q))
    # the other elbow, near it
    other = arm.inverse((x, y, z), pitch=pitch, near={"elbow": -40, "shoulder": 60})
    assert abs(other["elbow"] + 40) < 0.01
    # the pitch chosen, the roll given
    got = arm.inverse((200, 0, 100), roll=30)
    assert got["wrist-rotate"] == pytest.approx(30)
    p = arm.forward(got)
    assert abs(p.x_mm - 200) < 0.01 and abs(p.z_mm - 100) < 0.01


def test_unreachable(arm):
    with pytest.raises(lsc.Unreachable) as e:
        arm.inverse((0, 0, 600), pitch=90)
    assert e.value.by_mm == pytest.approx(183.0) and e.value.joint is None
    assert isinstance(e.value, lsc.InvalidArgument) and e.value.code == -1
    with pytest.raises(lsc.Unreachable) as e:
        arm.inverse((-250, 0, 64.7), pitch=0)
    assert e.value.joint == "base" and e.value.high and e.value.angle_deg == pytest.approx(180)
    assert e.value.by_mm is None
    assert "beyond its upper limit 115.00 degrees" in str(e.value)
    with pytest.raises(lsc.InvalidArgument):
        arm.inverse((0, 0))
    with pytest.raises(lsc.InvalidArgument):
        arm.inverse((0, 0, float("inf")))
    with pytest.raises(lsc.InvalidArgument):
        arm.inverse((1e9, 0, 0))


def test_no_geometry():
    plain = lsc.Arm.parse("base 6 bus\n")
    with pytest.raises(lsc.InvalidArgument, match="states no geometry"):
        plain.forward([0, 0, 0, 0, 0])
    with lsc.open("sim") as c:
        c.arm = plain
        with pytest.raises(lsc.InvalidArgument, match="states no geometry"):
            c.where()


def test_where_and_reach(arm):
    with lsc.open("sim", arm=arm) as c:
        c.move({n: "0deg" for n in CHAIN}, time_ms=0, wait=True)
        p = c.where()
        assert (round(p.x_mm, 1), round(p.z_mm, 1), round(p.pitch_deg, 1)) == (0.0, 417.0, 90.0)
        r = c.reach((200, 0, 100), pitch=-45, wait=True, tolerance=0)
        assert r.waypoints == 1 and r.time_ms == 1000 and r.pitch_deg == -45
        p = c.where()
        assert math.dist((p.x_mm, p.y_mm, p.z_mm), (200, 0, 100)) < 2
        x, y, z, pitch = fk([p.angles[n] for n in CHAIN])
        assert math.dist((p.x_mm, p.y_mm, p.z_mm), (x, y, z)) < 0.01
        r = c.reach((150, 150, 80), line=True, speed=60, wait=True)
        assert r.waypoints > 5
        r = c.reach((150, 100, 80), line=True, step_mm=20, time_ms=500)
        assert r.waypoints == 3 and r.time_ms == 500
        with pytest.raises(lsc.Unreachable) as e:
            c.reach((0, 0, 600))
        assert e.value.by_mm == pytest.approx(183.0)
        assert "out of reach by 183.0 mm; nothing was sent" in str(e.value)
        with pytest.raises(lsc.Unreachable) as e:
            c.reach((200, 0, 100), pitch=-45, roll=-120)
        assert e.value.joint == "wrist-rotate" and not e.value.high
        for kw in ({"time_ms": 10, "speed": 5}, {"time_ms": 0}, {"speed": -1},
                   {"step_mm": 5}, {"line": True, "step_mm": 0}, {"tolerance": -1}):
            with pytest.raises(lsc.InvalidArgument):
                c.reach((200, 0, 100), **kw)
    with lsc.open("sim") as c:
        with pytest.raises(lsc.InvalidArgument, match="no arm profile"):
            c.reach((200, 0, 100))


def test_reach_with_a_joint_held(arm, lsc_sim):
    """reach(wait=True) as move(wait=True): a joint held short of its target
    (lsc-sim --block: an obstacle) ends the wait, listed by name; strict=True
    raises lsc.Stalled."""
    sim = lsc_sim("--fast", "--block", "4:600")
    with lsc.open(sim.path, arm=arm) as c:
        rest = {n: 0.0 for n in CHAIN}
        c.move(rest, time_ms=0, wait=True)
        r = c.reach((200, 0, 100), pitch=-45, time_ms=500, wait=True)
        assert not r and r.reads and (r.waypoints, r.time_ms) == (1, 500)
        assert r.stopped == [lsc.StoppedServo("elbow", 4, 600, 729, 129)]
        assert r.message == "servo 4 stopped at 600, 129 short of its target 729"
        c.move(rest, time_ms=0, wait=True)
        with pytest.raises(lsc.Stalled) as e:
            c.reach((200, 0, 100), pitch=-45, time_ms=500, wait=True, strict=True)
        assert isinstance(e.value, lsc.Timeout)
        assert e.value.stopped == [lsc.StoppedServo("elbow", 4, 600, 729, 129)]
        assert str(e.value) == "servo 4 stopped at 600, 129 short of its target 729"
        # not held (the elbow to 536): strict is no error; no wait: nothing listed
        c.move(rest, time_ms=0, wait=True)
        r = c.reach((100, 50, 280), pitch=10, time_ms=100, wait=True, strict=True)
        assert r and r.stopped == [] and r.message == "" and r.reads
        r = c.reach((200, 0, 100), pitch=-45, time_ms=100)
        assert r and r.stopped == []
