/* The device layer (src/device, lsc/device.h): opening a controller and
 * finding one. Arguments and NULL, a failed open that leaves no handle,
 * discovery and listing (the transports' listings replaced through the
 * linker: device_listing.c), what a name selects, names from outside shown
 * escaped, the listing's bounds, out of memory (calloc wrapped), a config's
 * setters. */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "device_listing.h"
#include "device_test.h"
#include "lsc/device.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "lsc/env.h"
#include "lsc/hid.h"
#include "lsc/serial.h"
#include "../src/device/device_internal.h" /* the config's and the infos' fields */
#ifdef LSC_TEST_HID
#include "hid_double.h"
#endif

/* ---- Linker wrap: calloc (the listings: device_listing.c) ------------------------ */

void *__real_calloc(size_t n, size_t size);
void *__wrap_calloc(size_t n, size_t size);

static int calloc_fails_in; /* 0: never; N: the Nth call from now fails */

void *__wrap_calloc(size_t n, size_t size)
{
    if (calloc_fails_in > 0 && --calloc_fails_in == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

static int setup(void **state)
{
    device_listing_reset();
    calloc_fails_in = 0;
    return device_setup(state);
}

/* ---- Arguments and NULL ----------------------------------------------------------- */

/* Every call that talks to the controller returns err, sending nothing. */
static void every_call_fails(lsc_device *d, int err)
{
    lsc_notification n;
    lsc_servo s = {1, 1500};
    uint8_t id = 1, buf[4];
    uint16_t mv;
    assert_int_equal(lsc_device_move(d, 0, &s, 1), err);
    assert_int_equal(lsc_device_run(d, 1, 1), err);
    assert_int_equal(lsc_device_stop(d), err);
    assert_int_equal(lsc_device_speed(d, 1, 100), err);
    assert_int_equal(lsc_device_unload(d, &id, 1), err);
    assert_int_equal(lsc_device_adjust_offset(d, 1, 0), err);
    assert_int_equal(lsc_device_send(d, 7, NULL, 0, false), err);
    assert_int_equal(lsc_device_battery(d, &mv), err);
    assert_int_equal(lsc_device_read(d, &id, 1, &s), err);
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, NULL), err);
    assert_int_equal(lsc_device_request(d, 15, NULL, 0, 15, buf, sizeof buf), err);
    assert_int_equal(lsc_device_settle(d, &s, 1, 0, 10), err);
    assert_int_equal(lsc_device_poll(d, 0), err);
    assert_int_equal(lsc_device_notification(d, 0, &n), err);
    assert_int_equal(lsc_device_wait_group(d, 1, 0, &n), err);
}

static void null_and_bad_arguments(void **state)
{
    (void)state;
    uint8_t buf[4];
    assert_int_equal(lsc_device_open("sim", NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(NULL), LSC_DEVICE_CAUSE_NONE);
    assert_string_equal(lsc_device_name(NULL), "");
    assert_int_equal(lsc_device_kind_of(NULL), LSC_DEVICE_SERIAL);
    assert_int_equal(lsc_device_groups(NULL, buf, sizeof buf), 0);
    assert_int_equal(lsc_device_timeout(NULL), LSC_DEVICE_TIMEOUT_DEFAULT);
    assert_int_equal(lsc_device_now_ms(NULL), 0);
    assert_int_equal(lsc_device_dropped_notifications(NULL), 0);
    assert_false(lsc_device_group_started(NULL));
    assert_null(lsc_device_arm(NULL));
    lsc_device_set_timeout(NULL, 5);
    lsc_device_set_trace(NULL, NULL, NULL);
    lsc_device_set_last_word(NULL, NULL, NULL);
    lsc_device_close(NULL);
    assert_int_equal(lsc_device_set_arm(NULL, NULL), LSC_EINVAL);
    every_call_fails(NULL, LSC_EINVAL);
    /* a name longer than any path */
    char name[LSC_DEVICE_NAME_MAX + 8];
    memset(name, 'a', sizeof name - 1u);
    name[sizeof name - 1u] = '\0';
    lsc_device *d = open_fails(name, NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "is too long: at most 271 bytes");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NAME_TOO_LONG);
    lsc_device_close(d);
    /* a name that fits, but not as a serial port's path */
    name[LSC_SERIAL_PATH_MAX] = '\0';
    d = open_fails(name, NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "a serial port's path 'aaaa");
    assert_has(lsc_device_error(d), "is too long: at most 255 bytes");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NAME_TOO_LONG);
    lsc_device_close(d);
    name[LSC_SERIAL_PATH_MAX - 1u] = '\0'; /* 255 bytes: the serial layer's to open */
    d = open_fails(name, NULL, LSC_ENODEV);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
}

/* A failed open leaves no handle; what it says stays readable through NULL
 * (the calling thread's last open) until the thread's next open, which a
 * success clears; another thread's open does not touch it. */
static void *open_in_thread(void *arg)
{
    lsc_device *d = NULL;
    *(int *)arg = lsc_device_open("hid:", NULL, &d); /* fails, with its own line */
    return NULL;
}

static void failed_open_refuses_everything(void **state)
{
    (void)state;
    lsc_device *d = open_fails("/nonexistent/tty", NULL, LSC_ENODEV);
    char msg[256];
    snprintf(msg, sizeof msg, "%s", lsc_device_error(NULL));
    assert_has(msg, "/nonexistent/tty");
    assert_string_equal(lsc_device_name(NULL), "/nonexistent/tty");
    assert_int_equal(lsc_device_kind_of(NULL), LSC_DEVICE_SERIAL);
    assert_int_equal(lsc_device_error_cause(NULL), LSC_DEVICE_CAUSE_NONE);
    assert_int_equal(lsc_device_now_ms(d), 0);
    every_call_fails(d, LSC_EINVAL);
    assert_int_equal(lsc_device_sim_next_event_ms(d), LSC_DEVICE_FOREVER);
    assert_string_equal(lsc_device_error(NULL), msg);
    pthread_t t;
    int other = 0;
    assert_int_equal(pthread_create(&t, NULL, open_in_thread, &other), 0);
    assert_int_equal(pthread_join(t, NULL), 0);
    assert_int_equal(other, LSC_EINVAL);
    assert_string_equal(lsc_device_error(NULL), msg); /* the other thread's is its own */
    /* the kind and cause of the name tried */
    assert_null(open_fails("hid:", NULL, LSC_EINVAL));
    assert_int_equal(lsc_device_kind_of(NULL), LSC_DEVICE_HID);
    assert_string_equal(lsc_device_name(NULL), "hid:");
    char name[LSC_DEVICE_NAME_MAX + 8];
    memset(name, 'a', sizeof name - 1u);
    name[sizeof name - 1u] = '\0';
    assert_null(open_fails(name, NULL, LSC_EINVAL));
    assert_int_equal(lsc_device_error_cause(NULL), LSC_DEVICE_CAUSE_NAME_TOO_LONG);
    /* a success clears it */
    d = open_ok("sim", NULL);
    assert_string_equal(lsc_device_error(NULL), "");
    assert_string_equal(lsc_device_name(NULL), "");
    assert_int_equal(lsc_device_error_cause(NULL), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
}

/* ---- Discovery and listing --------------------------------------------------------- */

static void discovery_by_environment(void **state)
{
    (void)state;
    assert_int_equal(setenv("LSC_PORT", "sim", 1), 0);
    lsc_device *d = open_ok(NULL, NULL);
    assert_string_equal(lsc_device_name(d), "sim");
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SIM);
    lsc_device_close(d);
    /* empty: as if unset; the one controller is the fake CH340 (not there) */
    assert_int_equal(setenv("LSC_PORT", "", 1), 0);
    d = open_fails(NULL, NULL, LSC_ENODEV);
    assert_string_equal(lsc_device_name(d), "/nonexistent/ttyUSB7");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
}

static void discovery_none_and_several(void **state)
{
    (void)state;
    /* no listing at all */
    serial_mode = SERIAL_FAIL;
    hid_mode = HID_FAIL;
    lsc_device *d = open_fails(NULL, NULL, LSC_ENODEV);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_CONTROLLER);
    assert_has(lsc_device_error(d), "none can be found: cannot list serial ports: no serial "
                                    "listing here; nor HID: no HID listing here");
    assert_string_equal(lsc_device_name(d), "");
    lsc_device_close(d);
    serial_mode = SERIAL_FAIL_BARE;
    hid_mode = HID_FAIL_BARE;
    d = open_fails(NULL, NULL, LSC_ENODEV);
    assert_has(lsc_device_error(d), "cannot list serial ports: no such device");
    lsc_device_close(d);
    /* HID fails, serial has no controller: none */
    serial_mode = SERIAL_PORTS;
    d = open_fails(NULL, NULL, LSC_ENODEV); /* the CH340 is the one: not there */
    lsc_device_close(d);
    serial_mode = SERIAL_FAIL;
    hid_mode = HID_REAL;
#ifdef LSC_TEST_HID
    d = open_fails(NULL, NULL, LSC_ENODEV);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_CONTROLLER);
    assert_has(lsc_device_error(d), "none looks like a controller");
    lsc_device_close(d);
#endif
    /* several */
    serial_mode = SERIAL_TWO;
    d = open_fails(NULL, NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SEVERAL);
    assert_has(lsc_device_error(d), "several look like a controller: name one or set "
                                    "LSC_PORT; they are: /nonexistent/ttyUSB0 (serial number "
                                    "none), /nonexistent/ttyUSB1 (serial number F1)");
    lsc_device_close(d);
    /* more than the message holds: cut */
    serial_mode = SERIAL_MANY;
    d = open_fails(NULL, NULL, LSC_EINVAL);
    assert_true(strlen(lsc_device_error(d)) < 640);
    lsc_device_close(d);
}

static void listing(void **state)
{
    (void)state;
    lsc_device_info info[8];
    char msg[128] = "x";
    assert_int_equal(lsc_device_list(NULL, msg, sizeof msg), LSC_EINVAL);
    assert_string_equal(msg, "lsc_device_list: no list to fill");
    assert_int_equal(lsc_device_list(NULL, NULL, 0), LSC_EINVAL);
    msg[0] = 'x';
    assert_int_equal(lsc_device_list(NULL, msg, 0), LSC_EINVAL); /* no room: untouched */
    assert_int_equal(msg[0], 'x');
    int n = list_into(info, 8, msg, sizeof msg);
    assert_true(n >= 3);
    assert_string_equal(msg, "");
    assert_string_equal(info[0].name, "/nonexistent/ttyUSB7");
    assert_string_equal(info[0].path, "/nonexistent/ttyUSB7");
    assert_string_equal(info[0].description, "USB2.0-Serial");
    assert_string_equal(info[0].serial, "S1");
    assert_true(info[0].usb);
    assert_int_equal(info[0].vid, 0x1a86);
    assert_int_equal(info[0].pid, 0x7523);
    assert_int_equal(info[0].kind, LSC_DEVICE_SERIAL);
    assert_true(info[0].controller);
    assert_false(info[1].usb);
    assert_int_equal(info[1].vid, 0);
    assert_false(info[1].controller);
    assert_true(info[2].usb);
    assert_false(info[2].controller); /* an Arduino is no known adapter */
    assert_int_equal(list_into(NULL, 0, NULL, 0), n);
    assert_int_equal(list_into(info, 1, NULL, 0), n);
    /* the accessors: what the fields hold; for NULL "", 0, false, serial */
    lsc_device_info **all = NULL;
    assert_int_equal(lsc_device_list(&all, NULL, 0), n);
    assert_string_equal(lsc_device_info_name(all[0]), "/nonexistent/ttyUSB7");
    assert_string_equal(lsc_device_info_path(all[0]), "/nonexistent/ttyUSB7");
    assert_string_equal(lsc_device_info_description(all[0]), "USB2.0-Serial");
    assert_string_equal(lsc_device_info_serial(all[0]), "S1");
    assert_string_equal(lsc_device_info_manufacturer(all[0]), all[0]->manufacturer);
    assert_int_equal(lsc_device_info_vid(all[0]), 0x1a86);
    assert_int_equal(lsc_device_info_pid(all[0]), 0x7523);
    assert_true(lsc_device_info_usb(all[0]));
    assert_false(lsc_device_info_usb(all[1]));
    assert_int_equal(lsc_device_info_kind(all[0]), LSC_DEVICE_SERIAL);
    assert_true(lsc_device_info_controller(all[0]));
    assert_false(lsc_device_info_controller(all[1]));
    assert_null(all[n]);
    lsc_device_list_free(all);
    lsc_device_list_free(NULL);
    assert_string_equal(lsc_device_info_name(NULL), "");
    assert_string_equal(lsc_device_info_path(NULL), "");
    assert_string_equal(lsc_device_info_description(NULL), "");
    assert_string_equal(lsc_device_info_serial(NULL), "");
    assert_string_equal(lsc_device_info_manufacturer(NULL), "");
    assert_int_equal(lsc_device_info_vid(NULL), 0);
    assert_int_equal(lsc_device_info_pid(NULL), 0);
    assert_false(lsc_device_info_usb(NULL));
    assert_int_equal(lsc_device_info_kind(NULL), LSC_DEVICE_SERIAL);
    assert_false(lsc_device_info_controller(NULL));
    serial_mode = SERIAL_FAIL;
    hid_mode = HID_FAIL;
    assert_true(list_into(info, 8, msg, sizeof msg) < 0);
    assert_string_equal(msg, "cannot list serial ports: no serial listing here; nor HID: no "
                             "HID listing here");
    assert_true(list_into(info, 8, NULL, 0) < 0);
    /* one kind failing is no failure */
    serial_mode = SERIAL_PORTS;
    assert_int_equal(list_into(info, 8, msg, sizeof msg), 3);
    assert_string_equal(msg, "");
}

static void out_of_memory(void **state)
{
    (void)state;
    lsc_device *d = (lsc_device *)&d;
    lsc_device_info info[2];
    char msg[64];
    calloc_fails_in = 1;
    assert_int_equal(lsc_device_open("sim", NULL, &d), LSC_ENOSPC);
    assert_null(d);
    calloc_fails_in = 2; /* the device, then the listing of discovery */
    d = open_fails(NULL, NULL, LSC_ENOSPC);
    assert_string_equal(lsc_device_error(d), "out of memory");
    lsc_device_close(d);
    calloc_fails_in = 3; /* the device, discovery's room, then the listing's */
    d = open_fails(NULL, NULL, LSC_ENOSPC);
    assert_has(lsc_device_error(d), "out of memory");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
    calloc_fails_in = 2;
    assert_int_equal(list_into(info, 2, msg, sizeof msg), LSC_ENOSPC);
    assert_string_equal(msg, "out of memory");
    calloc_fails_in = 1;
    assert_int_equal(list_into(info, 2, NULL, 0), LSC_ENOSPC);
    /* the counting listing's two, then the list's block; then the second
     * listing's: no list either way */
    calloc_fails_in = 3;
    assert_int_equal(list_into(info, 2, msg, sizeof msg), LSC_ENOSPC);
    assert_string_equal(msg, "out of memory");
    calloc_fails_in = 3;
    assert_int_equal(list_into(info, 2, NULL, 0), LSC_ENOSPC);
    msg[0] = 'x';
    calloc_fails_in = 3;
    assert_int_equal(list_into(info, 2, msg, 0), LSC_ENOSPC);
    assert_int_equal(msg[0], 'x');
    calloc_fails_in = 4;
    assert_int_equal(list_into(info, 2, msg, sizeof msg), LSC_ENOSPC);
    assert_string_equal(msg, "out of memory");
    calloc_fails_in = 0;
}

/* ---- How to open a device ---------------------------------------------------------- */

/* A config's setters refuse what no open takes, leaving it as it was; the
 * open takes its values (NULL: the defaults). */
static void config_setters(void **state)
{
    (void)state;
    lsc_device_config_free(NULL);
    calloc_fails_in = 1;
    assert_null(lsc_device_config_new());
    lsc_device_config *cfg = lsc_device_config_new();
    assert_non_null(cfg);
    assert_int_equal(cfg->baud, 0); /* the defaults */
    assert_int_equal(cfg->timeout_ms, 0);
    assert_int_equal(cfg->hid_vid, 0);
    assert_int_equal(cfg->hid_pid, 0);
    assert_int_equal(lsc_device_config_set_baud(NULL, 9600), LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_baud(cfg, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_baud(cfg, LSC_DEVICE_BAUD_MAX + 1u), LSC_EINVAL);
    assert_int_equal(cfg->baud, 0);
    assert_int_equal(lsc_device_config_set_baud(cfg, LSC_DEVICE_BAUD_MAX), 0);
    assert_int_equal(lsc_device_config_set_baud(cfg, 1), 0);
    assert_int_equal(lsc_device_config_set_baud(cfg, 0), LSC_EINVAL);
    assert_int_equal(cfg->baud, 1);
    assert_int_equal(lsc_device_config_set_timeout_ms(NULL, 100), LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_timeout_ms(cfg, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_timeout_ms(cfg, LSC_DEVICE_TIMEOUT_MAX + 1u),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_timeout_ms(cfg, LSC_DEVICE_FOREVER), LSC_EINVAL);
    assert_int_equal(cfg->timeout_ms, 0);
    assert_int_equal(lsc_device_config_set_timeout_ms(cfg, LSC_DEVICE_TIMEOUT_MAX), 0);
    assert_int_equal(lsc_device_config_set_timeout_ms(cfg, 123), 0);
    assert_int_equal(lsc_device_config_set_hid_id(NULL, 1, 2), LSC_EINVAL);
    assert_int_equal(lsc_device_config_set_hid_id(cfg, 0x046d, 0xc52b), 0);
    assert_int_equal(cfg->hid_vid, 0x046d);
    assert_int_equal(cfg->hid_pid, 0xc52b);
    /* the open takes the timeout; the config may go at once */
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", cfg, &d), 0);
    lsc_device_config_free(cfg);
    assert_int_equal(lsc_device_timeout(d), 123);
    lsc_device_close(d);
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_timeout(d), LSC_DEVICE_TIMEOUT_DEFAULT);
    lsc_device_close(d);
}

/* ---- What a name selects; names from outside in messages ------------------------- */

/* lsc_device_kind_of_name: the open's rules, without opening anything. */
static void kind_of_names(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        lsc_device_kind kind;
    } cases[] = {
        {"sim", LSC_DEVICE_SIM},
        {"lscd:ttyUSB0", LSC_DEVICE_LSCD},
        {"lscd:/run/lsc/hidraw0", LSC_DEVICE_LSCD},
        {"lscd", LSC_DEVICE_SERIAL},
        {"hid", LSC_DEVICE_HID},
        {"hid:ARM-A", LSC_DEVICE_HID},
        {"hid:", LSC_DEVICE_HID},
        {"/dev/hidraw0", LSC_DEVICE_HID},
        {"./hidraw12", LSC_DEVICE_HID},
        {"/dev/ttyUSB0", LSC_DEVICE_SERIAL},
        {"hidraw0", LSC_DEVICE_SERIAL}, /* no directory: a serial port's name */
        {"/tmp/hidraw/tty", LSC_DEVICE_SERIAL},
        {"simulator", LSC_DEVICE_SERIAL},
        {"HID", LSC_DEVICE_SERIAL},
        {"", LSC_DEVICE_SERIAL},
    };
    lsc_device_kind k = LSC_DEVICE_SIM;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        k = (lsc_device_kind)-1;
        assert_int_equal(lsc_device_kind_of_name(cases[i].name, &k), 0);
        assert_int_equal(k, cases[i].kind);
    }
    assert_int_equal(lsc_device_kind_of_name("sim", NULL), LSC_EINVAL);
    /* NULL: $LSC_PORT's, as the open takes it; else discovery decides */
    k = LSC_DEVICE_SIM;
    assert_int_equal(lsc_device_kind_of_name(NULL, &k), LSC_ENODEV);
    assert_int_equal(k, LSC_DEVICE_SIM); /* untouched */
    assert_int_equal(setenv("LSC_PORT", "", 1), 0);
    assert_int_equal(lsc_device_kind_of_name(NULL, &k), LSC_ENODEV);
    assert_int_equal(setenv("LSC_PORT", "hid:ARM-B", 1), 0);
    assert_int_equal(lsc_device_kind_of_name(NULL, &k), 0);
    assert_int_equal(k, LSC_DEVICE_HID);
    assert_int_equal(setenv("LSC_PORT", "sim", 1), 0);
    assert_int_equal(lsc_device_kind_of_name(NULL, &k), 0);
    assert_int_equal(k, LSC_DEVICE_SIM);
    lsc_device *d = open_ok(NULL, NULL);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SIM);
    lsc_device_close(d);
    (void)unsetenv("LSC_PORT");
    /* the open decides by the same code: the kind of a failed open too
     * (lsc_device_kind_of(NULL): the thread's last open) */
    const char *names[] = {"hid:", node_a, "/nonexistent/ttyUSB9", "/nonexistent/hidraw9",
                           "lscd:/nonexistent/arm.sock"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        d = (lsc_device *)&d;
        assert_true(lsc_device_open(names[i], NULL, &d) < 0);
        assert_null(d);
        assert_int_equal(lsc_device_kind_of_name(names[i], &k), 0);
        assert_int_equal(lsc_device_kind_of(NULL), k);
    }
}

/* A name with control characters (a path from a user) is shown escaped in
 * every message, which stays one line; lsc_device_name gives it as it is. */
static void names_escaped(void **state)
{
    (void)state;
    char name[256];
    snprintf(name, sizeof name, "/nonexistent/a\nb\033[31m");
    lsc_device *d = open_fails(name, NULL, LSC_ENODEV);
    assert_has(lsc_device_error(d), "/nonexistent/a\\x0Ab\\x1B[31m");
    assert_null(strpbrk(lsc_device_error(d), "\n\033"));
    assert_string_equal(lsc_device_name(d), name);
    lsc_device_close(d);
    if (lsc_hid_available()) { /* else a hidraw name is "built without HID support" */
        snprintf(name, sizeof name, "%s/\thidraw\n", tmpdir);
        d = open_fails(name, NULL, LSC_ENODEV);
        assert_null(strpbrk(lsc_device_error(d), "\n\t"));
        lsc_device_close(d);
        snprintf(name, sizeof name, "/nonexistent/hidraw\n");
        d = open_fails(name, NULL, LSC_ENODEV);
        assert_has(lsc_device_error(d), "/nonexistent/hidraw\\x0A");
        assert_null(strchr(lsc_device_error(d), '\n'));
        lsc_device_close(d);
    }
    /* lscd's message names its socket */
    d = open_fails("lscd:/nonexistent/a\nb\033.sock", NULL, LSC_ENODEV);
    assert_has(lsc_device_error(d), "a\\x0Ab\\x1B.sock");
    assert_null(strpbrk(lsc_device_error(d), "\n\033"));
    lsc_device_close(d);
    /* too long: its start, escaped */
    char longer[LSC_DEVICE_NAME_MAX + 8];
    memset(longer, 'x', sizeof longer - 1u);
    longer[sizeof longer - 1u] = '\0';
    longer[3] = '\n';
    d = open_fails(longer, NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "the name 'xxx\\x0Axxx");
    assert_has(lsc_device_error(d), "...' is too long: at most 271 bytes");
    assert_null(strchr(lsc_device_error(d), '\n'));
    lsc_device_close(d);
    /* discovery: names and serial numbers from the devices */
    serial_mode = SERIAL_ODD;
    hid_mode = HID_FAIL;
    d = open_fails(NULL, NULL, LSC_EINVAL);
    assert_has(lsc_device_error(d), "they are: /nonexistent/ttyUSB0 (serial number "
                                    "S\\x0A\\x1B[2J), /nonexistent/tty\\x0AUSB1 (serial number F1)");
    assert_null(strpbrk(lsc_device_error(d), "\n\033"));
    lsc_device_close(d);
}

/* ---- Bounds of the listing and of discovery ---------------------------------------- */

/* Every listing bound: messages without room, counts past an int, more
 * controllers than discovery looks at, the other ids' listing failing. */
static void listing_bounds(void **state)
{
    (void)state;
    lsc_device_info info[2];
    char msg[16] = "x";
    /* a known adapter's vendor with another product is no controller */
    serial_mode = SERIAL_NEAR;
    hid_mode = HID_FAIL;
    assert_int_equal(list_into(info, 2, msg, 0), 1);
    assert_string_equal(msg, "x"); /* no room: untouched */
    assert_int_equal(info[0].vid, 0x1a86);
    assert_false(info[0].controller);
    /* failures, with no room for their message either */
    serial_mode = SERIAL_FAIL;
    assert_int_equal(list_into(info, 2, msg, 0), LSC_EIO);
    assert_string_equal(msg, "x");
    calloc_fails_in = 1;
    assert_int_equal(list_into(info, 2, msg, 0), LSC_ENOSPC);
    assert_string_equal(msg, "x");
    /* more than an int counts: the listing stops at LSC_DEVICE_LIST_MAX */
    serial_mode = SERIAL_HUGE;
    hid_mode = HID_REAL;
#ifdef LSC_TEST_HID
    hid_double_add(node_a, "ARM-A", 0, 0);
#endif
    memset(info, 0, sizeof info);
    assert_int_equal(list_into(info, 2, NULL, 0), LSC_DEVICE_LIST_MAX); /* the list's limit */
    assert_string_equal(info[1].name, "/nonexistent/ttyUSB9");
    assert_int_equal(info[1].kind, LSC_DEVICE_SERIAL);
    /* discovery looks at the first 80 (all controllers here): several */
    lsc_device *d = open_fails(NULL, NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SEVERAL);
    assert_true(strlen(lsc_device_error(d)) < 640);
    lsc_device_close(d);
    /* more HID controllers of the known ids than discovery has room for:
     * the other ids' listing only counts */
    serial_mode = SERIAL_FAIL;
    hid_mode = HID_MANY;
    const test_options other = {0, 0, 0x046d, 0xc52b};
    d = open_fails(NULL, &other, LSC_EINVAL);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SEVERAL);
    assert_has(lsc_device_error(d), "they are: hid:M0 (serial number M0), hid:M1 ");
    lsc_device_close(d);
}

/* A hidraw path the HID layer refuses (too long) is no "several controllers". */
static void hid_path_too_long(void **state)
{
    (void)state;
    char name[LSC_DEVICE_NAME_MAX], dir[LSC_DEVICE_NAME_MAX - 24u];
    memset(dir, 'x', sizeof dir - 1u);
    dir[sizeof dir - 1u] = '\0';
    snprintf(name, sizeof name, "/nonexistent/%s/hidraw0", dir); /* 268 bytes: past 255 */
    lsc_device *d = open_fails(name, NULL, LSC_EINVAL);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_HID);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(null_and_bad_arguments, setup, device_teardown),
        cmocka_unit_test_setup_teardown(failed_open_refuses_everything, setup, device_teardown),
        cmocka_unit_test_setup_teardown(discovery_by_environment, setup, device_teardown),
        cmocka_unit_test_setup_teardown(discovery_none_and_several, setup, device_teardown),
        cmocka_unit_test_setup_teardown(listing, setup, device_teardown),
        cmocka_unit_test_setup_teardown(out_of_memory, setup, device_teardown),
        cmocka_unit_test_setup_teardown(config_setters, setup, device_teardown),
        cmocka_unit_test_setup_teardown(kind_of_names, setup, device_teardown),
        cmocka_unit_test_setup_teardown(names_escaped, setup, device_teardown),
        cmocka_unit_test_setup_teardown(listing_bounds, setup, device_teardown),
        cmocka_unit_test_setup_teardown(hid_path_too_long, setup, device_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
