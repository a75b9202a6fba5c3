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

/* A controller found by lsc_device_list. Strings are NUL-terminated, "" when
 * unknown. */
typedef struct lsc_device_info { /* NOLINT(clang-analyzer-optin.performance.Padding): 6 bytes
                                   of 940; the order is the bindings' (ABI) */
    char name[LSC_DEVICE_NAME_MAX]; /* what lsc_device_open takes for it */
    char path[LSC_DEVICE_NAME_MAX]; /* the device node */
    char description[128];          /* the port's or the HID product's */
    char serial[128];               /* USB serial number */
    char manufacturer[128];
    uint16_t vid, pid;              /* USB ids (0 when not USB) */
    bool usb;                       /* vid, pid and serial are known */
    lsc_device_kind kind;           /* LSC_DEVICE_SERIAL or LSC_DEVICE_HID */
    bool controller;                /* a known controller (HID) or adapter (serial) */
} lsc_device_info;

/* Lists the serial ports and HID controllers present into out[0..cap)
 * (out may be NULL when cap is 0): serial ports first, then HID
 * controllers with known USB ids (lsc_hid_known_ids), each with the name lsc_device_open takes for it (a HID
 * controller: hid:SERIAL, or its path without a serial number). Returns how
 * many exist (may exceed cap), or an error: neither kind can be listed (the
 * serial listing's error; a build without libserialport and hidapi has
 * neither), LSC_ENOSPC (out of memory), LSC_EINVAL (out NULL, cap > 0).
 * message (msgcap bytes, may be NULL) receives why, "" on success. */
LSC_API int lsc_device_list(lsc_device_info *out, size_t cap, char *message, size_t msgcap);

#ifdef __cplusplus
}
#endif

#endif /* LSC_DISCOVERY_H */
