"""The API of the PyPI `xarm` package (ccourson's xArmServoController), over
lsc: a script written for it runs after changing one line,

    import xarm                     ->  from lsc.compat import xarm

and does what it did there: the same frames for the same calls, the same
values (positions 0..1000, angles -125.0..125.0 mapped linearly), the same
Servo, waits, debug lines and refusals, with exceptions that are both
lsc.Error (lsc's message) and the type the package raised. Where the package
did what a script probably did not mean (duration=True: a 1 ms move), a
warning says so once per line. bindings/python/README.md lists what differs.
On a bus of servos (Controller('lx:/dev/ttyUSB0')) the calls are done with
lsc's bus calls (xarm/bus.py): writeServoId renames the one servo alone on
the bus, or refuses, nothing written.
"""
import lsc

from . import controller, servo, util
from ._errors import DeviceNotFound, NoReply, PortBusy, WrongPortType, WrongType, XarmWarning
from .controller import Controller
from .servo import Servo
from .util import Util

#: The drop-in's version (lsc's): the names exist so that scripts that print them run.
__version__ = lsc.__version__
VERSION = __version__

__all__ = ["Controller", "Servo", "Util", "controller", "servo", "util", "XarmWarning",
           "NoReply", "WrongType", "WrongPortType", "DeviceNotFound", "PortBusy", "__version__",
           "VERSION"]
