"""Results print rounded (print(), str()) to what the arm can tell apart:
0.01 mm and 0.01 degree, never "-0.00" or 4.3e-06; repr() keeps every digit
(and the fields' names)."""
import re

import lsc

XARM = """
gripper 1 bus limits=0..700
wrist-rotate 2 bus limits=-115deg..115deg
wrist 3 bus limits=-115deg..115deg
elbow 4 bus limits=-115deg..115deg
shoulder 5 bus limits=-115deg..115deg
base 6 bus limits=-115deg..115deg
chain: base shoulder elbow wrist wrist-rotate gripper
links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm
"""


def test_pose_prints_rounded():
    arm = lsc.Arm.parse(XARM, "xarm.conf")
    p = arm.forward([0, 30, 40, 20, 0])
    assert abs(p.pitch_deg) < 1e-3 and p.pitch_deg != 0  # float32 noise, kept in the value
    assert str(p) == ("Pose(x=297.19 y=0.00 z=182.65 mm, pitch=0.00 deg; base=0.00 "
                      "shoulder=30.00 elbow=40.00 wrist=20.00 wrist-rotate=0.00 deg)")
    # repr: the NamedTuple's, every digit
    assert repr(p).startswith("Pose(x_mm=297.18")
    assert "pitch_deg=%r" % p.pitch_deg in repr(p)
    # the angles are those given (not their float32 copies)
    assert arm.forward([0, 3.88, 0, 0, 0]).angles["shoulder"] == 3.88
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
