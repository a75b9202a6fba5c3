/*
 * lsc calibrated: calibration on a controller (a step's reading of the
 * servos, lsc/calibrate.h's arithmetic on it), and where the calibrated
 * profile of an arm is kept, so that every program finds it without being
 * told (docs/arm-profile.md, "Calibration"). An arm is named by its controller: a key that stays the
 * same from one plugging to the next, and differs between two arms on one
 * computer. Its profile is $XDG_CONFIG_HOME/lsc/arms/KEY.conf
 * ($HOME/.config when XDG_CONFIG_HOME is not set or not an absolute path).
 *
 * Host only. Errors: 0 or a negative LSC_E... code.
 */
#ifndef LSC_CALIBRATED_H
#define LSC_CALIBRATED_H

#include <stddef.h>

#include "lsc/calibrate.h"
#include "lsc/device.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_CALIBRATED_KEY_MAX 128u /* room for a key and its NUL */

/* The key of the arm on the controller `name` (as lsc_device_open takes it):
 *   "hid:SERIAL"    "hid-SERIAL";
 *   "hid"           "hid-SERIAL" of the one HID controller present;
 *   "sim"           "sim";
 *   a serial port   "port-" and the name of the symbolic link it was given
 *                   by (one in /dev/serial/by-id, a udev rule's, lsc-sim
 *                   --link's), else of its link in /dev/serial/by-id (the
 *                   adapter's USB ids and serial number);
 *   lscd:NAME       the key of the port NAME stands for (lscd's
 *                   lsc_lscd_port_of_name: lscd:hid-SERIAL, lscd:ttyUSB0);
 *   NULL or ""      the key of the one controller present.
 * (The prefixes keep keys apart from the names of profiles in the same
 * directory: a port linked as /dev/xarm is "port-xarm", not "xarm".)
 * Bytes other than letters, digits, '.', '_' and '-' become '_', so that the
 * key is a file's name. Returns 0 and key[cap], or
 * LSC_ENODEV when the controller has no such name (a serial port without a
 * link, a HID controller without a serial number, none or several present,
 * lscd:PATH), LSC_EINVAL (key NULL, or cap too small). */
LSC_API int lsc_calibrated_key(const char *name, char *key, size_t cap);

/* The path of the calibrated profile of key into path[cap]: 0, or
 * LSC_EINVAL (no key, no HOME to find the configuration in, cap too small). */
LSC_API int lsc_calibrated_path(const char *key, char *path, size_t cap);

/* The calibrated profile of the arm on the controller `name` when there is
 * one (lsc_calibrated_key, lsc_calibrated_path, a regular file there): 0
 * and path[cap]; else LSC_ENODEV (none: no key, or no file), LSC_EINVAL. */
LSC_API int lsc_calibrated_find(const char *name, char *path, size_t cap);

/* One step of a calibration on d's arm: reads the servos the step needs
 * (lsc_calib_ids of the profile text[0..len)) and applies them to the text
 * (lsc_calib_apply, stamped with the time now, in UTC, and file: "2026-11-29
 * 10:04 UTC, from FILE"). file names the text in messages and the stamp
 * (NULL: "profile"). Nothing is written: the caller writes *out
 * (lsc_calibrated_write) when the owner wants it. Returns 0 and *out (a
 * NUL-terminated text of *outlen bytes: free() it), or an error with *out
 * NULL and lsc_device_error(d) saying why: LSC_EINVAL (the text or the
 * readings refused: a profile without geometry, a joint not leaned far
 * enough...; NULL arguments), LSC_ENOSPC, or the read's error. */
LSC_API int lsc_device_calibrate(lsc_device *d, lsc_calib_step step, const char *text, size_t len,
                                 const char *file, char **out, size_t *outlen);

/* Writes a calibrated profile text[0..len) to path, atomically
 * (lsc_file_replace), making the directories above it that are missing
 * (lsc_calibrated_path's). Returns 0, or an error with why (whylen bytes,
 * may be NULL) saying what failed: LSC_EINVAL (NULL arguments; a path that
 * is a link or no regular file), LSC_EIO (a directory that cannot be made,
 * a file that cannot be written), LSC_ENOSPC. */
LSC_API int lsc_calibrated_write(const char *path, const char *text, size_t len, char *why,
                                 size_t whylen);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CALIBRATED_H */
