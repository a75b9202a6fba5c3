"""Arm profiles (docs/arm-profile.md): joint names, servo ids, directions,
zero offsets and limits, read by the library's own parser (lsc/arm.h)."""
import ctypes
import math
import os
from typing import Any, Dict, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

from . import _native as N
from ._check import is_int, number, point as _point, shown
from .errors import Error, Unreachable, error_for, fs_bytes, invalid, wrong_type

Key = Union[int, str]      # a servo id, or a joint's name (or an id as text)
# a position (int), or an angle: in degrees (float, as read(..., degrees=True)
# gives it) or as text ("30deg", "-15.5deg")
Value = Union[int, float, str]


class Joint(NamedTuple):
    """One joint of a profile. Angles are in degrees (the library keeps
    hundredths)."""
    name: str
    id: int
    direction: int     #: +1 or -1
    pos_min: int       #: the servo's position range ...
    pos_max: int       #: ... pos_min < pos_max
    span: float        #: degrees the whole range covers
    zero: int          #: the position where the joint reads 0 degrees
    min_deg: float     #: the joint's limits, in its own degrees
    max_deg: float


class Pose(NamedTuple):
    """Where the grasp point is (mm: origin on the table under the base's axis,
    z up, x forward with the base at 0) and how the hand points (pitch from the
    horizontal: 0 forward, -90 down), with the joints' angles it came from
    (degrees, by name)."""
    x_mm: float
    y_mm: float
    z_mm: float
    pitch_deg: float
    angles: Dict[str, float]

    def __str__(self) -> str:
        """Rounded to 0.01 mm and 0.01 degree, as print() shows it:
        Pose(x=297.19 y=0.00 z=182.65 mm, pitch=0.00 deg; base=0.00
        shoulder=30.00 ... deg); repr() keeps every digit."""
        return "Pose(x=%s y=%s z=%s mm, pitch=%s deg; %s deg)" % (
            hundredths(self.x_mm), hundredths(self.y_mm), hundredths(self.z_mm),
            hundredths(self.pitch_deg),
            " ".join("%s=%s" % (k, hundredths(v)) for k, v in self.angles.items()))


def hundredths(v: float) -> str:
    """v with two decimals, never "-0.00"."""
    text = "%.2f" % v
    return text[1:] if text == "-0.00" else text


Angles = Union[Sequence[float], Mapping[str, float]]


def _why() -> "ctypes.Array[ctypes.c_char]":
    return ctypes.create_string_buffer(N.LSC_ARM_MESSAGE_MAX)


def _key_text(key: Key) -> str:
    if not isinstance(key, str) and not is_int(key):
        raise wrong_type("a servo is an id (int) or a joint's name (str), not %s" % shown(key))
    if not isinstance(key, str):
        return str(servo_id(None, key))
    return key


def _value_text(value: Value, arm: Optional["Arm"] = None) -> str:
    if value is None:
        raise invalid("None is no target (read(..., degrees=True) gives None for a servo on "
                      "no joint of the profile: leave it out, or give its position)")
    if isinstance(value, float):
        if arm is None:
            raise invalid("a float is an angle in degrees, which needs an arm profile "
                          "(lsc.open(..., arm=...)); a position is an int, not %r" % (value,))
        if not math.isfinite(value):
            raise invalid("an angle is a finite number of degrees, not %r" % (value,))
        return "%.2fdeg" % (round(value, 2) + 0.0)
    if is_int(value):
        value = int(value)
        if not -0x80000000 <= value <= 0x7FFFFFFF:  # (the library's message for the rest)
            raise invalid("a position is an int 0..65535, not %s" % shown(value))
        return str(value)
    if not isinstance(value, str):
        raise wrong_type("a target is a position (int), an angle in degrees (float) or as "
                         "text such as '30deg', not %s" % shown(value))
    return value


def _encode(s: str) -> bytes:
    if "\0" in s:
        raise invalid("a NUL character in %r" % s)
    return s.encode("utf-8")


class Arm:
    """An arm profile, loaded with the library's parser.

    >>> arm = lsc.Arm("xarm")         # by name: an installed profile
    >>> arm = lsc.Arm("examples/arms/xarm.conf")
    >>> arm.names()[:2]
    ['gripper', 'wrist-rotate']

    path is a file's path when it has a '/' or ends in ".conf"; else a
    profile's name, NAME.conf looked for in $XDG_CONFIG_HOME/lsc/arms
    (~/.config/lsc/arms), then among the installed profiles
    ($LSC_ARMS_DIR, else PREFIX/share/lsc/arms): as lscctl --arm takes it
    (the library's lsc_arm_open).

    Raises lsc.InvalidArgument when the text is refused ("FILE:LINE:COLUMN:
    reason"), lsc.Error when the file cannot be read. A profile never changes
    once loaded: any number of threads may use one.
    """

    def __init__(self, path: Union[str, "os.PathLike[str]"]):
        handle = ctypes.c_void_p()
        why = _why()
        rc = N.lib.lsc_arm_open(fs_bytes(path, "the profile's name or path"), ctypes.byref(handle),
                                why, len(why))
        if rc < 0:
            raise error_for(rc, N.text(why.value), file=True)
        self._handle = handle
        self.path: Optional[str] = os.fsdecode(path)

    @classmethod
    def parse(cls, text: str, name: str = "<string>") -> "Arm":
        """A profile from text (what a file would hold); name is used in messages."""
        data = _encode(text)
        handle = ctypes.c_void_p()
        why = _why()
        rc = N.lib.lsc_arm_parse(data, len(data), _encode(name), ctypes.byref(handle), why,
                                 len(why))
        if rc < 0:
            raise error_for(rc, N.text(why.value))
        arm = cls.__new__(cls)
        arm._handle = handle
        arm.path = None
        return arm

    def __del__(self) -> None:
        handle = getattr(self, "_handle", None)
        if handle:
            N.lib.lsc_arm_free(handle)
            self._handle = None  # type: ignore[assignment]

    def __len__(self) -> int:
        return int(N.lib.lsc_arm_count(self._handle))

    def __iter__(self) -> Iterator[Joint]:
        return iter(self.joints)

    def __repr__(self) -> str:
        return "lsc.Arm(%s: %s)" % (self.path or "<string>", ", ".join(self.names()))

    def names(self) -> List[str]:
        """The joints' names, in the order of the file."""
        return [N.text(N.lib.lsc_arm_name(self._handle, i)) for i in range(len(self))]

    @property
    def joints(self) -> List[Joint]:
        """Every joint, in the order of the file."""
        out = []
        for i in range(len(self)):
            j = N.lib.lsc_arm_joint(self._handle, i).contents
            out.append(Joint(N.text(N.lib.lsc_arm_name(self._handle, i)), j.id, j.direction,
                             j.pos_min, j.pos_max, j.span_cdeg / 100, j.zero,
                             j.min_cdeg / 100, j.max_cdeg / 100))
        return out

    def joint(self, key: Key) -> Joint:
        """The joint named key, or on servo id key; lsc.InvalidArgument if none."""
        i = N.lib.lsc_arm_find(self._handle, _encode(_key_text(key)))
        if i < 0:
            raise invalid("%r is no joint of %s (joints: %s)"
                          % (key, self.path or "the profile", ", ".join(self.names())))
        joint: Joint = self.joints[i]
        return joint

    def target(self, key: Key, value: Value) -> Tuple[int, int]:
        """(servo id, position) for a move of joint key to value: a position
        (700), or an angle in degrees (30.0, taken as given: 30.004 is not
        30.00) or as text ("30deg", at most two decimals). Outside the joint's
        limits or its servo's range: lsc.InvalidArgument naming the joint and
        its limits."""
        return target(self, key, value)

    def servo_id(self, key: Key) -> int:
        """The servo id of a joint's name, or of an id (0..255)."""
        return servo_id(self, key)

    def degrees(self, key: Key, position: int) -> Optional[float]:
        """The angle of joint key (a name or a servo id) at position, in degrees
        (two decimals); None when no joint is on that servo or the position lies
        outside its servo's range."""
        return degrees(self, servo_id(self, key), position)

    def forward(self, angles: Angles) -> Pose:
        """The pose of the chain's joints at angles (degrees): five, base,
        shoulder, elbow, wrist, wrist roll, or {joint name: degrees} (a joint
        left out at 0). The profile must state its geometry (its chain: and
        links: lines; else lsc.InvalidArgument saying what to add).
        docs/kinematics.md has the frame."""
        c, names = _chain(self)
        q, given = _floats("angles", names, angles)
        p = N.KinPose()
        if N.lib.lsc_kin_forward(ctypes.byref(c), q, ctypes.byref(p)) < 0:
            raise invalid("angles: each within -3600..3600 degrees")
        return Pose(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg, dict(zip(names, given)))

    def inverse(self, point: Sequence[float], pitch: Optional[float] = None,
                near: Optional[Angles] = None, roll: Optional[float] = None
                ) -> Dict[str, float]:
        """The joints' angles {name: degrees} that put the grasp point at
        point (x, y, z in mm) with the hand at pitch (None: the pitch nearest
        near's, over the whole circle, that reaches it), each within its
        limits; the base and the elbow kept as near's where they can be (near:
        the current angles as forward() takes them; None: all 0). lsc.Unreachable when out of reach (.by_mm) or reachable
        only beyond a joint's limit (.joint, .high, .angle_deg)."""
        c, names = _chain(self)
        t = kin_target(point, pitch, roll)
        q0, _ = _floats("near", names, near)
        q = (ctypes.c_float * N.LSC_KIN_JOINTS)()
        res = N.KinResult()
        if N.lib.lsc_kin_inverse(ctypes.byref(c), ctypes.byref(t), q0, q,
                                 ctypes.byref(res)) < 0:
            raise unreachable(res, names, c, "")
        return dict(zip(names, list(q)))


def _chain(arm: "Arm") -> Tuple[N.KinChain, List[str]]:
    """The arm's chain and its five joints' names (base .. wrist roll)."""
    c = N.KinChain()
    idx = (ctypes.c_int * N.LSC_ARM_CHAIN_MAX)()
    why = _why()
    rc = N.lib.lsc_arm_chain(arm._handle, ctypes.byref(c), idx, why, len(why))
    if rc < 0:
        raise error_for(rc, N.text(why.value))
    names = [N.text(N.lib.lsc_arm_name(arm._handle, idx[i])) for i in range(N.LSC_KIN_JOINTS)]
    return c, names


def _floats(what: str, names: List[str], values: Optional[Angles]
            ) -> Tuple["ctypes.Array[ctypes.c_float]", List[float]]:
    """Five angles, from a sequence (base .. wrist roll) or {joint name: angle}:
    for C, and as given (floats)."""
    out = (ctypes.c_float * N.LSC_KIN_JOINTS)()
    if values is None:
        return out, [0.0] * N.LSC_KIN_JOINTS
    if isinstance(values, Mapping):
        unknown = [k for k in values if k not in names]
        if unknown:
            raise invalid("%s: %r is no joint of the chain (%s)" % (what, unknown[0],
                                                                    ", ".join(names)))
        seq = [values.get(n, 0.0) for n in names]
    else:
        seq = list(values)
        if len(seq) != N.LSC_KIN_JOINTS:
            raise invalid("%s: five angles (base, shoulder, elbow, wrist, wrist roll), not %d"
                          % (what, len(seq)))
    given = [number("%s: an angle in degrees" % what, v) for v in seq]
    for i, v in enumerate(given):
        out[i] = v
    return out, given


def kin_target(point: Sequence[float], pitch: Optional[float],
               roll: Optional[float]) -> N.KinTarget:
    """A target for the library from (x, y, z) in mm and the optional angles."""
    t = N.KinTarget(*_point(point))
    if pitch is not None:
        t.pitch_deg, t.has_pitch = number("pitch", pitch), True
    if roll is not None:
        t.roll_deg, t.has_roll = number("roll", roll), True
    return t


def unreachable(res: N.KinResult, names: List[str], c: N.KinChain, message: str) -> Error:
    """The exception for a refused inverse (res), with message when given."""
    if res.status == N.LSC_KIN_OUT_OF_REACH:
        by = round(res.by_mm, 1)
        return Unreachable(message or "out of reach by %.1f mm" % by, by_mm=by)
    if res.status == N.LSC_KIN_BEYOND_LIMIT:
        name = names[res.joint]
        limit = c.max_deg[res.joint] if res.high else c.min_deg[res.joint]
        return Unreachable(message or "needs joint %s at %.2f degrees, beyond its %s limit "
                           "%.2f degrees" % (name, res.angle_deg, "upper" if res.high
                                             else "lower", limit),
                           joint=name, high=bool(res.high), angle_deg=round(res.angle_deg, 2))
    return invalid(message or "a value is refused (not finite, or too large)")


def _handle(arm: Optional[Arm]) -> Any:
    return None if arm is None else arm._handle


def target(arm: Optional[Arm], key: Key, value: Value) -> Tuple[int, int]:
    """(id, position) of "KEY:VALUE" through lsc_arm_target (arm may be None:
    then only ids and positions); a float value is degrees."""
    out = N.Servo()
    why = _why()
    text = _value_text(value, arm)  # (checked; for a float on a joint not used)
    joint = _encode(_key_text(key))
    if isinstance(value, float) and N.lib.lsc_arm_find(_handle(arm), joint) >= 0:
        # an angle as a number, as given (lsc_arm_target_deg: no rounding)
        rc = N.lib.lsc_arm_target_deg(_handle(arm), joint, value, ctypes.byref(out), why,
                                      len(why))
    else:
        rc = N.lib.lsc_arm_target(_handle(arm), _encode("%s:%s" % (_key_text(key), text)),
                                  ctypes.byref(out), why, len(why))
    if rc < 0:
        raise error_for(rc, N.text(why.value))
    return out.id, out.position


def servo_id(arm: Optional[Arm], key: Key) -> int:
    """The servo id of a joint's name or an id, through lsc_arm_servo_id."""
    if is_int(key):
        key = int(key)
        if not 0 <= key <= 255:
            raise invalid("servo id %s is outside 0..255" % shown(key))
        return key
    out = ctypes.c_uint8()
    why = _why()
    rc = N.lib.lsc_arm_servo_id(_handle(arm), _encode(_key_text(key)), ctypes.byref(out), why,
                                len(why))
    if rc < 0:
        raise error_for(rc, N.text(why.value))
    return out.value


def degrees(arm: Optional[Arm], sid: int, position: int) -> Optional[float]:
    """The angle of the joint on servo sid at position, or None."""
    if arm is None:
        return None
    if not is_int(position):
        raise wrong_type("a position is an int 0..65535, not %s" % shown(position))
    position = int(position)
    if not 0 <= position <= 65535:
        raise invalid("a position is an int 0..65535, not %s" % shown(position))
    s = N.Servo(sid, position)
    deg = ctypes.c_double()
    if N.lib.lsc_arm_angle(arm._handle, ctypes.byref(s), ctypes.byref(deg)) < 0:
        return None
    # (hundredths, as lscctl shows them; a move takes the value back to the position)
    return round(deg.value, 2) + 0.0


__all__ = ["Arm", "Joint", "Error"]
