"""xarm.controller: the package's Controller over lsc: the same frames for
the same calls, the same values, waits, debug lines and refusals (its types
of exception; lsc's messages). bindings/python/README.md lists what differs."""
import os
import time
from typing import Any, List, Tuple

import lsc
from lsc._check import shown
from lsc.errors import invalid

from ._errors import DeviceNotFound, NoReply, WrongPortType, WrongType, opened, warn
from . import bus as _bus
from .servo import Servo
from .util import Util

__all__ = ["Controller"]


def _byte(value: Any, what: str) -> int:
    """value as one byte of a frame, refused as the package's bytearray would:
    TypeError for a non-int, ValueError outside 0..255."""
    if not isinstance(value, int):
        raise WrongType("%s must be an int 0..255, not %r" % (what, value))
    if not 0 <= value <= 255:
        raise invalid("%s %s is outside 0..255" % (what, shown(value)))
    return int(value)


def _u16(value: Any, what: str) -> Tuple[int, int]:
    """The low and high bytes of an int (the package masks: 70000 sends 4464,
    -1 sends 65535); TypeError for anything else."""
    if not isinstance(value, int):
        raise WrongType("%s must be an int, not %r" % (what, value))
    return value & 0xFF, (value & 0xFF00) >> 8


def _checked_position(value: Any, last: Any) -> Any:
    """A pair's or an id's position as the package takes it: an int 0..1000;
    a float angle -125.0..125.0 as its position; anything else: `last` (the
    package kept the previous value of its variable)."""
    if isinstance(value, int):
        if not 0 <= value <= 1000:
            raise invalid("position %s is outside 0..1000" % shown(value))
        return value
    if isinstance(value, float):
        if not -125.0 <= value <= 125.0:
            raise invalid("angle %r is outside -125.0..125.0" % value)
        return Util._angle_to_position(value)
    return last


class Controller:
    """The xArm (or any LSC controller) on com_port:
      'USB'               $LSC_PORT if it is set (lscctl's default), else the
                          one xArm on USB (HID)
      'USB' + SERIAL      the xArm with that USB serial number
      'COM5'              a Windows port: not on Linux (lsc.NotFound, an OSError)
      any other lsc name  '/dev/ttyUSB0', lsc-sim's pseudo-terminal, 'sim',
                          'hid:SERIAL', '/dev/hidrawN', 'lscd:NAME'
    debug=True (or setting .debug later) prints every request and reply as the
    package did. usb_path: a hidraw node, for 'USB' without a serial number.
    timeout_ms (lsc's): how long a request waits for its reply.
    arm (lsc's): the arm profile that arm.lsc (the lsc.Controller underneath)
    uses for reach(), where() and joint names: an lsc.Arm or a profile's
    path (e.g. the xArm's, examples/arms/xarm.conf); None: $LSC_ARM's when
    it is set, else none. The package's calls send the same frames with or
    without it (on 'sim' the virtual controller then stands in for that arm).
    Opening fails with lsc.NotFound (also an OSError), lsc.PermissionDenied,
    lsc.Busy (an OSError), lsc.InvalidArgument (a ValueError); a com_port
    that is not text (None, a number) raises xarm.WrongPortType, an
    lsc.InvalidArgument (ValueError) that is also the AttributeError the
    package's code raised."""

    SIGNATURE = 0x55
    CMD_SERVO_MOVE = 0x03
    CMD_GET_BATTERY_VOLTAGE = 0x0F
    CMD_SERVO_STOP = 0x14
    CMD_GET_SERVO_POSITION = 0x15
    CMD_SERVO_ID_WRITE = 0x1B

    def __init__(self, com_port: Any, debug: bool = False, usb_path: Any = None,
                 timeout_ms: int = 1000, arm: Any = None) -> None:
        if isinstance(com_port, os.PathLike):
            com_port = os.fsdecode(com_port)
        if not isinstance(com_port, str):
            raise WrongPortType("com_port parameter incorrect: %r is no port's name (use "
                                "'USB', 'USB' + a serial number, or a port's path)"
                                % (com_port,), lsc._native.LSC_EINVAL)
        if com_port.startswith("COM"):
            name = com_port  # refused below: Windows names a port so
        elif com_port.startswith("USB"):
            serial = com_port.strip("USB")  # (as the package takes it apart)
            env = os.environ.get("LSC_PORT", "")
            name = ("hid:" + serial if serial else usb_path if usb_path is not None
                    else env if env else "hid")
        elif not com_port:
            raise invalid("com_port parameter incorrect: '' (use 'USB', 'USB' + a serial "
                          "number, or a port's path)")
        else:
            name = com_port
        if name.startswith("COM"):
            raise DeviceNotFound("%s is a Windows port name: on Linux, name the serial port's "
                                 "path (e.g. '/dev/ttyUSB0'), or 'USB' for the arm's USB link"
                                 % name, lsc._native.LSC_ENODEV)
        self._c = opened(name, timeout_ms, arm)
        self._hid = self._c.kind == "hid"
        self._bus = self._c.kind == "lx"  # a bus of servos: lsc/compat/xarm/bus.py
        self._reads = True  # False once the controller did not answer a position read
        if debug and self._hid:
            print("Serial number:", self._serial())
        self.debug = debug
        self.servos: List[int] = []

    def _serial(self) -> str:
        name = self._c.name
        if name.startswith("hid:"):
            return name[4:]
        arms = [p for p in lsc.ports() if p.kind == "hid" and (p.path == name or name == "hid")]
        return arms[0].serial if len(arms) == 1 else ""

    # ---- lsc's additions ---------------------------------------------------------------

    @property
    def lsc(self) -> "lsc.Controller":
        """The lsc.Controller underneath (groups, notifications, play...)."""
        return self._c

    def halt(self) -> str:
        """Stops everything (the package has no such call): the running action
        group, and every servo where it is (lsc.Controller.halt)."""
        return self._c.halt()

    def close(self) -> None:
        """Closes the port (the package had no close: it stayed open until exit)."""
        self._c.close()

    def __enter__(self) -> "Controller":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ---- the wire, with the package's debug lines -------------------------------------

    def _send(self, cmd: int, params: bytes) -> None:
        if self.debug:
            print("Tx Command 0x%02x (Length %d): %s"
                  % (cmd, len(params), " ".join("0x%02x" % b for b in params)))
        if self._bus:
            _bus.send(self._c, cmd, params)
            return
        self._c.send(cmd, params, force=True)

    def _request(self, cmd: int, params: bytes) -> bytes:
        """Sends cmd, returns its reply's parameters; NoReply (an IndexError
        too) when none comes."""
        if self.debug:
            print("Tx Command 0x%02x (Length %d): %s"
                  % (cmd, len(params), " ".join("0x%02x" % b for b in params)))
        try:
            reply = _bus.request(self._c, cmd, params) if self._bus else \
                self._c.request(cmd, params)
        except lsc.Timeout as e:
            if self.debug:
                print("Did not receive a response for the command 0x%02x" % cmd if self._hid
                      else "Rx Command 0x%02x (Length 0): " % cmd)
            raise NoReply(e.message, e.code) from None
        if self.debug:
            # serial: the package printed the frame's 4 header bytes; HID: the
            # report's bytes after them, LEN of them (2 past the parameters)
            shown = (bytes(reply) + b"\0\0" if self._hid
                     else bytes([self.SIGNATURE, self.SIGNATURE, len(reply) + 2, cmd]))
            print("Rx Command 0x%02x (Length %d): %s"
                  % (cmd, len(shown), " ".join("0x%02x" % b for b in shown)))
        return reply

    # ---- the package's calls ----------------------------------------------------------

    def setPosition(self, servos: Any, position: Any = None, duration: Any = 1000,  # noqa: N802
                    wait: bool = False) -> None:
        """Moves servos over duration ms: an id (position: an int 0..1000 or
        a float angle), a Servo, or a list of Servo and [id, position] pairs
        (then position is ignored). wait=True sleeps for the duration, then
        waits, without raising, while servos are still moving."""
        lo, hi = _u16(duration, "duration")
        if isinstance(duration, bool):
            warn("setPosition: duration=%r is a %d ms move (the third argument is the "
                 "duration; pass wait=%r by name)" % (duration, int(duration), duration))
        elif not 0 <= duration <= 0xFFFF:
            warn("setPosition: duration %d ms does not fit the frame: %d ms is sent"
                 % (duration, duration & 0xFFFF))
        params = bytearray([1, lo, hi])
        targets: List[Tuple[int, int]] = []

        def add(sid: Any, pos: Any, what: str) -> None:
            plo, phi = _u16(pos, "position")
            targets.append((_byte(sid, what), (phi << 8) | plo))

        if isinstance(servos, (int, float)):
            if position is None:
                raise invalid("setPosition(%r): the position is missing" % (servos,))
            pos = _checked_position(position, position)
            plo, phi = _u16(pos, "position")
            targets.append((_byte(servos, "a servo id"), (phi << 8) | plo))
        elif isinstance(servos, Servo):
            if position is not None:
                warn("setPosition: the position is ignored for a Servo (it moves to its own)")
            add(servos.servo_id, servos.position, "a Servo's servo_id")
        elif isinstance(servos, list):
            if position is not None:
                warn("setPosition: the position is ignored for a list (each entry has its own)")
            params[0] = _byte(len(servos), "the number of servos")
            last = position
            for s in servos:
                if isinstance(s, Servo):
                    add(s.servo_id, s.position, "a Servo's servo_id")
                    continue
                if len(s) != 2 or not isinstance(s[0], int):
                    raise invalid("setPosition: %r is neither a Servo nor an [id, position] "
                                  "pair" % (s,))
                last = _checked_position(s[1], last)
                add(s[0], last, "a servo id")
        else:
            raise invalid("setPosition: servos is an id, a Servo or a list, not %r" % (servos,))
        for sid, pos in targets:
            params += bytes([sid, pos & 0xFF, pos >> 8])
        self._send(self.CMD_SERVO_MOVE, bytes(params))
        if wait:
            time.sleep(duration / 1000)
            self._wait_moving(dict(targets), (hi << 8) | lo)

    def _wait_moving(self, targets: Any, duration_ms: int) -> None:
        """After the duration: while servos still move, waits (the device's
        timeout at most), never raising for where they stop. Tolerance 0: a
        servo ends the wait at its target, or once its reads stop changing
        (lsc.MoveResult.stopped: 200 ms within 3 positions)."""
        if not targets or not self._reads:
            return
        try:
            r = self._c.settle(targets, time_ms=0, tolerance=0)  # (the duration has passed)
            self._reads = r.reads
        except lsc.Timeout:
            pass  # still moving after the timeout: the package did not wait at all

    def getPosition(self, servos: Any, degrees: bool = False) -> Any:  # noqa: N802 (its name)
        """The position (degrees=True: the angle) of servos, an id or a
        Servo; a list of Servo gets each one's position (returns None).
        NoReply (lsc.Timeout, IndexError) when the controller does not answer."""
        if isinstance(servos, int):
            ids = [_byte(servos, "a servo id")]
        elif isinstance(servos, Servo):
            ids = [_byte(servos.servo_id, "a Servo's servo_id")]
        elif isinstance(servos, list) and all(isinstance(s, Servo) for s in servos):
            _byte(len(servos), "the number of servos")  # refused as the package's count byte
            ids = [_byte(s.servo_id, "a Servo's servo_id") for s in servos]
        else:
            raise invalid("getPosition: servos is an id, a Servo or a list of Servo, not %r"
                          % (servos,))
        data = self._request(self.CMD_GET_SERVO_POSITION, bytes([len(ids)] + ids))
        if isinstance(servos, list):
            for i in range(data[0]):
                servos[i].position = data[i * 3 + 3] * 256 + data[i * 3 + 2]
            return None
        position = data[3] * 256 + data[2]
        return Util._position_to_angle(position) if degrees else position

    def servoOff(self, servos: Any = None) -> None:  # noqa: N802 (its name)
        """Powers servos off: an id, a Servo, a list of either (other entries
        are skipped but counted, as the package did), or None: 1..6."""
        if servos is None:
            params = [6, 1, 2, 3, 4, 5, 6]
        elif isinstance(servos, int):
            params = [1, _byte(servos, "a servo id")]
        elif isinstance(servos, Servo):
            params = [1, _byte(servos.servo_id, "a Servo's servo_id")]
        elif isinstance(servos, list):
            params = [_byte(len(servos), "the number of servos")]
            params += [_byte(s, "a servo id") if isinstance(s, int)
                       else _byte(s.servo_id, "a Servo's servo_id")
                       for s in servos if isinstance(s, (int, Servo))]
        else:
            raise invalid("servoOff: servos is an id, a Servo, a list or None, not %r"
                          % (servos,))
        self._send(self.CMD_SERVO_STOP, bytes(params))

    def writeServoId(self, new_servo_id: int = 0,  # noqa: N802
                     overwrite_all_servo_ids: bool = False) -> Any:
        """On a board: writes new_servo_id to EVERY servo on its bus
        (command 27: the board has no way to address one): first lists the
        servos (listServos) unless overwrite_all_servo_ids, and refuses
        (ValueError) when none is listed, or several without
        overwrite_all_servo_ids. On a bus of servos (lx:PATH): the same
        checks, then only the one servo on the bus gets the id, proven
        alone by the library (a broadcast and a scan of every id): else
        lsc.Refused (a ValueError), nothing written, even with
        overwrite_all_servo_ids (a bus never gives several servos one id)."""
        if not overwrite_all_servo_ids:
            self.listServos()
        if not self.servos:
            raise invalid("writeServoId: no servo is listed (call listServos, or connect "
                          "the servo)")
        if len(self.servos) > 1 and not overwrite_all_servo_ids:
            raise invalid("writeServoId: %d servos answer (%s): %s"
                          % (len(self.servos), self.servos, _bus.NOT_ALONE if self._bus else
                             "the board writes an id to every servo on its bus at once: "
                             "connect only the one whose id to write, or pass "
                             "overwrite_all_servo_ids=True to give every servo on the bus "
                             "the id %r" % (new_servo_id,)))
        if new_servo_id == 0:
            raise invalid("writeServoId: new_servo_id must not be 0")
        self._send(self.CMD_SERVO_ID_WRITE, bytes([_byte(new_servo_id, "new_servo_id")]))

    def listServos(self, maximum_servo_id: int = 6) -> Any:  # noqa: N802 (its name)
        """The ids 1..maximum_servo_id whose position reads are answered (one
        read each: a missing servo costs the reply timeout). On a bus of
        servos (lx:PATH): a scan of those ids (8 ms an id)."""
        if self._bus:
            self.servos = _bus.list_servos(self._c, maximum_servo_id)
            if self.debug:
                print("Found %d Servos: %s" % (len(self.servos), self.servos))
            return self.servos
        self.servos = []
        for i in range(1, maximum_servo_id + 1):
            try:
                self.getPosition(i)
                self.servos.append(i)
            except Exception:  # noqa: BLE001 (the package skipped any failure)
                pass
        if self.debug:
            print("Found %d Servos: %s" % (len(self.servos), self.servos))
        return self.servos

    def getBatteryVoltage(self) -> float:  # noqa: N802 (its name)
        """The battery voltage in volts. Over USB (HID) it tries 5 times, a
        second apart, and returns 0.0 if none is answered; over a serial port
        no answer raises NoReply (lsc.Timeout, IndexError), as the package did.
        A bus of servos has no battery: lsc.InvalidArgument (a ValueError)
        saying where a servo's supply voltage is, nothing sent."""
        for _ in range(5):
            try:
                data = self._request(self.CMD_GET_BATTERY_VOLTAGE, b"")
            except NoReply:
                if not self._hid:
                    raise
                data = b""
            except lsc.LinkError:
                data = b""
            if not data:
                time.sleep(1)
                continue
            return (data[1] * 256 + data[0]) / 1000.0
        return 0.0
