/* A build without hidapi (-DLSC_WITH_HIDAPI=OFF): the HID calls fail with
 * LSC_EINVAL and "built without HID support", and nothing crashes. */
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <string.h>

#include "lsc/hid.h"

static void test_without_hid(void **state)
{
    (void)state;
    char msg[256];
    lsc_hid_info info[1] = {{.size = sizeof info[0]}};
    lsc_hid *h = NULL;
    lsc_io io;
    uint8_t b[4] = {0x55, 0x55, 0x02, 0x0F};
    assert_false(lsc_hid_available());
    assert_int_equal(lsc_hid_list(info, 1, 0, 0, msg, sizeof msg), LSC_EINVAL);
    assert_non_null(strstr(msg, "built without HID support"));
    assert_non_null(strstr(msg, "install the Debian package libhidapi-dev")); /* what to do */
    assert_int_equal(lsc_hid_open_serial(NULL, &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "built without HID support"));
    assert_int_equal(lsc_hid_open_path("/dev/hidraw0", &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "/dev/hidraw0: built without HID support"));
    assert_int_equal(lsc_hid_open_path_extra("/dev/hidraw1", 0x1234, 0x5678, &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "/dev/hidraw1: built without HID support"));
    assert_int_equal(lsc_hid_open_serial_extra("A", 0x1234, 0x5678, &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "built without HID support"));
    /* the known ids are there all the same */
    size_t n = 0;
    assert_non_null(lsc_hid_known_ids(&n));
    assert_true(n >= 1u);
    assert_true(lsc_hid_is_known(LSC_HID_VID, LSC_HID_PID));
    lsc_hid_get_io(h, &io);
    assert_int_equal(io.write(io.ctx, b, sizeof b), LSC_EINVAL);
    assert_int_equal(io.read(io.ctx, b, sizeof b, 0), LSC_EINVAL);
    lsc_hid_close(h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_without_hid)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
