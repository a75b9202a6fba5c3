"""What only a serial bus servo has (LX-16A, LX-15D, LX-224: the xArm's
servos, or servos on a BusLinker), on a bus of servos opened as
lsc.open("lx:/dev/ttyUSB0"): Controller.servo, an lsc.BusServos.

    with lsc.open("lx:/dev/ttyUSB0") as c:
        print(list(c.servo.scan()))       # [1, 2, 3]: the ids that answer
        print(c.servo.info(2).vin_mv)     # 7400: its supply voltage
        c.servo.set_id(1, 4)              # refused (lsc.Refused) if 4 answers

Every check is the library's (lsc/lxclient.h through lsc/bus.h), as
lscctl servo makes them, with lscctl's messages: values outside the
protocol's ranges raise lsc.InvalidArgument (a ValueError) before anything
is sent; the safe operations (set_id, set_id_alone, change_offset,
replace) raise lsc.Refused, nothing written, when the bus is not as they
need it; on a controller that is no bus every call raises
lsc.InvalidArgument saying to open lx:PATH, nothing sent. No answer:
lsc.Timeout; an answer that is no good frame (colliding answers, a flipped
bit): lsc.LinkError. Each request waits at most the controller's
timeout_ms for its reply.
"""
import ctypes
import enum
from dataclasses import dataclass
from typing import Any, Iterable, Iterator, List, NamedTuple, Optional, Tuple, Union

from . import _native as N
from ._check import integer as _int, is_int, shown as _shown
from ._handle import _Handle
from .arm import Arm
from .errors import Error, InvalidArgument, LinkError, invalid, wrong_type

__all__ = ["BusServos", "ServoInfo", "ServoMode", "ModeSetting", "Alarm", "Refusal", "Refused",
           "ScanResult", "Replaced"]


class ServoMode(str, enum.Enum):
    """A bus servo's mode; a str too ("servo", "motor"), as lscctl prints it."""
    SERVO = "servo"  #: position control
    MOTOR = "motor"  #: turning continuously at a speed

    def __str__(self) -> str:
        return self.value

    def __repr__(self) -> str:
        return repr(self.value)


class Alarm(enum.IntFlag):
    """The faults that flash a servo's LED (its alarm mask, 0..7)."""
    NONE = 0
    TEMPERATURE = 1  #: over its temperature limit
    VOLTAGE = 2      #: supply voltage outside its limits
    STALL = 4        #: stalled
    ALL = 7


class Refusal(str, enum.Enum):
    """Why a safe operation refused (lsc_lx_refusal): Refused.reason."""
    BAD_ARGUMENT = "bad_argument"  #: an argument outside its range
    ID_TAKEN = "id_taken"          #: the new id already answers: two servos would share it
    ID_ABSENT = "id_absent"        #: the old id does not answer
    ID_GARBLED = "id_garbled"      #: the old id answers garbled: several servos share it
    NO_SERVO = "no_servo"          #: no servo answers
    NOT_ALONE = "not_alone"        #: more than one servo answers (or answers collide)
    OUT_OF_RANGE = "out_of_range"  #: the result would leave the protocol's range

    def __str__(self) -> str:
        return self.value


# lsc_lx_refusal's values (LSC_LX_NOT_READ_BACK is no refusal: it was written)
_REFUSALS = {1: Refusal.BAD_ARGUMENT, 2: Refusal.ID_TAKEN, 3: Refusal.ID_ABSENT,
             4: Refusal.ID_GARBLED, 5: Refusal.NO_SERVO, 6: Refusal.NOT_ALONE,
             8: Refusal.OUT_OF_RANGE}


class Refused(InvalidArgument):
    """A safe operation refused, nothing written: reason (an lsc.Refusal)
    says why, str(e) says what to do (lscctl servo's line)."""

    def __init__(self, message: str, code: Optional[int] = None,
                 reason: Refusal = Refusal.BAD_ARGUMENT) -> None:
        super().__init__(message, code)
        self.reason = reason


@dataclass(frozen=True)
class ServoInfo:
    """Everything a servo tells (BusServos.info): the fields of lscctl servo
    info --json."""
    id: int
    position: int               #: where its shaft is (may be below 0)
    temperature_c: int
    vin_mv: int                 #: its supply voltage
    offset: int                 #: -125..125, in effect
    limits: Tuple[int, int]     #: its angle limits (min, max), 0..1000
    vin_limits_mv: Tuple[int, int]
    temp_limit_c: int
    mode: ServoMode
    speed: int                  #: motor mode's speed -1000..1000
    torque: bool                #: the motor powered
    led: bool                   #: the LED on
    alarms: Alarm               #: the faults that flash the LED


@dataclass(frozen=True)
class ScanResult:
    """The ids that answered a scan (BusServos.scan), in order. Iterating
    it, len() and `in` are over found: list(c.servo.scan()) == [1, 2, 3]."""
    found: Tuple[int, ...]     #: the ids that answered with a good frame
    collided: Tuple[int, ...]  #: ids whose answers collided (two servos share it, or noise)
    asked: int                 #: how many ids were asked

    def __iter__(self) -> Iterator[int]:
        return iter(self.found)

    def __len__(self) -> int:
        return len(self.found)

    def __contains__(self, servo_id: object) -> bool:
        return servo_id in self.found


class ModeSetting(NamedTuple):
    """A servo's mode and motor mode's speed (BusServos.mode)."""
    mode: ServoMode
    speed: int


class Replaced(NamedTuple):
    """What BusServos.replace did."""
    joint: str                #: the joint, as given
    old_id: int               #: the id the new servo had
    id: int                   #: the joint's id, which it has now
    limits: Tuple[int, int]   #: the joint's limits, now its angle limits (read back)


def _id(v: Any, what: str = "servo id") -> int:
    return _int(what, v, 0, N.LSC_LX_ID_MAX,
                "%s %%s is out of range: bus servos have 0..253 (254 is the broadcast)" % what)


def _on(v: Any, what: str) -> bool:
    if not isinstance(v, bool):
        raise wrong_type("%s is True or False, not %s" % (what, _shown(v)))
    return v


class BusServos:
    """What only a bus servo has, on the bus of an lx:PATH controller
    (Controller.servo). Ids are 0..253. Without a value each call reads
    what the servo has; the set_ calls write it, read it back and return
    what the servo reads back (lsc.LinkError when it differs). Kept at
    power-off: the id, a saved offset, the limits, the LED; lost: an
    offset not saved, motor mode, torque, the alarm mask."""

    def __init__(self, controller: _Handle) -> None:
        self._c = controller

    def __repr__(self) -> str:
        return "<lsc.BusServos of %r>" % (self._c,)

    # ---- the calls, as lscctl servo makes them ---------------------------------------

    def _bus(self) -> Any:
        """The device's bus client; lsc.InvalidArgument on any other kind."""
        bus = N.lib.lsc_device_lxclient(self._c._handle())
        if not bus:
            raise invalid("%s is no bus of servos: the servo calls talk to serial bus servos "
                          "directly, on a bus opened as lsc.open(\"lx:PATH\") (a BusLinker or "
                          "USB-serial adapter on the servos' bus); nothing was sent"
                          % self._c.name)
        return bus

    def _run(self, what: str, servo_id: int, fn: Any, *args: Any, why: bool = False) -> int:
        """fn(bus, *args[, &why]) for `what` ("servo id 1 3") asking
        servo_id, its outcome as the device's (lsc_device_lx_result):
        checked; a refusal raises Refused."""
        c = self._c
        with c._locked():
            bus = self._bus()
            reason = ctypes.c_int(N.LSC_LX_DONE)
            extra = (ctypes.byref(reason),) if why else ()
            rc = c._foreign(fn, bus, *args, *extra)
            rc = N.lib.lsc_device_lx_result(c._handle(), rc, what.encode(), servo_id,
                                            reason.value)
            return self._checked(rc, reason.value)

    def _checked(self, rc: int, why: int) -> int:
        """rc checked as the controller's; a refusal (why: its lsc_lx_refusal)
        raises Refused."""
        try:
            return self._c._check(rc)
        except InvalidArgument as e:
            if why in _REFUSALS and type(e) is InvalidArgument:
                raise Refused(e.message, e.code, _REFUSALS[why]) from None
            raise

    def _differs(self, what: str) -> Error:
        return LinkError("%s on %s: written, but the servo reads back another value (its "
                         "range, or a servo that does not take it)" % (what, self._c.name),
                         N.LSC_EREPLY)

    # ---- who is there ------------------------------------------------------------------

    def scan(self, ids: Optional[Iterable[int]] = None) -> ScanResult:
        """Which ids answer (ids: those, default every id 0..253: about 2 s
        for a whole bus). None answering is an empty result, not an error;
        ids whose answers collide (two servos that share an id) are in
        .collided, not in .found."""
        if ids is None:
            arr, n = None, 0
        else:
            if isinstance(ids, (str, bytes)) or is_int(ids):
                raise wrong_type("ids are servo ids (a list of ints 0..253), not %s"
                                 % _shown(ids))
            got: List[int] = []
            for i in ids:
                i = _id(i)
                if i in got:
                    raise invalid("servo %d is given twice" % i)
                got.append(i)
            if not got:
                raise invalid("scan needs at least one id (None: every id)")
            arr, n = (ctypes.c_uint8 * len(got))(*got), len(got)
        out = N.LxScan()
        self._run("servo scan", 0, N.lib.lsc_lxclient_scan, arr, n, 0, ctypes.byref(out))

        def bits(mask: Any) -> Tuple[int, ...]:
            return tuple(i for i in range(N.LSC_LX_ID_MAX + 1) if mask[i // 8] >> (i % 8) & 1)
        return ScanResult(bits(out.found), bits(out.garbled), int(out.asked))

    def info(self, servo_id: int) -> ServoInfo:
        """Everything servo_id tells: position, temperature, supply voltage,
        offset, limits, mode, torque, LED, alarms (12 requests)."""
        sid = _id(servo_id)
        s = N.LxInfo()
        self._run("servo info %d" % sid, sid, N.lib.lsc_lxclient_info, sid, ctypes.byref(s))
        return ServoInfo(id=s.id, position=s.position, temperature_c=s.temp_c,
                         vin_mv=s.vin_mv, offset=s.offset, limits=(s.limit_min, s.limit_max),
                         vin_limits_mv=(s.vin_min_mv, s.vin_max_mv),
                         temp_limit_c=s.temp_limit_c,
                         mode=ServoMode.MOTOR if s.mode == N.LSC_LX_MODE_MOTOR
                         else ServoMode.SERVO, speed=s.speed, torque=bool(s.torque),
                         led=bool(s.led), alarms=Alarm(s.alarms))

    # ---- ids ----------------------------------------------------------------------------

    def set_id(self, old_id: int, new_id: int) -> None:
        """Gives servo old_id the id new_id, then reads it back. Refused
        (lsc.Refused, nothing written) when new_id already answers
        (Refusal.ID_TAKEN), or old_id does not (ID_ABSENT), or answers
        garbled (ID_GARBLED: several servos share it)."""
        old, new = _id(old_id), _id(new_id, "new servo id")
        if old == new:
            raise invalid("servo %d has that id already: nothing to do" % old)
        self._run("servo id %d %d" % (old, new), new, N.lib.lsc_lxclient_change_id, old, new,
                  why=True)

    def set_id_alone(self, new_id: int) -> int:
        """Gives the one servo on the bus the id new_id, whatever its id
        (a new servo: 1), and returns the id it had. Only when it is
        alone, proven by a broadcast and a scan of every id: else
        lsc.Refused (Refusal.NO_SERVO, NOT_ALONE), nothing written."""
        new = _id(new_id, "new servo id")
        old = ctypes.c_uint8()
        self._run("servo id %d (the one servo on the bus)" % new, new,
                  N.lib.lsc_lxclient_set_id_alone, new, 0, ctypes.byref(old), why=True)
        return old.value

    # ---- offset -------------------------------------------------------------------------

    def offset(self, servo_id: int) -> int:
        """The offset in effect, -125..125 (0.24 degree a unit)."""
        sid = _id(servo_id)
        v = ctypes.c_int8()
        self._run("servo offset %d" % sid, sid, N.lib.lsc_lxclient_read_offset, sid,
                  ctypes.byref(v))
        return v.value

    def change_offset(self, servo_id: int, delta: int, save: bool = False) -> int:
        """Adds delta (-250..250) to the offset: in effect at once, lost at
        power-off unless save (which saves it). Returns the offset now in
        effect, read back. lsc.Refused (Refusal.OUT_OF_RANGE), nothing
        written, when the sum leaves -125..125."""
        sid = _id(servo_id)
        d = _int("offset change", delta, -250, 250,
                 "offset change %s is out of range: use -250..250")
        save = _on(save, "save")
        now = ctypes.c_int8()
        self._run("servo offset %d %d%s" % (sid, d, " --save" if save else ""), sid,
                  N.lib.lsc_lxclient_offset_change, sid, d, save, ctypes.byref(now), why=True)
        return now.value

    def save_offset(self, servo_id: int) -> int:
        """Saves the offset in effect (kept at power-off); returns it."""
        return self.change_offset(servo_id, 0, save=True)

    # ---- settings -------------------------------------------------------------------------

    def _pair(self, name: str, sid: int, write: Any, read: Any,
              values: Optional[Tuple[int, int]]) -> Tuple[int, int]:
        what = "servo %s %d" % (name, sid)
        a, b = ctypes.c_uint16(), ctypes.c_uint16()
        with self._c._locked():
            if values is not None:
                self._run(what, sid, write, sid, *values)
            self._run(what, sid, read, sid, ctypes.byref(a), ctypes.byref(b))
        if values is not None and (a.value, b.value) != values:
            raise self._differs(what)
        return a.value, b.value

    def _one(self, name: str, sid: int, write: Any, read: Any, value: Any,
             kind: Any = ctypes.c_uint8) -> Any:
        """One setting (a ctypes kind) of servo sid as read, after write sets
        it to value (not None): it must read back so."""
        what = "servo %s %d" % (name, sid)
        v = kind()
        with self._c._locked():
            if value is not None:
                self._run(what, sid, write, sid, value)
            self._run(what, sid, read, sid, ctypes.byref(v))
        if value is not None and v.value != value:
            raise self._differs(what)
        return v.value

    def _switch(self, name: str, servo_id: int, read: Any, write: Any = None,
                on: Any = None) -> bool:
        """The torque or the LED (name) of servo_id as read, after write
        sets it to on (True or False, checked after the id)."""
        sid = _id(servo_id)
        return bool(self._one(name, sid, write, read, None if write is None else _on(on, name),
                              ctypes.c_bool))

    @staticmethod
    def _range(what: str, lo: Any, hi: Any, low: int, high: int) -> Tuple[int, int]:
        msg = "%s %%s is out of range: use %d..%d" % (what, low, high)
        a, b = _int(what, lo, low, high, msg), _int(what, hi, low, high, msg)
        if a >= b:
            raise invalid("limits '%d %d': the first must be below the second" % (a, b))
        return a, b

    def limits(self, servo_id: int) -> Tuple[int, int]:
        """The angle limits (min, max), 0..1000."""
        sid = _id(servo_id)
        return self._pair("limits", sid, None, N.lib.lsc_lxclient_read_limits, None)

    def set_limits(self, servo_id: int, low: int, high: int) -> Tuple[int, int]:
        """Sets the angle limits, 0 <= low < high <= 1000 (kept)."""
        sid = _id(servo_id)
        v = self._range("angle limit", low, high, 0, N.LSC_LX_POSITION_MAX)
        return self._pair("limits", sid, N.lib.lsc_lxclient_write_limits,
                          N.lib.lsc_lxclient_read_limits, v)

    def vin_limits(self, servo_id: int) -> Tuple[int, int]:
        """The supply voltage limits (min, max) in mV."""
        sid = _id(servo_id)
        return self._pair("vin-limits", sid, None, N.lib.lsc_lxclient_read_vin_limits, None)

    def set_vin_limits(self, servo_id: int, low_mv: int, high_mv: int) -> Tuple[int, int]:
        """Sets the supply voltage limits, 4500 <= low_mv < high_mv <= 12000 (kept)."""
        sid = _id(servo_id)
        v = self._range("voltage limit (mV)", low_mv, high_mv, N.LSC_LX_VIN_MIN,
                        N.LSC_LX_VIN_MAX)
        return self._pair("vin-limits", sid, N.lib.lsc_lxclient_write_vin_limits,
                          N.lib.lsc_lxclient_read_vin_limits, v)

    def temp_limit(self, servo_id: int) -> int:
        """The temperature limit, degrees C."""
        sid = _id(servo_id)
        return int(self._one("temp-limit", sid, None, N.lib.lsc_lxclient_read_temp_limit, None))

    def set_temp_limit(self, servo_id: int, celsius: int) -> int:
        """Sets the temperature limit, 50..100 degrees C (kept)."""
        sid = _id(servo_id)
        v = _int("temperature limit (C)", celsius, N.LSC_LX_TEMP_LIMIT_MIN,
                 N.LSC_LX_TEMP_LIMIT_MAX, "temperature limit (C) %s is out of range: use 50..100")
        return int(self._one("temp-limit", sid, N.lib.lsc_lxclient_write_temp_limit,
                             N.lib.lsc_lxclient_read_temp_limit, v))

    def alarms(self, servo_id: int) -> Alarm:
        """The faults that flash the LED (lsc.Alarm, a mask 0..7)."""
        sid = _id(servo_id)
        return Alarm(self._one("alarms", sid, None, N.lib.lsc_lxclient_read_alarms, None))

    def set_alarms(self, servo_id: int, mask: int) -> Alarm:
        """Sets which faults flash the LED: a mask 0..7 (lsc.Alarm's; lost
        at power-off)."""
        sid = _id(servo_id)
        v = _int("alarm mask", mask, 0, N.LSC_LX_ALARM_ALL,
                 "alarm mask %s is out of range: use 0..7")
        return Alarm(self._one("alarms", sid, N.lib.lsc_lxclient_write_alarms,
                               N.lib.lsc_lxclient_read_alarms, v))

    def mode(self, servo_id: int) -> ModeSetting:
        """Position control (ServoMode.SERVO) or a motor turning at a speed."""
        sid = _id(servo_id)
        return self._mode(sid, None, 0)

    def set_mode(self, servo_id: int, mode: Union[ServoMode, str],
                 speed: Optional[int] = None) -> ModeSetting:
        """Position control ("servo", no speed), or a motor ("motor")
        turning at speed -1000..1000 (default 0). Lost at power-off."""
        sid = _id(servo_id)
        if mode not in (ServoMode.SERVO, ServoMode.MOTOR):
            raise invalid("%s: use motor or servo" % _shown(mode))
        m = ServoMode(mode)
        if m is ServoMode.SERVO and speed is not None:
            raise invalid("a speed is for motor mode: servo mode takes none (%s)"
                          % _shown(speed))
        v = 0 if speed is None else _int("motor speed", speed, -N.LSC_LX_SPEED_MAX,
                                         N.LSC_LX_SPEED_MAX,
                                         "motor speed %s is out of range: use -1000..1000")
        return self._mode(sid, m, v)

    def _mode(self, sid: int, mode: Optional[ServoMode], speed: int) -> ModeSetting:
        what = "servo mode %d" % sid
        m, s = ctypes.c_uint8(), ctypes.c_int16()
        with self._c._locked():
            if mode is not None:
                self._run(what, sid, N.lib.lsc_lxclient_write_mode, sid,
                          N.LSC_LX_MODE_MOTOR if mode is ServoMode.MOTOR
                          else N.LSC_LX_MODE_SERVO, speed)
            self._run(what, sid, N.lib.lsc_lxclient_read_mode, sid, ctypes.byref(m),
                      ctypes.byref(s))
        got = ModeSetting(ServoMode.MOTOR if m.value == N.LSC_LX_MODE_MOTOR
                          else ServoMode.SERVO, s.value)
        if mode is not None and (got.mode is not mode or
                                 (mode is ServoMode.MOTOR and got.speed != speed)):
            raise self._differs(what)
        return got

    def torque(self, servo_id: int) -> bool:
        """Whether the motor is powered (a move powers it)."""
        return self._switch("torque", servo_id, N.lib.lsc_lxclient_read_torque)

    def set_torque(self, servo_id: int, on: bool) -> bool:
        """Powers the motor (True) or lets it go limp (False)."""
        return self._switch("torque", servo_id, N.lib.lsc_lxclient_read_torque,
                            N.lib.lsc_lxclient_write_torque, on)

    def led(self, servo_id: int) -> bool:
        """Whether the LED is on."""
        return self._switch("led", servo_id, N.lib.lsc_lxclient_read_led)

    def set_led(self, servo_id: int, on: bool) -> bool:
        """Turns the LED on or off (kept)."""
        return self._switch("led", servo_id, N.lib.lsc_lxclient_read_led,
                            N.lib.lsc_lxclient_write_led, on)

    # ---- an arm's servo replaced -----------------------------------------------------------

    def _arm(self, arm: Optional[Union[Arm, str]], what: str) -> Arm:
        if arm is None:
            arm = self._c.arm
        if arm is None:
            raise invalid("%s needs the arm's profile: arm=FILE, or lsc.open(..., arm=FILE)"
                          % what)
        return arm if isinstance(arm, Arm) else Arm(arm)

    def replace(self, joint: str, arm: Optional[Union[Arm, str]] = None) -> Replaced:
        """A new servo for the arm's joint (arm: an lsc.Arm or a profile;
        default the controller's): connect it ALONE to the bus; it gets
        the joint's id, then the joint's limits as its angle limits. Refused
        (lsc.Refused: Refusal.NO_SERVO, NOT_ALONE), nothing written, unless
        it is alone; Refusal.BAD_ARGUMENT: the joint's limits are no bus
        servo's. Then connect the rest of the arm and call check_arm()."""
        a = self._arm(arm, "replace")
        if not isinstance(joint, str):
            raise wrong_type("joint is a joint's name, not %s" % _shown(joint))
        at = N.lib.lsc_arm_find(a._handle, joint.encode())
        if at < 0:
            raise invalid("the arm profile has no joint %r" % joint)
        sid = int(N.lib.lsc_arm_joint(a._handle, at).contents.id)
        c = self._c
        old = ctypes.c_uint8()
        with c._locked():
            self._bus()
            d = c._handle()
            reason = ctypes.c_int(N.LSC_LX_DONE)
            rc = c._foreign(N.lib.lsc_device_lx_replace, d, a._handle, joint.encode(),
                            ctypes.byref(old), ctypes.byref(reason))
            self._checked(rc, reason.value)
            limits = self._pair("replace", sid, None, N.lib.lsc_lxclient_read_limits, None)
        return Replaced(joint, old.value, sid, limits)

    def check_arm(self, arm: Optional[Union[Arm, str]] = None) -> int:
        """Whether every joint of arm (default the controller's profile)
        answers on the bus, once: returns the number of joints; lsc.Timeout
        (a joint's servo does not answer) or lsc.LinkError (two servos share
        a joint's id: their answers collide) naming the joint."""
        a = self._arm(arm, "check_arm")
        c = self._c
        with c._locked():
            self._bus()
            return c._check(c._foreign(N.lib.lsc_device_lx_check_arm, c._handle(), a._handle))


class _Bus:
    """lsc.Controller's accessor of the bus (lsc/servo.py)."""

    @property
    def servo(self) -> BusServos:
        """What only a bus servo has (lsc.BusServos), on a bus of servos
        opened as lsc.open("lx:PATH"); on any other controller its calls
        raise lsc.InvalidArgument, nothing sent."""
        assert isinstance(self, _Handle)
        return BusServos(self)
