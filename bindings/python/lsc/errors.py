"""Exceptions: every failure of the library is an lsc.Error carrying its
one-line message and its code (a negative LSC_E... value of lsc/core.h)."""
import os
from typing import Any, Iterable, Optional

from . import _native as N


class Error(Exception):
    """A failure of lsc. str(e) is the library's one-line message (it names the
    port, what failed and what to check); e.code is the LSC_E... code (negative)
    or None for a failure found by the bindings themselves."""

    def __init__(self, message: str, code: Optional[int] = None):
        super().__init__(message)
        self.message = message
        self.code = code

    def __str__(self) -> str:
        return self.message


class InvalidArgument(Error, ValueError):
    """An argument is refused (out of range, a servo outside the arm profile's
    limits, a name that selects nothing): nothing was sent."""


class WrongType(InvalidArgument, TypeError):
    """An argument of a type that cannot be used there (text or bytes where a
    number goes, a bool, bytes as a point): an InvalidArgument that is also
    a TypeError, so that either except clause catches it. Nothing was sent."""


class Unreachable(InvalidArgument):
    """The grasp point cannot be put there (Arm.inverse, Controller.reach):
    nothing was sent. Either out of reach: by_mm says by how much (joint is
    None); or reachable only beyond a joint's limit: joint names it, high says
    its upper limit (else its lower one), angle_deg the angle it would need
    (by_mm is None)."""

    def __init__(self, message: str, by_mm: Optional[float] = None,
                 joint: Optional[str] = None, high: bool = False,
                 angle_deg: Optional[float] = None):
        super().__init__(message, N.LSC_EINVAL)
        self.by_mm = by_mm
        self.joint = joint
        self.high = high
        self.angle_deg = angle_deg


class Timeout(Error, TimeoutError):
    """No reply (or no notification, or the servos not where they should be)
    within the timeout."""


class Stalled(Timeout):
    """move(wait=True, strict=True) or reach(wait=True, strict=True): a servo
    stopped short of its target (a
    gripper holding something, a joint against an obstacle). e.stopped lists
    them (lsc.StoppedServo). A Timeout, so code written for the strict waits
    of earlier versions still catches it."""

    def __init__(self, message: str, code: Optional[int] = None,
                 stopped: Iterable[Any] = ()) -> None:
        super().__init__(message, code)
        self.stopped = list(stopped)


class NeverStarted(Timeout):
    """run(group, wait=True): the group never started: the controller did
    not report its start within about a second of the run (a board reports
    it at once, and ignores a run of a group it does not have; "sim" says so
    at once). A Timeout, so code that catches lsc.Timeout still does."""


class Busy(Error):
    """Another program holds the port; nothing was sent."""


class NotFound(Error):
    """No such device, no controller present, or it went away."""


class PermissionDenied(Error, PermissionError):
    """Permission denied opening the device; the message says how to get access
    (the udev rule and the group)."""


class Interrupted(Error):
    """Controller.interrupt() (lsc_device_interrupt) ended the call while it
    waited for the controller; what was sent stays sent."""


class LinkError(Error):
    """The link failed: an I/O error of the transport, or something arrived that
    is not a valid reply."""


_BY_CODE = {
    N.LSC_EINVAL: InvalidArgument,
    N.LSC_ETIMEOUT: Timeout,
    N.LSC_EBUSY: Busy,
    N.LSC_ENODEV: NotFound,
    N.LSC_EACCES: PermissionDenied,
    N.LSC_EIO: LinkError,
    N.LSC_EINTR: Interrupted,
    N.LSC_EREPLY: LinkError,
    N.LSC_EFRAME: LinkError,
    N.LSC_ESYNC: LinkError,
    N.LSC_ETOOBIG: LinkError,
}

# What PermissionDenied of a device adds when the library's cause does not
# say that its message tells how to get access (LSC_DEVICE_CAUSE_ACCESS: it
# always should; this keeps the promise if it ever does not).
_ACCESS_HINT = {
    "hid": " (the lscctl package installs the udev rule /usr/lib/udev/rules.d/60-lsc.rules, "
           "which gives the logged-in user and the plugdev group access to the arm's hidraw "
           "node: install it and replug the arm, or sudo usermod -aG plugdev $USER and log in "
           "again)",
    "serial": " (add your user to the dialout group: sudo usermod -aG dialout $USER, then "
              "log in again; or give the device a udev rule with MODE=\"0660\" "
              "GROUP=\"dialout\")",
}


def error_for(code: int, message: str, hid: bool = False, file: bool = False,
              cause: Optional[int] = None) -> Error:
    """The exception for a negative LSC_E... code and the library's message.
    file: the code comes from reading or writing a file (profiles, action
    files), where LSC_EIO is no link's failure but a file's: lsc.Error.
    cause: the device's lsc_device_error_cause, for a device's error (None:
    no device's)."""
    if not message:
        message = N.text(N.lib.lsc_strerror(code))
    cls = Error if file and code == N.LSC_EIO else _BY_CODE.get(code, Error)
    if cls is Timeout and cause in (N.LSC_DEVICE_CAUSE_NEVER_STARTED,
                                    N.LSC_DEVICE_CAUSE_SIM_NO_GROUP):
        cls = NeverStarted
    if cls is PermissionDenied and cause is not None and cause != N.LSC_DEVICE_CAUSE_ACCESS:
        message += _ACCESS_HINT["hid" if hid else "serial"]
    return cls(message, code)


def invalid(message: str) -> InvalidArgument:
    """An argument the bindings refuse before calling the library."""
    return InvalidArgument(message, N.LSC_EINVAL)


def wrong_type(message: str) -> WrongType:
    """An argument of the wrong type, refused by the bindings (lsc._check)."""
    return WrongType(message, N.LSC_EINVAL)


def fs_bytes(path: Any, what: str = "a path") -> bytes:
    """path (str, bytes or os.PathLike) as the bytes the OS sees, as os.fsencode
    makes them (a str's undecodable bytes come back through surrogateescape);
    lsc.InvalidArgument for any other type or a NUL byte."""
    try:
        b = os.fsencode(path)
    except TypeError:
        raise wrong_type("%s is a str, bytes or os.PathLike, not %s"
                         % (what, type(path).__name__)) from None
    if b"\0" in b:
        raise invalid("a NUL character in %s: %r" % (what, path))
    return b
