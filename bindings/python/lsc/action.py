"""Action files (docs/action-files.md): keyframe sequences read and written by
the library (lsc/files.h), the format chosen by the file name's extension:
.txt (lsc's action-group text), .csv, .rob (xArm PC software), .d6a (LSC
boards' PC software, SQLite), .h (a C header, written only)."""
import ctypes
import os
from typing import Iterable, Iterator, List, NamedTuple, Optional, Sequence, Tuple, Union

from . import _native as N
from ._check import integer
from .arm import Arm
from .errors import Error, error_for, fs_bytes, invalid

PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
ArmLike = Union[Arm, str, "os.PathLike[str]"]


class Keyframe(NamedTuple):
    """One keyframe: the time since the previous one (ms), then the position of
    each of the action's servos (in the order of Action.ids)."""
    time_ms: int
    positions: Tuple[int, ...]


def _path(path: PathLike) -> bytes:
    return fs_bytes(path, "the path")


def _file_error(rc: int, path: str, err: N.FileError) -> Error:
    msg = N.text(err.message)
    return error_for(rc, "%s: %s" % (path, msg) if msg else "", file=True)


class Action:
    """A sequence of keyframes for the servos ids (1..32 distinct ids 0..255).

    >>> a = lsc.Action([1, 2], [(0, (500, 500)), (400, (700, 300))])
    >>> a.save("wave.csv"); lsc.Action.load("wave.csv").keyframes[1]
    Keyframe(time_ms=400, positions=(700, 300))
    """

    def __init__(self, ids: Sequence[int], keyframes: Iterable[Tuple[int, Sequence[int]]] = ()):
        ids = list(ids)
        if not 1 <= len(ids) <= N.LSC_PLAYER_SERVOS_MAX:
            raise invalid("an action has 1..%d servos, not %d" % (N.LSC_PLAYER_SERVOS_MAX, len(ids)))
        ids = [integer("", i, 0, 255, "a servo id is an int 0..255, not %s") for i in ids]
        if len(set(ids)) != len(ids):
            raise invalid("servo ids repeat in %r" % (ids,))
        self._a = N.ActionC()
        arr = (ctypes.c_uint8 * len(ids))(*ids)
        rc = N.lib.lsc_action_init(ctypes.byref(self._a), arr, len(ids))
        if rc < 0:
            raise error_for(rc, "")
        for time_ms, positions in keyframes:
            self.append(time_ms, positions)

    @classmethod
    def load(cls, path: PathLike, group: Optional[int] = None) -> "Action":
        """Reads an action file (format by extension). group: the number of
        the group to read from a .txt file of several groups (lsc-sim's group
        files: examples/groups/arm-demo.txt holds 0, 1 and 2), as lscctl's
        --group N; a .csv, .rob or .d6a file is one group, numbered by its
        name (10.rob: group 10), else 1, and another number is refused. None
        reads the file's only group. lsc.InvalidArgument says where and why a
        file is refused (a file of several groups without group: which ones
        it holds); lsc.Error when it cannot be read."""
        if group is not None:
            group = integer("", group, 0, 254,
                            "a group is an int 0..254 (or None: the file's only one), not %s")
        a = cls.__new__(cls)
        a._a = N.ActionC()
        err = N.FileError()
        rc = N.lib.lsc_action_read_group(_path(path), -1 if group is None else group,
                                         ctypes.byref(a._a), ctypes.byref(err))
        if rc < 0:
            raise _file_error(rc, os.fsdecode(path), err)
        return a

    def to_arm(self, from_arm: ArmLike, to_arm: ArmLike) -> "Action":
        """This action's positions, recorded on the arm from_arm, as the
        positions that put the arm to_arm in the same joint angles (as
        lscctl convert --from-arm --to-arm): servos are matched by joint name,
        servos on no joint of from_arm are kept as they are. from_arm and
        to_arm are lsc.Arm, profile names ("xarm") or paths.
        lsc.InvalidArgument names the keyframe and joint of a pose outside
        to_arm's limits (or a position outside from_arm's servo range);
        nothing is changed."""
        arms = [a if isinstance(a, Arm) else Arm(a) for a in (from_arm, to_arm)]
        out = Action.__new__(Action)
        out._a = N.ActionC()
        why = ctypes.create_string_buffer(N.LSC_ARM_MESSAGE_MAX)
        rc = N.lib.lsc_action_to_arm(ctypes.byref(self._a), arms[0]._handle, arms[1]._handle,
                                     ctypes.byref(out._a), why, len(why))
        if rc < 0:
            out._a = None  # type: ignore[assignment]
            raise error_for(rc, N.text(why.value))
        return out

    def save(self, path: PathLike) -> None:
        """Writes the action (format by extension), replacing the file
        atomically. lsc.InvalidArgument when the action does not fit the format
        (e.g. .rob: servos 1..6 only), naming the keyframe."""
        err = N.FileError()
        rc = N.lib.lsc_action_write(_path(path), ctypes.byref(self._a), ctypes.byref(err))
        if rc < 0:
            raise _file_error(rc, os.fsdecode(path), err)

    def append(self, time_ms: int, positions: Sequence[int]) -> None:
        """Adds a keyframe: time_ms (0..65535) after the previous one, a position
        (0..65535) for each servo of ids."""
        time_ms = integer("", time_ms, 0, 65535, "a keyframe's time is an int 0..65535 ms, not %s")
        positions = list(positions)
        n = self._a.nservos
        if len(positions) != n:
            raise invalid("a keyframe of this action has %d positions, not %d" % (n, len(positions)))
        positions = [integer("", p, 0, 65535, "a position is an int 0..65535, not %s")
                     for p in positions]
        arr = (ctypes.c_uint16 * n)(*positions)
        rc = N.lib.lsc_action_append(ctypes.byref(self._a), time_ms, arr)
        if rc < 0:
            raise error_for(rc, "")

    def __del__(self) -> None:
        a = getattr(self, "_a", None)
        if a is not None:
            N.lib.lsc_action_free(ctypes.byref(a))

    @property
    def ids(self) -> Tuple[int, ...]:
        """The servos, in the order of each keyframe's positions."""
        return tuple(self._a.ids[:self._a.nservos])

    @property
    def keyframes(self) -> List[Keyframe]:
        """Every keyframe (a copy)."""
        n = self._a.nservos
        count = self._a.count
        if count == 0:
            return []
        words = self._a.words[:count * (1 + n)]
        return [Keyframe(words[k * (1 + n)], tuple(words[k * (1 + n) + 1:(k + 1) * (1 + n)]))
                for k in range(count)]

    @property
    def duration_ms(self) -> int:
        """The sum of the keyframes' times (the lead-in of a play not included)."""
        return sum(k.time_ms for k in self.keyframes)

    def __len__(self) -> int:
        return int(self._a.count)

    def __iter__(self) -> Iterator[Keyframe]:
        return iter(self.keyframes)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Action):
            return NotImplemented
        return self.ids == other.ids and self.keyframes == other.keyframes

    def __repr__(self) -> str:
        return "lsc.Action(ids=%r, %d keyframes, %d ms)" % (list(self.ids), len(self),
                                                           self.duration_ms)
