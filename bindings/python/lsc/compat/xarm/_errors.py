"""The drop-in's exceptions: each is an lsc.Error (lsc's message, its code)
and also the built-in type the xarm package raised for the same mistake, so
that an except clause written for the package still catches it."""
from typing import Any
import warnings

import lsc


class WrongType(lsc.InvalidArgument, TypeError):
    """A value of a type the package could not use (a float duration, a text
    position): it raised TypeError. Nothing was sent."""


class WrongPortType(lsc.InvalidArgument, AttributeError):
    """A com_port that is not text (None, a number): the package's
    description refuses any other port with ValueError, and its code raised
    AttributeError (it called com_port.startswith): this is both, so that
    either except clause catches it. Nothing was opened."""


class NoReply(lsc.Timeout, IndexError):
    """The controller did not answer (a position or battery read): over a
    serial port the package raised IndexError (reading an empty reply)."""


class DeviceNotFound(lsc.NotFound, OSError, RuntimeError):
    """No controller at that port: the package's serial and HID modules raised
    OSError there."""


class PortBusy(lsc.Busy, OSError):
    """Another program holds the port (the package's serial module: OSError)."""


class XarmWarning(UserWarning):
    """A call the package accepts, doing what the script probably did not
    mean (a 1 ms move from duration=True, a position that is ignored). Shown
    once per line of the script (Python's default warning filter)."""


def warn(message: str) -> None:
    """Warns at the script's line (two frames above the drop-in's method)."""
    warnings.warn(message, XarmWarning, stacklevel=3)


def opened(name: str, timeout_ms: int, arm: Any = None) -> "lsc.Controller":
    """lsc.open(name, arm=arm), its failures as the package's types too."""
    try:
        return lsc.open(name, arm=arm, timeout_ms=timeout_ms)
    except lsc.NotFound as e:
        raise DeviceNotFound(e.message, e.code) from None
    except lsc.Busy as e:
        raise PortBusy(e.message, e.code) from None
