/* Fault injection end to end in virtual time: the client talks to the
 * virtual controller through its lsc_io adapter while the controller drops,
 * delays and corrupts its replies, and while a group floods the line with
 * notifications. Portable (no OS calls): it also runs big-endian on s390x.
 * Every timing below is exact: the clock is the simulator's. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <string.h>

#include "lsc/client.h"
#include "lsc/sim.h"

static lsc_sim sim;
static lsc_client client;
static lsc_io io;
static unsigned notes[9]; /* notifications seen, by command */

static void count(void *user, const lsc_notification *n)
{
    (void)user;
    notes[n->cmd % 9u]++;
}

static int setup(void **state)
{
    (void)state;
    memset(notes, 0, sizeof notes);
    if (lsc_sim_init(&sim) != 0 || lsc_sim_io_init(&sim, &io) != 0 ||
        lsc_client_init(&client, &io) != 0) {
        return -1;
    }
    lsc_sim_set_battery(&sim, 7400);
    lsc_client_set_notify(&client, count, NULL);
    return 0;
}

static uint32_t now(void)
{
    return io.now_ms(io.ctx);
}

/* A dropped reply is a timeout after exactly the timeout; the next one works. */
static void dropped_reply(void **state)
{
    (void)state;
    uint16_t mv = 0xBEEF;
    lsc_sim_fault_drop(&sim, 1);
    uint32_t t0 = now();
    assert_int_equal(lsc_client_get_battery(&client, &mv, 250), LSC_ETIMEOUT);
    assert_int_equal(now() - t0, 250);
    assert_int_equal(mv, 0xBEEF);
    assert_int_equal(sim.stats.dropped, 1);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 250), 0);
    assert_int_equal(mv, 7400);
}

/* A reply whose LEN byte was corrupted is malformed: LSC_EREPLY, not a
 * wrong value; one whose data byte was corrupted is a valid frame of the
 * wrong content for a position request (other id): LSC_EREPLY too. */
static void corrupted_replies(void **state)
{
    (void)state;
    uint16_t mv = 0xBEEF;
    lsc_sim_fault_corrupt(&sim, 1, 2, 0xFF);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), LSC_EREPLY);
    assert_int_equal(mv, 0xBEEF);

    const uint8_t ids[] = {1, 2};
    lsc_servo out[2];
    memset(out, 0xA5, sizeof out);
    lsc_sim_fault_corrupt(&sim, 1, 5, 0x01); /* the first id: 1 becomes 0 */
    assert_int_equal(lsc_client_read_positions(&client, ids, 2, out, 100), LSC_EREPLY);
    assert_int_equal(out[0].id, 0xA5);
    assert_int_equal(lsc_client_read_positions(&client, ids, 2, out, 100), 2);
    assert_int_equal(out[0].id, 1);
    assert_int_equal(out[0].position, 1500);
}

/* A controller slower than the timeout: the request times out; its late
 * reply, arriving before the next request, is not taken for that one's. */
static void slow_controller(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_sim_fault_delay(&sim, 300);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), LSC_ETIMEOUT);
    lsc_sim_advance_ms(&sim, 400); /* the late reply (7400) is now readable */
    lsc_sim_fault_delay(&sim, 0);
    lsc_sim_set_battery(&sim, 6900);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_int_equal(mv, 6900);
    /* within the timeout, slow is fine */
    lsc_sim_fault_delay(&sim, 90);
    uint32_t t0 = now();
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_true(now() - t0 >= 90);
}

/* A storm of notifications (the board's own start pressed again and again:
 * 7 then 6 each time) while a request waits: every notification that reached
 * the line is delivered, none is taken for the reply, the reply still comes. */
static void notification_storm(void **state)
{
    (void)state;
    static lsc_sim_step steps[1];
    static lsc_servo targets[1];
    static const char text[] = "group 3\nstep 1000 1:2000\n";
    static lsc_sim_groups groups;
    assert_int_equal(lsc_sim_groups_init(&groups, steps, 1, targets, 1), 0);
    assert_int_equal(lsc_sim_groups_parse(&groups, text, sizeof text - 1u, NULL), 1);
    lsc_sim_set_groups(&sim, &groups);
    uint32_t sent = 0;
    for (int i = 0; i < 30; i++) { /* 59 frames: within the 64-frame queue */
        assert_int_equal(lsc_sim_group_run(&sim, 3, 0), 0);
    }
    sent = sim.stats.frames_out;
    assert_int_equal(sent, 59);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_int_equal(mv, 7400);
    assert_int_equal(notes[LSC_CMD_GROUP_RUN], 30);
    assert_int_equal(notes[LSC_CMD_GROUP_STOP], 29);
    assert_int_equal(client.notifications, 59);
}

/* A controller that never answers anything (every reply dropped): each call
 * returns after its timeout, the client stays usable. */
static void silent_controller(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_sim_fault_drop(&sim, 1000);
    for (int i = 0; i < 20; i++) {
        uint32_t t0 = now();
        assert_int_equal(lsc_client_get_battery(&client, &mv, 50), LSC_ETIMEOUT);
        assert_int_equal(now() - t0, 50);
    }
    lsc_sim_fault_drop(&sim, 0);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 50), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(dropped_reply, setup),
        cmocka_unit_test_setup(corrupted_replies, setup),
        cmocka_unit_test_setup(slow_controller, setup),
        cmocka_unit_test_setup(notification_storm, setup),
        cmocka_unit_test_setup(silent_controller, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
