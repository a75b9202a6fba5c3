"""The C library, through ctypes: loading liblsc.so.2, the structures that
cross the boundary (their layouts are checked against the C compiler's by the
tests), and the prototypes of the functions the bindings call.

Private: the public API is the package's (lsc.open, lsc.Arm, lsc.Action...).
"""
import ctypes
import ctypes.util
import os
from typing import Any, List, Optional

#: The shared library's name (its SONAME): the ABI these bindings are written for.
SONAME = "liblsc.so.2"

# ---- constants of the headers (include/lsc/*.h) -----------------------------------

LSC_OK = 0
LSC_EINVAL = -1
LSC_ENOSPC = -2
LSC_ESYNC = -3
LSC_EFRAME = -4
LSC_ETOOBIG = -5
LSC_ETIMEOUT = -6
LSC_EIO = -7
LSC_EREPLY = -8
LSC_EBUSY = -9
LSC_ENODEV = -10
LSC_EACCES = -11
LSC_EINTR = -12

LSC_CMD_GROUP_RUN = 6
LSC_CMD_GROUP_STOP = 7
LSC_CMD_GROUP_COMPLETE = 8
LSC_GROUP_ALL = 0xFF

LSC_MOVE_MAX = 83
LSC_UNLOAD_MAX = 252
LSC_READ_MAX = 84
LSC_OFFSET_MAX = 40
LSC_PARAMS_MAX = 253

LSC_DEVICE_TIMEOUT_DEFAULT = 1000
LSC_DEVICE_FOREVER = 0xFFFFFFFF
LSC_DEVICE_BAUD_MAX = 4000000
LSC_DEVICE_TIMEOUT_MAX = 86400000
LSC_DEVICE_NAME_MAX = 272
LSC_DEVICE_TOLERANCE_DEFAULT = 10
LSC_DEVICE_SERIAL = 0
LSC_DEVICE_HID = 1
LSC_DEVICE_SIM = 2
LSC_DEVICE_LSCD = 3
LSC_DEVICE_LX = 4
LSC_DEVICE_CAUSE_NONE = 0
LSC_DEVICE_CAUSE_NO_REPLY = 9
LSC_DEVICE_CAUSE_NOT_SETTLED = 10
LSC_DEVICE_CAUSE_ACCESS = 11
LSC_DEVICE_CAUSE_WAIT_TIMEOUT = 3
LSC_DEVICE_CAUSE_SIM_NO_GROUP = 5
LSC_DEVICE_CAUSE_NEVER_STARTED = 12
LSC_HOLD_BEYOND = 1
LSC_MOVE_MAX = 83

LSC_DEVICE_CAUSE_STOPPED_SHORT = 7
LSC_SETTLE_STRICT = 1
LSC_SETTLE_NO_READS = 1
LSC_SETTLE_STOPPED = 2
LSC_SIM_BLOCK_NONE = 0
LSC_SIM_BLOCK_ABOVE = 1
LSC_SIM_BLOCK_BELOW = 2

LSC_PLAYER_SERVOS_MAX = 32
LSC_ARM_MESSAGE_MAX = 256
LSC_ARM_DEGREES_MAX = 16
LSC_TRACE_TX = 0
LSC_TRACE_RX = 1

LSC_KIN_JOINTS = 5
LSC_ARM_CHAIN_MAX = 6
LSC_KIN_OK = 0
LSC_KIN_BAD_INPUT = 1
LSC_KIN_OUT_OF_REACH = 2
LSC_KIN_BEYOND_LIMIT = 3

# ---- structures (the C declarations are in the comments) -------------------------


class Servo(ctypes.Structure):
    """lsc_servo (lsc/core.h): {uint8_t id; uint16_t position;}"""
    _fields_ = [("id", ctypes.c_uint8), ("position", ctypes.c_uint16)]


class ServoOffset(ctypes.Structure):
    """lsc_servo_offset (lsc/core.h): {uint8_t id; int8_t offset;}"""
    _fields_ = [("id", ctypes.c_uint8), ("offset", ctypes.c_int8)]


class NotificationC(ctypes.Structure):
    """lsc_notification (lsc/client.h)"""
    _fields_ = [("cmd", ctypes.c_uint8), ("group", ctypes.c_uint8), ("times", ctypes.c_uint16)]


class PlayerConfig(ctypes.Structure):
    """lsc_player_config (lsc/player.h)"""
    _fields_ = [("speed_pct", ctypes.c_uint16), ("times", ctypes.c_uint16),
                ("lead_ms", ctypes.c_uint16), ("baud", ctypes.c_uint32)]


class PlayerStep(ctypes.Structure):
    """lsc_player_step (lsc/player.h)"""
    _fields_ = [("wait_ms", ctypes.c_uint32), ("keyframe", ctypes.c_uint32),
                ("repetition", ctypes.c_uint16), ("lead_in", ctypes.c_bool),
                ("due_ms", ctypes.c_uint32), ("time_ms", ctypes.c_uint16),
                ("nservos", ctypes.c_uint8),
                ("servos", Servo * LSC_PLAYER_SERVOS_MAX),
                ("dropped", ctypes.c_uint32)]


class Sized(ctypes.Structure):
    """A structure that grows (its C struct starts with `size_t size;`, which the
    caller sets to the struct's size): a new one has its size set."""

    def __init__(self, *args: Any, **kw: Any) -> None:
        super().__init__(*args, **kw)
        self.size = ctypes.sizeof(self)


class PlayResult(Sized):
    """lsc_play_result (lsc/play.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("frames", ctypes.c_uint32), ("dropped", ctypes.c_uint32),
                ("keyframe", ctypes.c_uint32), ("max_late_ms", ctypes.c_uint32),
                ("total_ms", ctypes.c_uint32), ("stopped", ctypes.c_bool)]


class ActionC(ctypes.Structure):
    """lsc_action (lsc/files.h)"""
    _fields_ = [("nservos", ctypes.c_uint8),
                ("ids", ctypes.c_uint8 * LSC_PLAYER_SERVOS_MAX),
                ("count", ctypes.c_uint32), ("cap", ctypes.c_uint32),
                ("words", ctypes.POINTER(ctypes.c_uint16))]


class FileError(Sized):
    """lsc_file_error (lsc/files.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("at", ctypes.c_ulong), ("message", ctypes.c_char * 200)]


class Joint(ctypes.Structure):
    """lsc_joint (lsc/units.h)"""
    _fields_ = [("id", ctypes.c_uint8), ("direction", ctypes.c_int8),
                ("pos_min", ctypes.c_uint16), ("pos_max", ctypes.c_uint16),
                ("span_cdeg", ctypes.c_int32), ("zero", ctypes.c_uint16),
                ("min_cdeg", ctypes.c_int32), ("max_cdeg", ctypes.c_int32)]


class SettleStop(ctypes.Structure):
    """lsc_settle_stop (lsc/device.h): {uint8_t id; uint16_t position, target;}"""
    _fields_ = [("id", ctypes.c_uint8), ("position", ctypes.c_uint16),
                ("target", ctypes.c_uint16)]


class SettleResult(Sized):
    """lsc_settle_result (lsc/motion.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("nstopped", ctypes.c_size_t), ("stopped", SettleStop * LSC_READ_MAX)]


class HoldResult(Sized):
    """lsc_hold_result (lsc/motion.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("n", ctypes.c_size_t), ("held", Servo * LSC_READ_MAX),
                ("nbeyond", ctypes.c_size_t), ("beyond", ctypes.c_uint8 * LSC_READ_MAX)]


_F5 = ctypes.c_float * 5


class KinChain(ctypes.Structure):
    """lsc_kin_chain (lsc/kinematics.h)"""
    _fields_ = [("base_mm", ctypes.c_float), ("upper_mm", ctypes.c_float),
                ("fore_mm", ctypes.c_float), ("tool_mm", ctypes.c_float),
                ("min_deg", _F5), ("max_deg", _F5)]


class KinPose(ctypes.Structure):
    """lsc_kin_pose"""
    _fields_ = [("x_mm", ctypes.c_float), ("y_mm", ctypes.c_float), ("z_mm", ctypes.c_float),
                ("pitch_deg", ctypes.c_float), ("roll_deg", ctypes.c_float)]


class KinTarget(ctypes.Structure):
    """lsc_kin_target"""
    _fields_ = [("x_mm", ctypes.c_float), ("y_mm", ctypes.c_float), ("z_mm", ctypes.c_float),
                ("pitch_deg", ctypes.c_float), ("roll_deg", ctypes.c_float),
                ("has_pitch", ctypes.c_bool), ("has_roll", ctypes.c_bool)]


class KinResult(ctypes.Structure):
    """lsc_kin_result"""
    _fields_ = [("status", ctypes.c_int), ("by_mm", ctypes.c_float), ("joint", ctypes.c_int),
                ("high", ctypes.c_bool), ("angle_deg", ctypes.c_float),
                ("pitch_deg", ctypes.c_float)]


class Reach(Sized):
    """lsc_reach (lsc/motion.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("target", KinTarget), ("time_ms", ctypes.c_uint16),
                ("speed_dps", ctypes.c_float), ("line", ctypes.c_bool),
                ("step_mm", ctypes.c_float), ("wait", ctypes.c_bool),
                ("tolerance", ctypes.c_uint16), ("flags", ctypes.c_uint)]


class ReachResult(Sized):
    """lsc_reach_result (lsc/motion.h)"""
    _fields_ = [("size", ctypes.c_size_t), ("kin", KinResult), ("waypoints", ctypes.c_size_t),
                ("time_ms", ctypes.c_uint32), ("settle", SettleResult)]


#: Every structure that crosses the boundary, by its C name (the layout test
#: compares each with the C compiler's sizeof and offsetof).
STRUCTS = {
    "lsc_servo": Servo,
    "lsc_servo_offset": ServoOffset,
    "lsc_notification": NotificationC,
    "lsc_player_config": PlayerConfig,
    "lsc_player_step": PlayerStep,
    "lsc_play_result": PlayResult,
    "lsc_action": ActionC,
    "lsc_file_error": FileError,
    "lsc_joint": Joint,
    "lsc_settle_stop": SettleStop,
    "lsc_settle_result": SettleResult,
    "lsc_hold_result": HoldResult,
    "lsc_kin_chain": KinChain,
    "lsc_kin_pose": KinPose,
    "lsc_kin_target": KinTarget,
    "lsc_kin_result": KinResult,
    "lsc_reach": Reach,
    "lsc_reach_result": ReachResult,
}

#: Enums that cross the boundary as int (the layout test checks their size).
ENUMS = ("lsc_device_kind", "lsc_device_cause", "lsc_file_format", "lsc_trace_dir",
         "lsc_kin_status")

# ---- callbacks ----------------------------------------------------------------------

PLAY_FN = ctypes.CFUNCTYPE(ctypes.c_bool, ctypes.c_void_p, ctypes.POINTER(PlayerStep),
                           ctypes.c_uint32)
RECORD_FN = ctypes.CFUNCTYPE(ctypes.c_bool, ctypes.c_void_p, ctypes.POINTER(ActionC),
                             ctypes.c_bool)
TRACE_FN = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int,
                            ctypes.POINTER(ctypes.c_uint8), ctypes.c_size_t)
STATUS_FN = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p)

# ---- prototypes ---------------------------------------------------------------------

_p = ctypes.c_void_p
_cp = ctypes.c_char_p
_int = ctypes.c_int
_u8, _u16, _u32 = ctypes.c_uint8, ctypes.c_uint16, ctypes.c_uint32
_i8 = ctypes.c_int8
_size = ctypes.c_size_t
_bool = ctypes.c_bool
_P = ctypes.POINTER

#: name: (restype, argtypes). Device and arm handles are opaque pointers.
PROTOTYPES = {
    "lsc_strerror": (_cp, [_int]),
    "lsc_version": (_cp, []),
    "lsc_ids_first_repeat": (_size, [_P(_u8), _size, _size]),
    # lsc/device.h
    "lsc_device_open": (_int, [_cp, _p, _P(_p)]),
    "lsc_device_config_new": (_p, []),
    "lsc_device_config_free": (None, [_p]),
    "lsc_device_config_set_baud": (_int, [_p, _u32]),
    "lsc_device_config_set_timeout_ms": (_int, [_p, _u32]),
    "lsc_device_config_set_hid_id": (_int, [_p, _u16, _u16]),
    "lsc_device_close": (None, [_p]),
    "lsc_device_error": (_cp, [_p]),
    "lsc_device_name": (_cp, [_p]),
    "lsc_device_kind_of": (_int, [_p]),
    "lsc_device_error_cause": (_int, [_p]),
    "lsc_device_groups": (_size, [_p, _P(_u8), _size]),
    "lsc_device_list": (_int, [_P(_P(_p)), ctypes.c_char_p, _size]),
    "lsc_device_list_free": (None, [_P(_p)]),
    "lsc_device_info_name": (_cp, [_p]),
    "lsc_device_info_path": (_cp, [_p]),
    "lsc_device_info_description": (_cp, [_p]),
    "lsc_device_info_serial": (_cp, [_p]),
    "lsc_device_info_manufacturer": (_cp, [_p]),
    "lsc_device_info_vid": (_u16, [_p]),
    "lsc_device_info_pid": (_u16, [_p]),
    "lsc_device_info_usb": (_bool, [_p]),
    "lsc_device_info_kind": (_int, [_p]),
    "lsc_device_info_controller": (_bool, [_p]),
    "lsc_device_set_timeout": (None, [_p, _u32]),
    "lsc_device_timeout": (_u32, [_p]),
    "lsc_device_set_trace": (None, [_p, TRACE_FN, _p]),
    "lsc_device_set_arm": (_int, [_p, _p]),
    "lsc_device_now_ms": (_u32, [_p]),
    "lsc_device_fileno": (_int, [_p]),
    "lsc_device_interrupt": (None, [_p]),
    "lsc_device_set_virtual_clock": (_int, [_p, _bool]),
    "lsc_device_env_arm": (_cp, []),
    "lsc_device_env_port": (_cp, []),
    "lsc_device_config_from_env": (_int, [_p, ctypes.c_char_p, _size]),
    "lsc_device_next_event_ms": (_u32, [_p]),
    "lsc_device_move": (_int, [_p, _u16, _P(Servo), _size]),
    "lsc_device_run": (_int, [_p, _u8, _u16]),
    "lsc_device_stop": (_int, [_p]),
    "lsc_device_halt": (_int, [_p]),
    "lsc_device_hold": (_int, [_p, _P(_u8), _size, _P(HoldResult)]),
    "lsc_device_parse_ids_all": (_int, [_p, _cp, _cp, _P(_u8), _size, ctypes.c_char_p, _size]),
    "lsc_device_start_ms": (_u32, [_p]),
    "lsc_device_speed": (_int, [_p, _u8, _u16]),
    "lsc_device_unload": (_int, [_p, _P(_u8), _size]),
    "lsc_device_adjust_offset": (_int, [_p, _u8, _i8]),
    "lsc_device_send": (_int, [_p, _u8, _P(_u8), _size, _bool]),
    "lsc_device_battery": (_int, [_p, _P(_u16)]),
    "lsc_device_read": (_int, [_p, _P(_u8), _size, _P(Servo)]),
    "lsc_device_read_offsets": (_int, [_p, _P(_u8), _size, _P(ServoOffset)]),
    "lsc_device_request": (_int, [_p, _u8, _P(_u8), _size, _u8, _P(_u8), _size]),
    "lsc_device_settle": (_int, [_p, _P(Servo), _size, _u16, _u16]),
    "lsc_device_settle_ex": (_int, [_p, _P(Servo), _size, _u16, _u16, ctypes.c_uint,
                                    _P(SettleResult)]),
    "lsc_sim_block": (_int, [_p, _u8, _u16, ctypes.c_int]),
    "lsc_device_poll": (_int, [_p, _u32]),
    "lsc_device_notification": (_int, [_p, _u32, _P(NotificationC)]),
    "lsc_device_dropped_notifications": (_u32, [_p]),
    "lsc_device_wait_group": (_int, [_p, _u8, _u32, _P(NotificationC)]),
    "lsc_device_group_started": (_bool, [_p]),
    "lsc_device_play": (_int, [_p, _P(ActionC), _P(PlayerConfig), PLAY_FN, _p,
                               _P(PlayResult)]),
    "lsc_device_take_keyframe": (_int, [_p, _P(ActionC), _u32, ctypes.c_uint]),
    "lsc_device_record": (_int, [_p, _P(ActionC), _u32, _u32, RECORD_FN, _p]),
    "lsc_device_where": (_int, [_p, _P(ctypes.c_float), _P(KinPose)]),
    "lsc_device_reach": (_int, [_p, _P(Reach), _P(ReachResult)]),
    "lsc_device_move_time": (_int, [_p, _P(Servo), _size, ctypes.c_float, _P(_u16)]),
    "lsc_device_move_speed": (_int, [_p, _P(Servo), _size, ctypes.c_float, _bool, _u16,
                                     ctypes.c_uint, _P(_u16), _P(SettleResult)]),
    # lsc/kinematics.h
    "lsc_kin_forward": (_int, [_P(KinChain), _P(ctypes.c_float), _P(KinPose)]),
    "lsc_kin_inverse": (_int, [_P(KinChain), _P(KinTarget), _P(ctypes.c_float),
                               _P(ctypes.c_float), _P(KinResult)]),
    # lsc/arm.h
    "lsc_arm_chain": (_int, [_p, _P(KinChain), _P(_int), ctypes.c_char_p, _size]),
    "lsc_arm_parse": (_int, [_cp, _size, _cp, _P(_p), ctypes.c_char_p, _size]),
    "lsc_arm_load": (_int, [_cp, _P(_p), ctypes.c_char_p, _size]),
    "lsc_arm_open": (_int, [_cp, _P(_p), ctypes.c_char_p, _size]),
    "lsc_calibrated_find": (_int, [_cp, ctypes.c_char_p, _size]),
    "lsc_arm_free": (None, [_p]),
    "lsc_arm_count": (_size, [_p]),
    "lsc_arm_name": (_cp, [_p, _size]),
    "lsc_arm_joint": (_P(Joint), [_p, _size]),
    "lsc_arm_find": (_int, [_p, _cp]),
    "lsc_arm_target": (_int, [_p, _cp, _P(Servo), ctypes.c_char_p, _size]),
    "lsc_arm_servo_id": (_int, [_p, _cp, _P(_u8), ctypes.c_char_p, _size]),
    "lsc_arm_check": (_int, [_p, _P(Servo), _size, ctypes.c_char_p, _size]),
    "lsc_arm_degrees": (_int, [_p, _P(Servo), ctypes.c_char_p, _size]),
    "lsc_arm_target_deg": (_int, [_p, _cp, ctypes.c_double, _P(Servo), ctypes.c_char_p, _size]),
    "lsc_arm_angle": (_int, [_p, _P(Servo), _P(ctypes.c_double)]),
    # lsc/files.h
    "lsc_file_format_of": (_int, [_cp]),
    "lsc_action_init": (_int, [_P(ActionC), _P(_u8), _size]),
    "lsc_action_append": (_int, [_P(ActionC), _u16, _P(_u16)]),
    "lsc_action_free": (None, [_P(ActionC)]),
    "lsc_action_read": (_int, [_cp, _P(ActionC), _P(FileError)]),
    "lsc_action_read_group": (_int, [_cp, _int, _P(ActionC), _P(FileError)]),
    "lsc_action_to_arm": (_int, [_P(ActionC), _p, _p, _P(ActionC), ctypes.c_char_p, _size]),
    # lsc/lscd.h (through lsc_device_lscd)
    "lsc_device_lscd": (_p, [_p]),
    "lsc_lscd_error": (_cp, [_p]),
    "lsc_lscd_status": (_int, [_p, STATUS_FN, _p, _u32]),
    "lsc_lscd_lease": (_int, [_p, _u32, _u32]),
    "lsc_lscd_lease_ms": (_u32, [_p]),
    "lsc_lscd_release": (_int, [_p]),
    "lsc_action_write": (_int, [_cp, _P(ActionC), _P(FileError)]),
}


# ---- a bus of servos (lsc/bus.h, lsc/lxclient.h), for lsc/servo.py ---------------

LSC_LX_ID_MAX = 253
LSC_LX_BROADCAST = 254
LSC_LX_POSITION_MAX = 1000
LSC_LX_OFFSET_MAX = 125
LSC_LX_VIN_MIN = 4500
LSC_LX_VIN_MAX = 12000
LSC_LX_TEMP_LIMIT_MIN = 50
LSC_LX_TEMP_LIMIT_MAX = 100
LSC_LX_SPEED_MAX = 1000
LSC_LX_ALARM_ALL = 7
LSC_LX_MODE_SERVO = 0
LSC_LX_MODE_MOTOR = 1
LSC_LX_DONE = 0
LSC_LX_NOT_READ_BACK = 7


class LxScan(ctypes.Structure):
    """lsc_lx_scan (lsc/lxclient.h)"""
    _fields_ = [("found", ctypes.c_uint8 * 32), ("garbled", ctypes.c_uint8 * 32),
                ("count", ctypes.c_uint16), ("asked", ctypes.c_uint16)]


class LxInfo(ctypes.Structure):
    """lsc_lx_info (lsc/lxclient.h)"""
    _fields_ = [("id", ctypes.c_uint8), ("position", ctypes.c_int16),
                ("temp_c", ctypes.c_uint8), ("vin_mv", ctypes.c_uint16),
                ("offset", ctypes.c_int8), ("limit_min", ctypes.c_uint16),
                ("limit_max", ctypes.c_uint16), ("vin_min_mv", ctypes.c_uint16),
                ("vin_max_mv", ctypes.c_uint16), ("temp_limit_c", ctypes.c_uint8),
                ("mode", ctypes.c_uint8), ("speed", ctypes.c_int16),
                ("torque", ctypes.c_bool), ("led", ctypes.c_bool),
                ("alarms", ctypes.c_uint8)]


STRUCTS.update({"lsc_lx_scan": LxScan, "lsc_lx_info": LxInfo})
#: Enums of the bus that cross the boundary as int (lsc_lx_refusal: through an int *).
LX_ENUMS = ("lsc_lx_refusal",)

_i16 = ctypes.c_int16
PROTOTYPES.update({
    "lsc_device_lxclient": (_p, [_p]),
    "lsc_device_lx_result": (_int, [_p, _int, _cp, _u8, _int]),
    "lsc_device_lx_replace": (_int, [_p, _p, _cp, _P(_u8), _P(_int)]),
    "lsc_device_lx_check_arm": (_int, [_p, _p]),
    "lsc_lxclient_scan": (_int, [_p, _P(_u8), _size, _u32, _P(LxScan)]),
    "lsc_lxclient_info": (_int, [_p, _u8, _P(LxInfo)]),
    "lsc_lxclient_change_id": (_int, [_p, _u8, _u8, _P(_int)]),
    "lsc_lxclient_set_id_alone": (_int, [_p, _u8, _u32, _P(_u8), _P(_int)]),
    "lsc_lxclient_offset_change": (_int, [_p, _u8, _int, _bool, _P(_i8), _P(_int)]),
    "lsc_lxclient_read_offset": (_int, [_p, _u8, _P(_i8)]),
    "lsc_lxclient_write_limits": (_int, [_p, _u8, _u16, _u16]),
    "lsc_lxclient_read_limits": (_int, [_p, _u8, _P(_u16), _P(_u16)]),
    "lsc_lxclient_write_vin_limits": (_int, [_p, _u8, _u16, _u16]),
    "lsc_lxclient_read_vin_limits": (_int, [_p, _u8, _P(_u16), _P(_u16)]),
    "lsc_lxclient_write_temp_limit": (_int, [_p, _u8, _u8]),
    "lsc_lxclient_read_temp_limit": (_int, [_p, _u8, _P(_u8)]),
    "lsc_lxclient_write_mode": (_int, [_p, _u8, _u8, _i16]),
    "lsc_lxclient_read_mode": (_int, [_p, _u8, _P(_u8), _P(_i16)]),
    "lsc_lxclient_write_torque": (_int, [_p, _u8, _bool]),
    "lsc_lxclient_read_torque": (_int, [_p, _u8, _P(_bool)]),
    "lsc_lxclient_write_led": (_int, [_p, _u8, _bool]),
    "lsc_lxclient_read_led": (_int, [_p, _u8, _P(_bool)]),
    "lsc_lxclient_write_alarms": (_int, [_p, _u8, _u8]),
    "lsc_lxclient_read_alarms": (_int, [_p, _u8, _P(_u8)]),
    "lsc_lxclient_read_temp": (_int, [_p, _u8, _P(_u8)]),
    "lsc_lxclient_read_vin": (_int, [_p, _u8, _P(_u16)]),
    "lsc_lx_refusal_str": (_cp, [_int]),
})

# ---- end of the bus of servos -----------------------------------------------------


class Library:
    """liblsc with the prototypes above set: lib.lsc_device_open(...) etc."""

    def __init__(self, cdll: ctypes.CDLL, path: str) -> None:
        self.cdll = cdll
        self.path = path
        missing: List[str] = []
        for name, (restype, argtypes) in PROTOTYPES.items():
            try:
                fn = getattr(cdll, name)
            except AttributeError:
                missing.append(name)
                continue
            fn.restype = restype
            fn.argtypes = argtypes
            setattr(self, name, fn)
        if missing:
            raise ImportError(
                "lsc: the library %s lacks %s: it is older than these bindings (%s)"
                % (path, ", ".join(missing[:3]) +
                   (" and %d more" % (len(missing) - 3) if len(missing) > 3 else ""),
                   install_advice(os.path.dirname(os.path.abspath(__file__)), newer=True)))

    def __getattr__(self, name: str) -> Any:
        """(for a type checker: the functions set above, typed by ctypes only)"""
        raise AttributeError(name)


def install_advice(package_dir: str, newer: bool = False) -> str:
    """What to do when liblsc.so.2 cannot be loaded (or is too old), for the
    package installed in package_dir: Debian's python3-lsc (under /usr/lib/python3)
    gets its library from the package liblsc2; a package from the source tree
    (PYTHONPATH, a venv's pip install) from a build or an install of that tree."""
    if package_dir.startswith("/usr/lib/python3/"):
        return "apt install liblsc2" + (" (0.4.0 or later)" if newer else "")
    return ("%sbuild and install the C library from the source tree (cmake --install; "
            "under /usr/local then run sudo ldconfig), or set LSC_LIBRARY to the "
            "liblsc.so.2 of an install (PREFIX/lib/liblsc.so.2) or of a build "
            "(BUILD/src/liblsc.so.2)" % ("a newer library: " if newer else ""))


def _load() -> Library:
    """Loads the library: $LSC_LIBRARY (a path, for a build tree) if set and not
    empty, else liblsc.so.2 from the system's library path."""
    path = os.environ.get("LSC_LIBRARY", "")
    tried: List[str] = []
    if path:
        candidates = [path]
    else:
        candidates = [SONAME]
        found = ctypes.util.find_library("lsc")
        if found and found != SONAME and found.startswith("liblsc.so.2"):
            candidates.append(found)
    for c in candidates:
        try:
            return Library(ctypes.CDLL(c), c)
        except OSError as e:
            tried.append(str(e))
    if path:
        raise ImportError("lsc: cannot load LSC_LIBRARY=%s: %s" % (path, "; ".join(tried)))
    raise ImportError("lsc: cannot load %s (%s): %s"
                      % (SONAME, "; ".join(tried),
                         install_advice(os.path.dirname(os.path.abspath(__file__)))))


lib = _load()


def text(b: Optional[bytes]) -> str:
    """A C string (bytes or None) as str: UTF-8, undecodable bytes escaped."""
    return "" if b is None else b.decode("utf-8", "backslashreplace")
