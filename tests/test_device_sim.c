/* The device layer (src/device, lsc/device.h) on the built-in virtual
 * controller "sim", end to end: requests, raw frames, groups and their
 * waits, notifications, settling, an arm profile's limits, recording out of
 * memory (malloc and realloc wrapped), a program's own event loop. */
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

#include "device_test.h"
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
#include "test_time.h"
#include "sized_test.h"

/* ---- Linker wraps: malloc and realloc -------------------------------------------- */

void *__real_malloc(size_t size);
void *__wrap_malloc(size_t size);
void *__real_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int malloc_fails_in; /* the same for malloc */
static int realloc_fails_in; /* the same for realloc */

void *__wrap_realloc(void *p, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (realloc_fails_in > 0 && --realloc_fails_in == 0) {
        return NULL;
    }
    return __real_realloc(p, size);
}

void *__wrap_malloc(size_t size)
{
    if (malloc_fails_in > 0 && --malloc_fails_in == 0) {
        return NULL;
    }
    return __real_malloc(size);
}

static int setup(void **state)
{
    malloc_fails_in = 0;
    realloc_fails_in = 0;
    return device_setup(state);
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
    lsc_settle_result res = {.size = sizeof res};
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
    /* a caller's shorter struct (room for one stop): nothing written beyond
     * its size; its size stays */
    lsc_settle_result old;
    const size_t one = offsetof(lsc_settle_result, stopped) + sizeof(lsc_settle_stop);
    sized_guard(&old, sizeof old, one);
    assert_int_equal(lsc_device_settle_ex(d, to, 3, 0, 10, 0, &old), LSC_SETTLE_STOPPED);
    assert_int_equal(old.size, one);
    assert_int_equal(old.nstopped, 2);
    assert_int_equal(old.stopped[0].id, 1);
    assert_true(sized_untouched(&old, one, sizeof old));
    /* a size below the size field and nstopped: refused, nothing sent or written */
    uint64_t sent = sized_frames_sent(d);
    sized_guard(&old, sizeof old, offsetof(lsc_settle_result, nstopped));
    assert_int_equal(lsc_device_settle_ex(d, to, 3, 0, 10, 0, &old), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_settle_result.size is");
    assert_has(lsc_device_error(d), "set it to sizeof(lsc_settle_result); nothing was sent");
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    assert_int_equal(sized_frames_sent(d), sent);
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
    lsc_settle_result res = {.size = sizeof res};
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

/* ---- A program's own event loop: lsc_device_fileno, lsc_device_next_event_ms ---------- */

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(sim_requests, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_moves_refused, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_raw_frames, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_groups_listed, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group_switch, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_wait_group_restarted, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_notifications, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_settle, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_settle_stopped, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_settle_stopped_many, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_arm_limits, setup, device_teardown),
        cmocka_unit_test_setup_teardown(events_sim, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_wait_edges, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_settle_above, setup, device_teardown),
        cmocka_unit_test_setup_teardown(sim_record_out_of_memory, setup, device_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
