"""The drop-in's calls on a bus of servos (Controller('lx:/dev/ttyUSB0'):
a BusLinker, or the xArm's servos without their board): the package's
board commands, checked and shown (debug) as the package makes them, done
with lsc's bus calls instead of their frames, which no bus servo takes:

  3  setPosition    lsc.Controller.move (MOVE_TIME_WAIT_WRITE to each, then
                    one MOVE_START: the servos start together)
  20 servoOff       lsc.Controller.unload (torque off)
  21 getPosition    lsc.Controller.read, answered as the board answers
  15 battery        refused: a bus has no battery (a servo's supply
                    voltage: lsc.BusServos.info)
  27 writeServoId   lsc.BusServos.set_id_alone: only the one servo on the bus
listServos: lsc.BusServos.scan of the ids asked."""
from typing import Any, Dict, List

import lsc
from lsc._check import is_int, shown
from lsc.arm import Key, Value
from lsc.errors import invalid

from ._errors import WrongType

NOT_ALONE = ("a bus of servos gives an id to one servo only: connect only the one whose id "
             "to write")


def send(c: "lsc.Controller", cmd: int, params: bytes) -> None:
    """A board command that expects no reply (setPosition, servoOff) on the bus c."""
    if cmd == 3:  # count, time (LE), then id and position (LE) for each
        time_ms = params[1] | params[2] << 8
        targets: Dict[Key, Value] = {params[i]: params[i + 1] | params[i + 2] << 8
                   for i in range(3, len(params) - 2, 3)}
        if len(targets) != (len(params) - 3) // 3:
            raise invalid("setPosition: a servo is given twice: on a bus of servos each moves "
                          "once; nothing was sent")
        c.move(targets, time_ms=time_ms)
    elif cmd == 20:  # count, ids
        c.unload(list(params[1:]))
    elif cmd == 27:  # the new id
        write_id(c, params[0])
    else:  # (the drop-in sends no other command without a reply)
        raise invalid("command %d has no bus-servo equivalent on %s; nothing was sent"
                      % (cmd, c.name))


def request(c: "lsc.Controller", cmd: int, params: bytes) -> bytes:
    """A board request (getPosition, getBatteryVoltage) on the bus c, its
    reply's parameters as the board gives them."""
    if cmd == 21:  # count, ids -> count, then id and position (LE) for each
        ids = list(params[1:])
        got = c.read(ids)
        out = bytearray([len(ids)])
        for i in ids:
            p = int(got[i] or 0) & 0xFFFF
            out += bytes([i, p & 0xFF, p >> 8])
        return bytes(out)
    if cmd == 15:
        raise invalid("getBatteryVoltage: %s is a bus of servos: it has no battery reading; "
                      "a servo's supply voltage is arm.lsc.servo.info(ID).vin_mv (millivolts); "
                      "nothing was sent" % c.name)
    raise invalid("command %d has no bus-servo equivalent on %s; nothing was sent"
                  % (cmd, c.name))


def list_servos(c: "lsc.Controller", maximum_servo_id: Any) -> List[int]:
    """The ids 1..maximum_servo_id (at most 253) that answer a scan of the bus c."""
    if not is_int(maximum_servo_id):
        raise WrongType("listServos: maximum_servo_id must be an int, not %s"
                        % shown(maximum_servo_id))
    top = min(int(maximum_servo_id), lsc._native.LSC_LX_ID_MAX)
    return list(c.servo.scan(range(1, top + 1))) if top >= 1 else []


def write_id(c: "lsc.Controller", new_id: int) -> None:
    """The one servo on the bus c gets new_id (the library proves it alone)."""
    if new_id > lsc._native.LSC_LX_ID_MAX:
        raise invalid("writeServoId: new_servo_id %d is out of range: bus servos have 1..253 "
                      "(254 is the broadcast); nothing was written" % new_id)
    c.servo.set_id_alone(new_id)
