"""The checks of numbers (and points) given to the package, in one place,
before anything reaches C (ctypes would wrap 70000 into a 16-bit 4464, and a
float cannot hold 10**400):

  - a value of the wrong type (a str or bytes where a number goes, a bool,
    None, bytes as a point) is lsc.InvalidArgument that is also a TypeError;
  - a number of the right type but refused (outside its range, NaN, an
    infinity, an int too large for a float) is lsc.InvalidArgument (a
    ValueError).

Messages show a value with shown(): a huge int is described, not printed
(Python refuses to print one of more than 4300 digits).
"""
import math
import numbers
import operator
from typing import Any, Optional, Tuple

from .errors import invalid, wrong_type


def shown(v: Any) -> str:
    """v as messages show it: repr, but an int of more than 20 digits as how
    long it is."""
    if isinstance(v, int) and not isinstance(v, bool) and v.bit_length() > 66:
        return "an int of %d digits" % len(str(abs(v))) if v.bit_length() < 14000 \
            else "an int of about %d digits" % int(v.bit_length() * 0.30103)
    try:
        return repr(v)
    except ValueError:  # (an object whose repr holds such an int)
        return "a %s" % type(v).__name__


def is_int(v: Any) -> bool:
    """An int (or anything that is an index, e.g. numpy's ints), not a bool."""
    if isinstance(v, bool):
        return False
    if isinstance(v, int):
        return True
    try:
        operator.index(v)
    except TypeError:
        return False
    return True


def integer(what: str, v: Any, lo: int, hi: int, message: Optional[str] = None) -> int:
    """v as an int within lo..hi: lsc.InvalidArgument (also a TypeError for
    anything but an int) before anything is sent. message: the text of
    either refusal, %s the value (default: "WHAT must be an int LO..HI, not
    V", "WHAT V is outside LO..HI")."""
    if not is_int(v):
        raise wrong_type((message or "%s must be an int %d..%d, not %%s" % (what, lo, hi))
                         % shown(v))
    v = operator.index(v)
    if not lo <= v <= hi:
        raise invalid((message or "%s %%s is outside %d..%d" % (what, lo, hi)) % shown(v))
    return int(v)


def number(what: str, v: Any, lo: Optional[float] = None, hi: Optional[float] = None) -> float:
    """v (an int or a float, any real number but a bool) as a finite float,
    within lo..hi when given."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise wrong_type("%s: %s is not a number" % (what, shown(v)))
    try:
        f = float(v)
    except (OverflowError, ValueError):
        raise invalid("%s: %s is too large" % (what, shown(v))) from None
    if not math.isfinite(f):
        raise invalid("%s: %s is not a finite number" % (what, shown(v)))
    if (lo is not None and f < lo) or (hi is not None and f > hi):
        raise invalid("%s %s is outside %s..%s" % (what, shown(v), "%g" % lo if lo is not None
                                                   else "", "%g" % hi if hi is not None else ""))
    return f


def seconds(what: str, v: Any) -> Optional[int]:
    """A time in seconds (None: no limit) as ms, rounded up, at most
    0xFFFFFFFE: lsc.InvalidArgument when negative, NaN or infinite."""
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise wrong_type("%s is a number of seconds >= 0 (or None: no limit), not %s"
                         % (what, shown(v)))
    try:
        f = float(v)
    except (OverflowError, ValueError):
        f = math.inf
    if math.isnan(f) or f < 0 or math.isinf(f):
        raise invalid("%s is a finite number of seconds >= 0 (or None: no limit), not %s"
                      % (what, shown(v)))
    return min(math.ceil(f * 1000), 0xFFFFFFFE)


def octets(what: str, v: Any) -> bytes:
    """Bytes to send: bytes, bytearray, memoryview, or a sequence of ints
    0..255. An int (bytes(5) would be five zero bytes) or text is no bytes."""
    if isinstance(v, (bytes, bytearray, memoryview)):
        return bytes(v)
    if isinstance(v, (str, int)) or not hasattr(v, "__iter__"):
        raise wrong_type("%s are bytes (or a sequence of ints 0..255), not %s" % (what, shown(v)))
    return bytes(integer("a byte of %s" % what, b, 0, 255) for b in v)


def point(v: Any) -> Tuple[float, float, float]:
    """(x, y, z) in mm: three numbers. Text and bytes are no point (a
    TypeError: bytes would be three small ints)."""
    if isinstance(v, (str, bytes, bytearray, memoryview)):
        raise wrong_type("a point is (x, y, z) in millimetres, not %s" % shown(v))
    try:
        x, y, z = v
    except TypeError:
        raise wrong_type("a point is (x, y, z) in millimetres, not %s" % shown(v)) from None
    except ValueError:
        raise invalid("a point is (x, y, z) in millimetres, not %s" % shown(v)) from None
    return number("x", x), number("y", y), number("z", z)
