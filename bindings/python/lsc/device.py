"""A controller by name (lsc/device.h): lsc.open() and lsc.Controller, lsc.ports().

Times: arguments named *_ms are milliseconds (ints, as in the C library);
`timeout` arguments of calls that wait for the controller to do something are
seconds (float; None waits without limit, Ctrl-C still ends the wait at once).
Every request waits at most the controller's timeout_ms for its reply.
"""
import asyncio
import contextlib
import ctypes
import enum
import io
import math
import os
import sys
import threading
import time
from typing import (Any, AsyncIterator, Callable, Dict, Iterable, Iterator, List, Mapping,
                    NamedTuple, Optional, Union)

from . import _native as N
from . import hand as _hand
from .action import Action
from .arm import Arm, Key, Pose, Value, degrees as _degrees, servo_id as _servo_id, target as _target
from ._check import (integer as _int, number as _number, octets as _octets,
                     seconds as _seconds, shown as _shown)
from .errors import Error, Stalled, Timeout, error_for, fs_bytes, invalid, wrong_type

__all__ = ["open", "Controller", "Notification", "NotificationKind", "Port", "PlayStep",
           "PlayResult", "MoveResult", "StoppedServo", "ports", "ALL_GROUPS"]

#: The group number that means every group (speed) or any group (wait_group).
ALL_GROUPS = N.LSC_GROUP_ALL

# Waits on a real link are made of calls of at most this long, so that Ctrl-C
# (KeyboardInterrupt) and other threads' calls get in between.
_CHUNK_MS = 100


class NotificationKind(str, enum.Enum):
    """What a notification says; equal to the names lscctl prints."""
    RUN = "action_group_run"            #: a group started (command 6)
    STOP = "action_group_stop"          #: a running group was forced to stop (7)
    COMPLETE = "action_group_complete"  #: a group ran to its end (8)

    def __str__(self) -> str:
        return self.value

    def __repr__(self) -> str:
        return repr(self.value)


_KINDS = {N.LSC_CMD_GROUP_RUN: NotificationKind.RUN,
          N.LSC_CMD_GROUP_STOP: NotificationKind.STOP,
          N.LSC_CMD_GROUP_COMPLETE: NotificationKind.COMPLETE}


class Notification(NamedTuple):
    """A notification from the controller. For a stop, group and times are 0
    (the frame carries none)."""
    kind: NotificationKind
    group: int
    times: int

    @property
    def cmd(self) -> int:
        """The command value: 6, 7 or 8."""
        return {v: k for k, v in _KINDS.items()}[self.kind]


def _notification(n: N.NotificationC) -> Notification:
    return Notification(_KINDS.get(n.cmd, NotificationKind.STOP), n.group, n.times)


class Port(NamedTuple):
    """A controller (or serial port) found by lsc.ports()."""
    name: str           #: what lsc.open takes for it ("/dev/ttyUSB0", "hid:SERIAL")
    path: str           #: the device node
    kind: str           #: "serial" or "hid"
    description: str
    serial: str         #: USB serial number ("" if unknown)
    manufacturer: str
    vid: int            #: USB ids (0 when not USB)
    pid: int
    usb: bool
    controller: bool    #: a known controller (HID) or a controller's USB adapter (serial)


_KIND_NAMES = {N.LSC_DEVICE_SERIAL: "serial", N.LSC_DEVICE_HID: "hid", N.LSC_DEVICE_SIM: "sim",
               N.LSC_DEVICE_LSCD: "lscd", N.LSC_DEVICE_LX: "lx"}


class PlayStep(NamedTuple):
    """A frame lsc.Controller.play sent (to its progress callback)."""
    keyframe: int            #: 0..len(action)-1
    repetition: int          #: 0..times-1
    lead_in: bool            #: the move to keyframe 0 over lead_ms
    due_ms: int              #: when it was due, ms after the start
    time_ms: int             #: the move's time
    servos: Dict[int, int]   #: id -> position (servos that did not change are left out)
    dropped: int             #: keyframes dropped just before it (the line could not keep up)


class PlayResult(NamedTuple):
    """What a play did."""
    frames: int         #: frames sent
    dropped: int        #: keyframes dropped: faster than the line carries
    keyframe: int       #: 1-based keyframe of the last frame sent (0: none)
    max_late_ms: int    #: the latest a frame went out after its due time
    total_ms: int       #: the whole schedule: the end of the last move after the start
    stopped: bool       #: the progress callback stopped it


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


def _is_list(k: Any) -> bool:
    """Whether a servo key is a list in one string: "all", "1-6", "1,3-5"."""
    return isinstance(k, str) and (k == "all" or "," in k or "-" in k[1:])


def _timeout_ms(timeout: Optional[float]) -> Optional[int]:
    """A timeout in seconds (None: no limit) as ms, rounded up."""
    return _seconds("a timeout", timeout)


def _keys(ids: Union[Key, Iterable[Key]]) -> List[Key]:
    if isinstance(ids, (int, str)):
        return [ids]
    try:
        return list(ids)
    except TypeError:
        raise wrong_type("servos are an id, a joint's name, or several of them, not %s"
                         % _shown(ids)) from None


def _distinct(ids: List[int], keys: List[Any]) -> None:
    """Refuses a servo named twice (e.g. a joint's name and its id): the
    library's rule (lsc_ids_first_repeat)."""
    arr = (ctypes.c_uint8 * max(1, len(ids)))(*ids)
    at = N.lib.lsc_ids_first_repeat(arr, 1, len(ids))
    if at < len(ids):
        first = keys[ids.index(ids[at])]
        same = "" if first == keys[at] else " (%r and %r)" % (first, keys[at])
        raise invalid("servo %d appears twice%s" % (ids[at], same))


class Controller:
    """A controller, opened by lsc.open(). A context manager: `with
    lsc.open("sim") as c: ...` closes it at the end.

    One call at a time runs on a controller (calls from several threads take
    turns); a wait (notifications, run(wait=True), move(wait=True)) lets other
    threads' calls in between its steps, e.g. stop() from another thread.
    """

    def __init__(self, handle: ctypes.c_void_p, arm: Optional[Arm]):
        self._d = handle
        self._lock = threading.RLock()
        self._ilock = threading.Lock()  # interrupt() against close(): never held long
        self._arm = arm
        self._pending: Optional[BaseException] = None  # raised in a callback
        self._trace_fn = None  # keeps the C callback alive
        self._trace_py = None
        self._sim = N.lib.lsc_device_kind_of(handle) == N.LSC_DEVICE_SIM
        self._ready_at = time.monotonic()  # "sim": real time its clock last caught up

    # ---- the handle ------------------------------------------------------------

    def _handle(self) -> ctypes.c_void_p:
        if not self._d:
            raise Error("the controller is closed")
        return self._d

    def _check(self, rc: int) -> int:
        """rc, or the exception for a negative rc with the device's message."""
        pending, self._pending = self._pending, None
        if pending is not None:
            raise pending
        if rc < 0:
            raise error_for(rc, N.text(N.lib.lsc_device_error(self._d)),
                            hid=self.kind == "hid", cause=N.lib.lsc_device_error_cause(self._d))
        return rc

    def _call(self, fn, *args) -> int:
        with self._lock:
            d = self._handle()
            with self._guard():
                return self._check(fn(d, *args))

    def _guard(self):
        """_callbacks for the trace function, if one is set."""
        if self._trace_py is None:
            return contextlib.nullcontext()
        return self._callbacks(self._trace_py)

    @contextlib.contextmanager
    def _callbacks(self, *fns):
        """While the C library may call fns back: an exception one of them
        could not catch itself (a KeyboardInterrupt raised as it is entered,
        which ctypes reports as unraisable and then returns 0: stop) is kept
        and raised once the C call returns (_check)."""
        previous = sys.unraisablehook

        def hook(u):
            if u.object in fns or (u.err_msg or "").find("ctypes callback") >= 0:
                if self._pending is None:
                    self._pending = u.exc_value
            else:
                previous(u)
        sys.unraisablehook = hook
        try:
            yield
        finally:
            sys.unraisablehook = previous

    def close(self) -> None:
        """Closes the port (again is fine)."""
        with self._lock, self._ilock:
            if self._d:
                N.lib.lsc_device_close(self._d)
                self._d = None

    def interrupt(self) -> None:
        """Ends the call that waits for the controller now (from another
        thread: a play, a record, a wait, a request's wait for its reply),
        which raises lsc.Interrupted; when none waits, the next one that
        would does. Commands that only send (stop(), move()) neither wait
        nor take it. Safe from any thread; a no-op on a closed controller.
        (lsc_device_interrupt)"""
        with self._ilock:
            if self._d:
                N.lib.lsc_device_interrupt(self._d)

    def __enter__(self) -> "Controller":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __del__(self):
        if getattr(self, "_d", None) and N is not None and N.lib is not None:
            N.lib.lsc_device_close(self._d)
            self._d = None

    def __repr__(self) -> str:
        if not self._d:
            return "<lsc.Controller closed>"
        return "<lsc.Controller %s (%s)>" % (self.name, self.kind)

    # ---- what it is --------------------------------------------------------------

    @property
    def closed(self) -> bool:
        return not self._d

    @property
    def name(self) -> str:
        """The name it was opened as, after discovery ("/dev/ttyUSB0", "hid:1A2B", "sim")."""
        with self._lock:
            return N.text(N.lib.lsc_device_name(self._handle()))

    @property
    def kind(self) -> str:
        """"serial", "hid", "sim", "lscd" (through lscd: "lscd:NAME", or a
        port lscd holds) or "lx" (a bus of servos: "lx:PATH")."""
        with self._lock:
            return _KIND_NAMES.get(N.lib.lsc_device_kind_of(self._handle()), "serial")

    @property
    def arm(self) -> Optional[Arm]:
        """The arm profile moves and reads use (None: ids and positions only)."""
        return self._arm

    @arm.setter
    def arm(self, arm: Optional[Union[Arm, str, "os.PathLike[str]"]]) -> None:
        if arm is not None and not isinstance(arm, Arm):
            arm = Arm(arm)
        self._call(N.lib.lsc_device_set_arm, None if arm is None else arm._handle)
        self._arm = arm

    @property
    def timeout_ms(self) -> int:
        """How long each request waits for its reply (ms)."""
        with self._lock:
            return int(N.lib.lsc_device_timeout(self._handle()))

    @timeout_ms.setter
    def timeout_ms(self, ms: int) -> None:
        ms = _int("timeout_ms", ms, 1, N.LSC_DEVICE_FOREVER - 1)
        with self._lock:
            N.lib.lsc_device_set_timeout(self._handle(), ms)

    def now_ms(self) -> int:
        """The controller's monotonic clock in ms (the virtual one for "sim")."""
        with self._lock:
            return int(N.lib.lsc_device_now_ms(self._handle()))

    def groups(self) -> List[int]:
        """The action groups the controller is known to hold: "sim" has its demo
        groups (1, 2, 8); a real controller does not say ([])."""
        with self._lock:
            d = self._handle()
            n = N.lib.lsc_device_groups(d, None, 0)
            out = (ctypes.c_uint8 * max(1, n))()
            n = N.lib.lsc_device_groups(d, out, n)
            return list(out[:n])

    @property
    def dropped_notifications(self) -> int:
        """Notifications dropped because more than 64 were waiting to be read."""
        with self._lock:
            return int(N.lib.lsc_device_dropped_notifications(self._handle()))

    # ---- requests --------------------------------------------------------------------

    def battery(self) -> int:
        """The battery voltage in millivolts."""
        mv = ctypes.c_uint16()
        self._call(N.lib.lsc_device_battery, ctypes.byref(mv))
        return mv.value

    def _expand(self, keys: List[Key]) -> List[Key]:
        """keys with each list in one string ("all": the arm profile's
        joints, else every id of the controller's kind; "1-6"; "1,3-5")
        replaced by its ids (lsc_device_parse_ids_all)."""
        if not any(_is_list(k) for k in keys):
            return keys
        out: List[Key] = []
        for k in keys:
            if not _is_list(k):
                out.append(k)
                continue
            ids = (ctypes.c_uint8 * N.LSC_UNLOAD_MAX)()
            why = ctypes.create_string_buffer(N.LSC_ARM_MESSAGE_MAX)
            n = N.lib.lsc_device_parse_ids_all(None if self._arm is None else self._arm._handle,
                                               self.name.encode(), str(k).encode(), ids,
                                               len(ids), why, len(why))
            if n < 0:
                raise invalid(why.value.decode(errors="replace"))
            out.extend(ids[:n])
        return out

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
        if not self._sim:
            self._poll_ms(time_ms)  # the move's time in steps: Ctrl-C gets in
            time_ms = 0
        res = N.SettleResult()
        with self._lock:
            d = self._handle()
            with self._guard():
                rc = N.lib.lsc_device_settle_ex(d, arr, len(servos), time_ms, tolerance,
                                                N.LSC_SETTLE_STRICT if strict else 0,
                                                ctypes.byref(res))
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

    def reach(self, point, pitch: Optional[float] = None, time_ms: Optional[int] = None,
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
        self._wait(lambda ms: N.lib.lsc_device_wait_group(self._d, group, ms,
                                                          ctypes.byref(out)), timeout)
        return _notification(out)

    def stop(self) -> None:
        """Stops the running action group (no effect if none runs)."""
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
        (moved there by hand), the library's line that names it."""
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
        with self._lock:
            d = self._handle()
            with self._guard():
                rc = self._check(N.lib.lsc_device_hold(d, arr, len(ids), ctypes.byref(res)))
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

    # ---- notifications ------------------------------------------------------------

    def _wait(self, step: Callable[[int], int], timeout: Optional[float]) -> int:
        """Runs step(ms) (a C wait returning LSC_ETIMEOUT when nothing came) for
        up to timeout seconds (None: no limit): at once on "sim" (virtual time),
        else in steps of at most _CHUNK_MS, so that Ctrl-C and other threads
        get in. Returns step's result or raises."""
        ms = _timeout_ms(timeout)
        if self._sim:
            with self._lock, self._guard():
                self._handle()
                return self._check(step(N.LSC_DEVICE_FOREVER if ms is None else ms))
        deadline = None if ms is None else time.monotonic() + ms / 1000
        while True:
            chunk = _CHUNK_MS
            if deadline is not None:
                left = max(0, math.ceil((deadline - time.monotonic()) * 1000))
                chunk = min(chunk, left)
            with self._lock, self._guard():
                self._handle()
                rc = step(chunk)
                # a timeout of this chunk goes on; any other (a group that
                # never started) ends the wait
                if rc != N.LSC_ETIMEOUT or (deadline is not None and chunk <= 0) or \
                        N.lib.lsc_device_error_cause(self._d) != \
                        N.LSC_DEVICE_CAUSE_WAIT_TIMEOUT or \
                        (deadline is not None and time.monotonic() >= deadline):
                    return self._check(rc)

    def notification(self, timeout: Optional[float] = None) -> Notification:
        """The oldest notification, waiting up to timeout seconds for one
        (lsc.Timeout if none came; None: no limit)."""
        out = N.NotificationC()
        self._wait(lambda ms: N.lib.lsc_device_notification(self._d, ms, ctypes.byref(out)),
                   timeout)
        return _notification(out)

    def notifications(self, timeout: Optional[float] = None) -> Iterator[Notification]:
        """The notifications as they arrive (groups started by anything: a
        button, a handset, another link); the iteration ends when none arrives
        for timeout seconds (None: never)."""
        while True:
            try:
                yield self.notification(timeout)
            except Timeout:
                return

    def poll(self, timeout: float = 0) -> int:
        """Reads what arrives for up to timeout seconds (0: only what is there),
        keeping notifications for notification(); returns how many came."""
        ms = _timeout_ms(timeout)
        if ms is None:
            raise invalid("poll needs a timeout in seconds")
        return self._poll_ms(ms)

    def _poll_ms(self, ms: int) -> int:
        """poll() for ms: at once on "sim", else in steps of at most
        _CHUNK_MS, so that Ctrl-C and other threads get in."""
        if self._sim:
            return self._call(N.lib.lsc_device_poll, ms)
        total = 0
        deadline = time.monotonic() + ms / 1000
        while True:
            left = math.ceil((deadline - time.monotonic()) * 1000)
            total += self._call(N.lib.lsc_device_poll, max(0, min(left, _CHUNK_MS)))
            if left <= _CHUNK_MS:
                return total

    # ---- in a program's own event loop (selectors, asyncio, a GUI's) ----------------

    def fileno(self) -> int:
        """The descriptor that polls readable when the controller (or lscd)
        sent something: the serial port's, over HID the node's (the kernel
        gives it a copy of each report), through lscd the socket. So a
        Controller can be registered with selectors, or loop.add_reader.
        Read through ready(), never on it. io.UnsupportedOperation for "sim"
        (its clock is virtual: next_event() says when it is due)."""
        with self._lock:
            fd = N.lib.lsc_device_fileno(self._handle())
        if fd < 0:
            raise io.UnsupportedOperation("%s has no descriptor: its clock is virtual; "
                                          "wait for next_event() instead" % self.name)
        return fd

    def next_event(self) -> Optional[float]:
        """Seconds the event loop may sleep without the descriptor saying
        so: 0 when something waits already (a queued notification, input
        a request read ahead), for "sim" the time until it sends something
        of its own accord; None: nothing is due but by the descriptor."""
        with self._lock:
            ms = N.lib.lsc_device_next_event_ms(self._handle())
        return None if ms == N.LSC_DEVICE_FOREVER else ms / 1000

    def ready(self) -> List[Notification]:
        """Reads what has arrived, without waiting, and returns every
        notification queued (oldest first): what an event loop calls when
        fileno() polled readable or next_event() came. On "sim" the time
        that really passed since the last ready() passes on its clock."""
        with self._lock:
            self._advance()
            return self._queued()

    def _advance(self) -> None:
        """lsc_device_poll: what has arrived; on "sim" the real time since
        it last caught up (the lock held)."""
        d = self._handle()
        ms = 0
        if self._sim:
            ms = min(3600000, max(0, int((time.monotonic() - self._ready_at) * 1000)))
            self._ready_at += ms / 1000
        with self._guard():
            self._check(N.lib.lsc_device_poll(d, ms))

    def _queued(self) -> List[Notification]:
        """Every queued notification (the lock held)."""
        got = []
        out = N.NotificationC()
        while N.lib.lsc_device_notification(self._d, 0, ctypes.byref(out)) == 0:
            got.append(_notification(out))
        return got

    async def _readable(self, fd: int, seconds: Optional[float]) -> None:
        """Until fd polls readable (fd < 0: never) or seconds passed (None:
        no limit), in the running loop."""
        loop = asyncio.get_running_loop()
        woke = asyncio.Event()
        if fd >= 0:
            loop.add_reader(fd, woke.set)
        try:
            await asyncio.wait_for(woke.wait(), seconds)
        except asyncio.TimeoutError:
            pass
        finally:
            if fd >= 0:
                loop.remove_reader(fd)

    async def _until(self, take: Callable[[], Optional[Any]], timeout: Optional[float],
                     what: str) -> Any:
        """Runs take() (it reads) until it gives something, waiting
        in the running loop; lsc.Timeout after timeout seconds (None: no
        limit), or at once on "sim" when nothing can come."""
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._lock:
            fd = N.lib.lsc_device_fileno(self._handle())
        while True:
            got = take()
            if got is not None:
                return got
            nxt = self.next_event()
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if left is not None and left <= 0:
                raise Timeout("%s within %s s" % (what, timeout), N.LSC_ETIMEOUT)
            if fd < 0 and nxt is None:
                raise Timeout("nothing runs on the virtual controller (%s), so nothing will "
                              "arrive" % self.name, N.LSC_ETIMEOUT)
            wait = nxt if left is None else left if nxt is None else min(nxt, left)
            await self._readable(fd, wait)

    async def anotifications(self, timeout: Optional[float] = None
                             ) -> AsyncIterator[Notification]:
        """The notifications as they arrive, awaited in the running asyncio
        loop (loop.add_reader on fileno(); on "sim" its deadlines): `async
        for n in c.anotifications(): ...`. The iteration ends when none
        arrives for timeout seconds (None: never; on "sim", when nothing
        runs there)."""
        queued: List[Notification] = []
        while True:
            if not queued:
                try:
                    queued = await self._until(lambda: self.ready() or None, timeout,
                                               "nothing arrived")
                except Timeout:
                    return
            yield queued.pop(0)

    async def await_group(self, group: Optional[int] = None, timeout: Optional[float] = None
                          ) -> Notification:
        """wait_group() awaited in the running asyncio loop: the end of group
        (after its start following the last run() of it, or from now), or of
        any group when group is None. lsc.Timeout after timeout seconds."""
        group = N.LSC_GROUP_ALL if group is None else _int("group", group, 0, 255)
        ms = _timeout_ms(timeout)  # checked
        out = N.NotificationC()

        def take() -> Optional[Notification]:
            with self._lock:
                self._advance()  # (the queue stays for the wait to take from)
                rc = N.lib.lsc_device_wait_group(self._d, group, 0, ctypes.byref(out))
                if rc == N.LSC_ETIMEOUT:
                    return None
                self._check(rc)
                return _notification(out)
        return await self._until(take, None if ms is None else ms / 1000,
                                 "no action group ended")

    # ---- tracing -------------------------------------------------------------------

    def trace(self, fn: Optional[Callable[[str, bytes], Any]]) -> None:
        """Calls fn("tx" or "rx", frame bytes) for every frame sent and received
        (None: stop). An exception fn raises ends the call that traced it.
        Anything that is neither callable nor None is refused here (TypeError)."""
        if fn is not None and not callable(fn):
            raise TypeError("trace takes a function f(direction, frame) or None, not %r" % (fn,))
        if fn is None:
            with self._lock:
                N.lib.lsc_device_set_trace(self._handle(), N.TRACE_FN(), None)
                self._trace_fn = self._trace_py = None
            return

        def tramp(_user, direction, frame, n):
            try:
                fn("tx" if direction == N.LSC_TRACE_TX else "rx", ctypes.string_at(frame, n))
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                if self._pending is None:
                    self._pending = e
        with self._lock:
            self._trace_fn = N.TRACE_FN(tramp)
            self._trace_py = tramp
            N.lib.lsc_device_set_trace(self._handle(), self._trace_fn, None)

    # ---- lscd: its status, a lease -------------------------------------------------

    def _lscd(self) -> ctypes.c_void_p:
        """The lscd connection (under self._lock), or lsc.InvalidArgument."""
        h = N.lib.lsc_device_lscd(self._handle())
        if not h:
            raise invalid("%s does not go through lscd: status and leases are lscd's (open "
                          "lscd:NAME, lscd:PATH, or a port that lscd holds)" % self.name)
        return h

    @staticmethod
    def _lscd_check(h, rc: int) -> int:
        if rc < 0:
            raise error_for(rc, N.text(N.lib.lsc_lscd_error(h)))
        return rc

    def status(self) -> Dict[str, Any]:
        """What lscd says of itself (as lscctl --json status): the port, the
        controller, the clients, the lease, the counters (lscd(8) lists the
        keys), as {key: value}; a value of digits is an int, "client" a list
        (one text per client), as is any key that comes more than once. Only
        for a controller opened through lscd ("lscd:NAME", or a port lscd
        holds): else lsc.InvalidArgument. Sends nothing to the controller."""
        items: List[Any] = []

        def collect(_user, key, value):
            items.append((N.text(key), N.text(value)))
        fn = N.STATUS_FN(collect)
        with self._lock:
            h = self._lscd()
            with self._callbacks(collect):
                self._lscd_check(h, N.lib.lsc_lscd_status(h, fn, None,
                                                          N.lib.lsc_device_timeout(self._d)))
        keys = [k for k, _ in items]
        out: Dict[str, Any] = {}
        for k, v in items:
            value: Any = int(v) if v.isdigit() and len(v) < 16 and \
                (v == "0" or not v.startswith("0")) else v
            if k == "client" or keys.count(k) > 1:
                out.setdefault(k, []).append(value)
            else:
                out[k] = value
        return out

    @contextlib.contextmanager
    def lease(self, seconds: Optional[float] = None, wait: float = 0) -> Iterator[float]:
        """A lease from lscd: while it is held only this program's frames
        reach the controller (other programs wait, or are refused). A context
        manager: `with c.lease(10): ...` takes it for at most 10 seconds (None:
        lscd's longest, lscd --lease-max; a longer one is cut to that) and
        gives it back at the end of the block (its time running out first is
        fine); the value is the time granted, in seconds. wait: how long to
        wait (seconds) while another program holds it, then lsc.Busy. Only
        for a controller opened through lscd: else lsc.InvalidArgument."""
        if seconds is None:
            ms = 0
        else:
            ms = _timeout_ms(seconds)
            if ms == 0:
                raise invalid("a lease lasts more than 0 seconds (None: lscd's longest)")
        wait_ms = _timeout_ms(wait)
        if wait_ms is None:
            raise invalid("wait is a number of seconds >= 0, not None")
        with self._lock:
            h = self._lscd()
            self._lscd_check(h, N.lib.lsc_lscd_lease(h, ms, wait_ms))
            granted = N.lib.lsc_lscd_lease_ms(h) / 1000
        try:
            yield granted
        except BaseException:
            self._release(h)  # the block's exception is the one that counts
            raise
        self._lscd_check(h, self._release(h))

    def _release(self, h) -> int:
        """Gives the lease back; 0, or the error (its time having run out,
        LSC_EINVAL, is fine; a closed controller has none)."""
        with self._lock:
            if not self._d:
                return 0
            rc = N.lib.lsc_lscd_release(h)
            return 0 if rc == N.LSC_EINVAL else rc

    # ---- play and record ------------------------------------------------------------

    def play(self, action: Action, lead_ms: int = 1000, speed: int = 100, times: int = 1,
             baud: int = 0, progress: Optional[Callable[[Optional[PlayStep], int], Any]] = None
             ) -> PlayResult:
        """Plays action on a schedule fixed from one start (as lscctl play):
        the first move to keyframe 0 over lead_ms, then each keyframe when the
        move before it ends; speed in percent (200: twice as fast); times
        repetitions; baud: the line the "cannot keep up" rule models (0: the
        port's). With an arm profile every keyframe is checked first
        (lsc.InvalidArgument naming the keyframe and joint, nothing sent).

        progress(step, elapsed_ms), if given, is called after each frame sent
        (a PlayStep) and at least every 100 ms while waiting (None); returning
        False stops the play (the servos stay where they are). Ctrl-C stops it
        the same way, then raises KeyboardInterrupt."""
        if not isinstance(action, Action):
            raise wrong_type("play takes an lsc.Action, not %s" % _shown(action))
        if len(action) == 0:
            raise invalid("the action has no keyframes")
        cfg = N.PlayerConfig(_int("speed", speed, 1, 65535), _int("times", times, 1, 65535),
                             _int("lead_ms", lead_ms, 0, 65535), 0)
        cfg.baud = _int("baud", baud, 0, N.LSC_DEVICE_FOREVER)

        def tramp(_user, step, elapsed):
            if self._pending is not None:
                return False
            try:
                if progress is None:
                    return True
                s = None
                if step:
                    c = step.contents
                    s = PlayStep(c.keyframe, c.repetition, bool(c.lead_in), c.due_ms, c.time_ms,
                                 {c.servos[i].id: c.servos[i].position
                                  for i in range(c.nservos)}, c.dropped)
                return progress(s, elapsed) is not False
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                self._pending = e
                return False
        fn = N.PLAY_FN(tramp)
        result = N.PlayResult()
        with self._callbacks(tramp):
            self._call(N.lib.lsc_device_play, ctypes.byref(action._a), ctypes.byref(cfg), fn,
                       None, ctypes.byref(result))
        return PlayResult(result.frames, result.dropped, result.keyframe, result.max_late_ms,
                          result.total_ms, bool(result.stopped))

    def record(self, servos: Union[Key, Iterable[Key]], every_ms: int, count: int,
               unload: bool = True,
               progress: Optional[Callable[[Action, bool], Any]] = None) -> Action:
        """Records count keyframes (1..) of servos, one every every_ms ms
        (1..65535) on a schedule fixed from one start, and returns them as an
        Action. unload=True first powers the servos off so that they can be
        posed by hand. progress(action, taken), if given, is called after each
        keyframe (taken True) and at least every 100 ms while waiting; False
        ends the recording early."""
        keys = self._expand(_keys(servos))
        ids = [_servo_id(self._arm, k) for k in keys]
        every_ms = _int("every_ms", every_ms, 1, 65535)
        count = _int("count", count, 1, 1 << 24)
        action = Action(ids)
        if unload:
            self.unload(ids)

        def tramp(_user, _a, taken):
            if self._pending is not None:
                return False
            try:
                return progress is None or progress(action, bool(taken)) is not False
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                self._pending = e
                return False
        fn = N.RECORD_FN(tramp)
        with self._callbacks(tramp):
            self._call(N.lib.lsc_device_record, ctypes.byref(action._a), every_ms, count, fn,
                       None)
        return action


def open(name: Optional[Union[str, bytes, "os.PathLike[str]"]] = None, arm: Optional[Union[Arm, str, "os.PathLike[str]"]] = None,
         timeout_ms: int = N.LSC_DEVICE_TIMEOUT_DEFAULT, baud: int = 9600,
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
    request waits for its reply; baud: serial ports' speed;
    hid_vid/hid_pid: another HID controller's USB ids to accept (0, 0:
    $LSC_HID_ID's, when it is set). The environment is read by the library,
    the same way for every front end (lsc/device.h).

    Raises lsc.NotFound, lsc.PermissionDenied (the message says how to get
    access), lsc.Busy (another program has the port), lsc.InvalidArgument.
    Nothing is sent by the open."""
    if name is not None and not isinstance(name, (str, bytes, os.PathLike)):
        raise wrong_type("a controller's name is a str, bytes or os.PathLike, not %s"
                         % _shown(name))
    opt = N.DeviceOptions(_int("baud", baud, 1, N.LSC_DEVICE_FOREVER),
                          _int("timeout_ms", timeout_ms, 1, N.LSC_DEVICE_FOREVER - 1),
                          _int("hid_vid", hid_vid, 0, 0xFFFF), _int("hid_pid", hid_pid, 0, 0xFFFF))
    why = ctypes.create_string_buffer(256)
    if N.lib.lsc_device_options_from_env(ctypes.byref(opt), why, len(why)) != 0:
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
    rc = N.lib.lsc_device_open(encoded, ctypes.byref(opt), ctypes.byref(handle))
    if rc < 0:
        # no handle: the library keeps what this thread's open said (NULL)
        message = N.text(N.lib.lsc_device_error(None))
        # (a HID name's kind is known before anything is opened: the name decides)
        hid = N.lib.lsc_device_kind_of(None) == N.LSC_DEVICE_HID
        cause = N.lib.lsc_device_error_cause(None)
        raise error_for(rc, message, hid=hid, cause=cause)
    # "sim" on its virtual clock, caught up with real time by ready() (below)
    N.lib.lsc_device_set_virtual_clock(handle, True)
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
    cap = 16
    while True:
        out = (N.DeviceInfo * cap)()
        msg = ctypes.create_string_buffer(512)
        n = N.lib.lsc_device_list(out, cap, msg, len(msg))
        if n < 0:
            raise error_for(n, N.text(msg.value))
        if n <= cap:
            return [Port(N.text(i.name), N.text(i.path), _KIND_NAMES.get(i.kind, "serial"),
                         N.text(i.description), N.text(i.serial), N.text(i.manufacturer),
                         i.vid, i.pid, bool(i.usb), bool(i.controller)) for i in out[:n]]
        cap = n
