"""Notifications (lsc/device.h's event loop): lsc.Notification, waits for
them, and a controller in a program's own event loop (selectors, asyncio)."""
import asyncio
import ctypes
import enum
import io
import math
import time
from typing import Any, AsyncIterator, Callable, Iterator, List, NamedTuple, Optional, Tuple

from . import _native as N
from ._check import integer as _int
from .errors import Timeout, invalid
from ._handle import _Handle, _timeout_ms

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


class _Events(_Handle):
    """lsc.Controller's notifications and event loop."""

    # ---- notifications ------------------------------------------------------------

    def _wait(self, step: Callable[[int], int], timeout: Optional[float]) -> int:
        """Runs step(ms) (a C wait for notifications) for up to timeout
        seconds (None: no limit). A call from another thread ends it for
        its turn (_locked), then it goes on for the time left; in the main
        thread Ctrl-C ends it (_native_call). Returns step's result or
        raises."""
        ms = _timeout_ms(timeout)
        deadline = None if ms is None else time.monotonic() + ms / 1000
        while True:
            with self._locked():
                self._handle()
                left = N.LSC_DEVICE_FOREVER if deadline is None else \
                    max(0, math.ceil((deadline - time.monotonic()) * 1000))
                rc = self._foreign(step, left, own=True, long="wait")
                if rc != N.LSC_EINTR or not self._preempted:
                    return self._check(rc)
            with self._turn:  # the calls that ended it first
                while self._callers:
                    self._turn.wait()

    def notification(self, timeout: Optional[float] = None) -> Notification:
        """The oldest notification, waiting up to timeout seconds for one
        (lsc.Timeout if none came; None: no limit)."""
        out = N.NotificationC()
        self._wait(lambda ms: int(N.lib.lsc_device_notification(self._d, ms,
                                                                    ctypes.byref(out))),
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
        """poll() for ms, in steps of at most _CHUNK_MS, so that Ctrl-C and
        other threads get in."""
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
        gives it a copy of each report), through lscd the socket, for "sim" a
        timer that polls readable when it sends something of its own accord.
        So a Controller can be registered with selectors, or
        loop.add_reader. Read through ready(), never on it.
        io.UnsupportedOperation when the library gives none."""
        with self._locked():
            fd = N.lib.lsc_device_fileno(self._handle())
        if fd < 0:
            raise io.UnsupportedOperation("%s has no descriptor: wait for next_event() "
                                          "instead" % self.name)
        return int(fd)

    def next_event(self) -> Optional[float]:
        """Seconds the event loop may sleep without the descriptor saying
        so: 0 when something waits already (a queued notification, input
        a request read ahead); None: nothing is due but by the descriptor."""
        with self._locked():
            ms = N.lib.lsc_device_next_event_ms(self._handle())
        return None if ms == N.LSC_DEVICE_FOREVER else ms / 1000

    def ready(self) -> List[Notification]:
        """Reads what has arrived, without waiting, and returns every
        notification queued (oldest first): what an event loop calls when
        fileno() polled readable or next_event() came."""
        with self._locked():
            self._advance()
            return self._queued()

    def _advance(self) -> None:
        """lsc_device_poll: what has arrived (the lock held)."""
        self._check(self._foreign(N.lib.lsc_device_poll, self._handle(), 0))

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
        """Runs take() (it reads) until it gives something, waiting in the
        running loop on the descriptor and next_event(); lsc.Timeout after
        timeout seconds (None: no limit). take() and everything else that
        takes the controller's lock runs in the loop's default executor: the
        loop never waits for another thread's call."""
        loop = asyncio.get_running_loop()
        deadline = None if timeout is None else time.monotonic() + timeout

        def descriptor() -> int:
            with self._locked():
                return int(N.lib.lsc_device_fileno(self._handle()))

        def step() -> Tuple[Optional[Any], Optional[float]]:
            got = take()
            return got, (None if got is not None else self.next_event())
        fd = await loop.run_in_executor(None, descriptor)
        while True:
            got, nxt = await loop.run_in_executor(None, step)
            if got is not None:
                return got
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if left is not None and left <= 0:
                raise Timeout("%s within %s s" % (what, timeout), N.LSC_ETIMEOUT)
            if fd < 0 and nxt is None:
                raise Timeout("%s has no descriptor and nothing is due, so nothing will "
                              "arrive" % self.name, N.LSC_ETIMEOUT)
            wait = nxt if left is None else left if nxt is None else min(nxt, left)
            await self._readable(fd, wait)

    async def anotifications(self, timeout: Optional[float] = None
                             ) -> AsyncIterator[Notification]:
        """The notifications as they arrive, awaited in the running asyncio
        loop (loop.add_reader on fileno(), and next_event()): `async for n
        in c.anotifications(): ...`. The iteration ends when none arrives
        for timeout seconds (None: never)."""
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
            with self._locked():
                self._advance()  # (the queue stays for the wait to take from)
                rc = N.lib.lsc_device_wait_group(self._d, group, 0, ctypes.byref(out))
                if rc == N.LSC_ETIMEOUT:
                    return None
                self._check(rc)
                return _notification(out)
        got: Notification = await self._until(take, None if ms is None else ms / 1000,
                                              "no action group ended")
        return got
