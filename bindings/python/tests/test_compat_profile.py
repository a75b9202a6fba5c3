"""The xarm drop-in (lsc.compat.xarm) with an arm profile for what lsc adds
through arm.lsc (reach, where, joint names): given as arm=, or by $LSC_ARM;
and a com_port that is not text refused as the package refused it."""
import os

import pytest

import lsc
from lsc.compat import xarm

from conftest import XARM_PROFILE, DATA, child_env, run_python

XARM = XARM_PROFILE


def test_profile_as_an_argument(tmp_path):
    conf = tmp_path / "xarm.conf"
    conf.write_text(XARM)
    for given in (lsc.Arm.parse(XARM, "xarm.conf"), str(conf), conf):
        with xarm.Controller("sim", arm=given) as arm:
            assert arm.lsc.arm is not None and "base" in arm.lsc.arm.names()
            r = arm.lsc.reach((200, 0, 100), pitch=-45, wait=True, tolerance=0)
            assert r.waypoints == 1
            p = arm.lsc.where()
            assert abs(p.x_mm - 200) < 1 and abs(p.z_mm - 100) < 1
            # the package's own calls as without a profile
            arm.setPosition(6, 700, duration=100, wait=True)
            assert arm.getPosition(6) == 700


def test_without_a_profile_reach_says_so():
    with xarm.Controller("sim") as arm:
        if os.environ.get("LSC_ARM"):
            pytest.skip("$LSC_ARM is set here")
        with pytest.raises(lsc.InvalidArgument, match="no arm profile"):
            arm.lsc.reach((200, 0, 100))


def test_profile_from_the_environment(tmp_path):
    conf = tmp_path / "xarm.conf"
    conf.write_text(XARM)
    r = run_python("from lsc.compat import xarm\n"
                   "arm = xarm.Controller('sim')\n"
                   "print(arm.lsc.reach((200, 0, 100), pitch=-45).waypoints)\n",
                   env=child_env(LSC_ARM=str(conf)))
    assert r.returncode == 0, r.stderr
    assert r.stdout == "1\n"


def test_com_port_not_text():
    """The package refused a port that is not 'COM...' or 'USB...' with
    ValueError (and its code, calling com_port.startswith, with
    AttributeError for one that is not text): both catch it, and it is an
    lsc.InvalidArgument."""
    for bad in (None, 5, b"USB", ["USB"]):
        with pytest.raises(ValueError) as e:
            xarm.Controller(bad)
        assert isinstance(e.value, AttributeError)
        assert isinstance(e.value, lsc.InvalidArgument)
        assert isinstance(e.value, xarm.WrongPortType)
        assert "com_port parameter incorrect" in str(e.value)


def test_com_port_as_a_path(lsc_sim):
    import pathlib
    s = lsc_sim("--fast")
    with xarm.Controller(pathlib.Path(s.path)) as arm:
        assert arm.getBatteryVoltage() == 7.5


def test_shipped_profile_file_works():
    """tests/data/xarm.conf (a profile file on disk) as the drop-in's arm."""
    with xarm.Controller("sim", arm=os.path.join(DATA, "xarm.conf")) as arm:
        assert arm.lsc.arm.joint("base").id == 6
