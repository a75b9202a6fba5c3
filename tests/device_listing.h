/* The transports' listings replaced through the linker for the device
 * layer's test programs (tests/device_listing.c; link with
 * -Wl,--wrap=lsc_serial_list_ports -Wl,--wrap=lsc_hid_list): what discovery
 * and listing see. */
#ifndef LSC_TEST_DEVICE_LISTING_H
#define LSC_TEST_DEVICE_LISTING_H

#include <stddef.h>

#include "lsc/discovery.h"

/* What the serial listing gives. */
enum {
    SERIAL_REAL,     /* the system's */
    SERIAL_FAIL,     /* an error with a message */
    SERIAL_FAIL_BARE, /* an error without one */
    SERIAL_PORTS,    /* fake: one CH340 adapter, a UART, an Arduino */
    SERIAL_TWO,      /* fake: two known adapters, one without a serial number */
    SERIAL_MANY,     /* fake: eight known adapters with long paths */
    SERIAL_ODD,      /* fake: two known adapters, control characters in their names */
    SERIAL_NEAR,     /* fake: a known adapter's vendor with another product */
    SERIAL_HUGE      /* fake: more ports than an int counts (cap filled with adapters) */
};
extern int serial_mode;
/* What the HID listing gives: the double's (or the build's), or an error;
 * or the known ids' listing as usual and that of other ids failing; or 100
 * controllers of the known ids (cap filled). */
enum { HID_REAL, HID_FAIL, HID_FAIL_BARE, HID_FAIL_OTHER, HID_MANY };
extern int hid_mode;

/* Both listings as a test starts: SERIAL_PORTS, HID_REAL. */
void device_listing_reset(void);

/* lsc_device_list, copied into out[0..cap) (the infos' fields: the library's
 * own struct, device_internal.h) for the tests to read: how many were
 * listed (may exceed cap), or the error (the listing then NULL). Include
 * after cmocka.h. */
int list_into(lsc_device_info *out, size_t cap, char *msg, size_t msgcap);

#endif
