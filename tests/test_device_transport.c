/* The device's transport table (src/device/transport.h): each entry's state
 * is its own allocation (out of memory refused with its line, nothing left
 * open), and a kind whose entry leaves a board command out refuses that
 * command with a line naming what it lacks, sending nothing, while halt
 * falls back to a hold when the kind has no action groups. A test entry,
 * "sim"'s with fewer commands, stands in for such a kind. calloc wrapped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/device.h"
#include "lsc/lsc.h"
#include "../src/device/device_internal.h"

void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int calloc_fails_in; /* 0: never; N: the Nth call from now fails */

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (calloc_fails_in > 0 && --calloc_fails_in == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

static bool has(const char *text, const char *part)
{
    if (strstr(text, part) == NULL) {
        fprintf(stderr, "'%s' lacks '%s'\n", text, part);
        return false;
    }
    return true;
}

#define assert_has(text, part) assert_true(has((text), (part)))

/* The device, then the state of the kind the name selects: the second fails. */
static void state_out_of_memory(void **state)
{
    (void)state;
    static const char *const names[] = {"sim", "/nonexistent/tty", "hid:NOSUCH",
                                         "lx:/nonexistent/tty"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        lsc_device *d = (lsc_device *)&d;
        calloc_fails_in = 2;
        assert_int_equal(lsc_device_open(names[i], NULL, &d), LSC_ENOSPC);
        calloc_fails_in = 0;
        assert_null(d);
        assert_string_equal(lsc_device_error(NULL), "out of memory");
        assert_string_equal(lsc_device_name(NULL), names[i]);
    }
}

/* Counts the frames sent. */
static void count_tx(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)frame;
    (void)n;
    if (dir == LSC_TRACE_TX) {
        ++*(unsigned *)user;
    }
}

/* A kind of bus servos: moves and position reads, no action groups, no
 * battery, no offsets, no unload. */
static const lsc_dev_ops bus_ops = {
    .move = lsc_dev_board_move,
    .read_positions = lsc_dev_board_read_positions,
};

static const lsc_dev_ops no_ops = {0};

/* A link that fails: its line is the transport's own (for "sim": none). */
static int broken_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    (void)d;
    (void)time_ms;
    (void)servos;
    (void)n;
    return LSC_EIO;
}

static const lsc_dev_ops broken_ops = {.move = broken_move};

static void missing_commands(void **state)
{
    (void)state;
    lsc_device *d = NULL;
    lsc_dev_transport bus = lsc_dev_transport_sim, bare = lsc_dev_transport_sim;
    lsc_dev_transport broken = lsc_dev_transport_sim;
    const lsc_dev_transport *was;
    unsigned sent = 0;
    uint16_t mv = 0;
    uint8_t ids[2] = {1, 2};
    lsc_servo_offset offs[2];
    lsc_servo pos[2], to[1] = {{1, 1200}};
    bus.ops = &bus_ops;
    bus.name = "a test bus";
    bare.ops = &no_ops;
    bare.name = "a test bus";
    broken.ops = &broken_ops;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    lsc_device_set_trace(d, count_tx, &sent);
    was = d->t;
    d->t = &bus;
    assert_int_equal(lsc_device_run(d, 1, 1), LSC_EINVAL);
    assert_string_equal(lsc_device_error(d),
                        "sim is a test bus, which has no action groups; nothing was sent");
    assert_int_equal(lsc_device_stop(d), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no action groups; nothing was sent");
    assert_int_equal(lsc_device_speed(d, 1, 50), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no action groups; nothing was sent");
    assert_int_equal(lsc_device_unload(d, ids, 2), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no unload; nothing was sent");
    assert_int_equal(lsc_device_adjust_offset(d, 1, 3), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no servo offsets; nothing was sent");
    assert_int_equal(lsc_device_read_offsets(d, ids, 2, offs), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no servo offsets; nothing was sent");
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no battery; nothing was sent");
    assert_int_equal(sent, 0);
    /* what it has works; halt is a hold (no group to stop): a read, a move */
    assert_int_equal(lsc_device_move(d, 100, to, 1), 0);
    assert_int_equal(lsc_device_read(d, ids, 2, pos), 2);
    sent = 0;
    assert_int_equal(lsc_device_halt(d), 0);
    assert_int_equal(sent, 2);
    /* a kind with none of them */
    d->t = &bare;
    assert_int_equal(lsc_device_move(d, 100, to, 1), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no moves of several servos; nothing was sent");
    assert_int_equal(lsc_device_read(d, ids, 2, pos), LSC_EINVAL);
    assert_has(lsc_device_error(d), "which has no position reads; nothing was sent");
    assert_int_equal(sent, 2);
    d->t = &broken;
    assert_int_equal(lsc_device_move(d, 100, to, 1), LSC_EIO);
    assert_string_equal(lsc_device_error(d), "");
    d->t = was;
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(state_out_of_memory),
        cmocka_unit_test(missing_commands),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
