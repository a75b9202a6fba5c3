"""A controller by name (lsc/device.h): lsc.open() and lsc.Controller, lsc.ports().

Times: arguments named *_ms are milliseconds (ints, as in the C library);
`timeout` arguments of calls that wait for the controller to do something are
seconds (float; None waits without limit, Ctrl-C still ends the wait at once).
Every request waits at most the controller's timeout_ms for its reply.
"""
import ctypes
import os
import time
from typing import (Any, Callable, Dict, Iterable, List, Mapping, NamedTuple, Optional, Sequence,
                    Union)

from . import _native as N
from . import hand as _hand
from .arm import Arm, Key, Pose, Value, degrees as _degrees, servo_id as _servo_id, target as _target
from ._check import integer as _int, number as _number, octets as _octets, shown as _shown
from .errors import Error, Stalled, Timeout, error_for, fs_bytes, invalid, wrong_type

from .events import ALL_GROUPS, Notification, NotificationKind, _Events, _notification
from .lscd import _Lscd
from .play import PlayResult, PlayStep, _Play
from .servo import _Bus  # (a bus of servos: Controller.servo)
from ._handle import _KIND_NAMES, Kind, _distinct, _keys, _timeout_ms

__all__ = ["open", "Controller", "Kind", "Notification", "NotificationKind", "Port", "PlayStep",
           "PlayResult", "MoveResult", "StoppedServo", "ports", "ALL_GROUPS"]


class Port(NamedTuple):
    """A controller (or serial port) found by lsc.ports()."""
    name: str           #: what lsc.open takes for it ("/dev/ttyUSB0", "hid:SERIAL")
    path: str           #: the device node
    kind: "Kind"        #: Kind.SERIAL or Kind.HID
    description: str
    serial: str         #: USB serial number ("" if unknown)
    manufacturer: str
    vid: int            #: USB ids (0 when not USB)
    pid: int
    usb: bool
    controller: bool    #: a known controller (HID) or a controller's USB adapter (serial)


class StoppedServo(NamedTuple):
    """A servo that stopped short of its target during move(wait=True): its
    reads stayed within 3 positions of each other for 200 ms outside the
    tolerance (a gripper holding something, a joint against an obstacle)."""
    servo: Any      #: as move() was given it: an id or a joint's name
    id: int         #: its servo id
    position: int   #: where it stopped
    target: int     #: where it was going
    short: int      #: how far from the target: abs(target - position)


class MoveResult(NamedTuple):
    """How move(wait=True) ended. Falsy when a servo stopped short."""
    stopped: List[StoppedServo]  #: the servos that stopped short ([]: all arrived)
    reads: bool                  #: False: the controller does not answer position
                                 #: reads, so only the move's time was waited for
    message: str                 #: the library's line saying where they stopped ("")

    def __bool__(self) -> bool:
        return not self.stopped


class HoldResult(NamedTuple):
    """What hold() did. Falsy when a joint was held beyond its limits."""
    held: Dict[Any, int]  #: each servo (as given, ranges and "all" as ids): its position
    beyond: List[Any]     #: the servos held beyond their joints' limits ([]: none)
    message: str          #: the library's line naming the first of them ("")

    def __bool__(self) -> bool:
        return not self.beyond


class Controller(_Events, _Lscd, _Play, _Bus):
    """A controller, opened by lsc.open(). A context manager: `with
    lsc.open("sim") as c: ...` closes it at the end.

    One call at a time runs on a controller (calls from several threads take
    turns); a wait for notifications (run(wait=True), wait_group) lets another
    thread's call in at once and goes on; stop() and halt() from another
    thread end a play, record or move's wait there at once.

    Its parts: lsc/_handle.py (the handle, one call at a time, callbacks,
    interrupts), lsc/events.py (notifications, event loops), lsc/lscd.py
    (status, lease), lsc/play.py (play, record), lsc/servo.py (servo: what
    only a bus servo has); here requests, commands and the trace.
    """

    # ---- requests --------------------------------------------------------------------

    def battery(self) -> int:
        """The battery voltage in millivolts."""
        mv = ctypes.c_uint16()
        self._call(N.lib.lsc_device_battery, ctypes.byref(mv))
        return mv.value

    def read(self, servos: Union[Key, Iterable[Key]], degrees: bool = False
             ) -> Dict[Key, Union[int, Optional[float]]]:
        """The positions of servos (ids or, with an arm profile, joint names;
        a string may list several: "1-6", "1,3-5", or "all": the profile's
        joints, else every id of the controller's kind) as {servo as given:
        position}. degrees=True: each joint's angle in degrees instead (None
        for a servo on no joint), which needs an arm profile."""
        keys = self._expand(_keys(servos))
        if not keys:
            raise invalid("read needs at least one servo")
        if degrees and self._arm is None:
            raise invalid("degrees=True needs an arm profile (lsc.open(..., arm=...))")
        ids = [_servo_id(self._arm, k) for k in keys]
        _distinct(ids, keys)
        arr = (ctypes.c_uint8 * len(ids))(*ids)
        out = (N.Servo * len(ids))()
        self._call(N.lib.lsc_device_read, arr, len(ids), out)
        if degrees:
            return {k: _degrees(self._arm, s.id, s.position) for k, s in zip(keys, out)}
        return {k: s.position for k, s in zip(keys, out)}

    def offsets(self, servos: Union[Key, Iterable[Key]]) -> Dict[Key, int]:
        """The xArm's servo offsets (command 23) as {servo as given: offset}.
        LSC boards may not answer (lsc.Timeout)."""
        keys = _keys(servos)
        if not keys:
            raise invalid("offsets needs at least one servo")
        ids = [_servo_id(self._arm, k) for k in keys]
        _distinct(ids, keys)
        arr = (ctypes.c_uint8 * len(ids))(*ids)
        out = (N.ServoOffset * len(ids))()
        self._call(N.lib.lsc_device_read_offsets, arr, len(ids), out)
        return {k: s.offset for k, s in zip(keys, out)}

    def request(self, cmd: int, params: bytes = b"", reply_cmd: Optional[int] = None) -> bytes:
        """A raw request: sends cmd with params, returns the parameters of the
        first frame whose command is reply_cmd (default: cmd)."""
        cmd = _int("cmd", cmd, 0, 255)
        reply_cmd = cmd if reply_cmd is None else _int("reply_cmd", reply_cmd, 0, 255)
        params = _octets("params", params)
        if len(params) > N.LSC_PARAMS_MAX:
            raise invalid("at most %d parameter bytes, not %d" % (N.LSC_PARAMS_MAX, len(params)))
        p = (ctypes.c_uint8 * max(1, len(params))).from_buffer_copy(params.ljust(1, b"\0"))
        reply = (ctypes.c_uint8 * N.LSC_PARAMS_MAX)()
        n = self._call(N.lib.lsc_device_request, cmd, p, len(params), reply_cmd, reply,
                       len(reply))
        return bytes(reply[:n])

    # ---- commands ----------------------------------------------------------------------

    def move(self, targets: Mapping[Key, Value], time_ms: Optional[int] = None,
             wait: bool = False, tolerance: int = N.LSC_DEVICE_TOLERANCE_DEFAULT,
             strict: bool = False, speed: Optional[float] = None) -> Optional[MoveResult]:
        """Moves servos to targets over time_ms (0..65535; default 1000): {servo:
        target}, a servo an id or a joint's name, a target a position (int)
        or, for a joint, an angle: in degrees (float: 30.0, -15.5) or as text
        ("30deg", "-15.5deg"). What read(..., degrees=True) returned moves
        back to that pose: move(c.read(["base", "elbow"], degrees=True), 500).
        Everything is checked (ranges, the arm profile's limits) before
        anything is sent.

        speed (instead of time_ms): degrees a second (0.01..100000) for the
        joint that turns the most, from where the servos are (last moved or
        read; read first when not known), as lscctl move --speed: every
        servo must be a joint of the arm profile. The move's time is then
        that travel at that speed (at most 65535 ms).

        wait=True: returns, once the move's time has passed, when every
        servo reads within tolerance of its target or has stopped short of
        it (its reads stay within 3 positions for 200 ms: a gripper holding
        something), a MoveResult listing those that stopped short (falsy if
        any did), at once, not after the timeout; lsc.Timeout, naming the
        servo, when one still moving is not there within timeout_ms after
        the move's time. A controller that does not answer position reads is
        waited for the move's time only (result.reads False). strict=True: a
        servo stopping short raises lsc.Stalled (a Timeout) instead.
        wait=False returns None."""
        if speed is not None and time_ms is not None:
            raise invalid("give time_ms or speed, not both")
        time_ms = 1000 if time_ms is None else _int("time_ms", time_ms, 0, 65535)
        # (its range, 0.01..100000, is the library's to check: lscctl's message)
        speed_dps = None if speed is None else _number("speed (degrees a second)", speed)
        tolerance = _int("tolerance", tolerance, 0, 65535)
        if not isinstance(targets, Mapping):
            raise wrong_type("move takes {servo: target, ...}, not %s" % _shown(targets))
        if not targets:
            raise invalid("move needs at least one servo")
        servos = [_target(self._arm, k, v) for k, v in targets.items()]
        _distinct([i for i, _ in servos], list(targets))
        arr = (N.Servo * len(servos))(*[N.Servo(i, p) for i, p in servos])
        if speed_dps is None:
            self._call(N.lib.lsc_device_move, time_ms, arr, len(servos))
        else:  # the library times it (lsc_device_move_speed); the wait is settle()'s
            t = ctypes.c_uint16()
            self._call(N.lib.lsc_device_move_speed, arr, len(servos), speed_dps, False, 0, 0,
                       ctypes.byref(t), None)
            time_ms = t.value
        return self.settle(targets, time_ms, tolerance, strict) if wait else None

    def settle(self, targets: Mapping[Key, Value], time_ms: int = 0,
               tolerance: int = N.LSC_DEVICE_TOLERANCE_DEFAULT, strict: bool = False
               ) -> MoveResult:
        """move(wait=True)'s wait on its own, for a move sent otherwise (send(),
        another program): lets time_ms pass, then reads the servos until each
        is within tolerance of its target or has stopped short of it. The
        same MoveResult, lsc.Timeout and lsc.Stalled as move()."""
        time_ms = _int("time_ms", time_ms, 0, 65535)
        tolerance = _int("tolerance", tolerance, 0, 65535)
        if not isinstance(targets, Mapping) or not targets:
            raise invalid("settle takes {servo: target, ...} (at least one), not %r"
                          % (targets,))
        servos = [_target(self._arm, k, v) for k, v in targets.items()]
        _distinct([i for i, _ in servos], list(targets))
        if len(servos) > N.LSC_READ_MAX:
            raise invalid("settle: at most %d servos, not %d" % (N.LSC_READ_MAX, len(servos)))
        arr = (N.Servo * len(servos))(*[N.Servo(i, p) for i, p in servos])
        res = N.SettleResult()
        with self._locked():
            d = self._handle()
            rc = self._foreign(N.lib.lsc_device_settle_ex, d, arr, len(servos), time_ms,
                               tolerance, N.LSC_SETTLE_STRICT if strict else 0,
                               ctypes.byref(res), own=True, long="motion")
            return self._settled(rc, res, {i: k for k, (i, _) in zip(targets, servos)})

    def _settled(self, rc: int, res: N.SettleResult, keys: Mapping[int, Any]) -> MoveResult:
        """The outcome rc of lsc_device_settle_ex (or of lsc_device_reach's
        wait), res what it saw, keys each servo id as the caller named it:
        the MoveResult, or lsc.Stalled, or rc's exception (the lock held)."""
        d = self._d
        message = N.text(N.lib.lsc_device_error(d))
        stopped = [StoppedServo(keys.get(s.id, s.id), s.id, s.position, s.target,
                                abs(s.target - s.position))
                   for s in res.stopped[:res.nstopped]]
        if rc < 0 and N.lib.lsc_device_error_cause(d) == N.LSC_DEVICE_CAUSE_STOPPED_SHORT:
            self._check(0)  # a callback's exception first
            raise Stalled(message, rc, stopped)
        self._check(rc)
        return MoveResult(stopped, rc != N.LSC_SETTLE_NO_READS,
                          message if rc == N.LSC_SETTLE_STOPPED else "")

    def where(self) -> "Pose":
        """Where the grasp point is: reads the joints of the arm profile's
        chain (the profile must state its geometry, docs/kinematics.md)."""
        return _hand.where(self)

    def reach(self, point: Sequence[float], pitch: Optional[float] = None, time_ms: Optional[int] = None,
              speed: Optional[float] = None, line: bool = False, wait: bool = False,
              roll: Optional[float] = None, step_mm: Optional[float] = None,
              tolerance: int = N.LSC_DEVICE_TOLERANCE_DEFAULT, strict: bool = False
              ) -> "_hand.ReachResult":
        """Moves the grasp point to point (x, y, z in mm) with the hand at
        pitch (None: the one nearest its current pitch that reaches it) over
        time_ms (default 1000), or at speed degrees a second for the joint that
        turns the most; line=True keeps it on the straight line from where it
        is (waypoints every step_mm, default 5). wait=True and strict as
        move(): a joint that stops short of its target (against an obstacle)
        ends the wait at once, listed in the result's stopped (by its name;
        the result is falsy then), or raises lsc.Stalled with strict=True.
        Out of reach or beyond a limit: lsc.Unreachable, nothing sent."""
        return _hand.reach(self, point, pitch, roll, time_ms, speed, line, step_mm, wait,
                           _int("tolerance", tolerance, 0, 65535), bool(strict))

    def run(self, group: int, times: int = 1, wait: bool = False,
            timeout: Optional[float] = None) -> Optional[Notification]:
        """Runs action group (0..255) times times (0: for ever). wait=True:
        returns the notification of its end (its completion, or a stop), or
        lsc.Timeout after timeout seconds (None: no limit; on "sim" a wait that
        could never end is lsc.Timeout at once). A group the board does not
        have never starts: lsc.NeverStarted (a Timeout) when its start has not
        come within about a second of the run (the frames' time on the line
        plus the reply timeout, at most 1 s; "sim": at once). Notifications
        that arrived before the run are never taken for its start."""
        group = _int("group", group, 0, 255)
        times = _int("times", times, 0, 65535)
        _timeout_ms(timeout)  # checked before anything is sent
        self._call(N.lib.lsc_device_run, group, times)
        return self.wait_group(group, timeout) if wait else None

    def wait_group(self, group: Optional[int] = None, timeout: Optional[float] = None
                   ) -> Notification:
        """Waits for the end of group (after its start following the last
        run() of it, or from now), or of any group when group is None, taking
        notifications as it goes. A stop followed at once (within 50 ms) by
        the same group's start is the controller starting it again, not an
        end: the wait goes on. lsc.Timeout after timeout seconds."""
        group = N.LSC_GROUP_ALL if group is None else _int("group", group, 0, 255)
        out = N.NotificationC()
        self._wait(lambda ms: int(N.lib.lsc_device_wait_group(self._d, group, ms,
                                                              ctypes.byref(out))), timeout)
        return _notification(out)

    def stop(self) -> None:
        """Stops the running action group (no effect if none runs). From
        another thread it also ends a play or record there at once (which
        returns what it did so far), or a move's wait (lsc.Interrupted)."""
        with self._stopping():
            self._call(N.lib.lsc_device_stop)

    def speed(self, group: Optional[int], percent: int) -> None:
        """Sets a group's speed in percent of the original (100; 200 is twice as
        fast); group None or lsc.ALL_GROUPS: every group."""
        group = N.LSC_GROUP_ALL if group is None else _int("group", group, 0, 255)
        percent = _int("percent", percent, 1, 65535)
        self._call(N.lib.lsc_device_speed, group, percent)

    def halt(self) -> str:
        """Stops everything at once: the running action group, and every
        servo where it is (they hold their positions): every servo is the arm
        profile's joints, else every id of the controller's kind (1..6 over
        HID, 1..32 otherwise). Through lscd it is never refused for another
        client's lease. Returns "" or, when a joint was held beyond its limits
        (moved there by hand), the library's line that names it. From
        another thread it ends a play, record or move's wait there first, as
        stop() does."""
        with self._stopping():
            rc = self._call(N.lib.lsc_device_halt)
        return N.text(N.lib.lsc_device_error(self._d)) if rc == N.LSC_HOLD_BEYOND else ""

    def hold(self, servos: Union[Key, Iterable[Key], None] = None) -> HoldResult:
        """Holds servos where they are (None: "all"): reads their positions
        and moves each there (an unloaded servo is powered again). A joint
        beyond its limits is held there too, listed in the result's beyond
        (moving it further out stays refused)."""
        keys = self._expand(_keys("all" if servos is None else servos))
        if not keys:
            raise invalid("hold needs at least one servo")
        ids = [_servo_id(self._arm, k) for k in keys]
        _distinct(ids, keys)
        if len(ids) > N.LSC_MOVE_MAX:
            raise invalid("hold: at most %d servos, not %d" % (N.LSC_MOVE_MAX, len(ids)))
        arr = (ctypes.c_uint8 * len(ids))(*ids)
        res = N.HoldResult()
        with self._locked():
            d = self._handle()
            rc = self._check(self._foreign(N.lib.lsc_device_hold, d, arr, len(ids),
                                           ctypes.byref(res)))
            message = N.text(N.lib.lsc_device_error(d)) if rc == N.LSC_HOLD_BEYOND else ""
        by_id = dict(zip(ids, keys))
        held = {by_id[s.id]: s.position for s in res.held[:res.n]}
        return HoldResult(held, [by_id[i] for i in res.beyond[:res.nbeyond]], message)

    def unload(self, servos: Union[Key, Iterable[Key]]) -> None:
        """Powers servos off (they turn freely by hand until the next move);
        a string may list several, as for read(): "all", "1-6"."""
        keys = self._expand(_keys(servos))
        if not keys:
            raise invalid("unload needs at least one servo")
        ids = [_servo_id(self._arm, k) for k in keys]
        _distinct(ids, keys)
        arr = (ctypes.c_uint8 * len(ids))(*ids)
        self._call(N.lib.lsc_device_unload, arr, len(ids))

    def adjust_offset(self, servo: Key, offset: int) -> None:
        """The xArm's servo offset adjust (command 24): offset -128..127."""
        sid = _servo_id(self._arm, servo)
        offset = _int("offset", offset, -128, 127)
        self._call(N.lib.lsc_device_adjust_offset, sid, offset)

    def send(self, cmd: int, params: bytes = b"", force: bool = False) -> None:
        """A raw frame. Commands 8 (erases the action groups on xArm firmware)
        and 27 (writes a setting to every servo on the bus) are refused unless
        force=True."""
        cmd = _int("cmd", cmd, 0, 255)
        params = _octets("params", params)
        if len(params) > N.LSC_PARAMS_MAX:
            raise invalid("at most %d parameter bytes, not %d" % (N.LSC_PARAMS_MAX, len(params)))
        p = (ctypes.c_uint8 * max(1, len(params))).from_buffer_copy(params.ljust(1, b"\0"))
        self._call(N.lib.lsc_device_send, cmd, p, len(params), bool(force))

    # ---- tracing -------------------------------------------------------------------

    def trace(self, fn: Optional[Callable[[str, bytes], Any]]) -> None:
        """Calls fn("tx" or "rx", frame bytes) for every frame sent and received
        (None: stop). An exception fn raises ends the call that traced it.
        Anything that is neither callable nor None is refused here (TypeError)."""
        if fn is not None and not callable(fn):
            raise TypeError("trace takes a function f(direction, frame) or None, not %r" % (fn,))
        if fn is None:
            with self._locked():
                N.lib.lsc_device_set_trace(self._handle(), N.TRACE_FN(), None)  # type: ignore
                self._trace_fn = self._trace_py = None
            return

        call: Callable[[str, bytes], Any] = fn

        def tramp(_user: Any, direction: int, frame: Any, n: int) -> None:
            try:
                call("tx" if direction == N.LSC_TRACE_TX else "rx", ctypes.string_at(frame, n))
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                if self._pending is None:
                    self._pending = e
        with self._locked():
            self._trace_fn = N.TRACE_FN(tramp)
            self._trace_py = tramp
            N.lib.lsc_device_set_trace(self._handle(), self._trace_fn, None)


def open(name: Optional[Union[str, bytes, "os.PathLike[str]"]] = None, arm: Optional[Union[Arm, str, "os.PathLike[str]"]] = None,
         timeout_ms: int = N.LSC_DEVICE_TIMEOUT_DEFAULT, baud: Optional[int] = None,
         hid_vid: int = 0, hid_pid: int = 0) -> Controller:
    """Opens the controller name:
      "sim"            the built-in virtual controller (groups 1, 2 and 8)
      "/dev/ttyUSB0"   a serial port (also lsc-sim's pseudo-terminal)
      "hid"            the one USB HID controller present (xArm, LeArm)
      "hid:SERIAL"     the HID controller with that USB serial number
      "/dev/hidrawN"   a hidraw node
      "lscd:NAME"      the controller lscd shares on $LSC_LSCD_DIR/NAME.sock
                       (default /run/lsc/NAME.sock; NAME: ttyUSB0, hid-SERIAL, sim)
      "lscd:PATH"      the controller lscd shares on the socket PATH
      "lx:/dev/ttyUSB0" a bus of serial bus servos (a BusLinker, or any serial
                       port on the servos' bus, lsc-sim --lx's pseudo-terminal):
                       move, read, unload, settle, arm profiles, play and
                       record as on a board; Controller.servo has what only
                       a bus servo has (lsc.BusServos)
      None             $LSC_PORT, else the one controller present
    A port that lscd holds is used through lscd.
    A name, like every path the package takes, is a str, bytes or
    os.PathLike, taken as os.fsencode takes it (a str's undecodable bytes
    through surrogateescape).
    arm: an lsc.Arm, a profile's name ("xarm": an installed profile, or
    ~/.config/lsc/arms/xarm.conf) or a profile's path (lsc.Arm has the rule):
    moves and reads then take joint names and angles, and are checked
    against its limits; None: $LSC_ARM's profile when it is set, as lscctl
    takes it, else the profile calibrated for the arm on that controller
    (lscctl calibrate: $XDG_CONFIG_HOME/lsc/arms/KEY.conf) when there is
    one. timeout_ms: how long each
    request waits for its reply; baud: serial ports' speed (None: the
    kind's own, 9600 for a board, 115200 for a bus);
    hid_vid/hid_pid: another HID controller's USB ids to accept (0, 0:
    $LSC_HID_ID's, when it is set). The environment is read by the library,
    the same way for every front end (lsc/env.h).

    Raises lsc.NotFound, lsc.PermissionDenied (the message says how to get
    access), lsc.Busy (another program has the port), lsc.InvalidArgument.
    Nothing is sent by the open."""
    if name is not None and not isinstance(name, (str, bytes, os.PathLike)):
        raise wrong_type("a controller's name is a str, bytes or os.PathLike, not %s"
                         % _shown(name))
    settings = (None if baud is None else _int("baud", baud, 1, N.LSC_DEVICE_BAUD_MAX),
                _int("timeout_ms", timeout_ms, 1, N.LSC_DEVICE_TIMEOUT_MAX),
                _int("hid_vid", hid_vid, 0, 0xFFFF), _int("hid_pid", hid_pid, 0, 0xFFFF))
    cfg = N.lib.lsc_device_config_new()
    if not cfg:
        raise MemoryError("out of memory")
    try:
        return _open(name, arm, cfg, *settings)
    finally:
        N.lib.lsc_device_config_free(cfg)


def _open(name: Optional[Union[str, bytes, "os.PathLike[str]"]],
          arm: Optional[Union[Arm, str, "os.PathLike[str]"]], cfg: int,
          baud: Optional[int], timeout_ms: int, hid_vid: int, hid_pid: int) -> Controller:
    """open() with its settings checked, through the config cfg."""
    # (the values are within the setters' ranges: checked above)
    if baud is not None:  # (else the kind's own: a bus's is not a board's)
        N.lib.lsc_device_config_set_baud(cfg, baud)
    N.lib.lsc_device_config_set_timeout_ms(cfg, timeout_ms)
    N.lib.lsc_device_config_set_hid_id(cfg, hid_vid, hid_pid)
    why = ctypes.create_string_buffer(256)
    if N.lib.lsc_device_config_from_env(cfg, why, len(why)) != 0:
        raise invalid(N.text(why.value))
    encoded = None
    if name is not None:
        encoded = fs_bytes(name, "the controller's name")
        name = os.fsdecode(encoded)
    if arm is None:
        env_arm = N.lib.lsc_device_env_arm()
        arm = os.fsdecode(env_arm) if env_arm else None
    if arm is None:
        # the arm's calibrated profile, when its controller has one (lscctl calibrate)
        found = ctypes.create_string_buffer(4096)
        port = encoded if encoded is not None else N.lib.lsc_device_env_port()
        if N.lib.lsc_calibrated_find(port, found, len(found)) == 0:
            arm = os.fsdecode(found.value)
    if arm is not None and not isinstance(arm, Arm):
        arm = Arm(arm)
    handle = ctypes.c_void_p()
    rc = N.lib.lsc_device_open(encoded, cfg, ctypes.byref(handle))
    if rc < 0:
        # no handle: the library keeps what this thread's open said (NULL)
        message = N.text(N.lib.lsc_device_error(None))
        # (a HID name's kind is known before anything is opened: the name decides)
        hid = N.lib.lsc_device_kind_of(None) == N.LSC_DEVICE_HID
        cause = N.lib.lsc_device_error_cause(None)
        raise error_for(rc, message, hid=hid, cause=cause)
    c = Controller(handle, None)
    if arm is not None:
        try:
            c.arm = arm
        except BaseException:
            c.close()
            raise
    return c


def ports() -> List[Port]:
    """The serial ports and HID controllers present (serial ports first).
    lsc.Error when neither kind can be listed."""
    out = ctypes.POINTER(ctypes.c_void_p)()
    msg = ctypes.create_string_buffer(512)
    n = N.lib.lsc_device_list(ctypes.byref(out), msg, len(msg))
    if n < 0:
        raise error_for(n, N.text(msg.value))
    L = N.lib
    try:
        return [Port(N.text(L.lsc_device_info_name(i)), N.text(L.lsc_device_info_path(i)),
                     _KIND_NAMES.get(L.lsc_device_info_kind(i), Kind.SERIAL),
                     N.text(L.lsc_device_info_description(i)),
                     N.text(L.lsc_device_info_serial(i)),
                     N.text(L.lsc_device_info_manufacturer(i)),
                     L.lsc_device_info_vid(i), L.lsc_device_info_pid(i),
                     bool(L.lsc_device_info_usb(i)), bool(L.lsc_device_info_controller(i)))
                for i in (out[k] for k in range(n))]
    finally:
        N.lib.lsc_device_list_free(out)
