/* What the device layer's test programs (tests/test_device_*.c) share: the
 * fixture (a directory with two files as HID nodes; with the hidapi test
 * double, LSC_TEST_HID, its devices reset and every one closed at the end),
 * opening a device that must open or must fail (settings as tests/test_open.h
 * writes them), and assert_has. The linker
 * wraps each program needs are its own (and device_listing.h's for the
 * transports' listings). Include after cmocka.h. */
#ifndef LSC_TEST_DEVICE_TEST_H
#define LSC_TEST_DEVICE_TEST_H

#include <stdbool.h>

#include "lsc/device.h"
#include "test_open.h"

/* Whether text holds part (else it says so on stderr). */
bool has(const char *text, const char *part);
#define assert_has(text, part) assert_true(has((text), (part)))

/* The fixture's directory and the two files in it (hidraw0, hidraw1). */
extern char tmpdir[64];
extern char node_a[128], node_b[128];

/* cmocka setup and teardown of the fixture; also unsets LSC_PORT. */
int device_setup(void **state);
int device_teardown(void **state);

/* Opens name, which must open: the device (on "sim", its virtual clock). */
lsc_device *open_ok(const char *name, const test_options *opt);
/* Opens name, which must fail with err, leaving no handle; returns NULL, the
 * handle whose lsc_device_error and lsc_device_error_cause say why (the
 * calling thread's last open). */
lsc_device *open_fails(const char *name, const test_options *opt, int err);

#endif
