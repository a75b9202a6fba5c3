/* Unit tests of the virtual controller model (include/lsc/sim.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "sim_util.h"

static lsc_sim sim;
static lsc_sim_groups groups;

static int setup(void **state)
{
    (void)state;
    assert_int_equal(lsc_sim_init(&sim), 0);
    return 0;
}

static void move1(uint16_t time_ms, uint8_t id, uint16_t pos)
{
    uint8_t frame[16];
    lsc_servo s = {id, pos};
    sim_util_feed(&sim, frame, lsc_encode_servo_move(frame, sizeof frame, time_ms, &s, 1));
}

/* ---- Defaults, battery, positions ------------------------------------------ */

static void test_defaults(void **state)
{
    (void)state;
    for (unsigned id = 0; id < LSC_SIM_SERVOS; id++) {
        assert_int_equal(lsc_sim_position(&sim, (uint8_t)id), 1500);
        assert_true(lsc_sim_powered(&sim, (uint8_t)id));
        assert_false(lsc_sim_moving(&sim, (uint8_t)id));
    }
    assert_int_equal(lsc_sim_now_us(&sim), 0);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
    assert_int_equal(lsc_sim_group_speed(&sim, 0), 100);
    assert_int_equal(lsc_sim_group_speed(&sim, 254), 100);
    assert_int_equal(lsc_sim_group_speed(&sim, LSC_GROUP_ALL), 0);
    assert_int_equal(lsc_sim_next_event_us(&sim), LSC_SIM_TIME_NEVER);
    sim_util_expect_none(&sim);
    /* the protocol document's battery example, both ways */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    assert_int_equal(sim.stats.frames_in, 1);
    assert_int_equal(sim.stats.frames_out, 1);
    assert_int_equal(sim.stats.beeps, 0);
    assert_int_equal(sim_util_read_pos(&sim, 255), 1500);
    assert_int_equal(sim_util_read_pos(&sim, 0), 1500);
}

static void test_battery_settable(void **state)
{
    (void)state;
    lsc_sim_set_battery(&sim, 6123);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0xEB, 0x17);
}

/* xArm servo offsets (23 read, 24 adjust): kept per servo, 0 at power-on,
 * reported in the order asked; they do not move the servo. */
static void test_offsets(void **state)
{
    (void)state;
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x17, 0x02, 0x06, 0x01);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x07, 0x17, 0x02, 0x06, 0x00, 0x01, 0x00);
    SIM_FEED(&sim, 0x55, 0x55, 0x04, 0x18, 0x06, 0xF6); /* servo 6: -10 */
    SIM_FEED(&sim, 0x55, 0x55, 0x04, 0x18, 0x01, 0x7F); /* servo 1: 127 */
    sim_util_expect_none(&sim);
    SIM_FEED(&sim, 0x55, 0x55, 0x06, 0x17, 0x03, 0x01, 0x02, 0x06);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x09, 0x17, 0x03, 0x01, 0x7F, 0x02, 0x00, 0x06, 0xF6);
    assert_int_equal(lsc_sim_position(&sim, 6), 1500);
    assert_int_equal(sim.stats.beeps, 0);
    /* malformed: a repeated id, a 24 of the wrong length: two beeps each */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x17, 0x02, 0x06, 0x06);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x18, 0x06, 0xF6, 0xFF);
    sim_util_expect_none(&sim);
    assert_int_equal(sim.stats.beeps, 2);
}

static void test_move_mid_and_after(void **state)
{
    (void)state;
    /* the protocol document's example: 1000 ms, id 1 -> 2000 */
    SIM_FEED(&sim, 0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xD0, 0x07);
    assert_true(lsc_sim_moving(&sim, 1));
    assert_int_equal(sim_util_read_pos(&sim, 1), 1500);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(sim_util_read_pos(&sim, 1), 1625);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(sim_util_read_pos(&sim, 1), 1750);
    lsc_sim_advance_us(&sim, 499999);
    assert_int_equal(lsc_sim_position(&sim, 1), 1999);
    assert_true(lsc_sim_moving(&sim, 1));
    lsc_sim_advance_us(&sim, 1);
    assert_int_equal(sim_util_read_pos(&sim, 1), 2000);
    assert_false(lsc_sim_moving(&sim, 1));
    lsc_sim_advance_ms(&sim, 5000);
    assert_int_equal(lsc_sim_position(&sim, 1), 2000);
    /* other servos did not move */
    assert_int_equal(lsc_sim_position(&sim, 2), 1500);
}

static void test_move_rounds_towards_start(void **state)
{
    (void)state;
    move1(3, 7, 1000); /* 1500 -> 1000 over 3 ms: -166.67 per ms */
    lsc_sim_advance_ms(&sim, 1);
    assert_int_equal(lsc_sim_position(&sim, 7), 1334);
    lsc_sim_advance_ms(&sim, 1);
    assert_int_equal(lsc_sim_position(&sim, 7), 1167);
    move1(3, 8, 2000); /* upwards: +166.67 per ms */
    lsc_sim_advance_ms(&sim, 1);
    assert_int_equal(lsc_sim_position(&sim, 8), 1666);
}

static void test_move_from_interpolated_position(void **state)
{
    (void)state;
    move1(1000, 3, 2500);
    lsc_sim_advance_ms(&sim, 500); /* at 2000 */
    move1(100, 3, 1000);
    assert_int_equal(lsc_sim_position(&sim, 3), 2000);
    lsc_sim_advance_ms(&sim, 50);
    assert_int_equal(lsc_sim_position(&sim, 3), 1500);
    lsc_sim_advance_ms(&sim, 50);
    assert_int_equal(lsc_sim_position(&sim, 3), 1000);
}

static void test_move_time_zero_is_instant(void **state)
{
    (void)state;
    move1(0, 4, 600);
    assert_int_equal(lsc_sim_position(&sim, 4), 600);
    assert_false(lsc_sim_moving(&sim, 4));
}

static void test_move_many_and_read_in_order(void **state)
{
    (void)state;
    uint8_t frame[LSC_FRAME_MAX];
    lsc_servo s[6];
    for (uint8_t i = 0; i < 6; i++) {
        s[i].id = (uint8_t)(i + 1);
        s[i].position = 500;
    }
    sim_util_feed(&sim, frame, lsc_encode_servo_move(frame, sizeof frame, 20, s, 6));
    lsc_sim_advance_ms(&sim, 20);
    /* the protocol document's position read example, both ways (reply little-endian) */
    SIM_FEED(&sim, 0x55, 0x55, 0x09, 0x15, 0x06, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x15, 0x15, 0x06, 0x01, 0xF4, 0x01, 0x02, 0xF4, 0x01, 0x03,
               0xF4, 0x01, 0x04, 0xF4, 0x01, 0x05, 0xF4, 0x01, 0x06, 0xF4, 0x01);
    /* ids answered in the order asked */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x15, 0x02, 0x09, 0x02);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x09, 0x15, 0x02, 0x09, 0xDC, 0x05, 0x02, 0xF4, 0x01);
}

static void test_read_of_84_servos(void **state)
{
    (void)state;
    uint8_t ids[LSC_READ_MAX];
    uint8_t frame[LSC_FRAME_MAX];
    uint8_t got[LSC_FRAME_MAX];
    for (unsigned i = 0; i < LSC_READ_MAX; i++) {
        ids[i] = (uint8_t)(200 - i);
    }
    sim_util_feed(&sim, frame, lsc_encode_pos_request(frame, sizeof frame, ids, LSC_READ_MAX));
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 257);
    assert_int_equal(got[2], 255);
    assert_int_equal(got[4], LSC_READ_MAX);
    assert_int_equal(got[5], 200);
}

static void test_unload_then_move(void **state)
{
    (void)state;
    SIM_FEED(&sim, 0x55, 0x55, 0x06, 0x14, 0x03, 0x01, 0x02, 0x03);
    sim_util_expect_none(&sim);
    assert_false(lsc_sim_powered(&sim, 1));
    assert_false(lsc_sim_powered(&sim, 3));
    assert_true(lsc_sim_powered(&sim, 4));
    assert_int_equal(sim_util_read_pos(&sim, 2), 1500); /* keeps its position */
    move1(100, 2, 1000);
    assert_true(lsc_sim_powered(&sim, 2));
    assert_false(lsc_sim_powered(&sim, 1));
    lsc_sim_advance_ms(&sim, 100);
    assert_int_equal(lsc_sim_position(&sim, 2), 1000);
}

static void test_unload_mid_move_stops_there(void **state)
{
    (void)state;
    move1(1000, 5, 2500);
    lsc_sim_advance_ms(&sim, 300);
    SIM_FEED(&sim, 0x55, 0x55, 0x04, 0x14, 0x01, 0x05);
    assert_false(lsc_sim_moving(&sim, 5));
    lsc_sim_advance_ms(&sim, 1000);
    assert_int_equal(sim_util_read_pos(&sim, 5), 1800);
    assert_false(lsc_sim_powered(&sim, 5));
}

/* ---- Action groups ---------------------------------------------------------- */

static const char group_text[] = "# test groups\n"
                                 "group 1\n"
                                 "step 500 1:2000 2:1000\n"
                                 "step 500 1:1000\n"
                                 "group 8\n"
                                 "step 100 9:600\n";

static void load(void)
{
    sim_util_load(&sim, &groups, group_text);
}

/* A servo given a range (the arm the simulator stands in for): it rests at
 * the position given, brought into the range; a host's move or a group's
 * step beyond the range ends at its nearer end; range 0..0 removes it. */
static void test_servo_range(void **state)
{
    (void)state;
    load();
    assert_int_equal(lsc_sim_set_servo(&sim, 1, 500, 0, 1000), 0);
    assert_int_equal(lsc_sim_position(&sim, 1), 500);
    assert_int_equal(sim_util_read_pos(&sim, 1), 500);
    assert_false(lsc_sim_moving(&sim, 1));
    move1(100, 1, 1500);
    lsc_sim_advance_ms(&sim, 25);
    assert_int_equal(lsc_sim_position(&sim, 1), 750); /* a quarter of the way */
    lsc_sim_advance_ms(&sim, 25);
    assert_int_equal(lsc_sim_position(&sim, 1), 1000); /* at the end of its range */
    assert_true(lsc_sim_moving(&sim, 1));              /* pushing, as a servo would */
    lsc_sim_advance_ms(&sim, 50);
    assert_int_equal(sim_util_read_pos(&sim, 1), 1000);
    assert_int_equal(lsc_sim_set_servo(&sim, 2, 1500, 21, 979), 0);
    assert_int_equal(lsc_sim_position(&sim, 2), 979);
    move1(0, 2, 3);
    assert_int_equal(lsc_sim_position(&sim, 2), 21);
    /* group 1 moves servo 1 to 2000, then 1000 */
    assert_int_equal(lsc_sim_group_run(&sim, 1, 1), 0);
    lsc_sim_advance_ms(&sim, 500);
    assert_int_equal(lsc_sim_position(&sim, 1), 1000);
    assert_int_equal(lsc_sim_position(&sim, 2), 979);
    /* no range: positions as sent */
    assert_int_equal(lsc_sim_set_servo(&sim, 2, 2500, 0, 0), 0);
    assert_int_equal(lsc_sim_position(&sim, 2), 2500);
    /* refused: nothing changes */
    assert_int_equal(lsc_sim_set_servo(&sim, 3, 700, 800, 600), LSC_EINVAL);
    assert_int_equal(lsc_sim_set_servo(NULL, 3, 700, 0, 1000), LSC_EINVAL);
    assert_int_equal(lsc_sim_position(&sim, 3), 1500);
}

static void test_group_runs_at_100_percent(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x02, 0x00); /* group 1, twice */
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x02, 0x00);
    assert_int_equal(lsc_sim_group_running(&sim), 1);
    assert_int_equal(lsc_sim_next_event_us(&sim), 500000);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(lsc_sim_position(&sim, 1), 1750);
    assert_int_equal(lsc_sim_position(&sim, 2), 1250);
    lsc_sim_advance_ms(&sim, 250); /* step 2 starts */
    assert_int_equal(lsc_sim_position(&sim, 1), 2000);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    lsc_sim_advance_ms(&sim, 250); /* second time round */
    assert_int_equal(lsc_sim_position(&sim, 1), 1000);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    assert_int_equal(lsc_sim_position(&sim, 2), 1000);
    lsc_sim_advance_us(&sim, 749999);
    sim_util_expect_none(&sim);
    assert_int_equal(lsc_sim_group_running(&sim), 1);
    lsc_sim_advance_us(&sim, 1); /* 2000 ms: complete */
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x08, 0x01, 0x02, 0x00);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
    assert_int_equal(lsc_sim_position(&sim, 1), 1000);
    assert_int_equal(lsc_sim_next_event_us(&sim), LSC_SIM_TIME_NEVER);
}

static void test_clock_saturates_while_a_group_runs(void **state)
{
    (void)state;
    load();
    lsc_sim_advance_us(&sim, LSC_SIM_TIME_NEVER - 5000u);
    assert_int_equal(lsc_sim_group_run(&sim, 1, 0), 0); /* forever */
    lsc_sim_advance_us(&sim, 10000);                    /* must return */
    assert_true(lsc_sim_now_us(&sim) == LSC_SIM_TIME_NEVER - 1u);
    lsc_sim_advance_us(&sim, LSC_SIM_TIME_NEVER); /* and again, at the end of time */
    assert_true(lsc_sim_now_us(&sim) == LSC_SIM_TIME_NEVER - 1u);
}

static void test_group_complete_in_one_big_advance(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x03, 0x00); /* group 8, 3 times */
    lsc_sim_advance_ms(&sim, 10000);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x03, 0x00, 0x55, 0x55, 0x05, 0x08, 0x08,
               0x03, 0x00);
    assert_int_equal(lsc_sim_position(&sim, 9), 600);
}

static void test_group_at_200_percent(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0x01, 0xC8, 0x00); /* group 1 at 200 % */
    sim_util_expect_none(&sim);
    assert_int_equal(lsc_sim_group_speed(&sim, 1), 200);
    assert_int_equal(lsc_sim_group_speed(&sim, 8), 100);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x01, 0x00);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x01, 0x00);
    lsc_sim_advance_ms(&sim, 125);
    assert_int_equal(lsc_sim_position(&sim, 1), 1750);
    lsc_sim_advance_ms(&sim, 125);
    assert_int_equal(lsc_sim_position(&sim, 1), 2000);
    lsc_sim_advance_us(&sim, 249999);
    sim_util_expect_none(&sim);
    lsc_sim_advance_us(&sim, 1);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x08, 0x01, 0x01, 0x00);
}

static void test_speed_all_groups(void **state)
{
    (void)state;
    load();
    /* the protocol document's example: all groups at 300 % */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0xFF, 0x2C, 0x01);
    for (unsigned g = 0; g < LSC_SIM_GROUPS; g++) {
        assert_int_equal(lsc_sim_group_speed(&sim, (uint8_t)g), 300);
    }
    assert_int_equal(lsc_sim_group_run(&sim, 8, 1), 0);
    lsc_sim_advance_us(&sim, 33332);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);
    lsc_sim_advance_us(&sim, 1); /* 100 ms * 100 / 300 = 33333 us */
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x08, 0x08, 0x01, 0x00);
    /* speed for a group number with no group is kept */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0x20, 0x32, 0x00);
    assert_int_equal(lsc_sim_group_speed(&sim, 0x20), 50);
    assert_int_equal(sim.stats.ignored, 0);
}

static void test_speed_zero_ignored(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0x01, 0x00, 0x00);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0xFF, 0x00, 0x00);
    assert_int_equal(lsc_sim_group_speed(&sim, 1), 100);
    assert_int_equal(lsc_sim_group_speed(&sim, 2), 100);
    assert_int_equal(sim.stats.ignored, 2);
    assert_int_equal(sim.stats.beeps, 0);
    sim_util_expect_none(&sim);
}

static void test_speed_change_applies_from_next_step(void **state)
{
    (void)state;
    load();
    assert_int_equal(lsc_sim_group_run(&sim, 1, 1), 0);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x01, 0x00);
    lsc_sim_advance_ms(&sim, 100);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0x01, 0x32, 0x00); /* 50 %: steps take twice */
    lsc_sim_advance_ms(&sim, 400); /* first step still ends at 500 */
    assert_int_equal(lsc_sim_position(&sim, 1), 2000);
    assert_int_equal(lsc_sim_next_event_us(&sim), 1000000);
    lsc_sim_advance_ms(&sim, 500);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
}

static void test_step_never_shorter_than_1ms(void **state)
{
    (void)state;
    load();
    lsc_sim_group_run(&sim, 8, 1);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x0B, 0x08, 0xFF, 0xFF);
    assert_int_equal(lsc_sim_group_run(&sim, 8, 0), 0); /* restart: forever */
    assert_int_equal(lsc_sim_next_event_us(&sim), 0);   /* output waits */
    uint8_t buf[64];
    lsc_sim_read(&sim, buf, sizeof buf);
    assert_int_equal(lsc_sim_next_event_us(&sim), LSC_SIM_STEP_MIN_US);
    lsc_sim_advance_ms(&sim, 60000); /* 60000 steps: still quick */
    assert_int_equal(lsc_sim_group_running(&sim), 8);
}

static void test_group_stop(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x01, 0x00);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x01, 0x00);
    lsc_sim_advance_ms(&sim, 700); /* second step, 1 at 1600 */
    move1(1000, 30, 2500);         /* a host move the stop leaves alone */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x07);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x02, 0x07);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
    assert_int_equal(lsc_sim_position(&sim, 1), 1600);
    assert_false(lsc_sim_moving(&sim, 1));
    assert_true(lsc_sim_moving(&sim, 30));
    lsc_sim_advance_ms(&sim, 5000);
    sim_util_expect_none(&sim);
    assert_int_equal(lsc_sim_position(&sim, 1), 1600);
    assert_int_equal(lsc_sim_position(&sim, 30), 2500);
}

static void test_group_forever_then_stop(void **state)
{
    (void)state;
    load();
    /* the protocol document's "group 2 forever" example, for group 1 */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x00, 0x00);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x00, 0x00);
    for (int i = 0; i < 60; i++) {
        lsc_sim_advance_ms(&sim, 60000); /* an hour */
    }
    sim_util_expect_none(&sim);
    assert_int_equal(lsc_sim_group_running(&sim), 1);
    lsc_sim_advance_ms(&sim, 250); /* first step again, from 1000 to 2000 */
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    assert_int_equal(lsc_sim_group_stop(&sim), 0); /* from the board's side */
    SIM_EXPECT(&sim, 0x55, 0x55, 0x02, 0x07);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    assert_int_equal(lsc_sim_group_stop(&sim), LSC_EINVAL);
}

static void test_group_run_while_running(void **state)
{
    (void)state;
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x00, 0x00);
    lsc_sim_advance_ms(&sim, 100);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x01, 0x00, 0x00, /* group 1 started */
               0x55, 0x55, 0x02, 0x07,                          /* stopped */
               0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);       /* group 8 started */
    assert_int_equal(lsc_sim_group_running(&sim), 8);
    assert_int_equal(lsc_sim_position(&sim, 1), 1600);
    lsc_sim_advance_ms(&sim, 100);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x08, 0x08, 0x01, 0x00);
    assert_int_equal(lsc_sim_position(&sim, 1), 1600);
}

static void test_group_missing_and_stop_idle_ignored(void **state)
{
    (void)state;
    /* no groups at all */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);
    assert_int_equal(lsc_sim_group_run(&sim, 8, 1), LSC_EINVAL);
    load();
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x02, 0x01, 0x00); /* group 2 is not loaded */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0xFF, 0x01, 0x00);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x07); /* nothing runs */
    sim_util_expect_none(&sim);
    assert_int_equal(sim.stats.ignored, 4);
    assert_int_equal(sim.stats.beeps, 0);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
    /* a missing group does not disturb a running one */
    assert_int_equal(lsc_sim_group_run(&sim, 8, 1), 0);
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x06, 0x02, 0x01, 0x00);
    assert_int_equal(lsc_sim_group_run(&sim, 3, 1), LSC_EINVAL);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);
    assert_int_equal(lsc_sim_group_running(&sim), 8);
}

static void test_host_move_during_group(void **state)
{
    (void)state;
    load();
    lsc_sim_group_run(&sim, 1, 1);
    move1(0, 1, 700); /* overrides until the group's next step */
    lsc_sim_advance_ms(&sim, 100);
    assert_int_equal(lsc_sim_position(&sim, 1), 700);
    lsc_sim_advance_ms(&sim, 400); /* step 2 moves it again, from 700 */
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(lsc_sim_position(&sim, 1), 850);
}

static void test_set_groups_stops_running(void **state)
{
    (void)state;
    load();
    lsc_sim_group_run(&sim, 8, 0);
    lsc_sim_set_groups(&sim, NULL);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x00, 0x00, 0x55, 0x55, 0x02, 0x07);
    assert_int_equal(lsc_sim_group_running(&sim), -1);
}

/* ---- Bad input: two beeps, no reply, no change ------------------------------- */

typedef struct bad_case {
    const char *what;
    uint8_t bytes[16];
    size_t n;
} bad_case;

static void test_bad_frames_beep(void **state)
{
    (void)state;
    static const bad_case cases[] = {
        {"move: LEN contradicts count", {0x55, 0x55, 0x09, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xD0, 0x07, 0x00}, 11},
        {"move: repeated id", {0x55, 0x55, 0x0B, 0x03, 0x02, 0x20, 0x03, 0x01, 0xB0, 0x04, 0x01, 0xFC, 0x08}, 13},
        {"host sends command 8", {0x55, 0x55, 0x05, 0x08, 0x01, 0x01, 0x00}, 7},
        {"battery reply to the controller", {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D}, 6},
        {"position reply to the controller", {0x55, 0x55, 0x06, 0x15, 0x01, 0x01, 0xF4, 0x01}, 8},
        {"unknown command", {0x55, 0x55, 0x02, 0x30}, 4},
        {"unknown command with params", {0x55, 0x55, 0x04, 0x16, 0x01, 0x02}, 6},
        {"LEN below 2", {0x55, 0x55, 0x01, 0x0F}, 4},
        {"run with a wrong LEN", {0x55, 0x55, 0x04, 0x06, 0x01, 0x01}, 6},
        {"unload: repeated id", {0x55, 0x55, 0x05, 0x14, 0x02, 0x01, 0x01}, 7},
        {"read: repeated id", {0x55, 0x55, 0x05, 0x15, 0x02, 0x03, 0x03}, 7},
        {"move of no servo", {0x55, 0x55, 0x05, 0x03, 0x00, 0x10, 0x00}, 7},
    };
    load();
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        uint32_t beeps = sim.stats.beeps;
        assert_int_equal(lsc_sim_feed(&sim, cases[i].bytes, cases[i].n), (int)cases[i].n);
        if (sim.stats.beeps != beeps + 1u) {
            fail_msg("%s: %u beeps", cases[i].what, (unsigned)(sim.stats.beeps - beeps));
        }
        sim_util_expect_none(&sim);
        assert_int_equal(lsc_sim_position(&sim, 1), 1500);
        assert_true(lsc_sim_powered(&sim, 1));
        assert_int_equal(lsc_sim_group_running(&sim), -1);
        /* the controller still answers a good frame afterwards */
        SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
        SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    }
    assert_int_equal(sim.stats.ignored, 0);
}

static void test_position_request_too_long_beeps(void **state)
{
    (void)state;
    uint8_t frame[LSC_FRAME_MAX];
    uint8_t ids[LSC_READ_MAX + 1];
    for (unsigned i = 0; i < sizeof ids; i++) {
        ids[i] = (uint8_t)i;
    }
    /* a request the encoder would refuse: build it as a raw frame */
    uint8_t params[LSC_READ_MAX + 2];
    params[0] = (uint8_t)sizeof ids;
    memcpy(params + 1, ids, sizeof ids);
    int n = lsc_encode_frame(frame, sizeof frame, LSC_CMD_POS_READ, params, sizeof ids + 1);
    sim_util_feed(&sim, frame, n);
    assert_int_equal(sim.stats.beeps, 1);
    sim_util_expect_none(&sim);
}

static void test_unfinished_frame_beeps_after_gap(void **state)
{
    (void)state;
    SIM_FEED(&sim, 0x55, 0x55, 0x08, 0x03, 0x01); /* a move cut short */
    lsc_sim_advance_ms(&sim, LSC_SIM_FRAME_GAP_MS);
    SIM_FEED(&sim, 0xE8); /* within the gap: still the same frame */
    assert_int_equal(sim.stats.beeps, 0);
    lsc_sim_advance_ms(&sim, LSC_SIM_FRAME_GAP_MS + 1);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    assert_int_equal(sim.stats.beeps, 1);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    /* a lone header is noise, not a beep */
    SIM_FEED(&sim, 0x55, 0x55);
    lsc_sim_advance_ms(&sim, 500);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    assert_int_equal(sim.stats.beeps, 1);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
}

static void test_gap_after_a_whole_frame_is_no_beep(void **state)
{
    (void)state;
    /* the parser still holds the last frame (complete), not a partial one */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    lsc_sim_advance_ms(&sim, 10 * LSC_SIM_FRAME_GAP_MS);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    assert_int_equal(sim.stats.beeps, 0);
}

static void test_noise_counted_not_beeped(void **state)
{
    (void)state;
    SIM_FEED(&sim, 0x00, 0x13, 0xFF, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    assert_int_equal(sim.stats.noise_bytes, 3);
    assert_int_equal(sim.stats.beeps, 0);
}

/* ---- Log -------------------------------------------------------------------- */

typedef struct log_rec {
    int kinds[32];
    size_t lens[32];
    const char *texts[32];
    uint64_t times[32];
    size_t n;
} log_rec;

static void record(void *ctx, const lsc_sim_event *ev)
{
    log_rec *r = ctx;
    assert_true(r->n < 32);
    r->kinds[r->n] = (int)ev->kind;
    r->lens[r->n] = ev->len;
    r->texts[r->n] = ev->text;
    r->times[r->n] = ev->time_us;
    r->n++;
}

static void test_log_events(void **state)
{
    (void)state;
    log_rec r;
    memset(&r, 0, sizeof r);
    load();
    lsc_sim_set_log(&sim, record, &r);
    lsc_sim_advance_ms(&sim, 3);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);                   /* RX, TX */
    SIM_FEED(&sim, 0x55, 0x55, 0x05, 0x08, 0x01, 0x01, 0x00); /* RX, BEEP */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x07);                   /* RX, IGNORED */
    SIM_FEED(&sim, 0x42);                                     /* NOISE */
    lsc_sim_fault_drop(&sim, 1);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F); /* RX, DROPPED */
    assert_int_equal(r.n, 9);
    const int kinds[] = {LSC_SIM_EV_RX,      LSC_SIM_EV_TX, LSC_SIM_EV_RX,
                         LSC_SIM_EV_BEEP,    LSC_SIM_EV_RX, LSC_SIM_EV_IGNORED,
                         LSC_SIM_EV_NOISE,   LSC_SIM_EV_RX, LSC_SIM_EV_DROPPED};
    const size_t lens[] = {4, 6, 7, 0, 4, 0, 1, 4, 6};
    for (size_t i = 0; i < 9; i++) {
        assert_int_equal(r.kinds[i], kinds[i]);
        assert_int_equal(r.lens[i], lens[i]);
        assert_int_equal(r.times[i], 3000);
    }
    assert_non_null(r.texts[3]);
    assert_non_null(r.texts[5]);
    assert_non_null(r.texts[8]);
    assert_null(r.texts[0]);
    lsc_sim_set_log(&sim, NULL, NULL);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    assert_int_equal(r.n, 9);
}

/* ---- Faults, pacing, queue ------------------------------------------------------- */

static void test_fault_drop(void **state)
{
    (void)state;
    load();
    lsc_sim_fault_drop(&sim, 2);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    lsc_sim_group_run(&sim, 8, 1); /* notifications are never dropped */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    assert_int_equal(sim.stats.dropped, 2);
}

static void test_fault_delay(void **state)
{
    (void)state;
    lsc_sim_fault_delay(&sim, 50);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    assert_int_equal(lsc_sim_next_event_us(&sim), 50000);
    lsc_sim_advance_us(&sim, 49999);
    sim_util_expect_none(&sim);
    lsc_sim_advance_us(&sim, 1);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    lsc_sim_fault_delay(&sim, 0);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
}

static void test_fault_delay_keeps_order(void **state)
{
    (void)state;
    load();
    lsc_sim_fault_delay(&sim, 50);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    lsc_sim_fault_delay(&sim, 0);
    lsc_sim_group_run(&sim, 8, 1); /* due now, but queued behind the reply */
    sim_util_expect_none(&sim);
    lsc_sim_advance_ms(&sim, 50);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01,
               0x00);
}

static void test_fault_corrupt(void **state)
{
    (void)state;
    load();
    lsc_sim_fault_corrupt(&sim, 1, 2, 0xFF); /* the LEN byte */
    lsc_sim_group_run(&sim, 8, 1);           /* notifications are never corrupted */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00, 0x55, 0x55, 0xFB, 0x0F, 0x4C,
               0x1D, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    lsc_sim_fault_corrupt(&sim, 1, 200, 0x01); /* past the end: the last byte */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    SIM_EXPECT(&sim, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1C);
}

static void test_wire_pacing(void **state)
{
    (void)state;
    uint8_t got[8];
    lsc_sim_set_baud(&sim, 9600);
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    sim_util_expect_none(&sim);
    assert_int_equal(lsc_sim_next_event_us(&sim), 1042); /* ceil(10e6 / 9600) */
    lsc_sim_advance_us(&sim, 1041);
    sim_util_expect_none(&sim);
    lsc_sim_advance_us(&sim, 1);
    assert_int_equal(lsc_sim_available(&sim), 1);
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 1);
    assert_int_equal(got[0], 0x55);
    assert_int_equal(lsc_sim_next_event_us(&sim), 2084 - 1042);
    lsc_sim_advance_us(&sim, 5210); /* 5 more byte times: 6252 us, all 6 bytes are out at 6250 */
    assert_int_equal(lsc_sim_available(&sim), 5);
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 5);
    assert_memory_equal(got, "\x55\x04\x0F\x4C\x1D", 5);
    /* back to back: the second frame waits for the line */
    SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F, 0x55, 0x55, 0x02, 0x0F);
    lsc_sim_advance_us(&sim, 6250);
    assert_int_equal(lsc_sim_available(&sim), 6);
    lsc_sim_advance_us(&sim, 6250);
    assert_int_equal(lsc_sim_available(&sim), 12);
}

static void test_wire_pacing_101_bytes(void **state)
{
    (void)state;
    uint8_t ids[32];
    uint8_t frame[LSC_FRAME_MAX];
    uint8_t got[LSC_FRAME_MAX];
    for (unsigned i = 0; i < 32; i++) {
        ids[i] = (uint8_t)i;
    }
    lsc_sim_set_baud(&sim, 9600);
    sim_util_feed(&sim, frame, lsc_encode_pos_request(frame, sizeof frame, ids, 32));
    lsc_sim_advance_us(&sim, 105208); /* 101 bytes take 105208.3 us */
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 100);
    lsc_sim_advance_us(&sim, 1);
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 1);
}

static void test_output_queue_overflow(void **state)
{
    (void)state;
    uint8_t got[LSC_SIM_OUT_BYTES];
    for (unsigned i = 0; i < LSC_SIM_OUT_FRAMES + 5; i++) {
        SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
    }
    assert_int_equal(sim.stats.overflow, 5);
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 6 * LSC_SIM_OUT_FRAMES);
    /* byte-bound: 257-byte replies */
    uint8_t ids[LSC_READ_MAX];
    uint8_t frame[LSC_FRAME_MAX];
    for (unsigned i = 0; i < LSC_READ_MAX; i++) {
        ids[i] = (uint8_t)i;
    }
    int n = lsc_encode_pos_request(frame, sizeof frame, ids, LSC_READ_MAX);
    for (unsigned i = 0; i < 9; i++) {
        sim_util_feed(&sim, frame, n);
    }
    assert_int_equal(sim.stats.overflow, 5 + 2); /* 7 * 257 <= 2048 < 8 * 257 */
    assert_int_equal(lsc_sim_read(&sim, got, 100), 100); /* reads may split frames */
    assert_int_equal(lsc_sim_read(&sim, got, sizeof got), 7 * 257 - 100);
}

static void test_partial_reads_and_ring_wrap(void **state)
{
    (void)state;
    uint8_t got[3];
    for (unsigned round = 0; round < 1000; round++) {
        SIM_FEED(&sim, 0x55, 0x55, 0x02, 0x0F);
        assert_int_equal(lsc_sim_read(&sim, got, 3), 3);
        assert_memory_equal(got, "\x55\x55\x04", 3);
        assert_int_equal(lsc_sim_read(&sim, got, 3), 3);
        assert_memory_equal(got, "\x0F\x4C\x1D", 3);
    }
}

static void test_null_arguments(void **state)
{
    (void)state;
    uint8_t b[1] = {0};
    assert_int_equal(lsc_sim_init(NULL), LSC_EINVAL);
    assert_int_equal(lsc_sim_feed(NULL, b, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_feed(&sim, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_feed(&sim, NULL, 0), 0);
    assert_int_equal(lsc_sim_read(NULL, b, 1), 0);
    assert_int_equal(lsc_sim_read(&sim, NULL, 1), 0);
    assert_int_equal(lsc_sim_available(NULL), 0);
    assert_int_equal(lsc_sim_now_us(NULL), 0);
    assert_int_equal(lsc_sim_next_event_us(NULL), LSC_SIM_TIME_NEVER);
    assert_int_equal(lsc_sim_position(NULL, 1), 0);
    assert_false(lsc_sim_powered(NULL, 1));
    assert_false(lsc_sim_moving(NULL, 1));
    assert_int_equal(lsc_sim_group_run(NULL, 1, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_group_stop(NULL), LSC_EINVAL);
    assert_int_equal(lsc_sim_group_running(NULL), -1);
    assert_int_equal(lsc_sim_group_speed(NULL, 1), 0);
    lsc_sim_advance_us(NULL, 1);
    lsc_sim_set_groups(NULL, NULL);
    lsc_sim_set_battery(NULL, 1);
    lsc_sim_set_baud(NULL, 1);
    lsc_sim_set_log(NULL, NULL, NULL);
    lsc_sim_fault_drop(NULL, 1);
    lsc_sim_fault_delay(NULL, 1);
    lsc_sim_fault_corrupt(NULL, 1, 1, 1);
    /* clock saturates instead of wrapping */
    lsc_sim_advance_us(&sim, UINT64_MAX);
    lsc_sim_advance_us(&sim, UINT64_MAX);
    assert_int_equal(lsc_sim_now_us(&sim), UINT64_MAX - 1u);
}

/* A servo held by something in its way: a move beyond stops at the block
 * (read back there, while the move's time runs on), a move away is free;
 * either side; the block removed; refused arguments change nothing. */
static void test_block(void **state)
{
    (void)state;
    assert_int_equal(lsc_sim_block(NULL, 1, 600, LSC_SIM_BLOCK_ABOVE), LSC_EINVAL);
    assert_int_equal(lsc_sim_block(&sim, 1, 600, (lsc_sim_block_side)3), LSC_EINVAL);
    move1(0, 1, 500);
    assert_int_equal(lsc_sim_block(&sim, 1, 600, LSC_SIM_BLOCK_ABOVE), 0);
    move1(500, 1, 700);
    lsc_sim_advance_ms(&sim, 250);
    assert_int_equal(sim_util_read_pos(&sim, 1), 600); /* reached the object */
    lsc_sim_advance_ms(&sim, 100);
    assert_int_equal(lsc_sim_position(&sim, 1), 600);
    assert_true(lsc_sim_moving(&sim, 1)); /* still pushing */
    lsc_sim_advance_ms(&sim, 200);
    assert_int_equal(sim_util_read_pos(&sim, 1), 600);
    assert_false(lsc_sim_moving(&sim, 1));
    move1(100, 1, 300); /* opening: free */
    lsc_sim_advance_ms(&sim, 50);
    assert_int_equal(lsc_sim_position(&sim, 1), 450);
    lsc_sim_advance_ms(&sim, 50);
    assert_int_equal(lsc_sim_position(&sim, 1), 300);
    /* from the other side */
    assert_int_equal(lsc_sim_block(&sim, 2, 1200, LSC_SIM_BLOCK_BELOW), 0);
    move1(0, 2, 1000);
    assert_int_equal(sim_util_read_pos(&sim, 2), 1200);
    move1(0, 2, 1300);
    assert_int_equal(lsc_sim_position(&sim, 2), 1300);
    /* removed */
    assert_int_equal(lsc_sim_block(&sim, 1, 600, LSC_SIM_BLOCK_NONE), 0);
    move1(0, 1, 700);
    assert_int_equal(sim_util_read_pos(&sim, 1), 700);
    /* a servo already past the block is read at it */
    assert_int_equal(lsc_sim_block(&sim, 3, 600, LSC_SIM_BLOCK_ABOVE), 0);
    assert_int_equal(lsc_sim_position(&sim, 3), 600);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_defaults, setup),
        cmocka_unit_test_setup(test_block, setup),
        cmocka_unit_test_setup(test_battery_settable, setup),
        cmocka_unit_test_setup(test_offsets, setup),
        cmocka_unit_test_setup(test_servo_range, setup),
        cmocka_unit_test_setup(test_move_mid_and_after, setup),
        cmocka_unit_test_setup(test_move_rounds_towards_start, setup),
        cmocka_unit_test_setup(test_move_from_interpolated_position, setup),
        cmocka_unit_test_setup(test_move_time_zero_is_instant, setup),
        cmocka_unit_test_setup(test_move_many_and_read_in_order, setup),
        cmocka_unit_test_setup(test_read_of_84_servos, setup),
        cmocka_unit_test_setup(test_unload_then_move, setup),
        cmocka_unit_test_setup(test_unload_mid_move_stops_there, setup),
        cmocka_unit_test_setup(test_group_runs_at_100_percent, setup),
        cmocka_unit_test_setup(test_group_complete_in_one_big_advance, setup),
        cmocka_unit_test_setup(test_group_at_200_percent, setup),
        cmocka_unit_test_setup(test_speed_all_groups, setup),
        cmocka_unit_test_setup(test_speed_zero_ignored, setup),
        cmocka_unit_test_setup(test_speed_change_applies_from_next_step, setup),
        cmocka_unit_test_setup(test_step_never_shorter_than_1ms, setup),
        cmocka_unit_test_setup(test_group_stop, setup),
        cmocka_unit_test_setup(test_group_forever_then_stop, setup),
        cmocka_unit_test_setup(test_group_run_while_running, setup),
        cmocka_unit_test_setup(test_group_missing_and_stop_idle_ignored, setup),
        cmocka_unit_test_setup(test_host_move_during_group, setup),
        cmocka_unit_test_setup(test_set_groups_stops_running, setup),
        cmocka_unit_test_setup(test_bad_frames_beep, setup),
        cmocka_unit_test_setup(test_position_request_too_long_beeps, setup),
        cmocka_unit_test_setup(test_unfinished_frame_beeps_after_gap, setup),
        cmocka_unit_test_setup(test_gap_after_a_whole_frame_is_no_beep, setup),
        cmocka_unit_test_setup(test_clock_saturates_while_a_group_runs, setup),
        cmocka_unit_test_setup(test_noise_counted_not_beeped, setup),
        cmocka_unit_test_setup(test_log_events, setup),
        cmocka_unit_test_setup(test_fault_drop, setup),
        cmocka_unit_test_setup(test_fault_delay, setup),
        cmocka_unit_test_setup(test_fault_delay_keeps_order, setup),
        cmocka_unit_test_setup(test_fault_corrupt, setup),
        cmocka_unit_test_setup(test_wire_pacing, setup),
        cmocka_unit_test_setup(test_wire_pacing_101_bytes, setup),
        cmocka_unit_test_setup(test_output_queue_overflow, setup),
        cmocka_unit_test_setup(test_partial_reads_and_ring_wrap, setup),
        cmocka_unit_test_setup(test_null_arguments, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
