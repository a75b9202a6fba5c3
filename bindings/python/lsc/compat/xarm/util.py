"""xarm.util: the package's conversions between its units, as its Util class
has them (static methods with the package's names). Positions 0..1000 map
linearly onto -125.0..125.0 degrees; an angle is first rounded to a quarter
degree; a position from an angle is truncated towards zero."""
from typing import Any, Optional, Tuple

from lsc.errors import invalid

__all__ = ["Util"]


def _not_angle(degrees: Any) -> bool:
    return not isinstance(degrees, float) or not -125.0 <= degrees <= 125.0


class Util:
    """The package's conversions (its names, its arithmetic)."""

    @staticmethod
    def _lerp(i: float, j: float, k: float) -> float:
        """The point k (0..1) of the way from i to j: (1 - k)·i + k·j."""
        return float((1 - k) * i + j * k)

    @staticmethod
    def _invlerp(i: float, j: float, k: float) -> float:
        """How far (0..1) k is on the way from i to j."""
        return float((k - i) / (j - i))

    @staticmethod
    def _x_round(x: float) -> float:
        """x rounded to a quarter (Python's round: halves to even)."""
        return float(round(x * 4) / 4)

    @staticmethod
    def _learm_joint_constraints(servo: int) -> Optional[Tuple[int, int]]:
        """The LeArm's pulse range of a servo (1: 1500..2500; 2..6: 500..2500;
        None for another)."""
        if servo == 1:
            return (1500, 2500)
        if servo in range(2, 7):
            return (500, 2500)
        return None

    @staticmethod
    def _learm_angle_to_position(servo: int, degrees: float) -> int:
        """A LeArm servo's pulse for an angle -125.0..125.0 (a float)."""
        if _not_angle(degrees):
            raise invalid("an angle is a float -125.0..125.0, not %r" % (degrees,))
        lo, hi = Util._learm_joint_constraints(servo=servo)  # type: ignore[misc]
        return int(Util._lerp(lo, hi, Util._invlerp(-125.0, 125.0, Util._x_round(degrees))))

    @staticmethod
    def _angle_to_position(degrees: float) -> int:
        """The position 0..1000 of an angle -125.0..125.0 (a float)."""
        if _not_angle(degrees):
            raise invalid("an angle is a float -125.0..125.0, not %r" % (degrees,))
        return int(Util._lerp(0, 1000, Util._invlerp(-125.0, 125.0, Util._x_round(degrees))))

    @staticmethod
    def _position_to_angle(position: int) -> float:
        """The angle of a position 0..1000 (an int)."""
        if not isinstance(position, int) or not 0 <= position <= 1000:
            raise invalid("a position is an int 0..1000, not %r" % (position,))
        return Util._lerp(-125.0, 125.0, position / 1000)
