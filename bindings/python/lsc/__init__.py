"""lsc: LSC servo controllers (Hiwonder / LewanSoul LSC-6, LSC-16, LSC-32, the
xArm and LeArm) from Python, over the C library liblsc.so.2 (ctypes; no
compiler needed).

    import lsc
    with lsc.open("sim") as c:                  # or "/dev/ttyUSB0", "hid", "hid:SERIAL",
                                                # "lx:/dev/ttyUSB0" (a bus of servos: c.servo)
        print(c.battery())                      # 7500 (millivolts)
        c.move({1: 1500, 2: 1200}, time_ms=500, wait=True)
        print(c.read([1, 2]))                   # {1: 1500, 2: 1200}
        c.run(1, wait=True)                     # the group's end, as a Notification

Failures raise lsc.Error (subclasses Timeout (and its Stalled), Busy, NotFound,
PermissionDenied, InvalidArgument, LinkError) with the library's one-line
message; no call returns a sentinel for a failure, and no call waits without a
bound it was given. The library is $LSC_LIBRARY if set (a build tree's
src/liblsc.so.2), else liblsc.so.2 (the liblsc2 package).
"""
from .errors import (Busy, Error, Interrupted, InvalidArgument, LinkError, NeverStarted, NotFound,
                     PermissionDenied, Stalled, Timeout, Unreachable)
from .arm import Arm, Joint, Pose
from .hand import ReachResult
from .action import Action, Keyframe
from .device import (ALL_GROUPS, Controller, HoldResult, Kind, MoveResult, Notification,
                     NotificationKind, PlayResult, PlayStep, Port, StoppedServo, open, ports)
# (a bus of servos: Controller.servo)
from .servo import (Alarm, BusServos, ModeSetting, Refusal, Refused, Replaced, ScanResult,
                    ServoInfo, ServoMode)
from . import _native

#: The version of the C library the package runs on (lsc_version()), which is
#: the package's own: they are built from one tree.
__version__ = _native.text(_native.lib.lsc_version())

#: Where the C library was loaded from.
library_path = _native.lib.path

__all__ = ["open", "ports", "Controller", "Kind", "Notification", "NotificationKind", "Port",
           "PlayStep", "PlayResult", "MoveResult", "HoldResult", "StoppedServo", "ALL_GROUPS", "Arm", "Joint", "Action",
           "Keyframe", "Error", "Timeout", "Stalled", "NeverStarted", "Busy", "Interrupted", "NotFound", "PermissionDenied",
           "InvalidArgument", "LinkError", "Unreachable", "Pose", "ReachResult", "library_path"]
# (a bus of servos)
__all__ += ["BusServos", "ServoInfo", "ServoMode", "ModeSetting", "Alarm", "Refusal", "Refused",
            "ScanResult", "Replaced"]
