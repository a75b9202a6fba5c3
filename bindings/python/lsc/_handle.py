"""What every part of lsc.Controller stands on (lsc/device.h): the handle,
the one call at a time on it, calls that call Python back, interrupts, and
what the controller is."""
import contextlib
import ctypes
import enum
import os
import threading
import time
from typing import Any, Callable, Iterable, Iterator, List, Optional, TypeVar, Union

from . import _native as N
from .arm import Arm, Key
from ._check import integer as _int, seconds as _seconds, shown as _shown
from .errors import Error, error_for, invalid, wrong_type


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


_H = TypeVar("_H", bound="_Handle")


class Kind(str, enum.Enum):
    """What a controller is reached through (Controller.kind, Port.kind).
    A str too, equal to its name as text, so that c.kind == "hid" and
    print(c.kind) (hid) read as they did when it was a str."""
    SERIAL = "serial"  #: a serial port (also lsc-sim's pseudo-terminal)
    HID = "hid"        #: a USB HID controller (xArm, LeArm)
    SIM = "sim"        #: the virtual controller built into the library
    LSCD = "lscd"      #: through lscd
    LX = "lx"          #: a bus of serial bus servos (lx:PATH)

    def __str__(self) -> str:
        return self.value

    def __repr__(self) -> str:
        return repr(self.value)


_KIND_NAMES = {N.LSC_DEVICE_SERIAL: Kind.SERIAL, N.LSC_DEVICE_HID: Kind.HID,
               N.LSC_DEVICE_SIM: Kind.SIM, N.LSC_DEVICE_LSCD: Kind.LSCD,
               N.LSC_DEVICE_LX: Kind.LX}


# How long a helper thread that Ctrl-C interrupted in its start may take to
# begin (it was started, almost always: start() waits for it to begin).
_BEGIN_S = 10.0


def _waited(event: threading.Event, seconds: Optional[float]) -> bool:
    """event.wait(seconds), which a second Ctrl-C does not end early."""
    try:
        return event.wait(seconds)
    except BaseException:  # noqa: B902 (the first one is being raised)
        return event.is_set()


class _Handle:
    """The handle and its calls (lsc.Controller's base)."""

    def __init__(self, handle: ctypes.c_void_p, arm: Optional[Arm]):
        self._d: Optional[ctypes.c_void_p] = handle
        self._lock = threading.RLock()
        self._ilock = threading.Lock()  # interrupt() against close(): never held long
        self._arm = arm
        self._pending: Optional[BaseException] = None  # raised in a callback
        self._trace_fn: Any = None  # keeps the C callback alive
        self._trace_py: Optional[Callable[..., None]] = None
        self._long = ""          # what holds the controller: "", "motion" or "wait" (_foreign)
        self._preempted = False  # another thread's call ended it (_preempt)
        self._turn = threading.Condition(threading.Lock())  # _callers' changes
        self._callers = 0        # calls from other threads that ended a wait for their turn
        self._stoppers = 0       # stop() and halt() calls under way (_stopping)

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
            raise self._error(rc)
        return rc

    def _error(self, rc: int) -> Error:
        """The exception for rc < 0, with the device's message and cause."""
        return error_for(rc, N.text(N.lib.lsc_device_error(self._d)),
                         hid=self.kind == "hid", cause=N.lib.lsc_device_error_cause(self._d))

    def _call(self, fn: Callable[..., int], *args: Any, own: bool = False) -> int:
        """fn(d, *args) on the controller (_foreign: own says fn calls a
        callback of its own), checked (_check)."""
        with self._locked():
            d = self._handle()
            return self._check(self._foreign(fn, d, *args, own=own))

    def _long_call(self, fn: Callable[..., int], *args: Any) -> bool:
        """fn(d, *args), a play or a record (_foreign, "motion"): whether
        stop() or halt() from another thread ended it (else checked)."""
        with self._locked():
            d = self._handle()
            rc = self._foreign(fn, d, *args, own=True, long="motion")
            if rc == N.LSC_EINTR and self._preempted:
                self._check(0)  # (a callback's exception first)
                return True
            self._check(rc)
            return False

    @contextlib.contextmanager
    def _locked(self) -> Iterator[None]:
        """The controller to this thread (self._lock). When a wait of
        another thread holds it (_wait), that wait is ended (_preempt), and
        goes on once this call, and every other that ended it, are done."""
        if self._lock.acquire(blocking=False):
            try:
                yield
            finally:
                self._lock.release()
            return
        with self._turn:
            self._callers += 1
        try:
            self._preempt(waits_only=True)
            with self._lock:
                yield
        finally:
            with self._turn:
                self._callers -= 1
                self._turn.notify_all()

    def _foreign(self, fn: Callable[..., int], *args: Any, own: bool = False,
                 long: str = "") -> int:
        """fn(*args) (_native_call); long: a call that waits for the
        controller for as long as it takes, which another thread's call
        ends (_preempt): "motion" (a play, a record, a settle: stop() and
        halt() end it) or "wait" (a wait for notifications: any call ends
        it); then self._preempted is True once it returned."""
        if not long:
            return self._native_call(fn, *args, own=own)
        with self._ilock:
            self._long, self._preempted = long, False
            # a call that would end it is on its way (it found none to end)
            if self._stoppers or (long == "wait" and self._callers):
                self._preempted = True
                N.lib.lsc_device_interrupt(self._d)
        try:
            rc = self._native_call(fn, *args, own=own)
        finally:
            with self._ilock:
                self._long = ""
        if self._preempted and rc != N.LSC_EINTR:
            # it had stopped waiting: the interrupt is still there
            if rc < 0 and self._pending is None:
                self._pending = self._error(rc)
            self._drain_interrupt()
        return rc

    @contextlib.contextmanager
    def _stopping(self) -> Iterator[None]:
        """stop() and halt(): they end another thread's play, record, settle
        or wait (_preempt), and one that would begin meanwhile (_foreign)."""
        with self._ilock:
            self._stoppers += 1
        try:
            self._preempt()
            yield
        finally:
            with self._ilock:
                self._stoppers -= 1

    def _preempt(self, waits_only: bool = False) -> None:
        """Ends the play, record, settle (unless waits_only) or wait that
        holds the controller now (another thread's), so that this thread's
        call gets in at once."""
        with self._ilock:
            if self._d and self._long and not self._preempted and \
                    (self._long == "wait" or not waits_only):
                self._preempted = True
                N.lib.lsc_device_interrupt(self._d)

    def _native_call(self, fn: Callable[..., int], *args: Any, own: bool = False) -> int:
        """fn(*args): a C call on the controller (self._lock held) that may
        call Python back: the trace function, or a callback of its own (own:
        play's, record's, status's). Each trampoline catches what it raises
        (kept in self._pending, raised by _check once the call returned).
        The main thread needs one thing more: Python raises KeyboardInterrupt
        (Ctrl-C) there as the next function is entered, which in a C callback
        is before any try (ctypes could only report it as unraisable). So
        there such a call runs in a helper thread (Python handles signals in
        the main thread only) while the main thread waits for it: Ctrl-C
        interrupts the call (lsc_device_interrupt), which returns at once,
        and is raised then."""
        if not (own or self._trace_py is not None) or \
                threading.current_thread() is not threading.main_thread():
            return int(fn(*args))
        out: List[Any] = []
        began = threading.Event()
        done = threading.Event()

        def work() -> None:
            began.set()
            try:
                out.append(int(fn(*args)))
            except BaseException as e:  # noqa: B902 (raised in the caller's thread)
                out.append(e)
            finally:
                done.set()
        try:
            # (Ctrl-C may come while start() waits for the thread to begin)
            threading.Thread(target=work, name="lsc call", daemon=True).start()
            done.wait()
        except BaseException:  # Ctrl-C: the call ends, then it is raised
            N.lib.lsc_device_interrupt(self._d)
            # (a thread that had not begun when Ctrl-C came begins at once,
            # and its call takes the interrupt at once; one never started:
            # there is none to wait for)
            if not began.is_set():
                _waited(began, _BEGIN_S)
            while began.is_set() and not done.is_set():
                _waited(done, None)
            self._pending = None
            if not began.is_set() or (out and out[0] != N.LSC_EINTR):
                self._drain_interrupt()
            raise
        if isinstance(out[0], BaseException):
            raise out[0]
        return int(out[0])

    def _drain_interrupt(self) -> None:
        """Takes back an interrupt the call it was meant for did not take
        (it had stopped waiting): a wait of 1 ms takes it, instead of the
        next call (self._lock held)."""
        N.lib.lsc_device_poll(self._d, 1)

    def close(self) -> None:
        """Closes the port (again is fine)."""
        with self._locked(), self._ilock:
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

    def __enter__(self: _H) -> _H:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
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
        with self._locked():
            return N.text(N.lib.lsc_device_name(self._handle()))

    @property
    def kind(self) -> Kind:
        """Kind.SERIAL, HID, SIM, LSCD (through lscd: "lscd:NAME", or a
        port lscd holds) or LX (a bus of servos: "lx:PATH"); equal to
        "serial", "hid", "sim", "lscd" or "lx" too."""
        with self._locked():
            return _KIND_NAMES.get(N.lib.lsc_device_kind_of(self._handle()), Kind.SERIAL)

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
        with self._locked():
            return int(N.lib.lsc_device_timeout(self._handle()))

    @timeout_ms.setter
    def timeout_ms(self, ms: int) -> None:
        ms = _int("timeout_ms", ms, 1, N.LSC_DEVICE_FOREVER - 1)
        with self._locked():
            N.lib.lsc_device_set_timeout(self._handle(), ms)

    def now_ms(self) -> int:
        """The controller's monotonic clock in ms."""
        with self._locked():
            return int(N.lib.lsc_device_now_ms(self._handle()))

    def groups(self) -> List[int]:
        """The action groups the controller is known to hold: "sim" has its demo
        groups (1, 2, 8); a real controller does not say ([])."""
        with self._locked():
            d = self._handle()
            n = N.lib.lsc_device_groups(d, None, 0)
            out = (ctypes.c_uint8 * max(1, n))()
            n = N.lib.lsc_device_groups(d, out, n)
            return list(out[:n])

    @property
    def dropped_notifications(self) -> int:
        """Notifications dropped because more than 64 were waiting to be read."""
        with self._locked():
            return int(N.lib.lsc_device_dropped_notifications(self._handle()))

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
