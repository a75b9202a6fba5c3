/* The client over the in-process simulator (the `sim` port), at 9600 baud of
 * virtual wire time: every wait below costs no real time. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "sim_util.h"

static lsc_sim sim;
static lsc_sim_groups groups;
static lsc_io io;
static lsc_client client;
static lsc_notification seen[8];
static size_t nseen;

static void on_notify(void *user, const lsc_notification *n)
{
    (void)user;
    assert_true(nseen < 8);
    seen[nseen++] = *n;
}

static int setup(void **state)
{
    (void)state;
    assert_int_equal(lsc_sim_init(&sim), 0);
    lsc_sim_set_baud(&sim, 9600);
    assert_int_equal(lsc_sim_io_init(&sim, &io), 0);
    assert_int_equal(lsc_client_init(&client, &io), 0);
    lsc_client_set_notify(&client, on_notify, NULL);
    nseen = 0;
    sim_util_load(&sim, &groups, "group 4\nstep 400 1:2000\nstep 600 1:1000\n");
    return 0;
}

static void test_battery_takes_wire_time(void **state)
{
    (void)state;
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    /* 4 bytes out, 6 back: 10.4 ms of virtual wire time */
    assert_int_equal(lsc_sim_now_us(&sim), 4 * 1042 + 6250);
    lsc_sim_set_battery(&sim, 6800);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_int_equal(mv, 6800);
}

static void test_positions_mid_move(void **state)
{
    (void)state;
    const uint8_t ids[2] = {1, 2};
    lsc_servo out[2];
    assert_int_equal(lsc_client_move_one(&client, 1, 2500, 1000), 0);
    lsc_sim_advance_ms(&sim, 490);
    assert_int_equal(lsc_client_read_positions(&client, ids, 2, out, 100), 2);
    /* the move began when its 10th byte arrived (10 x 1042 us), the request was
     * read when its 7th byte did (490 ms + 7 x 1042 us later): 497294 us into
     * the move, 1000 x 497294 / 1000000 above 1500 */
    assert_int_equal(out[0].position, 1997);
    assert_int_equal(out[1].position, 1500);
    assert_int_equal(lsc_client_read_positions(&client, ids, 1, out, 100), 1);
    lsc_sim_advance_ms(&sim, 1000);
    assert_int_equal(lsc_client_read_positions(&client, ids, 1, out, 100), 1);
    assert_int_equal(out[0].position, 2500);
}

static void test_group_notifications(void **state)
{
    (void)state;
    lsc_notification end;
    assert_int_equal(lsc_client_run_group(&client, 4, 2), 0);
    uint64_t started = lsc_sim_now_us(&sim);
    assert_int_equal(lsc_client_wait_group(&client, 5000, &end), 0);
    assert_int_equal(end.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(end.group, 4);
    assert_int_equal(end.times, 2);
    /* two rounds of 1000 ms, then the 7-byte notification on the wire */
    assert_int_equal(lsc_sim_now_us(&sim) - started, 2000000 + 7292);
    assert_int_equal(nseen, 2);
    assert_int_equal(seen[0].cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(seen[0].group, 4);
    assert_int_equal(seen[0].times, 2);
    assert_int_equal(seen[1].cmd, LSC_CMD_GROUP_COMPLETE);
}

static void test_group_forever_then_stop(void **state)
{
    (void)state;
    lsc_notification end;
    assert_int_equal(lsc_client_set_group_speed(&client, LSC_GROUP_ALL, 200), 0);
    assert_int_equal(lsc_client_run_group(&client, 4, 0), 0);
    assert_int_equal(lsc_client_wait_group(&client, 60000, &end), LSC_ETIMEOUT);
    assert_int_equal(lsc_sim_group_running(&sim), 4);
    assert_int_equal(lsc_client_stop_group(&client), 0);
    assert_int_equal(lsc_client_wait_group(&client, 100, &end), 0);
    assert_int_equal(end.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(nseen, 2);
    assert_int_equal(seen[1].cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
}

static void test_faults_seen_by_client(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_sim_fault_drop(&sim, 1);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    lsc_sim_fault_corrupt(&sim, 1, 2, 0xFF);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), LSC_EREPLY);
    lsc_sim_fault_delay(&sim, 80);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 70), LSC_ETIMEOUT);
    lsc_sim_fault_delay(&sim, 0);
    lsc_sim_advance_ms(&sim, 100); /* the late reply arrives; the client drops it */
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), 0);
    assert_int_equal(mv, 7500);
}

static void test_unload_and_bad_frame(void **state)
{
    (void)state;
    const uint8_t ids[1] = {9};
    const uint8_t bad[3] = {1, 9, 9}; /* a position request repeating an id */
    uint8_t reply[8];
    assert_int_equal(lsc_client_unload(&client, ids, 1), 0);
    assert_int_equal(lsc_client_request_raw(&client, LSC_CMD_BATTERY, NULL, 0, LSC_CMD_BATTERY,
                                            reply, sizeof reply, 100),
                     2);
    assert_false(lsc_sim_powered(&sim, 9));
    assert_int_equal(lsc_client_request_raw(&client, LSC_CMD_POS_READ, bad, 3, LSC_CMD_POS_READ,
                                            reply, sizeof reply, 100),
                     LSC_ETIMEOUT);
    assert_int_equal(sim.stats.beeps, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_battery_takes_wire_time, setup),
        cmocka_unit_test_setup(test_positions_mid_move, setup),
        cmocka_unit_test_setup(test_group_notifications, setup),
        cmocka_unit_test_setup(test_group_forever_then_stop, setup),
        cmocka_unit_test_setup(test_faults_seen_by_client, setup),
        cmocka_unit_test_setup(test_unload_and_bad_frame, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
