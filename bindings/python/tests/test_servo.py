"""A bus of servos from Python: lsc.open("lx:PATH") with the board's calls
(lsc-sim --lx), and Controller.servo (lsc.BusServos) against a bus written
from the vendor's protocol document alone (tests/lxbus/lxbus_peer.py, which
counts the frames it receives: a refusal is checked to have written
nothing), with lscctl servo's refusals and messages."""
import ctypes
import os
import termios

import pytest

import lsc
from conftest import XARM_PROFILE, test_s
from lsc import _native as N
from lxpeer import (ANGLE_LIMIT_WRITE, ANGLE_OFFSET_ADJUST, ID_WRITE, LED_ERROR_WRITE,
                    OR_MOTOR_MODE_WRITE, TEMP_MAX_LIMIT_WRITE, VIN_LIMIT_WRITE, lx_peer)
from test_layout import layout

assert lx_peer and layout  # (fixtures)

TIMEOUT_MS = test_s(1000)


def bus(peer, **kw):
    return lsc.open(peer.port, timeout_ms=TIMEOUT_MS, **kw)


def test_refusal_enum_is_an_int(layout):
    for name in N.LX_ENUMS:
        assert layout[name] == [ctypes.sizeof(ctypes.c_int)]


# ---- lsc.open("lx:PATH"): what works on a board ----------------------------------------


def test_open_a_bus_with_the_boards_calls(lsc_sim, tmp_path):
    s = lsc_sim("--lx", "1-6")
    with lsc.open("lx:" + s.path, timeout_ms=TIMEOUT_MS) as c:
        assert c.kind == lsc.Kind.LX and c.kind == "lx"
        assert c.name == "lx:" + s.path
        assert c.read([1, 2, 3]) == {1: 500, 2: 500, 3: 500}
        r = c.move({2: 700, 3: 250}, time_ms=300, wait=True, tolerance=0)
        assert r and r.reads
        assert c.read("1-3") == {1: 500, 2: 700, 3: 250}
        assert c.servo.torque(2) is True  # a move powers it
        c.unload([2])
        assert c.servo.torque(2) is False
        c.move({1: 600}, time_ms=0)
        assert c.settle({1: 600}, tolerance=0)
        assert c.offsets([1]) == {1: 0}
        with pytest.raises(lsc.InvalidArgument) as e:
            c.battery()
        assert "servo's supply voltage" in str(e.value) and "nothing was sent" in str(e.value)
        with pytest.raises(lsc.InvalidArgument):
            c.run(1)
    profile = tmp_path / "xarm.conf"
    profile.write_text(XARM_PROFILE)
    with lsc.open("lx:" + s.path, arm=str(profile), timeout_ms=TIMEOUT_MS) as c:
        c.move({"base": 30.0}, time_ms=200, wait=True, tolerance=0)
        assert c.read(["base"], degrees=True)["base"] == pytest.approx(30.0, abs=0.5)
        assert c.read([6]) == {6: 625}  # 30 degrees of 240 over 0..1000, past 500


def test_a_bus_opens_at_115200_baud():
    master, slave = os.openpty()
    try:
        attrs = termios.tcgetattr(slave)
        attrs[4] = attrs[5] = termios.B9600
        termios.tcsetattr(slave, termios.TCSANOW, attrs)
        with lsc.open("lx:" + os.ttyname(slave)):
            attrs = termios.tcgetattr(slave)
            assert (attrs[4], attrs[5]) == (termios.B115200, termios.B115200)
        with lsc.open("lx:" + os.ttyname(slave), baud=57600):
            assert termios.tcgetattr(slave)[4] == termios.B57600
    finally:
        os.close(slave)
        os.close(master)


# ---- what only a bus servo has -------------------------------------------------------


def test_scan(lx_peer):
    p = lx_peer("1,2,3")
    with bus(p) as c:
        found = c.servo.scan()
        assert list(found) == [1, 2, 3] and len(found) == 3 and 2 in found
        assert found.collided == () and found.asked == 254
        some = c.servo.scan([2, 7, 8, 9])
        assert some.found == (2,) and some.asked == 4
        assert list(c.servo.scan(range(10, 20))) == []  # none answering: no error
        for bad, cls in (([254], ValueError), ([2, 2], ValueError), ([], ValueError),
                         ("1-3", TypeError), (5, TypeError), ([1.0], TypeError)):
            with pytest.raises(cls):
                c.servo.scan(bad)


def test_info(lx_peer):
    p = lx_peer("1,2,3")
    p.ctl("set 2 temp 41")
    p.ctl("set 2 vin 7600")
    with bus(p) as c:
        c.move({2: 700}, time_ms=100, wait=True, tolerance=0)
        i = c.servo.info(2)
        assert i == lsc.ServoInfo(id=2, position=700, temperature_c=41, vin_mv=7600, offset=0,
                                  limits=(0, 1000), vin_limits_mv=(4500, 12000),
                                  temp_limit_c=85, mode=lsc.ServoMode.SERVO, speed=0,
                                  torque=True, led=True, alarms=lsc.Alarm.ALL)
        assert i.mode == "servo" and i.alarms == 7
        with pytest.raises(AttributeError):
            i.id = 3  # frozen
        with pytest.raises(lsc.Timeout) as e:
            c.servo.info(9)
        assert "no reply from servo 9" in str(e.value)
        with pytest.raises(ValueError) as e2:
            c.servo.info(254)
        assert str(e2.value) == ("servo id 254 is out of range: bus servos have 0..253 (254 "
                                 "is the broadcast)")


def test_a_reply_with_a_flipped_bit_is_never_taken(lx_peer):
    p = lx_peer("1")
    with bus(p) as c:
        p.ctl("flip")
        with pytest.raises(lsc.LinkError):
            c.servo.offset(1)
        assert c.servo.offset(1) == 0


def test_set_id_refused_with_nothing_written(lx_peer):
    p = lx_peer("1,2,3")
    with bus(p) as c:
        with pytest.raises(lsc.Refused) as e:
            c.servo.set_id(1, 3)
        assert e.value.reason == lsc.Refusal.ID_TAKEN
        assert str(e.value) == ("servo id 1 3 on %s: a servo already answers at the new id "
                                "(two servos would share it); nothing was written" % c.name)
        assert isinstance(e.value, lsc.InvalidArgument) and isinstance(e.value, ValueError)
        with pytest.raises(lsc.Refused) as e:
            c.servo.set_id(5, 6)
        assert e.value.reason == lsc.Refusal.ID_ABSENT
        assert "no servo answers at that id; nothing was written" in str(e.value)
        with pytest.raises(lsc.Refused) as e:
            c.servo.set_id_alone(7)
        assert e.value.reason == lsc.Refusal.NOT_ALONE
        assert "connect the servo whose id you want to set alone; nothing was written" \
            in str(e.value)
        with pytest.raises(ValueError) as e2:
            c.servo.set_id(2, 2)
        assert str(e2.value) == "servo 2 has that id already: nothing to do"
        with pytest.raises(ValueError):
            c.servo.set_id(2, 300)
        assert p.count(ID_WRITE) == 0
        c.servo.set_id(2, 9)
        assert p.count(ID_WRITE) == 1
        assert list(c.servo.scan()) == [1, 3, 9]


def test_set_id_alone(lx_peer):
    p = lx_peer("1")
    with bus(p) as c:
        assert c.servo.set_id_alone(7) == 1
        assert list(c.servo.scan()) == [7]
        p.ctl("remove 7")
        with pytest.raises(lsc.Refused) as e:
            c.servo.set_id_alone(8)
        assert e.value.reason == lsc.Refusal.NO_SERVO
    assert p.count(ID_WRITE) == 1


def test_offset(lx_peer):
    p = lx_peer("1,3")
    with bus(p) as c:
        assert c.servo.offset(1) == 0
        assert c.servo.change_offset(1, 15, save=True) == 15
        assert c.servo.change_offset(3, -20) == -20
        assert c.servo.change_offset(3, 5) == -15
        with pytest.raises(lsc.Refused) as e:
            c.servo.change_offset(3, -120)
        assert e.value.reason == lsc.Refusal.OUT_OF_RANGE
        with pytest.raises(ValueError) as e2:
            c.servo.change_offset(3, 251)
        assert str(e2.value) == "offset change 251 is out of range: use -250..250"
        assert p.count(ANGLE_OFFSET_ADJUST) == 3
        p.ctl("power-cycle")
        assert (c.servo.offset(1), c.servo.offset(3)) == (15, 0)
        assert c.servo.change_offset(3, 10) == 10
        assert c.servo.save_offset(3) == 10
        p.ctl("power-cycle")
        assert c.servo.offset(3) == 10


def test_settings_written_and_read_back(lx_peer):
    p = lx_peer("1")
    with bus(p) as c:
        s = c.servo
        assert s.limits(1) == (0, 1000)
        assert s.set_limits(1, 100, 900) == (100, 900) == s.limits(1)
        assert s.vin_limits(1) == (4500, 12000)
        assert s.set_vin_limits(1, 5000, 9000) == (5000, 9000) == s.vin_limits(1)
        assert s.temp_limit(1) == 85
        assert s.set_temp_limit(1, 70) == 70 == s.temp_limit(1)
        assert s.torque(1) is False
        assert s.set_torque(1, True) is True and s.torque(1) is True
        assert s.set_torque(1, False) is False
        assert s.mode(1) == (lsc.ServoMode.SERVO, 0)
        assert s.set_mode(1, "motor", 300) == lsc.ModeSetting(lsc.ServoMode.MOTOR, 300)
        assert s.mode(1) == ("motor", 300)
        assert s.set_mode(1, lsc.ServoMode.SERVO).mode == "servo"
        assert s.led(1) is True
        assert s.set_led(1, False) is False and s.led(1) is False
        assert s.alarms(1) == lsc.Alarm.ALL
        assert s.set_alarms(1, lsc.Alarm.TEMPERATURE | lsc.Alarm.STALL) == 5
        assert s.alarms(1) == lsc.Alarm.TEMPERATURE | lsc.Alarm.STALL
        p.ctl("power-cycle")  # kept: limits, LED; lost: motor mode, torque, the alarm mask
        assert (s.limits(1), s.vin_limits(1), s.temp_limit(1), s.led(1)) == \
            ((100, 900), (5000, 9000), 70, False)
        assert s.alarms(1) == 7


def test_values_out_of_range_refused_with_nothing_sent(lx_peer):
    p = lx_peer("1")
    with bus(p) as c:
        s = c.servo
        before = p.writes()
        for call, message in (
                (lambda: s.set_limits(1, 0, 1001), "angle limit 1001 is out of range: use 0..1000"),
                (lambda: s.set_limits(1, 500, 500),
                 "limits '500 500': the first must be below the second"),
                (lambda: s.set_vin_limits(1, 4000, 9000),
                 "voltage limit (mV) 4000 is out of range: use 4500..12000"),
                (lambda: s.set_temp_limit(1, 101),
                 "temperature limit (C) 101 is out of range: use 50..100"),
                (lambda: s.set_mode(1, "motor", 1001),
                 "motor speed 1001 is out of range: use -1000..1000"),
                (lambda: s.set_mode(1, "servo", 5),
                 "a speed is for motor mode: servo mode takes none (5)"),
                (lambda: s.set_mode(1, "wheel"), "'wheel': use motor or servo"),
                (lambda: s.set_alarms(1, 8), "alarm mask 8 is out of range: use 0..7"),
                (lambda: s.set_torque(1, 1), "torque is True or False, not 1"),
                (lambda: s.set_led(1, "on"), "led is True or False, not 'on'")):
            with pytest.raises(ValueError) as e:
                call()
            assert str(e.value) == message
        assert p.writes() == before == 0
        for cmd in (ANGLE_LIMIT_WRITE, VIN_LIMIT_WRITE, TEMP_MAX_LIMIT_WRITE,
                    OR_MOTOR_MODE_WRITE, LED_ERROR_WRITE):
            assert p.count(cmd) == 0


def test_not_a_bus(sim):
    with pytest.raises(lsc.InvalidArgument) as e:
        sim.servo.scan()
    assert str(e.value) == (
        'sim is no bus of servos: the servo calls talk to serial bus servos directly, on a bus '
        'opened as lsc.open("lx:PATH") (a BusLinker or USB-serial adapter on the servos\' '
        'bus); nothing was sent')
    for call in (lambda: sim.servo.info(1), lambda: sim.servo.set_id(1, 2),
                 lambda: sim.servo.set_id_alone(2), lambda: sim.servo.led(1),
                 lambda: sim.servo.change_offset(1, 2)):
        with pytest.raises(lsc.InvalidArgument) as e:
            call()
        assert "lx:PATH" in str(e.value)
    with pytest.raises(ValueError) as e2:  # ranges first, as lscctl checks them
        sim.servo.set_alarms(1, 9)
    assert "alarm mask" in str(e2.value)


def test_replace_and_check_arm(lx_peer, tmp_path):
    profile = tmp_path / "xarm.conf"
    profile.write_text(XARM_PROFILE)
    p = lx_peer("1,2")  # two servos: refused
    with bus(p) as c:
        with pytest.raises(lsc.Refused) as e:
            c.servo.replace("base", arm=str(profile))
        assert e.value.reason == lsc.Refusal.NOT_ALONE
        assert "servo replace base (servo 6)" in str(e.value)
        assert p.count(ID_WRITE) == 0 and p.count(ANGLE_LIMIT_WRITE) == 0
        with pytest.raises(ValueError):
            c.servo.replace("base")  # no profile
    p = lx_peer("1")  # a new servo, alone
    with bus(p, arm=str(profile)) as c:
        with pytest.raises(ValueError) as e2:
            c.servo.replace("tail")
        assert "no joint 'tail'" in str(e2.value)
        fixed = tmp_path / "fixed.conf"
        fixed.write_text("fixed 7 bus limits=500..500\n")
        with pytest.raises(lsc.Refused) as e4:  # no bus servo's limits
            c.servo.replace("fixed", arm=str(fixed))
        assert e4.value.reason == lsc.Refusal.BAD_ARGUMENT
        assert "(positions 500..500)" in str(e4.value)
        p.ctl("remove 1")
        with pytest.raises(lsc.Refused) as e5:
            c.servo.replace("base")
        assert e5.value.reason == lsc.Refusal.NO_SERVO
        assert p.count(ID_WRITE) == 0 and p.count(ANGLE_LIMIT_WRITE) == 0
        p.ctl("add 1")
        r = c.servo.replace("base")
        assert (r.joint, r.old_id, r.id) == ("base", 1, 6)
        lo, hi = r.limits
        assert 0 <= lo < 500 < hi <= 1000 and lo + hi == 1000  # -115..115 degrees
        assert c.servo.limits(6) == r.limits
        with pytest.raises(lsc.Timeout) as e3:
            c.servo.check_arm()
        assert "joint gripper: no servo answers at id 1" in str(e3.value)
        for i in range(1, 6):
            p.ctl("add %d" % i)
        assert c.servo.check_arm() == 6


def test_threads_share_the_bus(lx_peer):
    """The servo calls take turns with the controller's others (its lock)."""
    import threading
    p = lx_peer("1,2")
    with bus(p) as c:
        errors = []

        def reads():
            try:
                for _ in range(20):
                    assert c.read([1]) == {1: 500}
            except BaseException as e:  # noqa: B902
                errors.append(e)
        t = threading.Thread(target=reads)
        t.start()
        for _ in range(20):
            assert c.servo.offset(2) == 0
        t.join(test_s(60))
        assert not t.is_alive() and not errors


def test_record_and_play_on_a_bus(lx_peer, tmp_path):
    """Keyframes recorded from servos posed by hand on the bus (the peer's
    limp servos placed between keyframes), then played back."""
    p = lx_peer("1,2")
    p.ctl("set 1 pos 300")
    p.ctl("set 2 pos 650")
    poses = iter([(420, 580)])

    def pose_next(action, taken):
        if taken:  # the keyframe was read: place the servos for the next one
            for sid, pos in zip((1, 2), next(poses, (420, 580))):
                p.ctl("set %d pos %d" % (sid, pos))
    with bus(p) as c:
        a = c.record([1, 2], every_ms=100, count=2, progress=pose_next)
        assert a.ids == (1, 2)
        assert [list(k.positions) for k in a] == [[300, 650], [420, 580]]
        assert c.servo.torque(1) is False  # recorded limp
        a.save(str(tmp_path / "taught.csv"))
        c.move({1: 800, 2: 200}, time_ms=100, wait=True, tolerance=0)
        r = c.play(lsc.Action.load(str(tmp_path / "taught.csv")), lead_ms=200)
        assert r.frames == 2 and not r.stopped
        assert c.settle({1: 420, 2: 580}, tolerance=0)
        assert c.read([1, 2]) == {1: 420, 2: 580}


def test_trace_shows_the_bus_frames(lx_peer):
    p = lx_peer("2")
    with bus(p) as c:
        got = []
        c.trace(lambda d, b: got.append((d, b.hex(" "))))
        assert c.servo.offset(2) == 0
        # ANGLE_OFFSET_READ (19) to servo 2, and its answer: offset 0
        assert got == [("tx", "55 55 02 03 13 e7"), ("rx", "55 55 02 04 13 00 e6")]


def test_the_docstrings_name_the_bus():
    assert '"lx:/dev/ttyUSB0"' in lsc.open.__doc__
    assert "LX" in lsc.Controller.kind.__doc__
    assert "lx:PATH" in lsc.Controller.servo.__doc__
    for name in ("scan", "info", "set_id", "set_id_alone", "offset", "change_offset",
                 "save_offset", "limits", "set_limits", "vin_limits", "set_vin_limits",
                 "temp_limit", "set_temp_limit", "mode", "set_mode", "torque", "set_torque",
                 "led", "set_led", "alarms", "set_alarms", "replace", "check_arm"):
        assert getattr(lsc.BusServos, name).__doc__, name
