"""lsc.compat.xarm: scripts written for the PyPI xarm package (xarm_scripts/)
run after changing their one import line, against "sim" and lsc-sim on a
pty; its units and argument checks; the documented differences."""
import os
import re

import pytest

import lsc
from conftest import HERE, run_python
from lsc.compat import xarm

SCRIPTS = os.path.join(HERE, "xarm_scripts")


def converted(name, tmp_path):
    """The script with its `import xarm` changed to lsc's, as a user would."""
    with open(os.path.join(SCRIPTS, name)) as f:
        text = f.read()
    new, n = re.subn(r"^import xarm$", "from lsc.compat import xarm", text, flags=re.M)
    assert n == 1, "%s: one `import xarm` line" % name
    path = tmp_path / name
    path.write_text(new)
    return str(path)


def run_script(name, tmp_path, *args):
    r = run_python([converted(name, tmp_path), *args])
    assert r.returncode == 0, r.stderr
    return r.stdout


BATTERY = "Battery voltage in volts: 7.5\nServos: [1, 2, 3, 4, 5, 6]\n"

MOVES = """1: 300 2: 700 3: 45.00000000000001
servo 2: 300
servo 1: 500 0.00
servo 2: 460 -10.00
servo 3: 860 90.00
servo 4: 200 -75.00
servo 5: 860 90.00
done
"""


def test_servos_script(tmp_path):
    assert run_script("servos.py", tmp_path) == """servo ID: 1
servo position: 300
servo angle: -50.0
servo 3: 860 90.0
servo 3: 320 -45.0
servo 3: 1000 125.0
default: 500 0.0
"""


def test_scripts_on_sim(tmp_path):
    assert run_script("battery.py", tmp_path, "sim") == BATTERY
    assert run_script("moves.py", tmp_path, "sim") == MOVES


def test_scripts_on_a_pty(tmp_path, lsc_sim):
    s = lsc_sim("--fast")
    assert run_script("battery.py", tmp_path, s.path) == BATTERY
    assert run_script("moves.py", tmp_path, s.path) == MOVES


def reference_position(degrees):
    """The xarm package's mapping (bindings/python/README.md): rounded to 0.25 degree,
    -125..125 linearly onto 0..1000, truncated."""
    x = round(degrees * 4) / 4
    return int(1000 * ((x + 125.0) / 250.0))


def test_angle_mapping_matches_the_package():
    for q in range(-500, 501):
        for d in (q / 4, q / 4 + 0.1, q / 4 - 0.1):
            if -125.0 <= d <= 125.0:
                assert xarm.Servo(1, float(d)).position == reference_position(d), d
    assert xarm.Servo(1, 0.0).position == 500
    assert xarm.Servo(1, -125.0).position == 0
    assert xarm.Servo(1, 125.0).position == 1000
    assert xarm.Servo(1, 0.12).angle == 0.0
    assert xarm.Servo(1, 0.13).angle == 0.25
    assert xarm.Servo(1, 1).angle == -124.75


def test_refused_like_the_package():
    for bad in (lambda: xarm.Servo(1, 1001), lambda: xarm.Servo(1, -1),
                lambda: xarm.Servo(1, 125.5), lambda: xarm.Servo(1, "500")):
        with pytest.raises(ValueError):
            bad()
    with pytest.raises(ValueError, match="com_port|Windows"):
        xarm.Controller("COM5")
    with pytest.raises(ValueError):
        xarm.Controller("")
    arm = xarm.Controller("sim")
    sent = []
    arm.lsc.trace(lambda d, f: sent.append(f))
    for bad in (lambda: arm.setPosition(1), lambda: arm.setPosition(1, 1001),
                lambda: arm.setPosition(1, -126.0), lambda: arm.setPosition("1", 500),
                lambda: arm.setPosition([[1, 500], [2]]), lambda: arm.setPosition([[1, 500], 7]),
                lambda: arm.setPosition(1, 500, duration=70000),
                lambda: arm.setPosition([[1, 500], [1, 600]]),
                lambda: arm.getPosition("1"), lambda: arm.getPosition([1, 2]),
                lambda: arm.servoOff("all"), lambda: arm.listServos(0),
                lambda: arm.writeServoId(0)):
        with pytest.raises(ValueError):
            bad()
    assert sent == [], "refused calls sent %r" % sent
    arm.close()


def test_errors_raise_where_the_package_returned(lsc_sim):
    s = lsc_sim("--fast", "--drop-replies", "5")
    arm = xarm.Controller(s.path, timeout_ms=100)
    with pytest.raises(lsc.Timeout):
        arm.getBatteryVoltage()  # the package: 0.0 after 5 s
    with pytest.raises(lsc.Timeout):
        arm.getPosition(1)       # the package: a bare Exception
    arm.close()


def test_port_names():
    from lsc.compat.xarm import _port_name
    assert _port_name("USB", None) == "hid"
    assert _port_name("USB497223563535", None) == "hid:497223563535"
    assert _port_name("USB", "/dev/hidraw3") == "/dev/hidraw3"
    assert _port_name("/dev/ttyUSB0", None) == "/dev/ttyUSB0"
    assert _port_name("hid:ABC", None) == "hid:ABC"
    assert _port_name("sim", None) == "sim"


def test_debug_prints_frames(tmp_path):
    r = run_python("from lsc.compat import xarm\n"
                   "xarm.Controller('sim', debug=True).getBatteryVoltage()\n")
    assert r.returncode == 0, r.stderr
    assert r.stdout == "Tx 0x55 0x55 0x02 0x0f\nRx 0x55 0x55 0x04 0x0f 0x4c 0x1d\n"


def test_write_servo_id():
    with xarm.Controller("sim") as arm:
        sent = []
        arm.lsc.trace(lambda d, f: sent.append(f) if d == "tx" else None)
        with pytest.raises(ValueError, match="6 servos answer"):
            arm.writeServoId(2)  # the sim answers for 1..6: refused
        assert all(f[3] == 21 for f in sent)  # only the position reads of listServos
        sent.clear()
        arm.writeServoId(2, overwrite_all_servo_ids=True)
        assert sent == [bytes([0x55, 0x55, 0x03, 27, 2])]


def test_servo_list_updated_in_place_beyond_1000():
    with xarm.Controller("sim") as arm:
        servos = [xarm.Servo(7)]
        assert arm.getPosition(servos) is None
        # sim's servos start at 1500 (an LSC board's middle): kept as read
        assert servos[0].position == 1500 and servos[0].angle == 250.0
        assert arm.getPosition(7, degrees=True) == 250.0
