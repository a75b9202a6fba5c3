/* The device layer (src/device, lsc/device.h): the built-in virtual
 * controller "sim" end to end; serial ports played by a peer on a
 * pseudo-terminal (every timeout message, the torn-write rule and the last
 * word before a signal); HID controllers of the hidapi test double
 * (hid_double.c: the first-request retry, the 19-servo bound, unplugging);
 * lscd, a daemon of the test's own on a Unix socket (refusals, the
 * controller going away); discovery and listing, with the transports'
 * listings, the allocator, the transports' clock and HID support replaced
 * through the linker (--wrap) to reach every outcome. */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/device.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#include "lsc/hid.h"
#include "lsc/lscd.h"
#include "lsc/serial.h"
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "test_hex.h"
#include "test_time.h"
#ifdef LSC_TEST_HID
#include "hid_double.h"
#include "../src/device/device_internal.h" /* lsc_device_config's fields */
#include "test_open.h"
#endif

static bool has(const char *text, const char *part)
{
    if (strstr(text, part) == NULL) {
        fprintf(stderr, "'%s' lacks '%s'\n", text, part);
        return false;
    }
    return true;
}

#define assert_has(text, part) assert_true(has((text), (part)))

/* ---- Linker wraps: calloc, and the transports' listings ------------------------- */

void *__real_calloc(size_t n, size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__real_malloc(size_t size);
void *__wrap_malloc(size_t size);
int __real_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);
int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);
int __real_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap);
int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap);

ssize_t __real_write(int fd, const void *buf, size_t n);
ssize_t __wrap_write(int fd, const void *buf, size_t n);
void *__real_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
/* the transports' clock (src/port) and HID support (src/hid) */
uint32_t __real_lsc_port_now_ms(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
uint32_t __wrap_lsc_port_now_ms(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
bool __real_lsc_hid_available(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
bool __wrap_lsc_hid_available(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int calloc_fails_in; /* 0: never; N: the Nth call from now fails */
static int malloc_fails_in; /* the same for malloc */
static int realloc_fails_in; /* the same for realloc */
static int write_raises;    /* a signal: the next write raises it, then fails (LSC_EIO) */
static bool clock_stands_still; /* the transports' clock stays at still_at */
static uint32_t still_at;
static bool hid_unavailable; /* lsc_hid_available says false, as a build without hidapi */

void *__wrap_realloc(void *p, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (realloc_fails_in > 0 && --realloc_fails_in == 0) {
        return NULL;
    }
    return __real_realloc(p, size);
}

uint32_t __wrap_lsc_port_now_ms(void) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    return clock_stands_still ? still_at : __real_lsc_port_now_ms();
}

bool __wrap_lsc_hid_available(void) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    return !hid_unavailable && __real_lsc_hid_available();
}

ssize_t __wrap_write(int fd, const void *buf, size_t n)
{
    if (write_raises != 0) {
        (void)kill(getpid(), write_raises);
        write_raises = 0;
        errno = ENOSPC; /* an OS error: LSC_EIO */
        return -1;
    }
    return __real_write(fd, buf, n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    if (calloc_fails_in > 0 && --calloc_fails_in == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

void *__wrap_malloc(size_t size)
{
    if (malloc_fails_in > 0 && --malloc_fails_in == 0) {
        return NULL;
    }
    return __real_malloc(size);
}

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
static int serial_mode = SERIAL_PORTS;
/* What the HID listing gives: the double's (or the build's), or an error;
 * or the known ids' listing as usual and that of other ids failing; or 100
 * controllers of the known ids (cap filled). */
enum { HID_REAL, HID_FAIL, HID_FAIL_BARE, HID_FAIL_OTHER, HID_MANY };
static int hid_mode = HID_REAL;

static void fake_port(lsc_port_info *p, const char *path, const char *desc, bool usb,
                      uint16_t vid, uint16_t pid, const char *serial)
{
    memset(p, 0, sizeof *p);
    snprintf(p->path, sizeof p->path, "%s", path);
    snprintf(p->description, sizeof p->description, "%s", desc);
    p->usb = usb;
    p->vid = vid;
    p->pid = pid;
    snprintf(p->serial, sizeof p->serial, "%s", serial);
}

int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap)
{
    lsc_port_info ports[8];
    size_t n = 0;
    switch (serial_mode) {
    case SERIAL_REAL: return __real_lsc_serial_list_ports(out, cap, message, msgcap);
    case SERIAL_FAIL:
        snprintf(message, msgcap, "no serial listing here");
        return LSC_EIO;
    case SERIAL_FAIL_BARE: return LSC_ENODEV;
    case SERIAL_PORTS:
        fake_port(&ports[n++], "/nonexistent/ttyUSB7", "USB2.0-Serial", true, 0x1a86, 0x7523,
                  "S1");
        fake_port(&ports[n++], "/nonexistent/ttyS0", "", false, 0, 0, "");
        fake_port(&ports[n++], "/nonexistent/ttyACM0", "Arduino Uno", true, 0x2341, 0x0043, "");
        break;
    case SERIAL_TWO:
        fake_port(&ports[n++], "/nonexistent/ttyUSB0", "CP2102", true, 0x10c4, 0xea60, "");
        fake_port(&ports[n++], "/nonexistent/ttyUSB1", "FT232R", true, 0x0403, 0x6001, "F1");
        break;
    case SERIAL_ODD:
        fake_port(&ports[n++], "/nonexistent/ttyUSB0", "CP2102", true, 0x10c4, 0xea60,
                  "S\n\033[2J");
        fake_port(&ports[n++], "/nonexistent/tty\nUSB1", "FT232R", true, 0x0403, 0x6001, "F1");
        break;
    case SERIAL_NEAR:
        fake_port(&ports[n++], "/nonexistent/ttyUSB3", "CH9102", true, 0x1a86, 0x55d4, "");
        break;
    case SERIAL_HUGE:
        for (size_t i = 0; i < cap; i++) {
            fake_port(&out[i], "/nonexistent/ttyUSB9", "CH340", true, 0x1a86, 0x7523, "");
        }
        return 0x7fffffff;
    default:
        for (; n < 8; n++) {
            char path[220];
            memset(path, 'x', sizeof path - 1u);
            path[sizeof path - 1u] = '\0';
            memcpy(path, "/nonexistent/", 13);
            path[13] = (char)('0' + n);
            fake_port(&ports[n], path, "CH340", true, 0x1a86, 0x7523, "");
        }
        break;
    }
    for (size_t i = 0; i < n && i < cap; i++) {
        out[i] = ports[i];
    }
    return (int)n;
}

int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap)
{
    if (hid_mode == HID_FAIL) {
        snprintf(message, msgcap, "no HID listing here");
        return LSC_EINVAL;
    }
    if (hid_mode == HID_FAIL_BARE || (hid_mode == HID_FAIL_OTHER && (vid != 0 || pid != 0))) {
        return LSC_EIO;
    }
    if (hid_mode == HID_MANY && vid == 0 && pid == 0) {
        for (size_t i = 0; i < cap; i++) {
            memset(&out[i], 0, sizeof out[i]);
            snprintf(out[i].path, sizeof out[i].path, "/nonexistent/hidraw%zu", i);
            snprintf(out[i].serial, sizeof out[i].serial, "M%zu", i);
            out[i].vid = LSC_HID_VID;
            out[i].pid = LSC_HID_PID;
        }
        return 100;
    }
    return __real_lsc_hid_list(out, cap, vid, pid, message, msgcap);
}

/* ---- Fixture --------------------------------------------------------------------- */

static char tmpdir[64];
static char node_a[128], node_b[128];

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    (void)fclose(f);
}

static int setup(void **state)
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
    serial_mode = SERIAL_PORTS;
    hid_mode = HID_REAL;
    calloc_fails_in = 0;
    malloc_fails_in = 0;
    realloc_fails_in = 0;
    clock_stands_still = false;
    hid_unavailable = false;
    (void)unsetenv("LSC_PORT");
    return 0;
}

static int teardown(void **state)
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

static lsc_device *open_ok(const char *name, const test_options *opt)
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

/* Opens name, which must fail with err, leaving no handle; returns NULL, the
 * handle whose lsc_device_error and lsc_device_error_cause say why (the
 * calling thread's last open). */
static lsc_device *open_fails(const char *name, const test_options *opt, int err)
{
    lsc_device *d = (lsc_device *)&d;
    assert_int_equal(test_open(name, opt, &d), err);
    assert_null(d);
    assert_true(lsc_device_error(d)[0] != '\0');
    return d;
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

/* ---- "sim" ----------------------------------------------------------------------- */

static void sim_requests(void **state)
{
    (void)state;
    lsc_device *d = open_ok("sim", NULL);
    assert_string_equal(lsc_device_name(d), "sim");
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SIM);
    assert_int_equal(lsc_device_timeout(d), LSC_DEVICE_TIMEOUT_DEFAULT);
    lsc_device_set_timeout(d, 250);
    assert_int_equal(lsc_device_timeout(d), 250);
    lsc_device_set_timeout(d, 0);
    assert_int_equal(lsc_device_timeout(d), LSC_DEVICE_TIMEOUT_DEFAULT);
    assert_null(lsc_device_arm(d));

    uint16_t mv = 0;
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    assert_int_equal(mv, 7500);
    const lsc_servo to[] = {{1, 2000}, {2, 1200}};
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_move(d, 500, to, 2), 0);
    assert_int_equal(lsc_device_settle(d, to, 2, 500, LSC_DEVICE_TOLERANCE_DEFAULT), 0);
    assert_true(lsc_device_now_ms(d) - t0 >= 500);
    const uint8_t ids[] = {2, 1};
    lsc_servo got[2];
    assert_int_equal(lsc_device_read(d, ids, 2, got), 2);
    assert_int_equal(got[0].id, 2);
    assert_int_equal(got[0].position, 1200);
    assert_int_equal(got[1].position, 2000);
    assert_int_equal(lsc_device_adjust_offset(d, 1, -5), 0);
    lsc_servo_offset off[1];
    assert_int_equal(lsc_device_read_offsets(d, ids + 1, 1, off), 1);
    assert_int_equal(off[0].offset, -5);
    assert_int_equal(lsc_device_speed(d, LSC_GROUP_ALL, 200), 0);
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_unload(d, ids, 2), 0);
    assert_string_equal(lsc_device_error(d), "");

    /* refused before anything is sent, each with its line */
    assert_int_equal(lsc_device_unload(d, ids, 0), LSC_EINVAL);
    assert_has(lsc_device_error(d), "mult_servo_unload (command 20): the arguments do not make");
    assert_int_equal(lsc_device_read(d, ids, 0, got), LSC_EINVAL);
    assert_has(lsc_device_error(d), "mult_servo_pos_read (command 21)");
    assert_int_equal(lsc_device_read_offsets(d, ids, 0, off), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo_offset_read (command 23)");
    assert_int_equal(lsc_device_battery(d, &mv), 0); /* a success clears the message */
    assert_string_equal(lsc_device_error(d), "");
    lsc_device_close(d);
}

static void sim_moves_refused(void **state)
{
    (void)state;
    lsc_servo many[LSC_MOVE_MAX + 1];
    for (size_t i = 0; i < LSC_MOVE_MAX + 1; i++) {
        many[i].id = (uint8_t)i;
        many[i].position = 1500;
    }
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_move(d, 0, NULL, 1), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a move of 0 servos: one move takes 1..83");
    assert_int_equal(lsc_device_move(d, 0, many, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_move(d, 0, many, LSC_MOVE_MAX + 1), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a move of 84 servos");
    assert_int_equal(lsc_device_move(d, 0, many, LSC_MOVE_MAX), 0); /* 83 on sim: fine */
    many[5].id = 2;
    assert_int_equal(lsc_device_move(d, 0, many, 6), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 2 is given twice in one move");
    assert_int_equal(lsc_device_set_arm(d, NULL), 0);
    lsc_device_close(d);
}

typedef struct traced {
    uint8_t cmd[16];
    lsc_trace_dir dir[16];
    size_t n;
} traced;

static void on_trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    traced *t = user;
    assert_true(n >= 4);
    if (t->n < 16) {
        t->cmd[t->n] = frame[3];
        t->dir[t->n++] = dir;
    }
}

static void sim_raw_frames(void **state)
{
    (void)state;
    traced t = {{0}, {0}, 0};
    lsc_device *d = open_ok("sim", NULL);
    lsc_device_set_trace(d, on_trace, &t);
    uint8_t reply[4];
    assert_int_equal(lsc_device_request(d, LSC_CMD_BATTERY, NULL, 0, LSC_CMD_BATTERY, reply,
                                        sizeof reply),
                     2);
    assert_int_equal(reply[0] | reply[1] << 8, 7500);
    assert_int_equal(t.n, 2);
    assert_int_equal(t.dir[0], LSC_TRACE_TX);
    assert_int_equal(t.dir[1], LSC_TRACE_RX);
    assert_int_equal(t.cmd[1], LSC_CMD_BATTERY);
    /* a reply longer than the room given */
    assert_int_equal(lsc_device_request(d, LSC_CMD_BATTERY, NULL, 0, LSC_CMD_BATTERY, reply, 1),
                     LSC_ENOSPC);
    assert_has(lsc_device_error(d), "is longer than the 1 bytes given for it");
    /* notifications are no replies; 8 and 27 are no requests */
    assert_int_equal(lsc_device_request(d, LSC_CMD_BATTERY, NULL, 0, LSC_CMD_GROUP_RUN, reply,
                                        sizeof reply),
                     LSC_EINVAL);
    assert_has(lsc_device_error(d), "get_battery_voltage (command 15): the arguments");
    assert_int_equal(lsc_device_request(d, 8, NULL, 0, 8, reply, sizeof reply), LSC_EINVAL);
    assert_has(lsc_device_error(d), "command 8 is no request");
    assert_int_equal(lsc_device_request(d, 27, NULL, 0, 27, reply, sizeof reply), LSC_EINVAL);

    /* send: 8 and 27 only when forced */
    const uint8_t params[] = {1, 1, 0};
    t.n = 0;
    assert_int_equal(lsc_device_send(d, 8, params, 3, false), LSC_EINVAL);
    assert_has(lsc_device_error(d), "command 8 erases the action groups");
    assert_int_equal(lsc_device_send(d, 27, params, 1, false), LSC_EINVAL);
    assert_has(lsc_device_error(d), "command 27 writes a setting");
    assert_int_equal(t.n, 0); /* nothing went out */
    assert_int_equal(lsc_device_send(d, 8, params, 3, true), 0);
    assert_int_equal(lsc_device_send(d, 27, params, 1, true), 0);
    assert_int_equal(lsc_device_send(d, LSC_CMD_GROUP_STOP, NULL, 0, false), 0);
    assert_int_equal(t.n, 3);
    assert_int_equal(t.cmd[0], 8);
    assert_int_equal(t.cmd[1], 27);
    assert_int_equal(t.cmd[2], LSC_CMD_GROUP_STOP);
    /* more parameters than a frame holds */
    uint8_t big[LSC_PARAMS_MAX + 1] = {0};
    assert_int_equal(lsc_device_send(d, 8, big, sizeof big, true), LSC_EINVAL);
    assert_has(lsc_device_error(d), "action_group_complete (command 8): the arguments");
    assert_int_equal(lsc_device_send(d, 50, big, sizeof big, false), LSC_EINVAL);
    assert_has(lsc_device_error(d), "unknown (command 50)");
    static const struct {
        uint8_t cmd;
        const char *name;
    } names[] = {{3, "servo_move"}, {6, "action_group_run"}, {7, "action_group_stop"},
                 {11, "action_group_speed"}, {15, "get_battery_voltage"},
                 {20, "mult_servo_unload"}, {21, "mult_servo_pos_read"},
                 {23, "servo_offset_read"}, {24, "servo_offset_adjust"}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char want[64];
        snprintf(want, sizeof want, "%s (command %u)", names[i].name, names[i].cmd);
        assert_int_equal(lsc_device_send(d, names[i].cmd, big, sizeof big, false), LSC_EINVAL);
        assert_has(lsc_device_error(d), want);
        assert_string_equal(lsc_device_cmd_name(names[i].cmd), names[i].name);
    }
    assert_string_equal(lsc_device_cmd_name(8), "action_group_complete");
    assert_string_equal(lsc_device_cmd_name(50), "unknown");
    lsc_device_set_trace(d, NULL, NULL);
    lsc_device_close(d);
}

static void sim_groups_listed(void **state)
{
    (void)state;
    uint8_t g[8];
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_groups(d, g, sizeof g), 3);
    assert_int_equal(g[0], 1);
    assert_int_equal(g[1], 2);
    assert_int_equal(g[2], 8);
    memset(g, 0, sizeof g);
    assert_int_equal(lsc_device_groups(d, g, 1), 3);
    assert_int_equal(g[1], 0);
    assert_int_equal(lsc_device_groups(d, NULL, 0), 3);
    lsc_device_close(d);
    d = open_fails("/nonexistent/tty", NULL, LSC_ENODEV);
    assert_int_equal(lsc_device_groups(d, g, sizeof g), 0); /* a real controller does not say */
    lsc_device_close(d);
}

static void sim_wait_group(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim", NULL);
    /* nothing runs: nothing can arrive */
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, LSC_DEVICE_FOREVER, &n),
                     LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE);
    assert_has(lsc_device_error(d), "nothing runs on the virtual controller (sim, groups 1, 2 "
                                    "and 8), so nothing will arrive");
    assert_int_equal(lsc_device_wait_group(d, 1, 1000, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE);

    assert_int_equal(lsc_device_sim_next_event_ms(d), LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_sim_next_event_ms(NULL), LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_false(lsc_device_group_started(d));
    /* its start is due at once, its first step's end later */
    assert_int_equal(lsc_device_sim_next_event_ms(d), 0);
    assert_int_equal(lsc_device_poll(d, 0), 1);
    uint32_t next = lsc_device_sim_next_event_ms(d);
    assert_true(next > 0 && next != LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_poll(d, next - 1u), 0);
    assert_int_equal(lsc_device_sim_next_event_ms(d), 1);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 8);
    assert_int_equal(n.times, 1);
    assert_true(lsc_device_group_started(d));
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);

    /* any group's end: a start is no end */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 1);

    /* a group it does not have never starts */
    assert_int_equal(lsc_device_run(d, 9, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 9, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_NO_GROUP);
    assert_has(lsc_device_error(d), "has no group 9, so it never starts: its groups are 1, 2 "
                                    "and 8");
    assert_int_equal(lsc_device_run(d, 255, 0), 0);
    assert_int_equal(lsc_device_wait_group(d, 255, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "has no group 255");

    /* a group that loops for ever ends no wait without limit... */
    assert_int_equal(lsc_device_run(d, 2, 0), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_FOREVER);
    assert_has(lsc_device_error(d), "group 2 loops for ever");
    assert_true(lsc_device_group_started(d));
    /* ... and a wait with one runs out on the virtual clock */
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_wait_group(d, 2, 2000, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    assert_string_equal(lsc_device_error(d), "no action group ended within 2000 ms");
    assert_true(lsc_device_now_ms(d) - t0 >= 2000);
    /* a stop ends it; any group's end (the stop) too */
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    lsc_device_close(d);
}

/* Starting a group while another runs: the old one's stop (7) and start are
 * not the new run's; a wait resumed after a timeout keeps the start it saw. */
static void sim_wait_group_switch(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_poll(d, 100), 1); /* 1 started */
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, 500, &n), LSC_ETIMEOUT); /* 7, 6: started */
    assert_true(lsc_device_group_started(d));
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 8);
    /* a run's notifications that were read before it do not count */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_poll(d, 2000), 2); /* 6 and 8 of group 1 */
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.group, 2);
    /* without a run: its start from now on (the queued start of 1 is older) */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_poll(d, 100), 1);
    assert_int_equal(lsc_device_wait_group(d, 8, 3000, &n), LSC_ETIMEOUT);
    assert_false(lsc_device_group_started(d));
    lsc_device_close(d);
}

/* A stop (7) and at once the same group's start (6): the controller switched
 * to another run of it (here a raw run frame, as another program's would
 * be), so the wait goes on to that run's end. */
static void sim_wait_group_restarted(void **state)
{
    (void)state;
    lsc_notification n;
    const uint8_t run_2_once[3] = {2, 1, 0};
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_run(d, 2, 0), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, 100, &n), LSC_ETIMEOUT);
    assert_true(lsc_device_group_started(d));
    assert_int_equal(lsc_device_send(d, LSC_CMD_GROUP_RUN, run_2_once, sizeof run_2_once, false),
                     0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 2);
    assert_int_equal(n.times, 1);
    lsc_device_close(d);
}

static void sim_notifications(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    assert_string_equal(lsc_device_error(d), "nothing arrived within 0 ms");
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE);
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, NULL), 0);
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE);
    /* a group that loops for ever sends nothing after its start */
    assert_int_equal(lsc_device_run(d, 2, 0), 0);
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(lsc_device_notification(d, LSC_DEVICE_FOREVER, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_FOREVER);
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);

    /* a full queue drops the oldest: 1 start, then a stop and a start for each
     * run after it; every run reads what has arrived */
    for (int i = 0; i < 40; i++) {
        assert_int_equal(lsc_device_run(d, (uint8_t)(i % 2 == 0 ? 1 : 2), 0), 0);
    }
    assert_int_equal(lsc_device_poll(d, 0), 2); /* the last run's 7 and 6 */
    assert_int_equal(lsc_device_dropped_notifications(d), 79u - LSC_DEVICE_QUEUE);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    size_t left = 1;
    while (lsc_device_notification(d, 0, &n) == 0) {
        left++;
    }
    assert_int_equal(left, LSC_DEVICE_QUEUE);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(n.group, 2);
    lsc_device_close(d);
}

static void sim_settle(void **state)
{
    (void)state;
    lsc_servo many[LSC_READ_MAX + 1];
    memset(many, 0, sizeof many);
    test_options opt = {0, 100, 0, 0};
    lsc_device *d = open_ok("sim", &opt);
    assert_int_equal(lsc_device_timeout(d), 100);
    assert_int_equal(lsc_device_settle(d, NULL, 1, 0, 10), LSC_EINVAL);
    assert_has(lsc_device_error(d), "settling 0 servos");
    assert_int_equal(lsc_device_settle(d, many, 0, 0, 10), LSC_EINVAL);
    assert_int_equal(lsc_device_settle(d, many, LSC_READ_MAX + 1, 0, 10), LSC_EINVAL);
    /* a slow move is not there 100 ms after the time given */
    const lsc_servo far[] = {{1, 2500}, {2, 1500}};
    assert_int_equal(lsc_device_move(d, 5000, far, 2), 0);
    assert_int_equal(lsc_device_settle(d, far, 2, 100, 10), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "servo 1 is at ");
    assert_has(lsc_device_error(d), "not within 10 of its target 2500, 100 ms after the move's "
                                    "time; raise the timeout or the tolerance");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NOT_SETTLED);
    /* ... and servo 2, already there, is not the one named */
    const lsc_servo near[] = {{2, 1500}, {1, 2500}};
    assert_int_equal(lsc_device_settle(d, near, 2, 0, 10), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "servo 1 is at ");
    /* within a wide tolerance it has settled */
    assert_int_equal(lsc_device_settle(d, near, 2, 0, 2000), 0);
    lsc_device_close(d);
}

/* A servo held short of its target (a gripper on an object) ends the wait
 * LSC_SETTLE_STILL_MS after it stopped, not after the timeout: not an error
 * unless strict; the result and the message say where each stopped. */
static void sim_settle_stopped(void **state)
{
    (void)state;
    lsc_settle_result res;
    test_options opt = {0, 1000, 0, 0};
    lsc_device *d = open_ok("sim", &opt);
    lsc_sim *sim = lsc_device_sim(d);
    assert_non_null(sim);
    assert_null(lsc_device_sim(NULL));
    assert_int_equal(lsc_sim_block(sim, 1, 600, LSC_SIM_BLOCK_ABOVE), 0);
    assert_int_equal(lsc_sim_block(sim, 3, 400, LSC_SIM_BLOCK_BELOW), 0);
    const lsc_servo to[] = {{1, 700}, {2, 1000}, {3, 300}};
    assert_int_equal(lsc_device_move(d, 500, to, 3), 0);
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_settle_ex(d, to, 3, 500, 10, 0, &res), LSC_SETTLE_STOPPED);
    uint32_t spent = lsc_device_now_ms(d) - t0;
    assert_true(spent >= 500u + LSC_SETTLE_STILL_MS && spent <= 500u + LSC_SETTLE_STILL_MS + 40u);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    assert_string_equal(lsc_device_error(d),
                        "servo 1 stopped at 600, 100 short of its target 700; "
                        "servo 3 stopped at 400, 100 short of its target 300");
    assert_int_equal(res.nstopped, 2);
    assert_int_equal(res.stopped[0].id, 1);
    assert_int_equal(res.stopped[0].position, 600);
    assert_int_equal(res.stopped[0].target, 700);
    assert_int_equal(res.stopped[1].id, 3);
    /* strict: an error, with the same words; lsc_device_settle is strict */
    assert_int_equal(lsc_device_settle_ex(d, to, 3, 0, 10, LSC_SETTLE_STRICT, &res), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_STOPPED_SHORT);
    assert_has(lsc_device_error(d), "servo 1 stopped at 600, 100 short of its target 700");
    assert_int_equal(res.nstopped, 2);
    assert_int_equal(lsc_device_settle(d, to, 1, 0, 10), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_STOPPED_SHORT);
    /* a stopped servo does not end the wait while another still moves */
    const lsc_servo slow[] = {{4, 2500}, {5, 500}};
    assert_int_equal(lsc_device_move(d, 5000, slow, 2), 0);
    const lsc_servo both[] = {{1, 700}, {4, 2500}, {5, 500}};
    assert_int_equal(lsc_device_settle_ex(d, both, 3, 0, 10, 0, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NOT_SETTLED);
    assert_has(lsc_device_error(d), "servo 4 is at ");
    /* refused: unknown flags, no device */
    assert_int_equal(lsc_device_settle_ex(d, to, 1, 0, 10, 2u, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "unknown flags 0x2");
    assert_int_equal(res.nstopped, 0);
    assert_int_equal(lsc_device_settle_ex(NULL, to, 1, 0, 10, 0, &res), LSC_EINVAL);
    lsc_device_close(d);
}

/* Every servo of a full read stopped short: all are listed; the message
 * stops where it is full. */
static void sim_settle_stopped_many(void **state)
{
    (void)state;
    lsc_servo to[LSC_READ_MAX];
    lsc_settle_result res;
    lsc_device *d = open_ok("sim", NULL);
    for (size_t i = 0; i < LSC_READ_MAX; i++) {
        to[i].id = (uint8_t)(i + 1u);
        to[i].position = 700;
        assert_int_equal(lsc_sim_block(lsc_device_sim(d), to[i].id, 600, LSC_SIM_BLOCK_ABOVE),
                         0);
    }
    assert_int_equal(lsc_device_move(d, 0, to, LSC_MOVE_MAX), 0);
    assert_int_equal(lsc_device_settle_ex(d, to, LSC_READ_MAX, 0, 10, 0, &res),
                     LSC_SETTLE_STOPPED);
    assert_int_equal(res.nstopped, LSC_READ_MAX);
    assert_int_equal(res.stopped[LSC_READ_MAX - 1u].id, LSC_READ_MAX);
    assert_true(strlen(lsc_device_error(d)) > 500u);
    lsc_device_close(d);
}

/* An arm profile on the device: moves outside its limits are refused before
 * anything is sent; the device keeps its own copy. */
static void sim_arm_limits(void **state)
{
    (void)state;
    static const char text[] = "gripper 1 bus limits=0..700\nbase 6 bus\n";
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    traced t = {{0}, {0}, 0};
    assert_int_equal(lsc_arm_parse(text, sizeof text - 1u, "t.conf", &arm, why, sizeof why), 0);
    lsc_device *d = open_ok("sim", NULL);
    lsc_device_set_trace(d, on_trace, &t);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    assert_non_null(lsc_device_arm(d));
    assert_ptr_not_equal(lsc_device_arm(d), arm);
    lsc_arm_free(arm);
    assert_int_equal(lsc_arm_count(lsc_device_arm(d)), 2);
    /* the virtual controller stands in for the arm: its joints at 0 degrees
     * (500 on bus servos), moves beyond a servo's range 0..1000 stop there */
    const uint8_t ids[3] = {1, 6, 2};
    lsc_servo got[3];
    assert_int_equal(lsc_device_read(d, ids, 3, got), 3);
    assert_int_equal(got[0].position, 500);
    assert_int_equal(got[1].position, 500);
    assert_int_equal(got[2].position, 1500); /* on no joint */
    const uint8_t raw[] = {1, 0, 0, 6, 0xD0, 0x07}; /* 0 ms, servo 6 to 2000 */
    assert_int_equal(lsc_device_send(d, LSC_CMD_SERVO_MOVE, raw, sizeof raw, false), 0);
    assert_int_equal(lsc_device_read(d, ids + 1, 1, got), 1);
    assert_int_equal(got[0].position, 1000);
    t.n = 0;
    lsc_servo s[2] = {{6, 500}, {1, 701}};
    assert_int_equal(lsc_device_move(d, 0, s, 2), LSC_EINVAL);
    assert_has(lsc_device_error(d), "joint gripper (servo 1)");
    assert_has(lsc_device_error(d), "nothing was sent");
    assert_int_equal(t.n, 0);
    s[1].position = 700;
    assert_int_equal(lsc_device_move(d, 0, s, 2), 0);
    assert_int_equal(t.n, 1);
    /* out of memory: the profile it had stays */
    const lsc_arm *had = lsc_device_arm(d);
    malloc_fails_in = 1;
    assert_int_equal(lsc_device_set_arm(d, had), LSC_ENOSPC);
    assert_has(lsc_device_error(d), "out of memory");
    assert_ptr_equal(lsc_device_arm(d), had);
    /* none: any position */
    assert_int_equal(lsc_device_set_arm(d, NULL), 0);
    assert_null(lsc_device_arm(d));
    s[1].position = 701;
    assert_int_equal(lsc_device_move(d, 0, s, 2), 0);
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

/* lsc_device_list, copied into out[0..cap) (the infos' fields: the library's
 * own struct, device_internal.h) for the tests to read: how many were
 * listed (may exceed cap), or the error (the listing then NULL). */
static int list_into(lsc_device_info *out, size_t cap, char *msg, size_t msgcap)
{
    lsc_device_info **all = (lsc_device_info **)&all;
    int n = lsc_device_list(&all, msg, msgcap);
    if (n < 0) {
        assert_null(all);
        return n;
    }
    size_t i = 0;
    for (; all[i] != NULL; i++) {
        if (i < cap) {
            out[i] = *all[i];
        }
    }
    assert_int_equal(i, n);
    lsc_device_list_free(all);
    return n;
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

/* ---- A serial port: a peer on a pseudo-terminal ------------------------------------ */

typedef struct peer {
    int master;
    char path[128];
    pthread_t thread;
    bool running;
    size_t expect;     /* bytes to receive (in all) before answering */
    const char *reply; /* hex, or NULL: none */
    bool hang_up;      /* then close the master */
    size_t ngot;
    uint8_t got[4096];
} peer;

static peer P;

static void *peer_main(void *arg)
{
    (void)arg;
    while (P.ngot < P.expect) {
        struct pollfd p = {P.master, POLLIN, 0};
        if (poll(&p, 1, (int)test_ms(5000)) <= 0) {
            return NULL;
        }
        ssize_t r = read(P.master, P.got + P.ngot, sizeof P.got - P.ngot);
        if (r <= 0) {
            return NULL;
        }
        P.ngot += (size_t)r;
    }
    if (P.reply != NULL) {
        uint8_t bytes[512];
        size_t n = test_hex(P.reply, bytes, sizeof bytes);
        assert_true(write(P.master, bytes, n) == (ssize_t)n);
    }
    if (P.hang_up) {
        (void)close(P.master);
        P.master = -1;
    }
    return NULL;
}

/* The peer answers reply once `more` further bytes arrived. */
static void answer(size_t more, const char *reply, bool hang_up)
{
    P.expect = P.ngot + more;
    P.reply = reply;
    P.hang_up = hang_up;
    assert_int_equal(pthread_create(&P.thread, NULL, peer_main, NULL), 0);
    P.running = true;
}

static void answered(void)
{
    if (P.running) {
        assert_int_equal(pthread_join(P.thread, NULL), 0);
        P.running = false;
    }
}

static int pty_setup(void **state)
{
    int slave;
    memset(&P, 0, sizeof P);
    if (openpty(&P.master, &slave, P.path, NULL, NULL) != 0) {
        return -1;
    }
    (void)close(slave);
    return setup(state);
}

static int pty_teardown(void **state)
{
    answered();
    if (P.master >= 0) {
        (void)close(P.master);
    }
    return teardown(state);
}

#define BATTERY_REQ 4u
#define POS_REQ_1 6u

/* A reply timeout that a peer thread answering a request meets on a busy
 * machine (its answer must arrive before it ends). */
static uint32_t short_ms(void)
{
    return (uint32_t)test_ms(250);
}

static lsc_device *open_pty(uint32_t timeout_ms)
{
    test_options opt = {9600, timeout_ms, 0, 0};
    lsc_device *d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SERIAL);
    assert_string_equal(lsc_device_name(d), P.path);
    return d;
}

static void serial_requests(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_device *d = open_pty(500);
    answer(BATTERY_REQ, "55 55 04 0F 4C 1D", false);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    answered();
    assert_int_equal(mv, 7500);
    /* a second opener: busy */
    lsc_device *e = open_fails(P.path, NULL, LSC_EBUSY);
    lsc_device_close(e);
    /* a baud rate the port cannot take */
    lsc_device_close(d);
    test_options opt = {12345, 0, 0, 0};
    e = open_fails(P.path, &opt, LSC_EINVAL);
    assert_has(lsc_device_error(e), "unsupported baud rate");
    lsc_device_close(e);
}

/* Each timeout says what did arrive. */
static void serial_timeouts(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_device *d = open_pty(short_ms());
    answer(BATTERY_REQ, NULL, false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "no reply from the controller on ");
    char within[64];
    snprintf(within, sizeof within, " within %u ms: nothing arrived", (unsigned)short_ms());
    assert_has(lsc_device_error(d), within);
    assert_has(lsc_device_error(d), "nothing arrived; check that it is powered "
                                    "and connected, and the port and baud rate (9600); or raise "
                                    "the timeout");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_REPLY);
    answer(BATTERY_REQ, "01 02 03", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "only 3 byte(s) arrived that formed no frame: likely a wrong "
                                    "baud rate (this was 9600");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NOISE);
    answer(BATTERY_REQ, "55 55 02 07", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "only 1 notification(s) arrived (and 0 byte(s)");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_ONLY_NOTIFICATIONS);
    answer(BATTERY_REQ, "55 55 06 15 01 01 DC 05", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    snprintf(within, sizeof within, " within %u ms: 1 frame(s)", (unsigned)short_ms());
    assert_has(lsc_device_error(d), within);
    assert_has(lsc_device_error(d), "did not answer get_battery_voltage (command 15) within ");
    assert_has(lsc_device_error(d), " ms: 1 frame(s) answering something else came instead (the "
                                    "last: mult_servo_pos_read (command 21)), with 0 "
                                    "notification(s)");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_OTHER_FRAMES);
    /* a malformed reply */
    answer(BATTERY_REQ, "55 55 03 0F 01", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EREPLY);
    answered();
    assert_has(lsc_device_error(d), "bad reply from the controller on ");
    assert_has(lsc_device_error(d), ": check the baud rate (9600)");
    /* offsets: LSC boards may not answer */
    const uint8_t id = 1;
    lsc_servo_offset off;
    answer(POS_REQ_1, NULL, false);
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_ETIMEOUT);
    answered();
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_REPLY);
    assert_has(lsc_device_error(d), "LSC-6/16/32 boards may not answer; else check the port, "
                                    "the power and the timeout");
    lsc_device_close(d);
}

/* move --wait on a board whose servos do not report: the move's time is all */
static void serial_settle(void **state)
{
    (void)state;
    const lsc_servo to = {1, 2000};
    lsc_device *d = open_pty(short_ms());
    answer(POS_REQ_1, NULL, false);
    assert_int_equal(lsc_device_settle(d, &to, 1, 20, 10), 1);
    answered();
    assert_null(lsc_device_sim(d)); /* not the virtual controller */
    assert_has(lsc_device_error(d), "does not answer position reads: the move's time has "
                                    "passed");
    answer(POS_REQ_1, "55 55 06 15 01 01 D0 07", false);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), 0);
    answered();
    lsc_device_close(d);
}

/* Waits on a real port: in chunks without limit, to their timeout with one. */
static void serial_waits(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    assert_int_equal(lsc_device_sim_next_event_ms(d), LSC_DEVICE_FOREVER); /* not "sim" */
    answer(7, "55 55 05 06 08 01 00 55 55 05 08 08 01 00", false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, 30, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    assert_int_equal(lsc_device_poll(d, 20), 0);
    lsc_device_close(d);
}

/* The notice of a run just before ours (another program's, of the same
 * group) comes after ours was sent: the 7 and 6 that our run makes the
 * controller send say that start was not ours. A stop with nothing after it,
 * or with another group's start, ends the wait; that start stays queued. */
static void serial_wait_late_start(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    answer(7, "55 55 05 06 02 00 00 55 55 02 07 55 55 05 06 02 01 00 55 55 05 08 02 01 00",
           false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 2);

    answer(7, "55 55 05 06 02 01 00 55 55 02 07 55 55 05 06 03 01 00", false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(n.group, 3);

    answer(7, "55 55 05 06 02 01 00 55 55 02 07", false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    lsc_device_close(d);
}

/* The port goes away: every call that reads or writes says so. */
static void serial_hang_up(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_notification n;
    const lsc_servo to = {1, 2000};
    lsc_device *d = open_pty(200);
    answer(BATTERY_REQ, NULL, true);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ENODEV);
    answered();
    char msg[256];
    snprintf(msg, sizeof msg, "%s", lsc_device_error(d));
    assert_has(msg, P.path);
    assert_int_equal(lsc_device_poll(d, 10), LSC_ENODEV);
    assert_int_equal(lsc_device_notification(d, 10, &n), LSC_ENODEV);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, 10, &n), LSC_ENODEV);
    assert_int_equal(lsc_device_run(d, 1, 1), LSC_ENODEV);
    assert_int_equal(lsc_device_settle(d, &to, 1, 10, 10), LSC_ENODEV);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), LSC_ENODEV);
    lsc_device_close(d);
}

#define BIG_PARAMS LSC_PARAMS_MAX /* a 257-byte frame */

/* A write the line never takes: the device says which frame and how much of
 * it went out. */
static void serial_write_stalls(void **state)
{
    (void)state;
    uint8_t params[BIG_PARAMS] = {0};
    lsc_device *d = open_pty(200);
    int r;
    do { /* the pty's buffers fill up: nobody reads the master */
        r = lsc_device_send(d, 0x30, params, sizeof params, false);
    } while (r == 0);
    assert_int_equal(r, LSC_EIO);
    assert_has(lsc_device_error(d), "sending unknown (command 48, 257 bytes): ");
    assert_has(lsc_device_error(d), "of 257 bytes went out");
    lsc_device_close(d);
}

static volatile sig_atomic_t caught;
static char last_said[640];
static int last_word_signal; /* the signal say_last_word catches */

static void on_signal(int sig)
{
    (void)sig;
    caught = 1;
}

/* Keeps the failure's line, then (so that the test lives on) catches the
 * signal that would have ended the process. */
static void say_last_word(void *user, const lsc_device *d)
{
    int *calls = user;
    (*calls)++;
    snprintf(last_said, sizeof last_said, "%s", lsc_device_error(d));
    (void)signal(last_word_signal, on_signal);
}

/* A signal that would end the process comes while a write fails: the
 * failure is said (the last word) while the signal is held back, then the
 * signal takes effect (lscctl's faults.sh sees the process end by it). A
 * signal that is caught, or was blocked before, needs no last word. */
static void serial_last_word_before_signal(void **state)
{
    (void)state;
    int calls = 0;
    const uint8_t id = 1;
    lsc_device *d = open_pty(200);
    lsc_device_set_last_word(d, say_last_word, &calls);
    last_word_signal = SIGHUP;
    (void)signal(SIGHUP, SIG_DFL);
    caught = 0;
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    assert_true(caught); /* after the last word */
    assert_has(last_said, "sending mult_servo_unload (command 20, 6 bytes): ");
    assert_has(last_said, "write");
    assert_string_equal(lsc_device_error(d), last_said);
    /* caught (the handler is still set): nothing to say first */
    caught = 0;
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    assert_true(caught);
    /* blocked by the caller: it stays pending after the call */
    sigset_t hup, old;
    sigemptyset(&hup);
    sigaddset(&hup, SIGHUP);
    (void)signal(SIGHUP, SIG_DFL);
    (void)pthread_sigmask(SIG_BLOCK, &hup, &old);
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    (void)signal(SIGHUP, on_signal);
    caught = 0;
    (void)pthread_sigmask(SIG_SETMASK, &old, NULL);
    assert_true(caught);
    /* without a callback, a write that fails says so as any error */
    lsc_device_set_last_word(d, NULL, NULL);
    assert_int_equal(lsc_device_unload(d, &id, 1), 0);
    (void)signal(SIGHUP, SIG_DFL);
    lsc_device_close(d);
}

/* ---- HID controllers (the hidapi test double) ---------------------------------------- */

#ifdef LSC_TEST_HID

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

#endif

/* ---- What a name selects; lists of servos; names from outside in messages -------- */

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

/* Parses list into ids[0..cap): the count, which must be want. */
static int ids_of(const lsc_arm *arm, const char *list, uint8_t *ids, size_t cap, char *why,
                  size_t whylen)
{
    memset(ids, 0xEE, cap);
    if (why != NULL && whylen > 0) {
        why[0] = '\0';
    }
    return lsc_device_parse_ids(arm, list, ids, cap, why, whylen);
}

/* lsc_device_parse_ids: ids, ranges and joint names; every refusal says why. */
static void id_lists(void **state)
{
    (void)state;
    static const char profile[] = "base 6 bus\nshoulder 5 bus\nwrist-roll 2 bus\n";
    lsc_arm *arm = NULL;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX + 1];
    char why[200];
    assert_int_equal(lsc_arm_parse(profile, sizeof profile - 1u, "t.conf", &arm, why, sizeof why),
                     0);
    /* ids and ranges, with or without a profile */
    for (int with = 0; with < 2; with++) {
        const lsc_arm *a = with ? arm : NULL;
        assert_int_equal(ids_of(a, "1-6", ids, 32, why, sizeof why), 6);
        for (uint8_t i = 0; i < 6; i++) {
            assert_int_equal(ids[i], i + 1);
        }
        assert_int_equal(ids_of(a, "1-3,8", ids, 32, why, sizeof why), 4);
        assert_int_equal(ids[3], 8);
        assert_int_equal(ids_of(a, "0x10,7,0-0,255", ids, 32, why, sizeof why), 4);
        assert_int_equal(ids[0], 16);
        assert_int_equal(ids[1], 7);
        assert_int_equal(ids[2], 0);
        assert_int_equal(ids[3], 255);
        assert_int_equal(ids_of(a, "0xfe-0xff", ids, 32, why, sizeof why), 2);
        assert_int_equal(ids[1], 255);
        assert_int_equal(ids_of(a, "9", ids, 1, why, sizeof why), 1); /* exactly cap */
        /* a negative id is said to be one (not "id ''") */
        assert_int_equal(ids_of(a, "-5", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "id '-5' is negative: use 0..255");
        assert_int_equal(ids_of(a, "1,-", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "id '-' is negative: use 0..255");
        assert_int_equal(ids_of(a, "5-3", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range 5-3 is empty: write the lower id first");
        assert_int_equal(ids_of(a, "1-", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-' has no end: write LO-HI, like 1-6");
        assert_int_equal(ids_of(a, "1-x", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-x': id 'x' is not a number: write it in decimal "
                                 "or 0x-hex");
        assert_int_equal(ids_of(a, "256-300", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '256-300': id 256 is out of range: use 0..255");
        assert_int_equal(ids_of(a, "1-3-5", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_has(why, "the range '1-3-5': id '3-5' is not a number");
        assert_int_equal(ids_of(a, "1,1", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "servo 1 listed twice");
        assert_int_equal(ids_of(a, "1-4,3", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "servo 3 listed twice");
        assert_int_equal(ids_of(a, "0-40", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "more than 32 servos");
        assert_int_equal(ids_of(a, "", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "no servos listed: give ids like 1-6, 1,2,5 or joint names");
        for (size_t k = 0; k < 4; k++) {
            static const char *const empty[] = {",", "1,", ",1", "1,,2"};
            assert_int_equal(ids_of(a, empty[k], ids, 32, why, sizeof why), LSC_EINVAL);
            assert_string_equal(why, "an empty item (two commas, or one at an end): give ids "
                                     "like 1-6, 1,2,5 or joint names");
        }
        /* text from outside stays one line */
        assert_int_equal(ids_of(a, "1,2\n\033[31m", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_has(why, "2\\x0A\\x1B[31m");
        assert_null(strchr(why, '\n'));
        assert_null(strchr(why, '\033'));
        assert_int_equal(ids_of(a, "1-\n", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-\\x0A': id '\\x0A' is not a number: write it in "
                                 "decimal or 0x-hex");
    }
    /* joint names, mixed with ids and ranges */
    assert_int_equal(ids_of(arm, "base,shoulder,3-4", ids, 32, why, sizeof why), 4);
    assert_int_equal(ids[0], 6);
    assert_int_equal(ids[1], 5);
    assert_int_equal(ids[2], 3);
    assert_int_equal(ids[3], 4);
    assert_int_equal(ids_of(arm, "wrist-roll,1", ids, 32, why, sizeof why), 2);
    assert_int_equal(ids[0], 2);
    assert_int_equal(ids_of(arm, "base,6", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "servo 6 listed twice");
    assert_int_equal(ids_of(arm, "4-6,base", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "servo 6 listed twice");
    assert_int_equal(ids_of(arm, "elbow", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'elbow' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(ids_of(arm, "base-3", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'base-3' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(ids_of(NULL, "base", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id 'base' is not a number: write it in decimal or 0x-hex");
    /* an item longer than any name or id: its start, escaped */
    char longer[64];
    memset(longer, 'a', sizeof longer - 1u);
    longer[sizeof longer - 1u] = '\0';
    longer[1] = '\t';
    assert_int_equal(ids_of(arm, longer, ids, 32, why, sizeof why), LSC_EINVAL);
    assert_has(why, "'a\\x09aaaa");
    assert_has(why, "...' is neither a joint nor a servo id");
    /* the most there can be: every id once */
    uint8_t all[256];
    assert_int_equal(lsc_device_parse_ids(NULL, "0-255", all, sizeof all, why, sizeof why), 256);
    assert_int_equal(all[255], 255);
    /* arguments */
    assert_int_equal(lsc_device_parse_ids(arm, NULL, ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_device_parse_ids: no list, or no room for ids");
    assert_int_equal(lsc_device_parse_ids(arm, "1", NULL, 32, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1", ids, 0, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1,1", ids, 32, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1,1", ids, 32, why, 0), LSC_EINVAL);
    lsc_arm_free(arm);
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

/* After the open: the name in the messages of a request, escaped. */
static void serial_name_escaped(void **state)
{
    (void)state;
    uint16_t mv;
    char link[256];
    snprintf(link, sizeof link, "%s/tty\n\033[31m", tmpdir);
    assert_int_equal(symlink(P.path, link), 0);
    test_options opt = {9600, 50, 0, 0};
    lsc_device *d = open_ok(link, &opt);
    assert_string_equal(lsc_device_name(d), link);
    answer(BATTERY_REQ, NULL, false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "/tty\\x0A\\x1B[31m within 50 ms");
    assert_null(strpbrk(lsc_device_error(d), "\n\033"));
    lsc_device_close(d);
    (void)unlink(link);
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

#ifdef LSC_TEST_HID
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
#endif

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

/* ---- More of "sim" ------------------------------------------------------------------ */

/* Waits: a stop ends a wait for any group; another group's start is not
 * the awaited one's; a group's end without room for it. */
static void sim_wait_edges(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 1, LSC_DEVICE_FOREVER, NULL), 0); /* no room */
    assert_true(lsc_device_group_started(d));
    /* any group's end: a stop */
    assert_int_equal(lsc_device_run(d, 2, 0), 0);
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    /* group 1 runs, not 8: its start and end are no end of 8 */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, 3000, &n), LSC_ETIMEOUT);
    assert_false(lsc_device_group_started(d));
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE); /* 1 is over */
    lsc_device_close(d);
}

/* A servo past its target (above it) is not settled either. */
static void sim_settle_above(void **state)
{
    (void)state;
    test_options opt = {0, 100, 0, 0};
    lsc_device *d = open_ok("sim", &opt);
    const lsc_servo high = {1, 2500}, low = {1, 1000};
    assert_int_equal(lsc_device_move(d, 0, &high, 1), 0);
    assert_int_equal(lsc_device_settle(d, &high, 1, 0, 10), 0);
    assert_int_equal(lsc_device_settle(d, &low, 1, 0, 10), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "servo 1 is at 2500, not within 10 of its target 1000");
    lsc_device_close(d);
}

/* Recording out of memory: the keyframe is not kept, the message says so. */
static void sim_record_out_of_memory(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2};
    lsc_action a;
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_action_init(&a, ids, 2), 0);
    realloc_fails_in = 1;
    assert_int_equal(lsc_device_take_keyframe(d, &a, 0, 1), LSC_ENOSPC);
    assert_string_equal(lsc_device_error(d), "out of memory after 0 keyframes");
    assert_int_equal(a.count, 0);
    assert_int_equal(lsc_device_take_keyframe(d, &a, 0, 1), 0);
    assert_int_equal(a.count, 1);
    assert_int_equal(a.words[1], 1500);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* ---- More of a serial port ----------------------------------------------------------- */

/* What came instead of the reply: a frame whose command is below the
 * notifications' (6..8) is no notification. */
static void serial_other_frame_low(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_device *d = open_pty((uint32_t)test_ms(1000)); /* the peer's frame comes in time */
    answer(BATTERY_REQ, "55 55 03 01 00", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "1 frame(s) answering something else came instead (the "
                                    "last: unknown (command 1))");
    lsc_device_close(d);
}

/* A wait for a group that started: another group's start and end do not
 * end it, its own end does. */
static void serial_wait_started(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    answer(7,
           "55 55 05 06 08 01 00 55 55 05 06 01 01 00 55 55 05 08 01 01 00 "
           "55 55 05 08 08 01 00",
           false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 8);
    lsc_device_close(d);
}

/* A stop that ends a wait, followed by anything but the same group's start
 * (here another stop): the wait ends; what followed stays queued. */
static void serial_wait_stop_then_other(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    answer(7, "55 55 05 06 08 01 00 55 55 02 07 55 55 02 07", false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    lsc_device_close(d);
}

/* SIGINT and SIGTERM that would end the process get the last word too. */

static void serial_last_word_int_term(void **state)
{
    (void)state;
    const uint8_t id = 1;
    static const int sigs[] = {SIGINT, SIGTERM};
    lsc_device *d = open_pty(200);
    for (size_t i = 0; i < 2; i++) {
        int calls = 0;
        lsc_device_set_last_word(d, say_last_word, &calls);
        last_word_signal = sigs[i];
        (void)signal(sigs[i], SIG_DFL);
        caught = 0;
        last_said[0] = '\0';
        write_raises = sigs[i];
        assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
        assert_int_equal(calls, 1);
        assert_true(caught);
        assert_has(last_said, "sending mult_servo_unload (command 20, 6 bytes): ");
        (void)signal(sigs[i], SIG_DFL);
    }
    lsc_device_close(d);
}

/* A busy port whose name no lscd socket can have: busy, as it is. */
static void serial_busy_long_name(void **state)
{
    (void)state;
    char link[256];
    snprintf(link, sizeof link, "%s/%070d", tmpdir, 0);
    assert_int_equal(symlink(P.path, link), 0);
    test_options opt = {9600, 50, 0, 0};
    lsc_device *d = open_ok(link, &opt);
    /* a profile on a real port changes nothing there */
    static const char text[] = "base 6 bus\n";
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse(text, sizeof text - 1u, "t.conf", &arm, NULL, 0), 0);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    lsc_device *e = open_fails(link, NULL, LSC_EBUSY);
    assert_int_equal(lsc_device_kind_of(e), LSC_DEVICE_SERIAL);
    assert_has(lsc_device_error(e), "port busy");
    lsc_device_close(e);
    lsc_device_close(d);
    (void)unlink(link);
}

/* A poll whose clock stands still while input keeps coming ends after a
 * bounded number of reads (LSC_CLIENT_WAIT_READS_MIN +
 * LSC_CLIENT_READS_PER_MS per ms), as the client's waits do. */
static void serial_poll_clock_stands_still(void **state)
{
    (void)state;
    uint8_t noise[4000];
    memset(noise, 0, sizeof noise);
    lsc_device *d = open_pty(200);
    /* more noise than the reads of a 1 ms poll take (32 bytes each) */
    size_t put = 0;
    while (put < sizeof noise) {
        struct pollfd p = {P.master, POLLOUT, 0};
        assert_true(poll(&p, 1, (int)test_ms(5000)) == 1);
        ssize_t w = write(P.master, noise + put, sizeof noise - put);
        assert_true(w > 0);
        put += (size_t)w;
    }
    still_at = __real_lsc_port_now_ms();
    clock_stands_still = true;
    (void)alarm((unsigned)test_ms(60)); /* a poll without that bound never ends: fail */
    int r = lsc_device_poll(d, 1);
    (void)alarm(0);
    clock_stands_still = false;
    assert_int_equal(r, 0);
    lsc_device_close(d);
}

/* ---- lscd: a daemon of the test's own on a Unix socket --------------------------------- */

/* What the daemon does with the Nth controller frame it gets: sends
 * `before` (hex), a VERDICT with `verdict`, then `after` (hex), all in one
 * write. */
typedef struct lscd_step {
    const char *before;
    int verdict;
    const char *after;
} lscd_step;

typedef struct lscd_daemon {
    int listener, fd;
    char path[108];
    char name[120]; /* "lscd:PATH" */
    pthread_t thread;
    bool running;
    const lscd_step *script; /* the last step repeats */
    size_t nsteps;
    unsigned frames;     /* controller frames it got */
    uint32_t timeout_ms; /* the value of the last TIMEOUT it got */
    uint8_t version;     /* the protocol version its HELLO says (0: the right one) */
} lscd_daemon;

static lscd_daemon L;

/* (A device that closed at once, its answer still on the way, is not the
 * test's failure: an assertion in this thread would end the whole program.) */
static void lscd_send(const uint8_t *data, size_t n)
{
    ssize_t sent = send(L.fd, data, n, MSG_NOSIGNAL);
    assert_true(sent == (ssize_t)n || (sent < 0 && (errno == EPIPE || errno == ECONNRESET)));
}

static size_t lscd_event(uint8_t *out, uint8_t op, const uint8_t *args, size_t n)
{
    uint8_t params[8];
    params[0] = op;
    memcpy(params + 1, args, n);
    int len = lsc_encode_frame(out, LSC_FRAME_MAX, LSC_LSCD_CMD, params, n + 1u);
    assert_true(len > 0);
    return (size_t)len;
}

static void lscd_frame(const lsc_frame *f)
{
    uint8_t out[1024];
    size_t len = 0;
    if (f->cmd == LSC_LSCD_CMD) {
        if (f->nparams == 5 && f->params[0] == LSC_LSCD_OP_PING) {
            len = lscd_event(out, LSC_LSCD_EV_PONG, f->params + 1, 4);
            lscd_send(out, len);
        } else if (f->nparams == 5 && f->params[0] == LSC_LSCD_OP_TIMEOUT) {
            const uint8_t *a = f->params + 1;
            L.timeout_ms = (uint32_t)a[0] | (uint32_t)a[1] << 8 | (uint32_t)a[2] << 16 |
                           (uint32_t)a[3] << 24;
        }
        return;
    }
    const lscd_step *s = &L.script[L.frames < L.nsteps ? L.frames : L.nsteps - 1u];
    L.frames++;
    if (s->before != NULL) {
        len += test_hex(s->before, out, 256);
    }
    const uint8_t verdict[] = {f->cmd, (uint8_t)(int8_t)s->verdict};
    len += lscd_event(out + len, LSC_LSCD_EV_VERDICT, verdict, sizeof verdict);
    if (s->after != NULL) {
        len += test_hex(s->after, out + len, 256);
    }
    lscd_send(out, len);
}

static void *lscd_main(void *arg)
{
    (void)arg;
    struct pollfd p = {L.listener, POLLIN, 0};
    if (poll(&p, 1, (int)test_ms(5000)) != 1) {
        return NULL;
    }
    L.fd = accept(L.listener, NULL, NULL);
    if (L.fd < 0) {
        return NULL;
    }
    uint8_t out[16];
    const uint8_t hello[] = {L.version != 0u ? L.version : LSC_LSCD_PROTOCOL, 1};
    lscd_send(out, lscd_event(out, LSC_LSCD_EV_HELLO, hello, sizeof hello));
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser parser;
    (void)lsc_parser_init(&parser, buf, sizeof buf);
    for (;;) {
        uint8_t in[512];
        struct pollfd q = {L.fd, POLLIN, 0};
        if (poll(&q, 1, (int)test_ms(5000)) != 1) {
            return NULL;
        }
        ssize_t n = read(L.fd, in, sizeof in);
        if (n <= 0) {
            return NULL; /* the device closed */
        }
        const uint8_t *at = in;
        size_t left = (size_t)n;
        while (left > 0) {
            lsc_frame f;
            int res = 0;
            size_t used = lsc_parser_feed_buf(&parser, at, left, &f, &res);
            at += used;
            left -= used;
            if (res == 1) {
                lscd_frame(&f);
            }
        }
    }
}

/* Starts the daemon with script (steps); its name is L.name. */
static void lscd_start(const lscd_step *script, size_t nsteps)
{
    L.script = script;
    L.nsteps = nsteps;
    assert_int_equal(pthread_create(&L.thread, NULL, lscd_main, NULL), 0);
    L.running = true;
}

/* Waits for the daemon's end (the device closed). */
static void lscd_done(void)
{
    if (L.running) {
        assert_int_equal(pthread_join(L.thread, NULL), 0);
        L.running = false;
    }
}

static int lscd_setup(void **state)
{
    if (setup(state) != 0) {
        return -1;
    }
    memset(&L, 0, sizeof L);
    L.fd = -1;
    snprintf(L.path, sizeof L.path, "%s/d.sock", tmpdir);
    snprintf(L.name, sizeof L.name, "lscd:%s", L.path);
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", L.path);
    L.listener = socket(AF_UNIX, SOCK_STREAM, 0);
    if (L.listener < 0 || bind(L.listener, (struct sockaddr *)&addr, sizeof addr) != 0 ||
        listen(L.listener, 1) != 0) {
        return -1;
    }
    return 0;
}

static int lscd_teardown(void **state)
{
    lscd_done();
    if (L.fd >= 0) {
        (void)close(L.fd);
    }
    (void)close(L.listener);
    (void)unlink(L.path);
    return teardown(state);
}

/* Writes lscd's record for port (in $LSC_LSCD_DIR) by hand. */
static void write_record(const char *record, long pid, const char *port, const char *sock)
{
    FILE *f = fopen(record, "w");
    assert_non_null(f);
    (void)fprintf(f, "pid %ld\nport %s\nsocket %s\n", pid, port, sock);
    assert_int_equal(fclose(f), 0);
}

/* A busy serial port that lscd serves: through its socket in lscd's
 * directory, or through the one its record names wherever it is; a record
 * whose process is gone is ignored (busy, the port's own message); a socket
 * that is not lscd's makes it busy, naming lscd and the socket. */
static void lscd_busy_port(void **state)
{
    (void)state;
    static const lscd_step ok[] = {{NULL, 0, NULL}};
    char dir[128], record[256], sock[256], name[LSC_LSCD_NAME_MAX];
    int slave;
    memset(&P, 0, sizeof P);
    assert_int_equal(openpty(&P.master, &slave, P.path, NULL, NULL), 0);
    (void)close(slave);
    assert_true(lsc_lscd_name(P.path, name, sizeof name) > 0);
    snprintf(dir, sizeof dir, "%s/run", tmpdir);
    snprintf(record, sizeof record, "%s/%s" LSC_LSCD_RECORD_SUFFIX, dir, name);
    snprintf(sock, sizeof sock, "%s/%s.sock", dir, name);
    assert_int_equal(mkdir(dir, 0755), 0);
    assert_int_equal(setenv("LSC_LSCD_DIR", dir, 1), 0);
    test_options opt = {9600, (uint32_t)test_ms(2000), 0, 0};
    lsc_device *held = open_ok(P.path, &opt);

    /* no record, no socket: busy as it is (this process holds it: so it says) */
    lsc_device *e = open_fails(P.path, &opt, LSC_EBUSY);
    assert_int_equal(lsc_device_kind_of(e), LSC_DEVICE_SERIAL);
    assert_has(lsc_device_error(e), "port busy: this program has it open already");
    lsc_device_close(e);

    /* a record left by an lscd that is gone */
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        _exit(0);
    }
    assert_int_equal(waitpid(child, NULL, 0), child);
    write_record(record, (long)child, P.path, L.path);
    e = open_fails(P.path, &opt, LSC_EBUSY);
    assert_has(lsc_device_error(e), "port busy: this program has it open already");
    lsc_device_close(e);

    /* a live record whose socket answers, but not as lscd */
    write_record(record, (long)getpid(), P.path, L.path);
    L.version = 99;
    lscd_start(ok, 1);
    e = open_fails(P.path, &opt, LSC_EBUSY);
    lscd_done();
    (void)close(L.fd);
    assert_has(lsc_device_error(e), "port busy: lscd holds it");
    assert_has(lsc_device_error(e), L.path);
    lsc_device_close(e);

    /* ... and as lscd */
    L.version = 0;
    lscd_start(ok, 1);
    lsc_device *d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    assert_non_null(lsc_device_lscd(d));
    assert_null(lsc_device_lscd(held));
    assert_null(lsc_device_lscd(NULL));
    lsc_device_close(d);
    lscd_done();
    (void)close(L.fd);

    /* no record, the socket in lscd's directory */
    assert_int_equal(unlink(record), 0);
    assert_int_equal(symlink(L.path, sock), 0);
    lscd_start(ok, 1);
    d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    lsc_device_close(d);
    lscd_done();
    (void)close(L.fd);
    L.fd = -1;

    lsc_device_close(held);
    (void)unlink(sock);
    (void)rmdir(dir);
    (void)unsetenv("LSC_LSCD_DIR");
    (void)close(P.master);
}

/* The device's timeout reaches lscd: at the open and when it is set. */
static void lscd_timeout_set(void **state)
{
    (void)state;
    static const lscd_step battery[] = {{"55 55 04 0F 4C 1D", 0, NULL}};
    uint16_t mv = 0;
    lscd_start(battery, 1);
    const uint32_t later = (uint32_t)test_ms(5000) + 1u;
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    lsc_device_set_timeout(d, later);
    assert_int_equal(lsc_device_timeout(d), later);
    assert_int_equal(lsc_device_battery(d, &mv), 0); /* after the TIMEOUT, in order */
    assert_int_equal(mv, 7500);
    lsc_device_close(d);
    lscd_done();
    assert_int_equal(L.frames, 1);
    assert_int_equal(L.timeout_ms, later);
}

/* No reply through lscd: the message speaks of lscd's port and baud rate,
 * not the device's own (it has none). */
static void lscd_no_reply(void **state)
{
    (void)state;
    static const lscd_step silent[] = {{NULL, LSC_ETIMEOUT, NULL}};
    uint16_t mv;
    lscd_start(silent, 1);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "no reply from the controller behind lscd:");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_LSCD_NO_REPLY);
    assert_has(lsc_device_error(d), "nothing arrived; check that it is powered and connected, "
                                    "and the port and baud rate lscd serves (its --port and "
                                    "--baud)");
    lsc_device_close(d);
    lscd_done();
}

/* lscd refuses frames (verdict -1, then -7): every call says so in lscd's
 * words, naming the frame. */
static void lscd_refusals(void **state)
{
    (void)state;
    static const lscd_step refuse[] = {{NULL, LSC_EINVAL, NULL}, {NULL, LSC_EINVAL, NULL},
                                       {NULL, LSC_EINVAL, NULL}, {NULL, LSC_EINVAL, NULL},
                                       {NULL, LSC_EIO, NULL}};
    uint16_t mv;
    uint8_t reply[4];
    const uint8_t id = 1, params[] = {1, 1, 0};
    lsc_servo_offset off;
    lscd_start(refuse, 5);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_stop(d), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending action_group_stop (command 7, 4 bytes): lscd at ");
    assert_has(lsc_device_error(d), ": command 7: invalid argument");
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending get_battery_voltage (command 15, 4 bytes): lscd at ");
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending servo_offset_read (command 23, 6 bytes): lscd at ");
    assert_int_equal(lsc_device_request(d, 0x30, NULL, 0, 0x31, reply, sizeof reply),
                     LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending unknown (command 48, 4 bytes): lscd at ");
    assert_int_equal(lsc_device_send(d, 8, params, 3, true), LSC_EIO);
    assert_has(lsc_device_error(d), "sending action_group_complete (command 8, 7 bytes): lscd at ");
    assert_has(lsc_device_error(d), ": command 8: I/O error");
    lsc_device_close(d);
    lscd_done();
    assert_int_equal(L.frames, 5);
}

/* The controller goes away while servos settle: the wait between two reads
 * says so; later requests fail with lscd's word for it. */
static void lscd_controller_gone(void **state)
{
    (void)state;
    static const lscd_step gone[] = {
        {"55 55 06 15 01 01 DC 05", 0, "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"},
        {NULL, LSC_ENODEV, NULL}};
    const lsc_servo to = {1, 2000};
    const uint8_t id = 1;
    lsc_servo_offset off;
    lscd_start(gone, 2);
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), LSC_ENODEV);
    assert_has(lsc_device_error(d), "the controller of lscd at ");
    assert_has(lsc_device_error(d), " went away: unplugged (lscd opens it again when it is back)");
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_ENODEV);
    assert_has(lsc_device_error(d), "sending servo_offset_read (command 23, 6 bytes): the "
                                    "controller of lscd at ");
    lsc_device_close(d);
    lscd_done();
}

/* The controller goes away just after a stop ended a wait (while the wait
 * looks for the same group's start at once): the wait says so. */
static void lscd_gone_after_stop(void **state)
{
    (void)state;
    static const lscd_step run[] = {
        {NULL, 0,
         "55 55 05 06 08 01 00 55 55 02 07 "
         "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"}};
    lsc_notification n;
    lscd_start(run, 1);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), LSC_ENODEV);
    assert_has(lsc_device_error(d), " went away: unplugged (lscd opens it again when it is back)");
    lsc_device_close(d);
    lscd_done();
}

/* ---- The environment, as every front end reads it ------------------------------------ */

/* How to open a device: a config's setters refuse what no open takes,
 * leaving it as it was; the open takes its values (NULL: the defaults). */
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

static void env_vars(void **state)
{
    (void)state;
    char why[160];
    uint16_t vid = 7, pid = 7;
    (void)unsetenv("LSC_ARM");
    assert_null(lsc_device_env_arm());
    assert_int_equal(setenv("LSC_ARM", "", 1), 0);
    assert_null(lsc_device_env_arm());
    assert_int_equal(setenv("LSC_ARM", "arm.conf", 1), 0);
    assert_string_equal(lsc_device_env_arm(), "arm.conf");
    (void)unsetenv("LSC_ARM");
    assert_null(lsc_device_env_port());
    assert_int_equal(setenv("LSC_PORT", "sim", 1), 0);
    assert_string_equal(lsc_device_env_port(), "sim");
    (void)unsetenv("LSC_PORT");
    /* VID:PID */
    assert_int_equal(lsc_device_parse_hid_id("0483:5750", &vid, &pid), 0);
    assert_int_equal(vid, 0x0483);
    assert_int_equal(pid, 0x5750);
    assert_int_equal(lsc_device_parse_hid_id("aBcD:Ef", &vid, &pid), 0);
    assert_int_equal(vid, 0xABCD);
    assert_int_equal(pid, 0xEF);
    assert_int_equal(lsc_device_parse_hid_id("0:1", &vid, &pid), 0);
    static const char *const bad[] = {"",    ":1",   "1:",  "12345:1", "123456:1", "1:12345",
                                      "1:2x", "12",   "0:0", "g:1",     "G:1",      "1/2",
                                      "1:2:3", "1 :2", "0x1:2"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        vid = pid = 7;
        assert_int_equal(lsc_device_parse_hid_id(bad[i], &vid, &pid), LSC_EINVAL);
        assert_int_equal(vid, 7);
        assert_int_equal(pid, 7);
    }
    assert_int_equal(lsc_device_parse_hid_id(NULL, &vid, &pid), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_hid_id("1:2", NULL, &pid), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_hid_id("1:2", &vid, NULL), LSC_EINVAL);
    /* $LSC_HID_ID into the config, unless it names ids */
    lsc_device_config *opt = lsc_device_config_new();
    assert_non_null(opt);
    (void)unsetenv("LSC_HID_ID");
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), 0);
    assert_string_equal(why, "");
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(setenv("LSC_HID_ID", "046d:c52b", 1), 0);
    assert_int_equal(lsc_device_config_from_env(opt, NULL, 0), 0);
    assert_int_equal(opt->hid_vid, 0x046d);
    assert_int_equal(opt->hid_pid, 0xc52b);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 1, 2), 0);
    assert_int_equal(lsc_device_config_from_env(opt, why, 0), 0);
    assert_int_equal(opt->hid_vid, 1);
    assert_int_equal(opt->hid_pid, 2);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 0, 2), 0); /* a pid alone */
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), 0);
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(opt->hid_pid, 2);
    assert_int_equal(setenv("LSC_HID_ID", "usb", 1), 0);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 0, 0), 0);
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), LSC_EINVAL);
    assert_has(why, "$LSC_HID_ID needs a USB VID:PID in hex");
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(opt->hid_pid, 0);
    assert_int_equal(lsc_device_config_from_env(NULL, why, sizeof why), LSC_EINVAL);
    lsc_device_config_free(opt);
    (void)unsetenv("LSC_HID_ID");
}

/* ---- A program's own event loop: lsc_device_fileno, lsc_device_next_event_ms ---------- */

/* Whether fd polls readable within the test's time. */
static bool readable(int fd)
{
    struct pollfd p = {fd, POLLIN, 0};
    return poll(&p, 1, (int)test_ms(5000)) == 1 && (p.revents & POLLIN) != 0;
}

/* "sim" has no descriptor: its deadlines drive the loop, group 1's start
 * and end come by lsc_device_poll with the time that passed. */
static void events_sim(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim", NULL);
    assert_int_equal(lsc_device_fileno(d), -1);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_next_event_ms(d), 0); /* its start is due */
    assert_int_equal(lsc_device_poll(d, 0), 1);
    /* queued: due now, though the virtual controller itself waits */
    assert_int_equal(lsc_device_next_event_ms(d), 0);
    assert_int_equal(lsc_device_sim_next_event_ms(d), 500);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    bool ended = false;
    for (unsigned round = 0; round < 10u && !ended; round++) {
        uint32_t next = lsc_device_next_event_ms(d);
        assert_true(next != LSC_DEVICE_FOREVER);
        assert_true(lsc_device_poll(d, next) >= 0);
        while (lsc_device_notification(d, 0, &n) == 0) {
            ended = n.cmd == LSC_CMD_GROUP_COMPLETE;
        }
    }
    assert_true(ended);
    assert_int_equal(n.group, 1);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    lsc_device_close(d);
    /* NULL, and a failed open */
    assert_int_equal(lsc_device_fileno(NULL), -1);
    assert_int_equal(lsc_device_next_event_ms(NULL), LSC_DEVICE_FOREVER);
    d = open_fails("/nonexistent/ttyUSB9", NULL, LSC_ENODEV);
    assert_int_equal(lsc_device_fileno(d), -1);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    lsc_device_close(d);
}

/* Waits until the port's side of the pty holds n bytes. */
static void pty_holds(int fd, int n)
{
    int held = 0;
    for (uint64_t i = 0; i < (uint64_t)test_ms(5000) && held < n; i++) { /* 1 ms each */
        assert_true(readable(fd));
        assert_int_equal(ioctl(fd, FIONREAD, &held), 0);
        if (held < n) {
            struct timespec t = {0, 1000000}; /* (the pty's own queue moves bytes on) */
            (void)nanosleep(&t, NULL);
        }
    }
    assert_true(held >= n);
}

/* A serial port: its descriptor polls readable when a notification came;
 * lsc_device_poll(d, 0) takes it without waiting, at most 64 reads at once
 * (then the deadline is now); a hang-up is the port's error. */
static void events_serial(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    int fd = lsc_device_fileno(d);
    assert_true(fd >= 0);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    static const uint8_t stop[] = {0x55, 0x55, 0x02, 0x07};
    assert_true(write(P.master, stop, sizeof stop) == (ssize_t)sizeof stop);
    assert_true(readable(fd));
    assert_int_equal(lsc_device_poll(d, 0), 1);
    assert_int_equal(lsc_device_next_event_ms(d), 0);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    /* more than 64 reads of 32 bytes hold: 2048 + 4 bytes of stops */
    uint8_t many[2052];
    for (size_t i = 0; i < sizeof many; i += sizeof stop) {
        memcpy(many + i, stop, sizeof stop);
    }
    assert_true(write(P.master, many, sizeof many) == (ssize_t)sizeof many);
    pty_holds(fd, (int)sizeof many);
    assert_int_equal(lsc_device_poll(d, 0), (int)LSC_DEVICE_QUEUE);
    assert_int_equal(lsc_device_dropped_notifications(d), 512u - LSC_DEVICE_QUEUE);
    for (unsigned i = 0; i < LSC_DEVICE_QUEUE; i++) { /* (the queue only: no read) */
        assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    }
    assert_int_equal(lsc_device_next_event_ms(d), 0); /* input is left */
    assert_int_equal(lsc_device_poll(d, 0), 1);
    assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    /* the other end hangs up */
    (void)close(P.master);
    P.master = -1;
    assert_true(readable(fd));
    assert_int_equal(lsc_device_poll(d, 0), LSC_ENODEV);
    lsc_device_close(d);
}

/* lscd: the socket; frames a request took off it, and the controller's
 * loss it heard of, make the deadline now. */
static void events_lscd(void **state)
{
    (void)state;
    static const lscd_step script[] = {
        /* a battery reply, then 8 stops: more than the request reads */
        {"55 55 04 0F 4C 1D 55 55 02 07 55 55 02 07 55 55 02 07 55 55 02 07 55 55 02 07 "
         "55 55 02 07 55 55 02 07 55 55 02 07",
         0, NULL},
        {NULL, 0, "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"}};
    uint16_t mv = 0;
    lscd_start(script, 2);
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_true(lsc_device_fileno(d) >= 0);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    /* the request read 32 bytes: the reply and 6 stops (taken from the
     * queue without a read); the rest stays in the transport */
    for (unsigned i = 0; i < 6u; i++) {
        assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    }
    assert_int_equal(lsc_device_next_event_ms(d), 0); /* the rest waits in the transport */
    assert_true(lsc_device_poll(d, 0) > 0);
    while (lsc_device_notification(d, 0, NULL) == 0) {
    }
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    /* a stop, answered with the controller's loss */
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_next_event_ms(d), 0);
    assert_int_equal(lsc_device_poll(d, 0), LSC_ENODEV);
    lsc_device_close(d);
    lscd_done();
}

#ifdef LSC_TEST_HID
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
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(null_and_bad_arguments, setup, teardown),
        cmocka_unit_test_setup_teardown(failed_open_refuses_everything, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_requests, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_moves_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_raw_frames, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_groups_listed, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group_switch, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group_restarted, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_notifications, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_settle, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_settle_stopped, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_settle_stopped_many, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_arm_limits, setup, teardown),
        cmocka_unit_test_setup_teardown(discovery_by_environment, setup, teardown),
        cmocka_unit_test_setup_teardown(discovery_none_and_several, setup, teardown),
        cmocka_unit_test_setup_teardown(listing, setup, teardown),
        cmocka_unit_test_setup_teardown(out_of_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(kind_of_names, setup, teardown),
        cmocka_unit_test_setup_teardown(id_lists, setup, teardown),
        cmocka_unit_test_setup_teardown(names_escaped, setup, teardown),
        cmocka_unit_test_setup_teardown(serial_requests, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_timeouts, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_settle, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_waits, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_late_start, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(config_setters, setup, teardown),
        cmocka_unit_test_setup_teardown(env_vars, setup, teardown),
        cmocka_unit_test_setup_teardown(events_sim, setup, teardown),
        cmocka_unit_test_setup_teardown(events_serial, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(events_lscd, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(serial_hang_up, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_write_stalls, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_last_word_before_signal, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_name_escaped, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(listing_bounds, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_path_too_long, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_wait_edges, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_settle_above, setup, teardown),
        cmocka_unit_test_setup_teardown(sim_record_out_of_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(serial_other_frame_low, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_started, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_stop_then_other, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_last_word_int_term, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_busy_long_name, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_poll_clock_stands_still, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(lscd_timeout_set, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_busy_port, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_refusals, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_no_reply, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_controller_gone, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_gone_after_stop, lscd_setup, lscd_teardown),
#ifdef LSC_TEST_HID
        cmocka_unit_test_setup_teardown(hid_listing_bounds, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_retry_first_only, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_unavailable_is_not_several, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_open_by_name, setup, teardown),
        cmocka_unit_test_setup_teardown(events_hid, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_other_ids, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_denied, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_first_request_retried, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_timeout_and_bad_reply, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_move_bound, setup, teardown),
        cmocka_unit_test_setup_teardown(hid_unplugged, setup, teardown),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
