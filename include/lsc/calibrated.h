/*
 * lsc calibrated: where the calibrated profile of an arm is kept, so that
 * every program finds it without being told (docs/arm-profile.md,
 * "Calibration"). An arm is named by its controller: a key that stays the
 * same from one plugging to the next, and differs between two arms on one
 * computer. Its profile is $XDG_CONFIG_HOME/lsc/arms/KEY.conf
 * ($HOME/.config when XDG_CONFIG_HOME is not set or not an absolute path).
 *
 * Host only. Errors: 0 or a negative LSC_E... code.
 */
#ifndef LSC_CALIBRATED_H
#define LSC_CALIBRATED_H

#include <stddef.h>

#include "lsc/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_CALIBRATED_KEY_MAX 128u /* room for a key and its NUL */

/* The key of the arm on the controller `name` (as lsc_device_open takes it):
 *   "hid:SERIAL"    "hid-SERIAL";
 *   "hid"           "hid-SERIAL" of the one HID controller present;
 *   "sim"           "sim";
 *   a serial port   the name of the symbolic link it was given by (one in
 *                   /dev/serial/by-id, a udev rule's, lsc-sim --link's), else
 *                   of its link in /dev/serial/by-id (the adapter's USB ids
 *                   and serial number);
 *   NULL or ""      the key of the one controller present.
 * Bytes other than letters, digits, '.', '_' and '-' become '_' (and a
 * leading '.'), so that the key is a file's name. Returns 0 and key[cap], or
 * LSC_ENODEV when the controller has no such name (a serial port without a
 * link, a HID controller without a serial number, none or several present,
 * lscd:...), LSC_EINVAL (key NULL, or cap too small). */
LSC_API int lsc_calibrated_key(const char *name, char *key, size_t cap);

/* The path of the calibrated profile of key into path[cap]: 0, or
 * LSC_EINVAL (no key, no HOME to find the configuration in, cap too small). */
LSC_API int lsc_calibrated_path(const char *key, char *path, size_t cap);

/* The calibrated profile of the arm on the controller `name` when there is
 * one (lsc_calibrated_key, lsc_calibrated_path, a regular file there): 0
 * and path[cap]; else LSC_ENODEV (none: no key, or no file), LSC_EINVAL. */
LSC_API int lsc_calibrated_find(const char *name, char *path, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CALIBRATED_H */
