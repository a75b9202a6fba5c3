"""The public calls over USB HID, against the HID test double (tests/hid_double.c:
xArms backed by the virtual controller, with the real link's report rules),
in a child Python whose liblsc.so.2 has the double in place of hidapi
($LSC_HID_DOUBLE_LIB, built by CMake). Arms come from $LSC_HID_DOUBLE
("NODE|SERIAL|FLAGS;..."); every report written is logged to
$LSC_HID_DOUBLE_LOG."""
import os
import textwrap

import pytest

from conftest import child_env, run_python
from test_compat import BATTERY, MOVES, converted

LIB = os.environ.get("LSC_HID_DOUBLE_LIB", "")
pytestmark = pytest.mark.skipif(not LIB, reason="no HID test double (LSC_HID_DOUBLE_LIB: a "
                                "build with hidapi and the tests)")


@pytest.fixture
def arms(tmp_path):
    """A function: arms("SERIAL|FLAGS", ...) -> the environment of a child
    Python that sees those xArms (nodes tmp/hidrawN)."""
    def env(*specs):
        spec = []
        for i, s in enumerate(specs):
            node = tmp_path / ("hidraw%d" % i)
            node.write_text("")
            spec.append("%s|%s" % (node, s))
        return child_env(LSC_LIBRARY=LIB, LSC_HID_DOUBLE=";".join(spec),
                         LSC_HID_DOUBLE_LOG=str(tmp_path / "reports"))
    env.reports = tmp_path / "reports"
    env.node = lambda i: str(tmp_path / ("hidraw%d" % i))
    return env


def run(code, env):
    r = run_python(textwrap.dedent(code), env=env)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_every_call(arms):
    out = run("""
        import lsc
        with lsc.open("hid") as c:
            print(c.kind, c.battery(), c.read([1, 2, 3]))
            c.move({1: 200, 2: 800}, time_ms=300, wait=True)
            p = c.read([1, 2])  # within the wait's tolerance (the double's clock may lag)
            print(abs(p[1] - 200) <= 10 and abs(p[2] - 800) <= 10)
            print(c.run(8, wait=True, timeout=30))
            c.speed(8, 50); c.stop(); c.unload([1, 2, 3])
            c.adjust_offset(2, -3)
            print(c.offsets([1, 2]))
            a = lsc.Action([1, 2], [(0, (100, 900)), (200, (150, 850))])
            r = c.play(a, lead_ms=100)
            # the last move's end: the double's clock runs only while the link
            # waits, so it lags play's (the host's) by the time the process was
            # kept from running: waited for as move(wait=True) does
            c.settle({1: 150, 2: 850})
            end = c.read([1, 2])
            print(r.frames, r.dropped, abs(end[1] - 150) <= 10 and abs(end[2] - 850) <= 10)
            print(len(c.record([1, 2], every_ms=100, count=2, unload=False)))
        """, arms("ARM-A|"))
    assert out.splitlines() == [
        "hid 7500 {1: 1500, 2: 1500, 3: 1500}",
        "True",
        "Notification(kind='action_group_complete', group=8, times=1)",
        "{1: 0, 2: -3}",
        "2 0 True",
        "2"]
    reports = arms.reports.read_text().splitlines()
    # each report 65 bytes: no report id (00), the frame, zero padding
    assert reports[0] == "00 55 55 02 0F" + " 00" * 60
    assert all(len(r.split()) == 65 and r.startswith("00 55 55") for r in reports)


def test_names(arms):
    env = arms("ARM-A|", "ARM-B|")
    out = run("""
        import lsc
        for name in ("hid:ARM-B", "%s"):
            with lsc.open(name) as c:
                print(c.kind, c.battery())
        print(sorted(p.serial for p in lsc.ports() if p.kind == "hid"))
        try:
            lsc.open("hid")
        except lsc.InvalidArgument as e:
            print("several:", "ARM-A" in str(e) and "ARM-B" in str(e))
        try:
            lsc.open("hid:NOPE")
        except lsc.NotFound as e:
            print("NotFound:", "NOPE" in str(e))
        """ % arms.node(0), env)
    assert out.splitlines() == ["hid 7500", "hid 7500", "['ARM-A', 'ARM-B']",
                                "several: True", "NotFound: True"]


def test_permission_denied_names_the_udev_rule(arms):
    out = run("""
        import lsc
        try:
            lsc.open("hid")
        except lsc.PermissionDenied as e:
            print(isinstance(e, PermissionError), e.code)
            print(e)
        """, arms("ARM-A|deny"))
    first, message = out.splitlines()
    assert first == "True -11"
    assert "60-lsc.rules" in message and "plugdev" in message


def test_first_request_unanswered_is_sent_again(arms):
    assert run("import lsc\nprint(lsc.open('hid').battery())\n", arms("ARM-A|mute-first")) \
        == "7500\n"


def test_notifications_of_the_arm(arms):
    out = run("""
        import lsc
        with lsc.open("hid") as c:
            for n in c.notifications(timeout=30):
                print(n.kind, n.group, n.times)
                if n.kind == "action_group_complete":
                    break
        """, arms("ARM-A|run=8"))
    assert out == "action_group_run 8 1\naction_group_complete 8 1\n"


def test_unplugged(arms):
    out = run("""
        import lsc
        c = lsc.open("hid", timeout_ms=200)
        try:
            c.battery()  # the arm is unplugged as this request goes out
        except lsc.Error as e:
            print(type(e).__name__, bool(str(e)))
        """, arms("ARM-A|unplug"))
    assert out in ("LinkError True\n", "NotFound True\n")


def test_too_many_servos_for_a_report(arms):
    out = run("""
        import lsc
        try:
            lsc.open("hid").move({i: 500 for i in range(20)}, time_ms=100)
        except lsc.InvalidArgument as e:
            print("refused")
        """, arms("ARM-A|"))
    assert out == "refused\n"
    assert not arms.reports.exists() or arms.reports.read_text() == ""


def near(got, want):
    """The same lines, numbers within a move's tolerance (10 positions, 2.5
    degrees): the double's clock only moves while the link waits, so a servo
    may be read a little short of its target once it is within tolerance."""
    g, w = got.splitlines(), want.splitlines()
    if len(g) != len(w):
        return False
    for gl, wl in zip(g, w):
        gt, wt = gl.replace(":", " ").split(), wl.replace(":", " ").split()
        if len(gt) != len(wt):
            return False
        for a, b in zip(gt, wt):
            if a == b:
                continue
            try:
                if abs(float(a) - float(b)) > (2.5 if "." in b else 10):
                    return False
            except ValueError:
                return False
    return True


def test_xarm_scripts_with_usb(arms, tmp_path):
    """The xarm package's scripts as written: Controller('USB') and 'USB' + serial."""
    env = arms("497223563535|")
    for args, want in ((["battery.py"], BATTERY), (["moves.py"], MOVES),
                       (["battery.py", "USB497223563535"], BATTERY)):
        r = run_python([converted(args[0], tmp_path), *args[1:]], env=env)
        assert r.returncode == 0, r.stderr
        assert near(r.stdout, want), r.stdout


def test_xarm_debug_names_the_serial(arms):
    out = run("""
        from lsc.compat import xarm
        xarm.Controller('USB', debug=True).getBatteryVoltage()
        """, arms("497223563535|"))
    # the package's lines for a USB link: the reply's report bytes after the
    # frame's header, LEN of them (the parameters and two bytes of padding)
    assert out.splitlines() == ["Serial number: 497223563535",
                                "Tx Command 0x0f (Length 0): ",
                                "Rx Command 0x0f (Length 4): 0x4c 0x1d 0x00 0x00"]
