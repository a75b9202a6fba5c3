"""The `xarm` drop-in (lsc.compat.xarm) on a bus of servos (lx:PATH, the
stand-in bus of tests/lxbus/lxbus_peer.py, which counts the frames it
receives): listServos and writeServoId through the bus, the id written to
the one servo alone, or refused with nothing written; the package's other
calls done with lsc's bus calls; and on a board, why writeServoId cannot
address one servo."""
import io
from contextlib import redirect_stdout

import pytest

import lsc
from conftest import test_s
from lsc.compat import xarm
from lxpeer import ID_WRITE, lx_peer

assert lx_peer  # (a fixture)

TIMEOUT_MS = test_s(1000)


def test_list_servos_on_a_bus(lx_peer):
    p = lx_peer("1,2,3,40")
    with xarm.Controller(p.port, timeout_ms=TIMEOUT_MS) as arm:
        assert arm.listServos() == [1, 2, 3] == arm.servos  # 1..6, as the package asks
        assert arm.listServos(2) == [1, 2]
        assert arm.listServos(0) == [] and arm.listServos(-3) == []
        assert arm.listServos(300) == [1, 2, 3, 40]  # (ids end at 253 on a bus)
        with pytest.raises(TypeError):
            arm.listServos("6")
        arm.debug = True
        out = io.StringIO()
        with redirect_stdout(out):
            arm.listServos()
        assert out.getvalue() == "Found 3 Servos: [1, 2, 3]\n"


def test_write_servo_id_refused_on_a_bus_with_nothing_written(lx_peer):
    p = lx_peer("1,2,40")
    with xarm.Controller(p.port, timeout_ms=TIMEOUT_MS) as arm:
        with pytest.raises(ValueError) as e:
            arm.writeServoId(7)  # the package's own check: 1 and 2 listed
        assert str(e.value) == ("writeServoId: 2 servos answer ([1, 2]): a bus of servos "
                                "gives an id to one servo only: connect only the one whose id "
                                "to write")
        p.ctl("remove 2")
        with pytest.raises(lsc.Refused) as e2:  # 1 listed, 40 is there too: not alone
            arm.writeServoId(7)
        assert e2.value.reason == lsc.Refusal.NOT_ALONE
        assert isinstance(e2.value, ValueError)
        arm.listServos(60)
        with pytest.raises(lsc.Refused):  # never every servo at once on a bus
            arm.writeServoId(7, overwrite_all_servo_ids=True)
        with pytest.raises(ValueError):
            arm.writeServoId(0, True)
        with pytest.raises(ValueError) as e3:
            arm.writeServoId(254, True)
        assert "bus servos have 1..253" in str(e3.value)
        with pytest.raises(TypeError):
            arm.writeServoId(2.0, True)
    assert p.count(ID_WRITE) == 0


def test_write_servo_id_on_a_bus(lx_peer):
    p = lx_peer("1")  # a new servo, alone
    with xarm.Controller(p.port, timeout_ms=TIMEOUT_MS) as arm:
        assert arm.writeServoId(5) is None
        assert p.count(ID_WRITE) == 1
        assert arm.listServos() == [5]
        arm.writeServoId(6, overwrite_all_servo_ids=True)  # (alone: the same)
        assert arm.listServos() == [6]
    assert p.count(ID_WRITE) == 2


def test_the_packages_calls_on_a_bus(lx_peer):
    p = lx_peer("1,2,3")
    with xarm.Controller(p.port, timeout_ms=TIMEOUT_MS) as arm:
        arm.setPosition(2, 700, 200, wait=True)
        assert arm.getPosition(2) == 700
        arm.setPosition([[1, 300], xarm.Servo(3, 800)], duration=200, wait=True)
        servos = [xarm.Servo(1), xarm.Servo(2), xarm.Servo(3)]
        arm.getPosition(servos)
        assert [s.position for s in servos] == [300, 700, 800]
        assert arm.getPosition(1, degrees=True) == xarm.Util._position_to_angle(300)
        assert arm.lsc.servo.torque(2) is True
        arm.servoOff(2)
        assert arm.lsc.servo.torque(2) is False
        arm.servoOff()  # 1..6: the bus's 1, 2, 3
        assert arm.lsc.servo.torque(1) is False
        with pytest.raises(xarm.NoReply):  # the package's type: IndexError, a Timeout
            arm.getPosition(9)
        with pytest.raises(ValueError) as e:
            arm.getBatteryVoltage()
        assert "has no battery reading; a servo's supply voltage is " \
            "arm.lsc.servo.info(ID).vin_mv" in str(e.value)
        with pytest.raises(ValueError):  # a bus servo's move is at most 30 s
            arm.setPosition(1, 500, 40000)


def test_write_servo_id_on_a_board_says_why_not(lsc_sim):
    s = lsc_sim("--fast")
    with xarm.Controller(s.path) as arm:
        with pytest.raises(ValueError) as e:
            arm.writeServoId(7)
        assert "the board writes an id to every servo on its bus at once" in str(e.value)
        with pytest.raises(lsc.InvalidArgument) as e2:
            arm.lsc.servo.set_id(1, 7)
        assert "lx:PATH" in str(e2.value)
