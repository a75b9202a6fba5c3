/*
 * lsc bus: a bus of serial bus servos through the device layer ("lx:PATH":
 * a BusLinker or any serial port at 115200 by default), for what only a bus
 * has. Host only; errors as lsc/device.h says.
 *
 * What works on a board works on a bus with the same calls: lsc_device_move
 * (positions 0..1000, times 0..30000 ms; the servos start together:
 * MOVE_TIME_WAIT_WRITE to each, then one broadcast MOVE_START),
 * lsc_device_read (POS_READ to each; the ids must be given), lsc_device_unload
 * (torque off; no ids: every servo), the offsets, settle, hold, halt (one
 * broadcast MOVE_STOP: every servo stops where it is, nothing read), arm
 * profiles, play and record. A bus has no action groups and no board's
 * battery: lsc_device_run, _stop, _speed and _battery are refused (LSC_EINVAL,
 * nothing sent, the line says where a servo's supply voltage is), and waits
 * for notifications end at once (LSC_ETIMEOUT). lsc_device_kind_of_name says
 * LSC_DEVICE_LX for "lx:...". */
#ifndef LSC_BUS_H
#define LSC_BUS_H

#include <stdint.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/lxclient.h" /* lsc_lxclient, lsc_lx_refusal */

#ifdef __cplusplus
extern "C" {
#endif

/* The bus client of an lx:PATH device, for what only a bus has (lsc/lxclient.h:
 * scan, info, the safe id change, offsets, limits, modes); NULL for any other
 * kind, or NULL d. Its timeout is the device's. Valid until lsc_device_close;
 * use it from the device's thread only. */
LSC_API struct lsc_lxclient *lsc_device_lxclient(lsc_device *d);
/* The outcome r of a call of that bus client (why: its lsc_lx_refusal, or
 * LSC_LX_DONE for the calls without one) made for `what` ("servo id 1 3"),
 * asking servo id, as d's error: "" when r >= 0; a refusal (LSC_EINVAL,
 * nothing written) in the client's words; no reply, or a bad one, from servo
 * id; a value written but not read back; else the port's line. Returns r, or
 * LSC_EINVAL when d is no lx:PATH device (or what is NULL). */
LSC_API int lsc_device_lx_result(lsc_device *d, int r, const char *what, uint8_t id, int why);
/* A new servo for joint `joint` (its name, or its servo's id) of arm on the
 * bus d: it must be alone on the bus (lsc_lxclient_set_id_alone: else
 * refused, nothing written); it gets the joint's id, then the joint's limits
 * as its angle limits, read back. *old_id (may be NULL) gets the id it had.
 * Returns 0, or an error after d's line. Refused (LSC_EINVAL, nothing
 * written): no such joint, limits no bus servo takes, d no lx:PATH device or
 * NULL arguments (LSC_LX_BAD_ARGUMENT); no servo answers (LSC_LX_NO_SERVO);
 * more than one does (LSC_LX_NOT_ALONE). The new id or the limits not read
 * back as written: LSC_LX_NOT_READ_BACK (LSC_EREPLY, or the read's error).
 * why (may be NULL) says which; a transport error leaves LSC_LX_DONE. */
LSC_API int lsc_device_lx_replace(lsc_device *d, const lsc_arm *arm, const char *joint,
                                  uint8_t *old_id, lsc_lx_refusal *why);
/* Whether every joint of arm answers on the bus d, once: a scan of their ids.
 * Returns the number of joints, or an error after d's line: LSC_ETIMEOUT (a
 * joint's servo does not answer), LSC_EREPLY (its answers collide: two
 * servos share the id), LSC_EINVAL (an id no bus servo has; d no lx:PATH
 * device, arm NULL). */
LSC_API int lsc_device_lx_check_arm(lsc_device *d, const lsc_arm *arm);

#ifdef __cplusplus
}
#endif

#endif
