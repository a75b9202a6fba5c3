"""lsc.compat.xarm against what the xarm package does: the table of its calls
(data/xarm_calls.json: the frames each sends and what it returns or raises,
read from the package's source) checked byte for byte on lsc-sim; scripts in
its README's style (xarm_scripts/) run with only their import line and port
changed, their printed output checked; the warnings, debug lines, port names
and exceptions the drop-in adds or shares."""
import builtins
import json
import os
import re
import warnings

import pytest

import lsc
from conftest import DATA, HERE, child_env, run_python, test_s
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


def run_script(name, tmp_path, *args, env=None):
    r = run_python([converted(name, tmp_path), *args], env=env)
    assert r.returncode == 0, r.stderr
    return r


# ---- the table --------------------------------------------------------------------------


def _frames(sent, then_reads):
    """The frames sent as the table writes them; with then_reads, the
    drop-in's position reads after the move left out."""
    out = [" ".join("%02x" % b for b in f) for f in sent]
    return out[:1] + [f for f in out[1:] if f.split()[3] != "15"] if then_reads else out


def _plain(v):
    """A return value as JSON holds it (tuples are lists)."""
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return v


def test_calls_as_the_package_makes_them(lsc_sim):
    with open(os.path.join(DATA, "xarm_calls.json")) as f:
        rows = json.load(f)["rows"]
    assert len(rows) >= 60
    s = lsc_sim("--fast")
    arm = xarm.Controller(s.path)
    sent = []
    arm.lsc.trace(lambda d, frame: sent.append(frame) if d == "tx" else None)
    for row in rows:
        sent.clear()
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            try:
                got = ("returns", _plain(eval(row["call"], {"arm": arm, "xarm": xarm})))
            except Exception as e:  # noqa: BLE001 (the table names the type)
                got = ("raises", e)
        call = row["call"]
        if "raises" in row:
            assert got[0] == "raises", "%s returned %r" % (call, got[1])
            assert isinstance(got[1], getattr(builtins, row["raises"])), \
                "%s raised %r, the package %s" % (call, got[1], row["raises"])
        else:
            assert got == ("returns", row["returns"]), call
        assert _frames(sent, row.get("then_reads", False)) == row["sends"], call
        assert bool([x for x in w if issubclass(x.category, xarm.XarmWarning)]) == \
            row.get("warns", False), "%s warned %s" % (call, [str(x.message) for x in w])
    arm.close()


# ---- scripts in the package's style ------------------------------------------------------

WALKTHROUGH = """Battery voltage in volts: 7.5
Servos:  [1, 2, 3, 4, 5, 6]
servo ID: 1
servo position: 300
servo angle: -50.0
Servo 1 position: 200
Servo 2 position: 860
Servo 3 position (degrees): 90.0
Servo 1 position (degrees): -75.0
Servo 2 position (degrees): 90.0
Servo 3 position (degrees): 90.0
Battery voltage (volts): 7.5
"""


def test_walkthrough_on_sim(tmp_path):
    """On "sim" no time passes between calls but what they wait: the moves
    the README starts without waiting are read where they began."""
    r = run_script("walkthrough.py", tmp_path, "sim")
    assert r.stdout == WALKTHROUGH
    # its one call whose second argument the package ignores
    assert r.stderr.count("XarmWarning") == 1
    assert "the position is ignored for a list" in r.stderr


def test_walkthrough_on_a_pty(tmp_path, lsc_sim):
    s = lsc_sim("--fast")
    out = run_script("walkthrough.py", tmp_path, s.path).stdout.splitlines()
    want = WALKTHROUGH.splitlines()
    # what is read while a move the script did not wait for runs depends on
    # the time it takes: those lines' words, not their numbers
    for i, (o, w) in enumerate(zip(out, want)):
        if 5 <= i <= 10:
            assert o.rsplit(":", 1)[0] == w.rsplit(":", 1)[0], o
        else:
            assert o == w
    assert len(out) == len(want)


WAVE = """wave 1 at 700
wave 2 at 700
wave 3 at 700
rest: [500, 500, 500, 500]
"""

TEACH = """taught: [(2, 200, -75.0), (3, 800, 75.0)]
taught: [(2, 400, -25.0), (3, 600, 25.0)]
taught: [(2, 600, 25.0), (3, 400, -25.0)]
replay 1 [200, 800] True
replay 1 [400, 600] True
replay 1 [600, 400] True
replay 2 [200, 800] True
replay 2 [400, 600] True
replay 2 [600, 400] True
done
"""

ANGLES = """servo 3: 860 90.1
position 90.0: 90 -102.5
angle -30: 380 -30.0
servo 3 380 -30.0
servo 4 318 -45.499999999999986
servo 5 549 12.250000000000007
servo 6 0 -125.0
"""

GRAB = """Battery voltage in volts: 7.5
open at 200
closed at 600 (holding something)
lifted: 300 700
let go at 200
"""


def test_scripts_on_a_pty(tmp_path, lsc_sim):
    s = lsc_sim("--fast")
    assert run_script("wave.py", tmp_path, s.path).stdout == WAVE
    r = run_script("teach.py", tmp_path, s.path, str(test_s(0.5)))
    assert r.stdout == TEACH
    # setPosition(pose, 1000, True), six times on one line: warned once each way
    assert r.stderr.count("XarmWarning") == 2, r.stderr
    assert "duration=True is a 1 ms move" in r.stderr
    assert run_script("angles.py", tmp_path, s.path).stdout == ANGLES
    assert run_script("battery.py", tmp_path, s.path).stdout == BATTERY
    assert run_script("moves.py", tmp_path, s.path).stdout == MOVES


def test_grab_with_the_gripper_held(tmp_path, lsc_sim):
    """The gripper closes on an object at 600: wait=True returns (the
    package only slept), and the script goes on."""
    s = lsc_sim("--fast", "--block", "1:600")
    r = run_script("grab.py", tmp_path, s.path)
    assert r.stdout == GRAB
    assert r.stderr == ""


def test_held_gripper_returns_at_once(lsc_sim):
    s = lsc_sim("--fast", "--block", "1:600")
    with xarm.Controller(s.path) as arm:
        arm.setPosition(1, 700, duration=500, wait=True)
        assert arm.getPosition(1) == 600


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


def test_scripts_on_sim(tmp_path):
    assert run_script("battery.py", tmp_path, "sim").stdout == BATTERY
    assert run_script("moves.py", tmp_path, "sim").stdout == MOVES
    assert run_script("servos.py", tmp_path).stdout == """servo ID: 1
servo position: 300
servo angle: -50.0
servo 3: 860 90.0
servo 3: 320 -45.1
servo 3: 1000 125.0
default: 500 0.0
"""


def test_usb_takes_lsc_port(tmp_path):
    """Controller('USB') is $LSC_PORT when it is set, as lscctl's default: a
    script written for the arm runs on the simulator unchanged."""
    r = run_script("battery.py", tmp_path, env=child_env(LSC_PORT="sim"))
    assert r.stdout == BATTERY


# ---- exceptions, debug output ------------------------------------------------------------


def test_angle_mapping_matches_the_package():
    def reference_position(degrees):
        """Rounded to 0.25 degree, -125..125 linearly onto 0..1000, truncated."""
        x = round(degrees * 4) / 4
        return int(1000 * ((x + 125.0) / 250.0))
    for q in range(-500, 501):
        for d in (q / 4, q / 4 + 0.1, q / 4 - 0.1):
            if -125.0 <= d <= 125.0:
                assert xarm.Servo(1, float(d)).position == reference_position(d), d


def test_errors_are_the_packages_types_too(lsc_sim):
    s = lsc_sim("--fast", "--drop-replies", "5")
    arm = xarm.Controller(s.path)
    arm.lsc.timeout_ms = 100
    with pytest.raises(IndexError) as e:
        arm.getBatteryVoltage()  # serial: the package indexed an empty reply
    assert isinstance(e.value, lsc.Timeout)
    with pytest.raises(IndexError):
        arm.getPosition(1)
    with pytest.raises(TypeError) as e:
        arm.setPosition(1, 500, 300.0)
    assert isinstance(e.value, lsc.InvalidArgument)
    arm.close()
    with pytest.raises(OSError) as e:
        xarm.Controller("/nonexistent/ttyUSB9")
    assert isinstance(e.value, lsc.NotFound) and isinstance(e.value, RuntimeError)
    with pytest.raises(OSError) as e:
        xarm.Controller("COM5")
    assert "Windows" in str(e.value)


def test_debug_prints_as_the_package(tmp_path):
    r = run_python("from lsc.compat import xarm\n"
                   "arm = xarm.Controller('sim')\n"
                   "arm.getBatteryVoltage()\n"
                   "arm.debug = True\n"
                   "arm.getBatteryVoltage()\n"
                   "arm.setPosition(1, 500, 0)\n"
                   "arm.listServos(2)\n")
    assert r.returncode == 0, r.stderr
    assert r.stdout == ("Tx Command 0x0f (Length 0): \n"
                        "Rx Command 0x0f (Length 4): 0x55 0x55 0x04 0x0f\n"
                        "Tx Command 0x03 (Length 6): 0x01 0x00 0x00 0x01 0xf4 0x01\n"
                        "Tx Command 0x15 (Length 2): 0x01 0x01\n"
                        "Rx Command 0x15 (Length 4): 0x55 0x55 0x06 0x15\n"
                        "Tx Command 0x15 (Length 2): 0x01 0x02\n"
                        "Rx Command 0x15 (Length 4): 0x55 0x55 0x06 0x15\n"
                        "Found 2 Servos: [1, 2]\n")


def test_names_of_the_package():
    assert xarm.__version__ == xarm.VERSION == lsc.__version__
    import lsc.compat.xarm.controller as c
    import lsc.compat.xarm.servo as sv
    import lsc.compat.xarm.util as u
    assert c.Controller is xarm.Controller and sv.Servo is xarm.Servo and u.Util is xarm.Util
