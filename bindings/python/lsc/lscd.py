"""lscd from a controller opened through it (lsc/lscd.h): its status, a
lease."""
import contextlib
import time
from typing import Any, Dict, Iterator, List, Optional

from . import _native as N
from .errors import error_for, invalid
from ._handle import _Handle, _timeout_ms


class _Lscd(_Handle):
    """lsc.Controller's lscd calls."""

    # ---- lscd: its status, a lease -------------------------------------------------

    def _lscd(self) -> Any:
        """The lscd connection (under self._lock), or lsc.InvalidArgument."""
        h = N.lib.lsc_device_lscd(self._handle())
        if not h:
            raise invalid("%s does not go through lscd: status and leases are lscd's (open "
                          "lscd:NAME, lscd:PATH, or a port that lscd holds)" % self.name)
        return h

    @staticmethod
    def _lscd_check(h: Any, rc: int) -> int:
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

        def collect(_user: Any, key: bytes, value: bytes) -> None:
            try:
                items.append((N.text(key), N.text(value)))
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                if self._pending is None:
                    self._pending = e
        fn = N.STATUS_FN(collect)
        with self._locked():
            h = self._lscd()
            rc = self._foreign(N.lib.lsc_lscd_status, h, fn, None,
                               N.lib.lsc_device_timeout(self._d), own=True)
            self._check(0)  # collect's exception
            self._lscd_check(h, rc)
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
        ms: Optional[int] = 0
        if seconds is None:
            ms = 0
        else:
            ms = _timeout_ms(seconds)
            if ms == 0:
                raise invalid("a lease lasts more than 0 seconds (None: lscd's longest)")
        wait_ms = _timeout_ms(wait)
        if wait_ms is None:
            raise invalid("wait is a number of seconds >= 0, not None")
        with self._locked():
            h = self._lscd()
            self._lscd_check(h, N.lib.lsc_lscd_lease(h, ms, wait_ms))
            granted = N.lib.lsc_lscd_lease_ms(h) / 1000
        try:
            yield granted
        except BaseException:
            self._release(h)  # the block's exception is the one that counts
            raise
        self._lscd_check(h, self._release(h))

    def _release(self, h: Any) -> int:
        """Gives the lease back; 0, or the error (its time having run out,
        LSC_EINVAL, is fine; a closed controller has none)."""
        with self._locked():
            if not self._d:
                return 0
            rc = N.lib.lsc_lscd_release(h)
            return 0 if rc == N.LSC_EINVAL else int(rc)
