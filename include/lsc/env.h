/*
 * lsc env: what every front end (lscctl, lscd, the Python bindings) takes
 * from the environment, read the same way for all, and the USB ids' grammar
 * (VID:PID) that --hid-id and $LSC_HID_ID share.
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
 *                 (lsc_device_options' hid_vid, hid_pid)
 *   LSC_LSCD_DIR  where the names lscd:NAME are (lsc/lscd.h; default
 *                 LSC_LSCD_DIR)
 * $LSC_PORT's value, or NULL. */
LSC_API const char *lsc_device_env_port(void);
/* $LSC_ARM's value, or NULL. */
LSC_API const char *lsc_device_env_arm(void);
/* $LSC_HID_ID into opt's hid_vid and hid_pid, when it is set and they are
 * 0:0 (a value the front end was given wins). Returns 0, or LSC_EINVAL with
 * opt unchanged and why[whylen] (may be NULL) saying so when it is no
 * VID:PID, or opt is NULL. */
LSC_API int lsc_device_options_from_env(lsc_device_options *opt, char *why, size_t whylen);
/* USB ids as "VID:PID": 1..4 hex digits each, not 0:0 (what --hid-id and
 * $LSC_HID_ID take). Returns 0 and *vid, *pid, or LSC_EINVAL (they are
 * unchanged; any argument NULL too). */
LSC_API int lsc_device_parse_hid_id(const char *s, uint16_t *vid, uint16_t *pid);

#ifdef __cplusplus
}
#endif

#endif /* LSC_ENV_H */
