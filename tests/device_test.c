/* The fixture and helpers the device layer's test programs share
 * (tests/device_test.h). */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "device_test.h"
#ifdef LSC_TEST_HID
#include "hid_double.h"
#endif

bool has(const char *text, const char *part)
{
    if (strstr(text, part) == NULL) {
        fprintf(stderr, "'%s' lacks '%s'\n", text, part);
        return false;
    }
    return true;
}

char tmpdir[64];
char node_a[128], node_b[128];

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    (void)fclose(f);
}

int device_setup(void **state)
{
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/lsc-test-device-XXXXXX");
    if (mkdtemp(tmpdir) == NULL) {
        return -1;
    }
    snprintf(node_a, sizeof node_a, "%s/hidraw0", tmpdir);
    snprintf(node_b, sizeof node_b, "%s/hidraw1", tmpdir);
    touch(node_a);
    touch(node_b);
#ifdef LSC_TEST_HID
    hid_double_reset();
#endif
    (void)unsetenv("LSC_PORT");
    return 0;
}

int device_teardown(void **state)
{
    (void)state;
    unlink(node_a);
    unlink(node_b);
    rmdir(tmpdir);
#ifdef LSC_TEST_HID
    assert_int_equal(hid_double_open_handles(), 0); /* every device was closed */
#endif
    return 0;
}

lsc_device *open_ok(const char *name, const test_options *opt)
{
    lsc_device *d = NULL;
    int r = test_open(name, opt, &d);
    if (r != 0) {
        fprintf(stderr, "open %s: %s\n", name != NULL ? name : "NULL", lsc_device_error(d));
    }
    assert_int_equal(r, 0);
    assert_non_null(d);
    assert_string_equal(lsc_device_error(d), "");
    if (lsc_device_kind_of(d) == LSC_DEVICE_SIM) { /* exact times: its virtual clock */
        assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    }
    return d;
}

lsc_device *open_fails(const char *name, const test_options *opt, int err)
{
    lsc_device *d = (lsc_device *)&d;
    assert_int_equal(test_open(name, opt, &d), err);
    assert_null(d);
    assert_true(lsc_device_error(d)[0] != '\0');
    return d;
}
