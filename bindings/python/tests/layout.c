/* Prints the layout of every structure the Python bindings pass across the
 * boundary (bindings/python/lsc/_native.py), as the C compiler sees it:
 *   NAME SIZEOF
 *   NAME.FIELD OFFSETOF SIZEOF
 *   CONSTANT VALUE
 * tests/test_layout.py compares each line with the ctypes declarations: a
 * mismatch fails the tests. Built by bindings/python/CMakeLists.txt, or by
 * the test itself against installed headers. */
#include <stddef.h>
#include <stdio.h>

#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/arm.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/kinematics.h"
#include "lsc/discovery.h"
#include "lsc/lxclient.h" /* the bus of servos (lsc/servo.py) */

#define STRUCT(type) printf("%s %zu\n", #type, sizeof(type))
#define FIELD(type, field) \
    printf("%s.%s %zu %zu\n", #type, #field, offsetof(type, field), sizeof(((type *)0)->field))

int main(void)
{
    STRUCT(lsc_servo);
    FIELD(lsc_servo, id);
    FIELD(lsc_servo, position);

    STRUCT(lsc_servo_offset);
    FIELD(lsc_servo_offset, id);
    FIELD(lsc_servo_offset, offset);

    STRUCT(lsc_notification);
    FIELD(lsc_notification, cmd);
    FIELD(lsc_notification, group);
    FIELD(lsc_notification, times);



    STRUCT(lsc_player_config);
    FIELD(lsc_player_config, speed_pct);
    FIELD(lsc_player_config, times);
    FIELD(lsc_player_config, lead_ms);
    FIELD(lsc_player_config, baud);

    STRUCT(lsc_player_step);
    FIELD(lsc_player_step, wait_ms);
    FIELD(lsc_player_step, keyframe);
    FIELD(lsc_player_step, repetition);
    FIELD(lsc_player_step, lead_in);
    FIELD(lsc_player_step, due_ms);
    FIELD(lsc_player_step, time_ms);
    FIELD(lsc_player_step, nservos);
    FIELD(lsc_player_step, servos);
    FIELD(lsc_player_step, dropped);

    STRUCT(lsc_play_result);
    FIELD(lsc_play_result, size);
    FIELD(lsc_play_result, frames);
    FIELD(lsc_play_result, dropped);
    FIELD(lsc_play_result, keyframe);
    FIELD(lsc_play_result, max_late_ms);
    FIELD(lsc_play_result, total_ms);
    FIELD(lsc_play_result, stopped);

    STRUCT(lsc_action);
    FIELD(lsc_action, nservos);
    FIELD(lsc_action, ids);
    FIELD(lsc_action, count);
    FIELD(lsc_action, cap);
    FIELD(lsc_action, words);

    STRUCT(lsc_file_error);
    FIELD(lsc_file_error, size);
    FIELD(lsc_file_error, at);
    FIELD(lsc_file_error, message);

    STRUCT(lsc_joint);
    FIELD(lsc_joint, id);
    FIELD(lsc_joint, direction);
    FIELD(lsc_joint, pos_min);
    FIELD(lsc_joint, pos_max);
    FIELD(lsc_joint, span_cdeg);
    FIELD(lsc_joint, zero);
    FIELD(lsc_joint, min_cdeg);
    FIELD(lsc_joint, max_cdeg);

    STRUCT(lsc_settle_stop);
    FIELD(lsc_settle_stop, id);
    FIELD(lsc_settle_stop, position);
    FIELD(lsc_settle_stop, target);

    STRUCT(lsc_settle_result);
    FIELD(lsc_settle_result, size);
    FIELD(lsc_settle_result, nstopped);
    FIELD(lsc_settle_result, stopped);

    STRUCT(lsc_hold_result);
    FIELD(lsc_hold_result, size);
    FIELD(lsc_hold_result, n);
    FIELD(lsc_hold_result, held);
    FIELD(lsc_hold_result, nbeyond);
    FIELD(lsc_hold_result, beyond);

    STRUCT(lsc_kin_chain);
    FIELD(lsc_kin_chain, base_mm);
    FIELD(lsc_kin_chain, upper_mm);
    FIELD(lsc_kin_chain, fore_mm);
    FIELD(lsc_kin_chain, tool_mm);
    FIELD(lsc_kin_chain, min_deg);
    FIELD(lsc_kin_chain, max_deg);

    STRUCT(lsc_kin_pose);
    FIELD(lsc_kin_pose, x_mm);
    FIELD(lsc_kin_pose, y_mm);
    FIELD(lsc_kin_pose, z_mm);
    FIELD(lsc_kin_pose, pitch_deg);
    FIELD(lsc_kin_pose, roll_deg);

    STRUCT(lsc_kin_target);
    FIELD(lsc_kin_target, x_mm);
    FIELD(lsc_kin_target, y_mm);
    FIELD(lsc_kin_target, z_mm);
    FIELD(lsc_kin_target, pitch_deg);
    FIELD(lsc_kin_target, roll_deg);
    FIELD(lsc_kin_target, has_pitch);
    FIELD(lsc_kin_target, has_roll);

    STRUCT(lsc_kin_result);
    FIELD(lsc_kin_result, status);
    FIELD(lsc_kin_result, by_mm);
    FIELD(lsc_kin_result, joint);
    FIELD(lsc_kin_result, high);
    FIELD(lsc_kin_result, angle_deg);
    FIELD(lsc_kin_result, pitch_deg);

    STRUCT(lsc_reach);
    FIELD(lsc_reach, size);
    FIELD(lsc_reach, target);
    FIELD(lsc_reach, time_ms);
    FIELD(lsc_reach, speed_dps);
    FIELD(lsc_reach, line);
    FIELD(lsc_reach, step_mm);
    FIELD(lsc_reach, wait);
    FIELD(lsc_reach, tolerance);
    FIELD(lsc_reach, flags);

    STRUCT(lsc_reach_result);
    FIELD(lsc_reach_result, size);
    FIELD(lsc_reach_result, kin);
    FIELD(lsc_reach_result, waypoints);
    FIELD(lsc_reach_result, time_ms);
    FIELD(lsc_reach_result, settle);

    /* enums passed or returned as int */
    STRUCT(lsc_device_kind);
    STRUCT(lsc_device_cause);
    STRUCT(lsc_file_format);
    STRUCT(lsc_trace_dir);
    STRUCT(lsc_kin_status);
    /* the constants the bindings copy */
    printf("LSC_DEVICE_NAME_MAX %u\n", (unsigned)LSC_DEVICE_NAME_MAX);
    printf("LSC_PLAYER_SERVOS_MAX %u\n", (unsigned)LSC_PLAYER_SERVOS_MAX);
    printf("LSC_ARM_MESSAGE_MAX %u\n", (unsigned)LSC_ARM_MESSAGE_MAX);
    printf("LSC_ARM_DEGREES_MAX %u\n", (unsigned)LSC_ARM_DEGREES_MAX);
    printf("LSC_DEVICE_TIMEOUT_DEFAULT %u\n", (unsigned)LSC_DEVICE_TIMEOUT_DEFAULT);
    printf("LSC_DEVICE_TOLERANCE_DEFAULT %u\n", (unsigned)LSC_DEVICE_TOLERANCE_DEFAULT);
    printf("LSC_DEVICE_FOREVER %lu\n", (unsigned long)LSC_DEVICE_FOREVER);
    printf("LSC_DEVICE_BAUD_MAX %lu\n", (unsigned long)LSC_DEVICE_BAUD_MAX);
    printf("LSC_DEVICE_TIMEOUT_MAX %lu\n", (unsigned long)LSC_DEVICE_TIMEOUT_MAX);
    printf("LSC_GROUP_ALL %u\n", (unsigned)LSC_GROUP_ALL);
    printf("LSC_PARAMS_MAX %u\n", (unsigned)LSC_PARAMS_MAX);
    printf("LSC_DEVICE_SERIAL %d\n", (int)LSC_DEVICE_SERIAL);
    printf("LSC_DEVICE_HID %d\n", (int)LSC_DEVICE_HID);
    printf("LSC_DEVICE_SIM %d\n", (int)LSC_DEVICE_SIM);
    printf("LSC_DEVICE_LSCD %d\n", (int)LSC_DEVICE_LSCD);
    printf("LSC_DEVICE_LX %d\n", (int)LSC_DEVICE_LX);
    printf("LSC_DEVICE_CAUSE_NONE %d\n", (int)LSC_DEVICE_CAUSE_NONE);
    printf("LSC_DEVICE_CAUSE_NO_REPLY %d\n", (int)LSC_DEVICE_CAUSE_NO_REPLY);
    printf("LSC_DEVICE_CAUSE_NOT_SETTLED %d\n", (int)LSC_DEVICE_CAUSE_NOT_SETTLED);
    printf("LSC_DEVICE_CAUSE_ACCESS %d\n", (int)LSC_DEVICE_CAUSE_ACCESS);
    printf("LSC_DEVICE_CAUSE_WAIT_TIMEOUT %d\n", (int)LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    printf("LSC_DEVICE_CAUSE_SIM_NO_GROUP %d\n", (int)LSC_DEVICE_CAUSE_SIM_NO_GROUP);
    printf("LSC_DEVICE_CAUSE_NEVER_STARTED %d\n", (int)LSC_DEVICE_CAUSE_NEVER_STARTED);
    printf("LSC_HOLD_BEYOND %d\n", (int)LSC_HOLD_BEYOND);
    printf("LSC_MOVE_MAX %u\n", (unsigned)LSC_MOVE_MAX);
    printf("LSC_TRACE_TX %d\n", (int)LSC_TRACE_TX);
    printf("LSC_DEVICE_CAUSE_STOPPED_SHORT %d\n", (int)LSC_DEVICE_CAUSE_STOPPED_SHORT);
    printf("LSC_SETTLE_STRICT %d\n", (int)LSC_SETTLE_STRICT);
    printf("LSC_SETTLE_NO_READS %d\n", (int)LSC_SETTLE_NO_READS);
    printf("LSC_SETTLE_STOPPED %d\n", (int)LSC_SETTLE_STOPPED);
    printf("LSC_SIM_BLOCK_NONE %d\n", (int)LSC_SIM_BLOCK_NONE);
    printf("LSC_SIM_BLOCK_ABOVE %d\n", (int)LSC_SIM_BLOCK_ABOVE);
    printf("LSC_SIM_BLOCK_BELOW %d\n", (int)LSC_SIM_BLOCK_BELOW);
    printf("LSC_TRACE_RX %d\n", (int)LSC_TRACE_RX);
    printf("LSC_CMD_GROUP_RUN %d\n", (int)LSC_CMD_GROUP_RUN);
    printf("LSC_CMD_GROUP_STOP %d\n", (int)LSC_CMD_GROUP_STOP);
    printf("LSC_CMD_GROUP_COMPLETE %d\n", (int)LSC_CMD_GROUP_COMPLETE);
    printf("LSC_EINVAL %d\n", (int)LSC_EINVAL);
    printf("LSC_ENOSPC %d\n", (int)LSC_ENOSPC);
    printf("LSC_ESYNC %d\n", (int)LSC_ESYNC);
    printf("LSC_EFRAME %d\n", (int)LSC_EFRAME);
    printf("LSC_ETOOBIG %d\n", (int)LSC_ETOOBIG);
    printf("LSC_ETIMEOUT %d\n", (int)LSC_ETIMEOUT);
    printf("LSC_EIO %d\n", (int)LSC_EIO);
    printf("LSC_EREPLY %d\n", (int)LSC_EREPLY);
    printf("LSC_EBUSY %d\n", (int)LSC_EBUSY);
    printf("LSC_ENODEV %d\n", (int)LSC_ENODEV);
    printf("LSC_EACCES %d\n", (int)LSC_EACCES);
    printf("LSC_EINTR %d\n", (int)LSC_EINTR);
    printf("LSC_KIN_JOINTS %d\n", (int)LSC_KIN_JOINTS);
    printf("LSC_ARM_CHAIN_MAX %u\n", (unsigned)LSC_ARM_CHAIN_MAX);
    printf("LSC_KIN_OK %d\n", (int)LSC_KIN_OK);
    printf("LSC_KIN_BAD_INPUT %d\n", (int)LSC_KIN_BAD_INPUT);
    printf("LSC_KIN_OUT_OF_REACH %d\n", (int)LSC_KIN_OUT_OF_REACH);
    printf("LSC_KIN_BEYOND_LIMIT %d\n", (int)LSC_KIN_BEYOND_LIMIT);
    /* ---- a bus of servos (lsc/servo.py) ---- */
    STRUCT(lsc_lx_scan);
    FIELD(lsc_lx_scan, found);
    FIELD(lsc_lx_scan, garbled);
    FIELD(lsc_lx_scan, count);
    FIELD(lsc_lx_scan, asked);
    STRUCT(lsc_lx_info);
    FIELD(lsc_lx_info, id);
    FIELD(lsc_lx_info, position);
    FIELD(lsc_lx_info, temp_c);
    FIELD(lsc_lx_info, vin_mv);
    FIELD(lsc_lx_info, offset);
    FIELD(lsc_lx_info, limit_min);
    FIELD(lsc_lx_info, limit_max);
    FIELD(lsc_lx_info, vin_min_mv);
    FIELD(lsc_lx_info, vin_max_mv);
    FIELD(lsc_lx_info, temp_limit_c);
    FIELD(lsc_lx_info, mode);
    FIELD(lsc_lx_info, speed);
    FIELD(lsc_lx_info, torque);
    FIELD(lsc_lx_info, led);
    FIELD(lsc_lx_info, alarms);
    STRUCT(lsc_lx_refusal);
    printf("LSC_LX_ID_MAX %u\n", (unsigned)LSC_LX_ID_MAX);
    printf("LSC_LX_BROADCAST %u\n", (unsigned)LSC_LX_BROADCAST);
    printf("LSC_LX_POSITION_MAX %u\n", (unsigned)LSC_LX_POSITION_MAX);
    printf("LSC_LX_OFFSET_MAX %d\n", (int)LSC_LX_OFFSET_MAX);
    printf("LSC_LX_VIN_MIN %u\n", (unsigned)LSC_LX_VIN_MIN);
    printf("LSC_LX_VIN_MAX %u\n", (unsigned)LSC_LX_VIN_MAX);
    printf("LSC_LX_TEMP_LIMIT_MIN %u\n", (unsigned)LSC_LX_TEMP_LIMIT_MIN);
    printf("LSC_LX_TEMP_LIMIT_MAX %u\n", (unsigned)LSC_LX_TEMP_LIMIT_MAX);
    printf("LSC_LX_SPEED_MAX %d\n", (int)LSC_LX_SPEED_MAX);
    printf("LSC_LX_ALARM_ALL %u\n", (unsigned)LSC_LX_ALARM_ALL);
    printf("LSC_LX_MODE_SERVO %d\n", (int)LSC_LX_MODE_SERVO);
    printf("LSC_LX_MODE_MOTOR %d\n", (int)LSC_LX_MODE_MOTOR);
    printf("LSC_LX_DONE %d\n", (int)LSC_LX_DONE);
    printf("LSC_LX_NOT_READ_BACK %d\n", (int)LSC_LX_NOT_READ_BACK);
    /* ---- end of the bus of servos ---- */
    return 0;
}
