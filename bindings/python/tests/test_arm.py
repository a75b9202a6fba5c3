"""lsc.Arm: profiles read by the library's parser (docs/arm-profile.md)."""
import os

import pytest

import lsc
from conftest import DATA

XARM = os.path.join(DATA, "xarm.conf")


def test_load():
    arm = lsc.Arm(XARM)
    assert arm.path == XARM
    assert len(arm) == 3
    assert arm.names() == ["gripper", "wrist", "base"]
    assert "gripper" in repr(arm)
    g, w, b = arm.joints
    assert g == lsc.Joint("gripper", 1, 1, 0, 1000, 240.0, 500, -120.0, 48.0)
    assert (w.id, w.direction, w.min_deg, w.max_deg) == (3, -1, -90.0, 90.0)
    assert [j.name for j in arm] == arm.names()
    assert arm.joint("base") == b
    assert arm.joint(6) == b


def test_target_and_degrees():
    arm = lsc.Arm(XARM)
    assert arm.target("base", "30deg") == (6, 625)
    assert arm.target("base", "-30deg") == (6, 375)
    assert arm.target("wrist", "30deg") == (3, 375)  # dir=-1
    assert arm.target("gripper", 700) == (1, 700)
    assert arm.target(9, 2000) == (9, 2000)  # a servo on no joint: positions only
    assert arm.degrees("base", 625) == 30.0
    assert arm.degrees(6, 500) == 0.0
    assert arm.degrees(9, 500) is None
    assert arm.servo_id("base") == 6
    assert arm.servo_id(200) == 200


def test_limits_refused():
    arm = lsc.Arm(XARM)
    with pytest.raises(lsc.InvalidArgument, match="gripper"):
        arm.target("gripper", 701)
    with pytest.raises(lsc.InvalidArgument, match="base"):
        arm.target("base", "116deg")
    with pytest.raises(lsc.InvalidArgument):
        arm.target("nose", 500)
    with pytest.raises(lsc.InvalidArgument, match="base"):
        arm.target("base", 116.0)  # a float is degrees: beyond the limits
    assert arm.target("base", 30.0) == arm.target("base", "30deg")
    assert arm.target("base", -15.504) == arm.target("base", "-15.50deg")
    with pytest.raises(lsc.InvalidArgument):
        arm.joint("nose")
    with pytest.raises(lsc.InvalidArgument):
        arm.servo_id("nose")


def test_parse_errors_name_the_place():
    with pytest.raises(lsc.InvalidArgument, match=r"^my.conf:2:"):
        lsc.Arm.parse("base 6 bus\nbad line here\n", "my.conf")
    arm = lsc.Arm.parse("base 6 bus limits=-90deg..90deg\n")
    assert arm.path is None
    assert arm.names() == ["base"]


def test_file_errors(tmp_path):
    with pytest.raises(lsc.Error) as e:
        lsc.Arm(tmp_path / "missing.conf")
    assert "missing.conf" in str(e.value)
    assert not isinstance(e.value, lsc.LinkError)
    with pytest.raises(lsc.InvalidArgument):
        lsc.Arm(tmp_path)  # a directory


def test_shared_between_controllers():
    arm = lsc.Arm(XARM)
    with lsc.open("sim", arm=arm) as a, lsc.open("sim", arm=arm) as b:
        a.move({"base": "10deg"}, time_ms=0, wait=True)
        b.move({"base": "20deg"}, time_ms=0, wait=True)
        assert a.read(["base"], degrees=True) == {"base": 10.08}
        assert b.read(["base"], degrees=True) == {"base": 19.92}
    del arm  # the controllers keep their own copy


def test_controller_keeps_working_after_the_arm_is_gone():
    c = lsc.open("sim", arm=lsc.Arm(XARM))
    import gc
    gc.collect()
    c.move({"gripper": 600}, time_ms=0, wait=True)
    assert c.read(["gripper"]) == {"gripper": 600}
    c.close()


def test_environment_as_lscctl_reads_it(monkeypatch):
    # $LSC_ARM: lsc.open(name) takes joint names and degrees, as lscctl does
    monkeypatch.setenv("LSC_ARM", XARM)
    with lsc.open("sim") as c:
        assert c.arm is not None and c.arm.path == XARM
        c.move({"base": "30deg"}, time_ms=100, wait=True)
        assert c.read(["base"], degrees=True) == {"base": 30.0}
    with lsc.open("sim", arm=lsc.Arm(XARM)) as c:  # given: it wins
        assert c.arm.path == XARM
    monkeypatch.setenv("LSC_ARM", "")  # empty: unset
    with lsc.open("sim") as c:
        assert c.arm is None
    monkeypatch.setenv("LSC_ARM", os.path.join(DATA, "none.conf"))
    with pytest.raises(lsc.Error):
        lsc.open("sim")
    monkeypatch.delenv("LSC_ARM")
    # $LSC_HID_ID: checked as lscctl checks it
    monkeypatch.setenv("LSC_HID_ID", "usb")
    with pytest.raises(lsc.InvalidArgument, match=r"\$LSC_HID_ID needs a USB VID:PID"):
        lsc.open("sim")
    monkeypatch.setenv("LSC_HID_ID", "046d:c52b")
    lsc.open("sim").close()


def test_profiles_by_name(tmp_path, monkeypatch):
    """A name (no '/', no .conf) is looked up as lscctl --arm does
    (lsc_arm_open): $XDG_CONFIG_HOME/lsc/arms first, then the installed
    profiles ($LSC_ARMS_DIR here); from any working directory."""
    installed = tmp_path / "installed"
    mine = tmp_path / "config" / "lsc" / "arms"
    installed.mkdir()
    mine.mkdir(parents=True)
    (installed / "xarm.conf").write_bytes(open(XARM, "rb").read())
    monkeypatch.setenv("LSC_ARMS_DIR", str(installed))
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.chdir(tmp_path)
    assert lsc.Arm("xarm").names() == ["gripper", "wrist", "base"]
    with lsc.open("sim", arm="xarm") as c:  # lsc.open(..., arm=NAME)
        c.move({"base": "30deg"}, time_ms=0, wait=True)
        assert c.read(["base"], degrees=True) == {"base": 30.0}
    monkeypatch.setenv("LSC_ARM", "xarm")  # $LSC_ARM may name one too
    with lsc.open("sim") as c:
        assert c.arm.names() == ["gripper", "wrist", "base"]
    monkeypatch.delenv("LSC_ARM")
    # the user's own comes first
    (mine / "xarm.conf").write_text("hand 3 bus\n")
    assert lsc.Arm("xarm").names() == ["hand"]
    with lsc.open("sim", arm="xarm") as c:
        assert c.arm.names() == ["hand"]
    # a path stays a path
    with pytest.raises(lsc.Error) as e:
        lsc.Arm("xarm.conf")
    assert "cannot read the arm profile xarm.conf" in str(e.value)
    # found nowhere: where it looked
    with pytest.raises(lsc.Error) as e:
        lsc.Arm("xram")
    assert str(e.value) == ("no arm profile named xram: looked for %s/xram.conf, %s/xram.conf "
                            "(a file in this directory: ./xram)" % (mine, installed))
    assert not isinstance(e.value, lsc.LinkError)


def test_an_angle_is_taken_as_given(tmp_path):
    # a float reaches the library as a number (lsc_arm_target_deg), not as
    # text with two decimals: 30.004 degrees is beyond a limit of 30.00
    path = tmp_path / "a.conf"
    path.write_text("base 6 pwm limits=-30deg..30deg\n")
    arm = lsc.Arm(str(path))
    assert arm.target("base", 30.0) == (6, 1833)
    with pytest.raises(lsc.InvalidArgument, match=r"30\.004deg is outside the limits of joint "
                                                  r"base \(servo 6\): -30\.00deg\.\.30\.00deg"):
        arm.target("base", 30.004)
    # half a position is 0.045 degrees: 0.0449 and 0.0451 fall either side of it
    assert arm.target("base", 0.0449) == (6, 1500)
    assert arm.target("base", 0.0451) == (6, 1501)
    assert arm.target(6, -0.0451) == (6, 1499)
    assert arm.target("base", "30deg") == (6, 1833)  # text stays text
    assert arm.degrees("base", 1501) == 0.09
