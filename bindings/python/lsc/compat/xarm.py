"""The Controller API of the PyPI `xarm` package, over lsc: a script written
for it runs after changing one line,

    import xarm                     ->  from lsc.compat import xarm

with that package's units: positions 0..1000; a float is degrees
-125.0..125.0, rounded to 0.25 degree and mapped linearly onto 0..1000 (its
mapping, which is not the bus servos' 240 degrees: use lsc.Arm for real
angles). What differs (bindings/python/README.md lists every difference):
ports are also Linux paths, "hid:SERIAL" and "sim"; failures raise lsc.Error
subclasses (getBatteryVoltage raises lsc.Timeout where the package returned
0.0 after 5 s of retries); wait=True waits until the servos are there
instead of only sleeping.
"""
import sys
from typing import Any, List, Optional, Sequence, Tuple, Union

import lsc
from lsc.errors import invalid

__all__ = ["Controller", "Servo"]

_POSITION_MAX = 1000
_ANGLE_MAX = 125.0
_ALL_SERVOS = [1, 2, 3, 4, 5, 6]
_CMD_SERVO_ID_WRITE = 27


def _round_quarter(degrees: float) -> float:
    return float(round(degrees * 4) / 4)


def _angle_to_position(degrees: float) -> int:
    """The package's mapping: -125.0..125.0 degrees (to 0.25) onto 0..1000,
    truncated."""
    if not isinstance(degrees, float) or not -_ANGLE_MAX <= degrees <= _ANGLE_MAX:
        raise invalid("an angle is a float -125.0..125.0, not %r" % (degrees,))
    k = (_round_quarter(degrees) + _ANGLE_MAX) / (2 * _ANGLE_MAX)
    return int(_POSITION_MAX * k)


def _position_to_angle(position: int) -> float:
    """The package's mapping back: 0..1000 onto -125.0..125.0 degrees."""
    if isinstance(position, bool) or not isinstance(position, int) or \
            not 0 <= position <= _POSITION_MAX:
        raise invalid("a position is an int 0..1000, not %r" % (position,))
    return _linear_angle(position)


def _linear_angle(position: int) -> float:
    """The same mapping for any position read back (beyond 0..1000 it goes on
    linearly, where the package raised ValueError)."""
    k = position / _POSITION_MAX
    return float((1 - k) * -_ANGLE_MAX + _ANGLE_MAX * k)


def _position(value: Union[int, float]) -> int:
    """An int position 0..1000, or a float angle, as a position."""
    if isinstance(value, bool):
        raise invalid("a position is an int 0..1000 or a float angle -125.0..125.0, not %r"
                      % (value,))
    if isinstance(value, int):
        if not 0 <= value <= _POSITION_MAX:
            raise invalid("Parameter 'position' must be between 0 and 1000 (not %d)." % value)
        return value
    if isinstance(value, float):
        if not -_ANGLE_MAX <= value <= _ANGLE_MAX:
            raise invalid("Parameter 'position' must be between -125.0 and 125.0 (not %r)."
                          % value)
        return _angle_to_position(value)
    raise invalid("a position is an int 0..1000 or a float angle -125.0..125.0, not %r"
                  % (value,))


def _servo_id(value: Any) -> int:
    if isinstance(value, Servo):
        return value.servo_id
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 255:
        raise invalid("a servo is an id 0..255 or an xarm.Servo, not %r" % (value,))
    return value


class Servo:
    """A servo id and a position (0..1000) or angle (-125.0..125.0 degrees, to
    0.25): setting one sets the other.

    Servo(1) is at 500 (0.0 degrees); Servo(2, 300) at -50.0 degrees;
    Servo(3, 90.0) at position 860."""

    def __init__(self, servo_id: int, position: Union[int, float] = 500):
        self.servo_id = _servo_id(servo_id)
        self.position = position  # type: ignore[assignment]

    @property
    def position(self) -> int:
        """Position in units, 0..1000."""
        return self._position

    @position.setter
    def position(self, value: Union[int, float]) -> None:
        if isinstance(value, float):
            self.angle = value
            return
        self._position = _position(value)
        self._angle = _position_to_angle(self._position)

    @property
    def angle(self) -> float:
        """Angle in degrees, -125.0..125.0 in steps of 0.25."""
        return self._angle

    @angle.setter
    def angle(self, value: float) -> None:
        if isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        self._position = _position(value)
        self._angle = _round_quarter(value)

    def _read_back(self, position: int) -> None:
        """A position read from the controller (kept as read, even outside 0..1000)."""
        self._position = position
        self._angle = _linear_angle(position)

    def __repr__(self) -> str:
        return "Servo(%d, %d)" % (self.servo_id, self._position)


def _port_name(com_port: str, usb_path: Optional[str]) -> str:
    """The lsc name for the package's com_port ('USB', 'USB' + serial,
    'COM...'), or any lsc name (a path, 'hid', 'hid:SERIAL', 'sim')."""
    if not isinstance(com_port, str):
        raise invalid("com_port parameter incorrect: %r" % (com_port,))
    if com_port.startswith("USB"):
        serial = com_port[3:]
        if serial:
            return "hid:" + serial
        if usb_path is not None:
            return usb_path
        return "hid"
    if com_port.startswith("COM"):
        raise invalid("%s is a Windows port name: on Linux, name the serial port's path "
                      "(e.g. '/dev/ttyUSB0'), or 'USB' for the arm's USB link" % com_port)
    if not com_port:
        raise invalid("com_port parameter incorrect: ''")
    return com_port


class Controller:
    """The xArm (or any LSC controller) on com_port:
      'USB'               the one xArm on USB (HID)
      'USB' + SERIAL      the xArm with that USB serial number
      '/dev/ttyUSB0'      a serial port (any path; lsc-sim's pseudo-terminal)
      'hid:SERIAL', '/dev/hidrawN', 'sim' (lsc's built-in virtual controller)
    debug=True prints every frame sent and received. usb_path: a hidraw
    node, for 'USB' without a serial number.

    Raises lsc.NotFound, lsc.PermissionDenied (saying how to get access),
    lsc.Busy, lsc.InvalidArgument (a ValueError, as the package raised).
    Controller(port, timeout_ms=...) sets the reply timeout (lsc's default
    1000 ms)."""

    def __init__(self, com_port: str, debug: bool = False, usb_path: Optional[str] = None,
                 timeout_ms: int = 1000):
        self.debug = debug
        self.servos: List[int] = []
        self._c = lsc.open(_port_name(com_port, usb_path), timeout_ms=timeout_ms)
        if debug:
            if self._c.kind == "hid":
                print("Serial number:", self._serial())
            self._c.trace(self._print_frame)

    def _serial(self) -> str:
        """The USB serial number of the arm on the open HID link ("" if unknown)."""
        name = self._c.name
        if name.startswith("hid:"):
            return name[4:]
        arms = [p for p in lsc.ports() if p.kind == "hid" and (p.path == name or name == "hid")]
        return arms[0].serial if len(arms) == 1 else ""

    @staticmethod
    def _print_frame(direction: str, frame: bytes) -> None:
        print("%s %s" % ("Tx" if direction == "tx" else "Rx",
                         " ".join("0x%02x" % b for b in frame)), file=sys.stdout)

    @property
    def lsc(self) -> "lsc.Controller":
        """The lsc.Controller underneath (groups, notifications, play...)."""
        return self._c

    def close(self) -> None:
        """Closes the port (the package had no close: it stayed open until exit)."""
        self._c.close()

    def __enter__(self) -> "Controller":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def setPosition(self, servos: Union[int, Servo, Sequence[Any]],  # noqa: N802 (its name)
                    position: Optional[Union[int, float]] = None, duration: int = 1000,
                    wait: bool = False) -> None:
        """Moves servos over duration ms: servos is an id (then position is
        required: an int 0..1000 or a float angle), a Servo, or a list of Servo
        and (id, position) pairs. wait=True returns once the servos are there
        (lsc.Timeout if they are not within the timeout after duration)."""
        targets: List[Tuple[int, int]] = []
        if isinstance(servos, Servo):
            targets.append((servos.servo_id, servos.position))
        elif isinstance(servos, (int, float)) and not isinstance(servos, bool):
            if position is None:
                raise invalid("Parameter 'position' missing.")
            if isinstance(servos, float):
                if not servos.is_integer():
                    raise invalid("Parameter 'servos' is not valid: %r" % servos)
                servos = int(servos)
            targets.append((_servo_id(servos), _position(position)))
        elif isinstance(servos, (list, tuple)):
            for s in servos:
                if isinstance(s, Servo):
                    targets.append((s.servo_id, s.position))
                elif isinstance(s, (list, tuple)) and len(s) == 2 and \
                        isinstance(s[0], int) and not isinstance(s[0], bool):
                    targets.append((_servo_id(s[0]), _position(s[1])))
                else:
                    raise invalid("Parameter list 'servos' is not valid: %r" % (s,))
        else:
            raise invalid("Parameter 'servos' is not valid: %r" % (servos,))
        if isinstance(duration, bool) or not isinstance(duration, int) or \
                not 0 <= duration <= 65535:
            raise invalid("duration is an int 0..65535 ms, not %r" % (duration,))
        ids = [i for i, _ in targets]
        if len(set(ids)) != len(ids):
            raise invalid("a servo appears twice in %r" % (servos,))
        self._c.move(dict(targets), duration, wait=wait)

    def getPosition(self, servos: Union[int, Servo, List[Servo]],  # noqa: N802 (its name)
                    degrees: bool = False) -> Optional[Union[int, float]]:
        """The position (or, degrees=True, the angle) of servos, an id or a
        Servo; a list of Servo is updated in place (returns None).
        lsc.Timeout when the controller does not answer."""
        if isinstance(servos, list):
            if not servos or not all(isinstance(s, Servo) for s in servos):
                raise invalid("Parameter 'servos' is not valid: a list of xarm.Servo")
            read = self._c.read([s.servo_id for s in servos])
            for s in servos:
                s._read_back(read[s.servo_id])
            return None
        if isinstance(servos, bool) or not isinstance(servos, (int, Servo)):
            raise invalid("Parameter 'servos' is not valid: %r" % (servos,))
        sid = _servo_id(servos)
        position = self._c.read([sid])[sid]
        if isinstance(servos, Servo):
            servos._read_back(position)
        return _linear_angle(position) if degrees else position

    def servoOff(self, servos: Optional[Union[int, Servo, List[Union[int, Servo]]]] = None  # noqa: N802
                 ) -> None:
        """Powers servos off (an id, a Servo, a list of either; None: 1..6)."""
        if servos is None:
            ids = list(_ALL_SERVOS)
        elif isinstance(servos, list):
            ids = [_servo_id(s) for s in servos]
        else:
            ids = [_servo_id(servos)]
        self._c.unload(ids)

    def getBatteryVoltage(self) -> float:  # noqa: N802 (its name)
        """The battery voltage in volts. lsc.Timeout when it does not answer
        (the package returned 0.0 after 5 s)."""
        return self._c.battery() / 1000.0

    def listServos(self, maximum_servo_id: int = 6) -> List[int]:  # noqa: N802 (its name)
        """The ids 1..maximum_servo_id whose position reads are answered (one
        read each: a missing servo costs the reply timeout)."""
        if isinstance(maximum_servo_id, bool) or not isinstance(maximum_servo_id, int) or \
                not 1 <= maximum_servo_id <= 254:
            raise invalid("maximum_servo_id is an int 1..254, not %r" % (maximum_servo_id,))
        found = []
        for i in range(1, maximum_servo_id + 1):
            try:
                self._c.read([i])
            except (lsc.Timeout, lsc.LinkError):
                continue
            found.append(i)
        self.servos = found
        if self.debug:
            print("Found %d Servos: %s" % (len(found), found))
        return found

    def writeServoId(self, new_servo_id: int = 0,  # noqa: N802 (its name)
                     overwrite_all_servo_ids: bool = False) -> None:
        """Writes new_servo_id (1..254) to EVERY servo on the bus (command 27,
        sent to all of them): refused unless exactly one servo answers, or
        overwrite_all_servo_ids=True."""
        if isinstance(new_servo_id, bool) or not isinstance(new_servo_id, int) or \
                not 1 <= new_servo_id <= 254:
            raise invalid("new_servo_id must be an int 1..254, not %r" % (new_servo_id,))
        if not overwrite_all_servo_ids:
            self.listServos()
            if len(self.servos) != 1:
                raise invalid("%d servos answer (%s): connect only the one whose id to "
                              "write, or pass overwrite_all_servo_ids=True to give every "
                              "servo on the bus the id %d"
                              % (len(self.servos), self.servos, new_servo_id))
        self._c.send(_CMD_SERVO_ID_WRITE, bytes([new_servo_id]), force=True)

