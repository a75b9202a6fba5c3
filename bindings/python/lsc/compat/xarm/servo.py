"""xarm.servo: the package's Servo, a servo id with a position (0..1000)
and an angle (degrees) that follow each other."""
from typing import Any
from lsc.errors import invalid

from .util import Util

__all__ = ["Servo"]


class Servo:
    """Servo(servo_id, position=500): an int position 0..1000, or a float
    angle -125.0..125.0 (the position is then the angle's, rounded to a
    quarter degree; the angle stays as given). As in the package: servo_id is
    kept as given (checked when it is sent); a position of another type sets
    neither; setting .position takes int(value) (90.0 is position 90), and
    .angle float(value); a value out of range raises ValueError after the
    attribute itself was set."""

    def __init__(self, servo_id: int, position: int = 500) -> None:
        self.servo_id = servo_id
        if isinstance(position, int):
            if not 0 <= position <= 1000:
                raise invalid("Servo(%r, %r): a position is 0..1000" % (servo_id, position))
            self.position = position
        elif isinstance(position, float):
            if not -125.0 <= position <= 125.0:
                raise invalid("Servo(%r, %r): an angle is -125.0..125.0" % (servo_id, position))
            self.angle = position

    @property
    def position(self) -> int:
        """Position in units, 0..1000."""
        return self.__position

    @position.setter
    def position(self, value: int) -> None:
        self.__position = int(value)
        self.__angle = Util._position_to_angle(self.__position)

    @property
    def angle(self) -> float:
        """Angle in degrees (as given; its position is the angle rounded to
        0.25 degree)."""
        return self.__angle

    @angle.setter
    def angle(self, value: float) -> None:
        self.__angle = float(value)
        self.__position = Util._angle_to_position(self.__angle)

    def __repr__(self) -> str:
        # the package's Servo has no repr of its own: Python's default, its module's name
        return "<xarm.servo.Servo object at 0x%x>" % id(self)
