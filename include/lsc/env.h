/*
 * lsc env: what every front end (lscctl, lscd, the Python bindings) takes
 * from the environment, read the same way for all, the USB ids' grammar
 * (VID:PID) that --hid-id and $LSC_HID_ID share, and the kind of controller
 * a name (or $LSC_PORT) selects before anything is opened.
 *
 * Host only.
 */
#ifndef LSC_ENV_H
#define LSC_ENV_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What every front end (lscctl, lscd, the Python bindings) takes from the
 * environment, read here the same way for all (a variable set to "" is
 * unset):
 *   LSC_PORT      the controller when none is named: lsc_device_open(NULL),
 *                 lsc_device_kind_of_name(NULL)
 *   LSC_ARM       the path of an arm profile (lsc/arm.h) when none is given:
 *                 joint names, degrees and limits
 *   LSC_HID_ID    VID:PID in hex: another HID controller's USB ids to accept
 *                 (lsc_device_config_set_hid_id)
 *   LSC_LSCD_DIR  where the names lscd:NAME are (lsc/lscd.h; default
 *                 LSC_LSCD_DIR)
 * $LSC_PORT's value, or NULL. */
LSC_API const char *lsc_device_env_port(void);
/* $LSC_ARM's value, or NULL. */
LSC_API const char *lsc_device_env_arm(void);
/* $LSC_HID_ID into cfg's HID ids (lsc_device_config_set_hid_id), when it is
 * set and cfg has none (0:0: ids the front end was given win). Returns 0, or
 * LSC_EINVAL with cfg unchanged and why[whylen] (may be NULL) saying so when
 * it is no VID:PID, or cfg is NULL. */
LSC_API int lsc_device_config_from_env(lsc_device_config *cfg, char *why, size_t whylen);
/* USB ids as "VID:PID": 1..4 hex digits each, not 0:0 (what --hid-id and
 * $LSC_HID_ID take). Returns 0 and *vid, *pid, or LSC_EINVAL (they are
 * unchanged; any argument NULL too). */
LSC_API int lsc_device_parse_hid_id(const char *s, uint16_t *vid, uint16_t *pid);

/* The kind of controller name selects, by the rules lsc_device_open follows
 * (the same code decides), without opening or checking anything:
 * LSC_DEVICE_SIM for "sim"; LSC_DEVICE_LSCD for "lscd:..."; LSC_DEVICE_HID
 * for "hid", "hid:..." and a path whose last component begins with
 * "hidraw"; else LSC_DEVICE_SERIAL (a serial port that lscd holds turns out
 * LSC_DEVICE_LSCD when it is opened: lsc_device_kind_of). NULL stands for
 * $LSC_PORT when it is set and not empty, as in lsc_device_open. For a front
 * end that checks its arguments before it opens a port (at most
 * LSC_DEVICE_HID_MOVE_MAX servos in one move over HID). The open may still
 * refuse the name. Returns 0 and *kind, or LSC_EINVAL (kind NULL), or
 * LSC_ENODEV (name NULL and $LSC_PORT unset or empty: the controller that
 * discovery finds decides; lsc_device_kind_of tells after the open). */
LSC_API int lsc_device_kind_of_name(const char *name, lsc_device_kind *kind);

#ifdef __cplusplus
}
#endif

#endif /* LSC_ENV_H */
