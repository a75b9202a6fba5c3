/*
 * lsc discovery: the serial ports and HID controllers present, each with the
 * name lsc_device_open (lsc/device.h) takes for it.
 *
 * Host only.
 */
#ifndef LSC_DISCOVERY_H
#define LSC_DISCOVERY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A controller found by lsc_device_list: an opaque object, read through the
 * accessors below. */
typedef struct lsc_device_info lsc_device_info;

#define LSC_DEVICE_LIST_MAX 4096u /* controllers in one listing, at most */

/* Lists the serial ports and HID controllers present: serial ports first,
 * then HID controllers with known USB ids (lsc_hid_known_ids), each with the
 * name lsc_device_open takes for it (a HID controller: hid:SERIAL, or its
 * path without a serial number). *out becomes a NULL-terminated array of
 * them (at most LSC_DEVICE_LIST_MAX), to free with lsc_device_list_free.
 * Returns how many are in it, or an error with *out NULL: neither kind can
 * be listed (the serial listing's error; a build without libserialport and
 * hidapi has neither), LSC_ENOSPC (out of memory), LSC_EINVAL (out NULL).
 * message (msgcap bytes, may be NULL) receives why, "" on success. */
LSC_API int lsc_device_list(lsc_device_info ***out, char *message, size_t msgcap);
/* Frees a listing and every info in it (NULL is fine). */
LSC_API void lsc_device_list_free(lsc_device_info **list);

/* What an info says, valid until its listing is freed. Strings are never
 * NULL: "" when unknown (and for a NULL info); numbers 0, false and
 * LSC_DEVICE_SERIAL for a NULL info.
 *   name          what lsc_device_open takes for it
 *   path          the device node
 *   description   the port's or the HID product's
 *   serial        the USB serial number
 *   manufacturer  the USB manufacturer
 *   vid, pid      USB ids (0 when not USB)
 *   usb           vid, pid and serial are known
 *   kind          LSC_DEVICE_SERIAL or LSC_DEVICE_HID
 *   controller    a known controller (HID) or adapter (serial) */
LSC_API const char *lsc_device_info_name(const lsc_device_info *info);
LSC_API const char *lsc_device_info_path(const lsc_device_info *info);
LSC_API const char *lsc_device_info_description(const lsc_device_info *info);
LSC_API const char *lsc_device_info_serial(const lsc_device_info *info);
LSC_API const char *lsc_device_info_manufacturer(const lsc_device_info *info);
LSC_API uint16_t lsc_device_info_vid(const lsc_device_info *info);
LSC_API uint16_t lsc_device_info_pid(const lsc_device_info *info);
LSC_API bool lsc_device_info_usb(const lsc_device_info *info);
LSC_API lsc_device_kind lsc_device_info_kind(const lsc_device_info *info);
LSC_API bool lsc_device_info_controller(const lsc_device_info *info);

#ifdef __cplusplus
}
#endif

#endif /* LSC_DISCOVERY_H */
