/* The device layer (src/device, lsc/device.h) on HID controllers of the
 * hidapi test double (hid_double.c): opening by name, serial number, path
 * and other USB ids, access denied, the first-request retry, timeouts and
 * bad replies, the 19-servo bound, unplugging, the listing's bounds (the
 * transports' listings replaced: device_listing.c), a build without hidapi
 * (HID support wrapped), a program's own event loop. Built with hidapi
 * only. */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "device_listing.h"
#include "device_test.h"
#include "hid_double.h"
#include "lsc/device.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "lsc/hid.h"
#include "../src/device/device_internal.h" /* lsc_device_info's fields */
#include "test_time.h"

/* ---- Linker wrap: HID support (src/hid; the listings: device_listing.c) ------------ */

bool __real_lsc_hid_available(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
bool __wrap_lsc_hid_available(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static bool hid_unavailable; /* lsc_hid_available says false, as a build without hidapi */

bool __wrap_lsc_hid_available(void) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    return !hid_unavailable && __real_lsc_hid_available();
}

static int setup(void **state)
{
    device_listing_reset();
    hid_unavailable = false;
    return device_setup(state);
}

/* ---- HID controllers (the hidapi test double) ---------------------------------------- */


static void hid_open_by_name(void **state)
{
    (void)state;
    uint16_t mv = 0;
    hid_double_add(node_a, "ARM-A", 0, 0);
    lsc_device *d = open_ok("hid", NULL);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_HID);
    assert_string_equal(lsc_device_name(d), "hid");
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    assert_int_equal(mv, 7500);
    lsc_device_close(d);
    d = open_ok("hid:ARM-A", NULL);
    lsc_device_close(d);
    d = open_ok(node_a, NULL);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_HID);
    lsc_device_close(d);
    /* discovery: the one controller (the fake serial ports hold none) */
    serial_mode = SERIAL_FAIL;
    d = open_ok(NULL, NULL);
    assert_string_equal(lsc_device_name(d), "hid:ARM-A");
    lsc_device_close(d);
    d = open_fails("hid:", NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "needs a serial number after the colon");
    lsc_device_close(d);
    d = open_fails("hid:ARM-C", NULL, LSC_ENODEV);
    assert_has(lsc_device_error(d), "ARM-C");
    lsc_device_close(d);
    hid_double_add(node_b, "", 0, 0);
    d = open_fails("hid", NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SEVERAL);
    lsc_device_close(d);
    /* listed: by serial number, or by path without one */
    lsc_device_info info[4];
    assert_int_equal(list_into(info, 4, NULL, 0), 2);
    assert_string_equal(info[0].name, "hid:ARM-A");
    assert_string_equal(info[1].name, node_b);
    assert_int_equal(info[0].kind, LSC_DEVICE_HID);
    assert_true(info[0].controller);
    assert_int_equal(info[0].vid, LSC_HID_VID);
    d = open_fails(NULL, NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "hid:ARM-A (serial number ARM-A), ");
    assert_has(lsc_device_error(d), " (serial number none)");
    lsc_device_close(d);
}

/* Another controller's USB ids, named in the options: opened by name, path
 * and discovery; without them it is no controller. */
static void hid_other_ids(void **state)
{
    (void)state;
    uint16_t mv = 0;
    int x = hid_double_add(node_a, "ARM-X", 0, 0);
    hid_double_set_ids(x, 0x046d, 0xc52b);
    lsc_device *d = open_fails("hid", NULL, LSC_ENODEV);
    lsc_device_close(d);
    d = open_fails(node_a, NULL, LSC_ENODEV);
    assert_has(lsc_device_error(d), "046d:c52b");
    lsc_device_close(d);
    const test_options opt = {0, 0, 0x046d, 0xc52b};
    d = open_ok("hid", &opt);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    lsc_device_close(d);
    d = open_ok(node_a, &opt);
    lsc_device_close(d);
    d = open_ok("hid:ARM-X", &opt);
    lsc_device_close(d);
    serial_mode = SERIAL_FAIL;
    d = open_fails(NULL, NULL, LSC_ENODEV); /* not listed without its ids */
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_CONTROLLER);
    lsc_device_close(d);
    d = open_ok(NULL, &opt);
    assert_string_equal(lsc_device_name(d), "hid:ARM-X");
    lsc_device_close(d);
    /* with an arm of the known ids too: both, the known one first */
    hid_double_add(node_b, "ARM-A", 0, 0);
    d = open_fails(NULL, &opt, LSC_EINVAL);
    assert_has(lsc_device_error(d), "they are: hid:ARM-A (serial number ARM-A), hid:ARM-X");
    lsc_device_close(d);
    /* naming the known ids adds nothing */
    const test_options known = {0, 0, LSC_HID_VID, LSC_HID_PID};
    d = open_ok(NULL, &known);
    assert_string_equal(lsc_device_name(d), "hid:ARM-A");
    lsc_device_close(d);
}

static void hid_denied(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_DENY, 0);
    lsc_device *d = open_fails("hid", NULL, LSC_EACCES);
    /* the cause says that the message tells how to get access */
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_ACCESS);
    assert_has(lsc_device_error(d), "60-lsc.rules");
    lsc_device_close(d);
}

/* An arm that leaves the first request unanswered: it is sent again, once. */
static void hid_first_request_retried(void **state)
{
    (void)state;
    uint16_t mv = 0;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_MUTE_FIRST, 0);
    test_options opt = {0, 100, 0, 0};
    lsc_device *d = open_ok("hid", &opt);
    unsigned before = hid_double_writes();
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(hid_double_writes() - before, 2);
    lsc_device_close(d);
}

/* Over HID a timeout says what there is to check on USB; a first request is
 * retried before it counts. */
static void hid_timeout_and_bad_reply(void **state)
{
    (void)state;
    uint8_t reply[8];
    uint16_t mv;
    int a = hid_double_add(node_a, "ARM-A", 0, 0);
    test_options opt = {0, 50, 0, 0};
    lsc_device *d = open_ok("hid", &opt);
    unsigned before = hid_double_writes();
    assert_int_equal(lsc_device_request(d, 0x30, NULL, 0, 0x31, reply, sizeof reply),
                     LSC_ETIMEOUT);
    assert_int_equal(hid_double_writes() - before, 2); /* retried once */
    assert_has(lsc_device_error(d), "no reply from the controller on hid within 50 ms: check "
                                    "that it is switched on and connected; or raise the "
                                    "timeout");
    /* a reply whose command byte is another's: malformed */
    lsc_sim_fault_corrupt(hid_double_sim(a), 1, 3, 0x1A);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EREPLY);
    assert_has(lsc_device_error(d), "bad reply from the controller on hid (timeout 50 ms)");
    lsc_device_close(d);
}

/* At most 19 servos in one move over HID: refused before anything is sent. */
static void hid_move_bound(void **state)
{
    (void)state;
    lsc_servo s[LSC_DEVICE_HID_MOVE_MAX + 1];
    for (size_t i = 0; i < LSC_DEVICE_HID_MOVE_MAX + 1; i++) {
        s[i].id = (uint8_t)(i + 1);
        s[i].position = 1000;
    }
    hid_double_add(node_a, "ARM-A", 0, 0);
    lsc_device *d = open_ok("hid", NULL);
    unsigned before = hid_double_writes();
    assert_int_equal(lsc_device_move(d, 100, s, LSC_DEVICE_HID_MOVE_MAX + 1), LSC_EINVAL);
    assert_has(lsc_device_error(d), "at most 19 servos in one move over HID");
    assert_int_equal(hid_double_writes(), before);
    assert_int_equal(lsc_device_move(d, 100, s, LSC_DEVICE_HID_MOVE_MAX), 0);
    assert_int_equal(hid_double_writes(), before + 1);
    lsc_device_close(d);
}

/* Unplugged: the read and the write that fail say so, naming the frame. */
static void hid_unplugged(void **state)
{
    (void)state;
    uint16_t mv;
    const lsc_servo s = {1, 1000};
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_UNPLUG, 0);
    lsc_device *d = open_ok("hid", NULL);
    assert_int_equal(lsc_device_settle(d, &s, 1, 0, 10), LSC_ENODEV); /* its read fails */
    assert_has(lsc_device_error(d), node_a);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ENODEV);
    assert_has(lsc_device_error(d), "read failed"); /* what came before the request */
    assert_int_equal(lsc_device_move(d, 100, &s, 1), LSC_ENODEV);
    assert_has(lsc_device_error(d), "sending servo_move (command 3, 10 bytes): ");
    lsc_device_close(d);
}


/* HID controllers past the room given; another controller's listing failing
 * or named by its product id alone. */
static void hid_listing_bounds(void **state)
{
    (void)state;
    lsc_device_info info[1];
    serial_mode = SERIAL_FAIL;
    hid_double_add(node_a, "ARM-A", 0, 0);
    int x = hid_double_add(node_b, "ARM-X", 0, 0);
    hid_double_set_ids(x, 0x046d, 0xc52b);
    const test_options other = {0, 0, 0x046d, 0xc52b};
    lsc_device *d = open_fails(NULL, &other, LSC_EINVAL); /* both */
    lsc_device_close(d);
    /* the other ids' listing fails: the known controllers stand */
    hid_mode = HID_FAIL_OTHER;
    d = open_ok(NULL, &other);
    assert_string_equal(lsc_device_name(d), "hid:ARM-A");
    lsc_device_close(d);
    /* a product id alone (vendor 0): any vendor's */
    hid_mode = HID_REAL;
    const test_options product = {0, 0, 0, 0xc52b};
    d = open_fails(NULL, &product, LSC_EINVAL);
    assert_has(lsc_device_error(d), "hid:ARM-X");
    lsc_device_close(d);
    /* room for one of the two: the count says two */
    hid_double_set_ids(x, LSC_HID_VID, LSC_HID_PID);
    assert_int_equal(list_into(info, 1, NULL, 0), 2);
    assert_string_equal(info[0].name, "hid:ARM-A");
}

/* Only the first request after the open is sent again: once an arm has
 * answered, a timeout is a timeout. */
static void hid_retry_first_only(void **state)
{
    (void)state;
    uint8_t reply[8];
    uint16_t mv = 0;
    hid_double_add(node_a, "ARM-A", 0, 0);
    test_options opt = {0, 50, 0, 0};
    lsc_device *d = open_ok("hid", &opt);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    unsigned before = hid_double_writes();
    assert_int_equal(lsc_device_request(d, 0x30, NULL, 0, 0x31, reply, sizeof reply),
                     LSC_ETIMEOUT);
    assert_int_equal(hid_double_writes() - before, 1);
    lsc_device_close(d);
}

/* Built without hidapi, "hid" that fails is never "several controllers"
 * (the HID layer refuses every name then). */
static void hid_unavailable_is_not_several(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_double_add(node_b, "ARM-B", 0, 0);
    lsc_device *d = open_fails("hid", NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SEVERAL);
    lsc_device_close(d);
    hid_unavailable = true;
    d = open_fails("hid", NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
}

/* ---- A program's own event loop: lsc_device_fileno, lsc_device_next_event_ms ---------- */

/* HID: the node's own descriptor (the double's node is a file: what it
 * holds stands for the copies of reports, read away before the reports). */
static void events_hid(void **state)
{
    (void)state;
    lsc_notification n;
    int a = hid_double_add(node_a, "ARM-A", 0, 0);
    FILE *f = fopen(node_a, "w");
    assert_non_null(f);
    for (int i = 0; i < 3 * 64; i++) {
        (void)fputc(0, f);
    }
    (void)fclose(f);
    lsc_device *d = open_ok("hid", NULL);
    int fd = lsc_device_fileno(d);
    assert_true(fd >= 0);
    struct stat by_fd, by_path;
    assert_int_equal(fstat(fd, &by_fd), 0);
    assert_int_equal(stat(node_a, &by_path), 0);
    assert_true(by_fd.st_ino == by_path.st_ino && by_fd.st_dev == by_path.st_dev);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_poll(d, 0), 1); /* its start */
    assert_int_equal(lseek(fd, 0, SEEK_CUR), 3 * 64); /* the copies were read first */
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    (void)a;
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(hid_listing_bounds, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_retry_first_only, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_unavailable_is_not_several, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_open_by_name, setup, device_teardown),
        cmocka_unit_test_setup_teardown(events_hid, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_other_ids, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_denied, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_first_request_retried, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_timeout_and_bad_reply, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_move_bound, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_unplugged, setup, device_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
