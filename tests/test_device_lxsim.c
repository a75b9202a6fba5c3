/* The virtual bus inside the library ("lx:sim", "lx:sim:IDS";
 * src/device/lxsim.c under the "lx:" entry of src/device/transport_lx.c):
 * its servos, the board's calls and the bus client on it, the real clock
 * (a late reply waited for, a servo that never answers waited for the whole
 * timeout), its descriptor polling readable while bytes wait, bad lists of
 * ids, halt, a board's frames, an open without a timer (timerfd_create
 * wrapped) or without memory (calloc wrapped), a write the bus does not take
 * (lsc_lxbus_io_init wrapped). Linux (timerfd). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../src/device/device_sim.h" /* lsc_device_lxbus: not public */
#include "lsc/lsc.h"
#include "test_time.h"
#include "timerfd_test.h"

/* ---- calloc and the bus's port, wrapped (timerfd_create: timerfd_test.h) ------------- */

void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
int __real_lsc_lxbus_io_init(lsc_lxbus *bus, lsc_io *io); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
int __wrap_lsc_lxbus_io_init(lsc_lxbus *bus, lsc_io *io); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int calloc_fails_in; /* 0: never; N: the Nth call from now fails */
static bool bus_refuses;    /* the bus's port, made now, refuses every write */

static int refuse_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    (void)data;
    (void)n;
    return LSC_EIO;
}

int __wrap_lsc_lxbus_io_init(lsc_lxbus *bus, lsc_io *io) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    int r = __real_lsc_lxbus_io_init(bus, io);
    if (bus_refuses) {
        io->write = refuse_write;
    }
    return r;
}

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (calloc_fails_in > 0 && --calloc_fails_in == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

/* ---- helpers ------------------------------------------------------------------------ */

static lsc_device *open_ok(const char *name)
{
    lsc_device *d = NULL;
    if (lsc_device_open(name, NULL, &d) != 0) {
        fail_msg("open %s: %s", name, lsc_device_error(NULL));
    }
    lsc_device_set_timeout(d, (uint32_t)test_ms(1000));
    return d;
}

static bool has(const char *text, const char *part)
{
    if (strstr(text, part) == NULL) {
        fprintf(stderr, "'%s' lacks '%s'\n", text, part);
        return false;
    }
    return true;
}

/* Whether fd polls readable within ms. */
static bool readable(int fd, int ms)
{
    struct pollfd p = {fd, POLLIN, 0};
    return poll(&p, 1, ms) == 1 && (p.revents & POLLIN) != 0;
}

/* ---- tests -------------------------------------------------------------------------- */

/* "lx:sim" is a bus (of servos 1..6) with a bus client and a descriptor;
 * no other kind has a virtual bus. */
static void test_kind(void **state)
{
    (void)state;
    lsc_device_kind kind = LSC_DEVICE_SERIAL;
    assert_int_equal(lsc_device_kind_of_name("lx:sim", &kind), 0);
    assert_int_equal(kind, LSC_DEVICE_LX);
    lsc_device *d = open_ok("lx:sim");
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LX);
    assert_non_null(lsc_device_lxclient(d));
    lsc_lxbus *bus = lsc_device_lxbus(d);
    assert_non_null(bus);
    assert_int_equal(bus->nservos, 6u);
    for (size_t i = 0; i < 6u; i++) {
        assert_int_equal(bus->servo[i].id, i + 1u);
    }
    assert_true(lsc_device_fileno(d) >= 0);
    lsc_device_close(d);

    d = open_ok("sim");
    assert_null(lsc_device_lxbus(d));
    lsc_device_close(d);
    assert_null(lsc_device_lxbus(NULL));
}

/* Servos move together and read back where they went; a scan finds the
 * servos of the list and only those. */
static void test_move_read_scan(void **state)
{
    (void)state;
    lsc_device *d = open_ok("lx:sim");
    const lsc_servo to[] = {{2, 700}, {3, 250}};
    assert_int_equal(lsc_device_move(d, 300, to, 2), 0);
    assert_int_equal(lsc_device_settle(d, to, 2, 300, 0), 0);
    const uint8_t ids[] = {1, 2, 3};
    lsc_servo got[3];
    assert_int_equal(lsc_device_read(d, ids, 3, got), 3);
    assert_int_equal(got[0].position, 500);
    assert_int_equal(got[1].position, 700);
    assert_int_equal(got[2].position, 250);
    lsc_device_close(d);

    d = open_ok("lx:sim:3,9");
    lsc_lxclient *c = lsc_device_lxclient(d);
    const uint8_t ask[] = {1, 2, 3, 4, 9, 10};
    lsc_lx_scan found;
    assert_int_equal(lsc_lxclient_scan(c, ask, 6, 0, &found), 2);
    assert_true(lsc_lx_scan_found(&found, 3));
    assert_true(lsc_lx_scan_found(&found, 9));
    assert_false(lsc_lx_scan_found(&found, 1));
    uint16_t mv = 0;
    assert_int_equal(lsc_lxclient_read_vin(c, 9, &mv), 0);
    assert_int_equal(mv, LSC_LXBUS_VIN_DEFAULT);
    lsc_device_close(d);
}

/* The real clock: a servo that does not answer costs the whole timeout (as
 * on a pseudo-terminal); a reply that comes late is waited for; one later
 * than the timeout is not, and makes the descriptor readable when it comes. */
static void test_real_clock(void **state)
{
    (void)state;
    lsc_device *d = open_ok("lx:sim");
    lsc_device_set_timeout(d, 100);
    const uint8_t seven = 7, two = 2;
    lsc_servo got;
    long t0 = mono_ms();
    assert_int_equal(lsc_device_read(d, &seven, 1, &got), LSC_ETIMEOUT);
    assert_true(mono_ms() - t0 >= 100); /* not earlier: the timeout is kept */
    assert_true(has(lsc_device_error(d), "no reply from servo 7 on lx:sim"));

    int fd = lsc_device_fileno(d);
    assert_false(readable(fd, 0)); /* nothing waits */
    lsc_lxbus *bus = lsc_device_lxbus(d);
    lsc_lxbus_fault_delay(bus, 30); /* within the timeout: waited for */
    lsc_device_set_timeout(d, (uint32_t)test_ms(1000));
    t0 = mono_ms();
    assert_int_equal(lsc_device_read(d, &two, 1, &got), 1);
    assert_int_equal(got.position, 500);
    assert_true(mono_ms() - t0 >= 30);

    lsc_lxbus_fault_delay(bus, 150); /* later than the timeout */
    lsc_device_set_timeout(d, 20);
    assert_int_equal(lsc_device_read(d, &two, 1, &got), LSC_ETIMEOUT);
    assert_false(readable(fd, 0));
    assert_true(readable(fd, (int)test_ms(5000))); /* the late reply came */
    lsc_lxbus_fault_delay(bus, 0);
    lsc_device_set_timeout(d, (uint32_t)test_ms(1000));
    assert_int_equal(lsc_device_read(d, &two, 1, &got), 1); /* the late one not taken */
    assert_false(readable(fd, 0));
    lsc_device_close(d);
}

/* Halt: every servo stops where it is, mid-way through a move. */
static void test_halt(void **state)
{
    (void)state;
    lsc_device *d = open_ok("lx:sim");
    const lsc_servo to = {2, 1000};
    assert_int_equal(lsc_device_move(d, 10000, &to, 1), 0);
    lsc_servo a, b;
    do { /* (under way: somewhere past its start) */
        assert_int_equal(lsc_device_read(d, &to.id, 1, &a), 1);
    } while (a.position == 500);
    assert_true(lsc_lxbus_moving(lsc_device_lxbus(d), 1));
    assert_int_equal(lsc_device_halt(d), 0);
    assert_false(lsc_lxbus_moving(lsc_device_lxbus(d), 1)); /* stopped, not on its way */
    assert_int_equal(lsc_device_read(d, &to.id, 1, &b), 1);
    assert_true(b.position >= a.position && b.position < 1000);
    lsc_device_close(d);
}

/* A board's frame given to a bus (lscd forwards its clients' frames): a
 * move, an unload, an offset adjustment done as the calls they stand for;
 * any other command, and a malformed one, refused with nothing sent. */
static void test_board_frames(void **state)
{
    (void)state;
    lsc_device *d = open_ok("lx:sim");
    lsc_lxbus *bus = lsc_device_lxbus(d);
    uint8_t f[LSC_FRAME_MAX];
    const lsc_servo to[] = {{2, 700}, {3, 250}};
    int n = lsc_encode_servo_move(f, sizeof f, 0, to, 2);
    assert_true(n > 0);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), 0);
    const uint8_t ids[] = {2, 3};
    lsc_servo got[2];
    assert_int_equal(lsc_device_read(d, ids, 2, got), 2);
    assert_int_equal(got[0].position, 700);
    assert_int_equal(got[1].position, 250);
    assert_true(bus->servo[1].torque);
    n = lsc_encode_unload(f, sizeof f, ids, 1);
    assert_true(n > 0);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), 0);
    assert_false(bus->servo[1].torque);
    assert_true(bus->servo[2].torque);
    n = lsc_encode_offset_adjust(f, sizeof f, 3, -20);
    assert_true(n > 0);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), 0);
    assert_int_equal(bus->servo[2].offset, -20);

    uint32_t frames = bus->stats.frames_in;
    /* a call the bus refuses: its line */
    const uint16_t bad_pos = 1001;
    const lsc_servo far = {2, bad_pos};
    n = lsc_encode_servo_move(f, sizeof f, 0, &far, 1);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), LSC_EINVAL);
    assert_true(has(lsc_device_error(d), "position 1001 is out of range for bus servos"));
    /* a group's run, stop, speed: a bus has none */
    n = lsc_encode_group_run(f, sizeof f, 1, 1);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), LSC_EINVAL);
    assert_true(has(lsc_device_error(d), "lx:sim is a bus of servos, which has no action "
                                         "groups; nothing was sent"));
    n = lsc_encode_group_stop(f, sizeof f);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), LSC_EINVAL);
    n = lsc_encode_group_speed(f, sizeof f, 1, 50);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), LSC_EINVAL);
    assert_true(has(lsc_device_error(d), "which has no action groups"));
    /* other commands */
    n = lsc_encode_battery_request(f, sizeof f);
    assert_int_equal(lsc_device_send_frame(d, f, (size_t)n), LSC_EINVAL);
    assert_true(has(lsc_device_error(d), "lx:sim is a bus of servos: a board's frame of "
                                         "command 15 (get_battery_voltage) has no meaning"));
    /* malformed: a move, an unload, an offset adjustment without their parameters */
    const uint8_t cmds[] = {LSC_CMD_SERVO_MOVE, LSC_CMD_UNLOAD, LSC_CMD_OFFSET_ADJUST};
    for (size_t i = 0; i < sizeof cmds; i++) {
        const uint8_t empty[] = {0x55, 0x55, 0x03, cmds[i], 0x07};
        assert_int_equal(lsc_device_send_frame(d, empty, sizeof empty), LSC_EINVAL);
        assert_true(has(lsc_device_error(d), "a malformed frame of command"));
    }
    assert_int_equal(bus->stats.frames_in, frames); /* nothing reached the bus */
    lsc_device_close(d);
}

/* A bus with a baud rate set (each byte takes its time on the wire, the
 * bus's clock running ahead of real time while the host's bytes go out): a
 * read takes the request's and the reply's bytes' time, and gets its reply. */
static void test_wire_time(void **state)
{
    (void)state;
    lsc_device *d = open_ok("lx:sim");
    lsc_lxbus_set_baud(lsc_device_lxbus(d), 9600);
    const uint8_t two = 2;
    lsc_servo got;
    long t0 = mono_ms();
    assert_int_equal(lsc_device_read(d, &two, 1, &got), 1);
    assert_int_equal(got.position, 500);
    assert_true(mono_ms() - t0 >= 14); /* 6 bytes out, 8 back: 14.6 ms at 9600 baud */
    lsc_device_close(d);
}

/* Lists of ids the virtual bus cannot have: refused with a line; a name
 * that only starts like it is a serial port's. */
static void test_bad_names(void **state)
{
    (void)state;
    lsc_device *d = NULL;
    const char *const bad[] = {"lx:sim:", "lx:sim:x", "lx:sim:254", "lx:sim:0-40"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(lsc_device_open(bad[i], NULL, &d), LSC_EINVAL);
        assert_null(d);
        assert_true(has(lsc_device_error(NULL), "lx:sim:IDS"));
    }
    assert_true(has(lsc_device_error(NULL), "more than 32 servos"));
    assert_int_equal(lsc_device_open("lx:sim:254", NULL, &d), LSC_EINVAL);
    assert_true(has(lsc_device_error(NULL), "254 is the broadcast id"));
    assert_int_equal(lsc_device_open("lx:simulated", NULL, &d), LSC_ENODEV);
    assert_true(has(lsc_device_error(NULL), "simulated"));
    d = open_ok("lx:sim:0,253");
    lsc_device_close(d);
}

/* Without a timer (no descriptor left) it still works, on the real clock;
 * its descriptor is -1. */
static void test_without_timer(void **state)
{
    (void)state;
    timerfd_fails = true;
    lsc_device *d = open_ok("lx:sim");
    timerfd_fails = false;
    assert_int_equal(lsc_device_fileno(d), -1);
    const lsc_servo to = {1, 900};
    assert_int_equal(lsc_device_move(d, 0, &to, 1), 0);
    lsc_servo got;
    assert_int_equal(lsc_device_read(d, &to.id, 1, &got), 1);
    assert_int_equal(got.position, 900);
    lsc_device_close(d);
}

/* A write the bus does not take (it never happens but by this test's hand):
 * the line says so, not a servo's. */
static void test_write_fails(void **state)
{
    (void)state;
    bus_refuses = true;
    lsc_device *d = open_ok("lx:sim");
    bus_refuses = false;
    const lsc_servo to = {1, 900};
    assert_int_equal(lsc_device_move(d, 0, &to, 1), LSC_EIO);
    assert_true(has(lsc_device_error(d), "the virtual bus (lx:sim) did not take the bytes"));
    lsc_device_close(d);
}

/* Out of memory at each allocation of the open: LSC_ENOSPC, nothing left
 * open; then it opens. */
static void test_out_of_memory(void **state)
{
    (void)state;
    lsc_device *d = NULL;
    int n = 1;
    for (;; n++) {
        calloc_fails_in = n;
        int r = lsc_device_open("lx:sim", NULL, &d);
        calloc_fails_in = 0;
        if (r == 0) {
            break;
        }
        assert_int_equal(r, LSC_ENOSPC);
        assert_null(d);
        assert_true(has(lsc_device_error(NULL), "out of memory"));
    }
    assert_true(n >= 3); /* the device, its state, the bus */
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kind),
        cmocka_unit_test(test_move_read_scan),
        cmocka_unit_test(test_real_clock),
        cmocka_unit_test(test_halt),
        cmocka_unit_test(test_board_frames),
        cmocka_unit_test(test_wire_time),
        cmocka_unit_test(test_bad_names),
        cmocka_unit_test(test_without_timer),
        cmocka_unit_test(test_write_fails),
        cmocka_unit_test(test_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
