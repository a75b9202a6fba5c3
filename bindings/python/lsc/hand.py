"""The hand through the arm profile's geometry (docs/kinematics.md):
Controller.where() and Controller.reach(), over lsc_device_where and
lsc_device_reach (lsc/device.h), which do the planning."""
import ctypes
from typing import TYPE_CHECKING, Any, Dict, List, NamedTuple, Optional, Sequence

from . import _native as N
from ._check import integer, number
from .arm import Pose, _chain, hundredths, kin_target, unreachable
from .errors import invalid

if TYPE_CHECKING:
    from .device import Controller


class ReachResult(NamedTuple):
    """What a reach did: the moves sent (waypoints), their times together, and
    the hand's pitch at the end (the one chosen when none was given); with
    wait=True how the wait ended, as move()'s MoveResult says it. Falsy when
    a joint stopped short."""
    waypoints: int
    time_ms: int
    pitch_deg: float
    stopped: List[Any]  #: lsc.StoppedServo of the joints that stopped short, by name
    reads: bool         #: False: the controller does not answer position reads
    message: str        #: the library's line saying where they stopped ("")

    def __bool__(self) -> bool:
        return not self.stopped

    def __str__(self) -> str:
        """As repr(), the pitch rounded to 0.01 degree."""
        return repr(self._replace(pitch_deg=float(hundredths(self.pitch_deg))))


def where(c: "Controller") -> Pose:
    """Controller.where()"""
    q = (ctypes.c_float * N.LSC_KIN_JOINTS)()
    p = N.KinPose()
    c._call(N.lib.lsc_device_where, q, ctypes.byref(p))
    assert c.arm is not None  # the call succeeded: the profile has a chain
    _, names = _chain(c.arm)
    # (the angles are of positions: whole hundredths of a degree)
    return Pose(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg,
                {n: round(a, 2) + 0.0 for n, a in zip(names, list(q))})


def reach(c: "Controller", point: Sequence[float], pitch: Optional[float], roll: Optional[float],
          time_ms: Optional[int], speed: Optional[float], line: bool, step_mm: Optional[float],
          wait: bool, tolerance: int, strict: bool) -> ReachResult:
    """Controller.reach()"""
    r = N.Reach()
    r.target = kin_target(point, pitch, roll)
    if time_ms is not None and speed is not None:
        raise invalid("give time_ms or speed, not both")
    if time_ms is not None:
        r.time_ms = integer("time_ms", time_ms, 1, 65535)
    if speed is not None:
        r.speed_dps = number("speed", speed)
        if r.speed_dps <= 0:
            raise invalid("speed %r: give 0.01..100000 degrees a second" % (speed,))
    if step_mm is not None:
        if not line:
            raise invalid("step_mm is the distance between the waypoints of line=True")
        r.step_mm = number("step_mm", step_mm)
        if r.step_mm <= 0:
            raise invalid("step_mm %r: give 0.1..1000" % (step_mm,))
    r.line = bool(line)
    r.wait = bool(wait)
    r.tolerance = tolerance
    r.flags = N.LSC_SETTLE_STRICT if strict else 0
    res = N.ReachResult()
    with c._locked():
        d = c._handle()
        rc = c._foreign(N.lib.lsc_device_reach, d, ctypes.byref(r), ctypes.byref(res),
                        own=bool(wait),
                        long="motion" if wait else "")
        if rc < 0 and res.kin.status in (N.LSC_KIN_OUT_OF_REACH, N.LSC_KIN_BEYOND_LIMIT):
            assert c.arm is not None  # (its kinematics found it out of reach)
            chain, joints = _chain(c.arm)
            raise unreachable(res.kin, joints, chain, N.text(N.lib.lsc_device_error(d)))
        names: Dict[int, str] = {}
        if res.settle.nstopped > 0:  # (a stop needs the profile's chain)
            arm = c.arm
            assert arm is not None  # (a stop needs the profile's chain)
            names = {arm.servo_id(n): n for n in _chain(arm)[1]}
        settled = c._settled(rc, res.settle, names)
    return ReachResult(int(res.waypoints), int(res.time_ms), float(res.kin.pitch_deg),
                       settled.stopped, settled.reads if wait else True, settled.message)
