"""Results print rounded (print(), str()) to what the arm can tell apart:
0.01 mm and 0.01 degree, never "-0.00" or 4.3e-06; repr() keeps every digit
(and the fields' names)."""
import re

import lsc
from conftest import XARM_PROFILE

XARM = XARM_PROFILE


def test_pose_prints_rounded():
    arm = lsc.Arm.parse(XARM, "xarm.conf")
    p = arm.forward([0, 30, 40, 20, 0])
    assert str(p) == ("Pose(x=297.19 y=0.00 z=182.65 mm, pitch=0.00 deg; base=0.00 "
                      "shoulder=30.00 elbow=40.00 wrist=20.00 wrist-rotate=0.00 deg)")
    # repr: the NamedTuple's, every digit
    assert repr(p).startswith("Pose(x_mm=297.18")
    assert "pitch_deg=%r" % p.pitch_deg in repr(p)
    # the angles are those given (not their float32 copies)
    assert arm.forward([0, 3.88, 0, 0, 0]).angles["shoulder"] == 3.88
    # float32 noise (4.3e-06 from a solve) prints as 0.00, and is kept in the value
    n = lsc.Pose(4.325710960983997e-06, -1e-7, 182.654, 2e-6, {"base": 1e-9})
    assert str(n) == "Pose(x=0.00 y=0.00 z=182.65 mm, pitch=0.00 deg; base=0.00 deg)"
    assert n.x_mm == 4.325710960983997e-06
    # never -0.00
    q = arm.forward([-0.001, 0, 0, 0, 0])
    assert "-0.00" not in str(q) and "y=0.00" in str(q)


def test_where_and_reach_print_rounded():
    with lsc.open("sim", arm=lsc.Arm.parse(XARM, "xarm.conf")) as c:
        r = c.reach((200, 0, 100), pitch=-45, wait=True)
        assert str(r) == ("ReachResult(waypoints=1, time_ms=1000, pitch_deg=-45.0, stopped=[], "
                          "reads=True, message='')")
        p = c.where()
        # the joints' angles come from positions: whole hundredths of a degree
        assert all(round(v, 2) == v for v in p.angles.values()), p.angles
        assert re.fullmatch(r"Pose\(x=200\.\d\d y=0\.00 z=100\.\d\d mm, pitch=-44\.\d\d deg; "
                            r"base=0\.00 shoulder=3\.84 elbow=54\.96 wrist=76\.08 "
                            r"wrist-rotate=0\.00 deg\)", str(p)), str(p)
        assert "e-" not in str(p)
