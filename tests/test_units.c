/* Tests of joint angles <-> positions and limits (include/lsc/units.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "lsc/lsc.h"

static int32_t cdeg_of(const lsc_joint *j, uint16_t pos)
{
    int32_t c = 99999;
    assert_int_equal(lsc_joint_to_cdeg(j, pos, &c), 0);
    return c;
}

static uint16_t pos_of(const lsc_joint *j, int32_t cdeg)
{
    uint16_t p = 65535;
    assert_int_equal(lsc_joint_to_pos(j, cdeg, &p), 0);
    return p;
}

static void test_kinds_at_their_edges(void **state)
{
    (void)state;
    lsc_joint j;
    assert_int_equal(lsc_joint_init(&j, 3, LSC_JOINT_PWM), 0);
    assert_int_equal(j.id, 3);
    assert_int_equal(j.zero, 1500);
    assert_int_equal(j.min_cdeg, -9000);
    assert_int_equal(j.max_cdeg, 9000);
    assert_int_equal(cdeg_of(&j, 500), -9000);
    assert_int_equal(cdeg_of(&j, 2500), 9000);
    assert_int_equal(cdeg_of(&j, 1501), 9); /* 0.09 degree a unit */
    assert_int_equal(pos_of(&j, -9000), 500);
    assert_int_equal(pos_of(&j, 9000), 2500);
    assert_int_equal(pos_of(&j, 3000), 1833); /* 333.33 -> 333 */
    assert_int_equal(pos_of(&j, 3001), 1833); /* 333.44 */
    assert_int_equal(pos_of(&j, 3004), 1834); /* 333.78 */

    assert_int_equal(lsc_joint_init(&j, 6, LSC_JOINT_BUS), 0);
    assert_int_equal(j.zero, 500);
    assert_int_equal(j.min_cdeg, -12000);
    assert_int_equal(j.max_cdeg, 12000);
    assert_int_equal(cdeg_of(&j, 0), -12000);
    assert_int_equal(cdeg_of(&j, 1000), 12000);
    assert_int_equal(cdeg_of(&j, 501), 24); /* 0.24 degree a unit */
    assert_int_equal(pos_of(&j, 3000), 625);
    assert_int_equal(pos_of(&j, -2000), 417); /* -83.33 -> -83 */
    /* one past either end is outside the servo's range */
    uint16_t p = 77;
    assert_int_equal(lsc_joint_to_pos(&j, 12013, &p), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_pos(&j, -12013, &p), LSC_EINVAL);
    assert_int_equal(p, 77);
    assert_int_equal(pos_of(&j, 12011), 1000); /* 500.46 rounds back in */
    assert_int_equal(lsc_joint_init(&j, 1, (lsc_joint_kind)2), LSC_EINVAL);
    assert_int_equal(lsc_joint_init(NULL, 1, LSC_JOINT_BUS), LSC_EINVAL);
}

static void test_rounding_halves_away_from_zero(void **state)
{
    (void)state;
    lsc_joint j;
    /* 0..100 over 200 cdeg: exactly 2 cdeg a unit, so odd angles are halves */
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, 100, 200), 0);
    assert_int_equal(j.zero, 50);
    assert_int_equal(pos_of(&j, 1), 51);  /* +0.5 -> +1 */
    assert_int_equal(pos_of(&j, -1), 49); /* -0.5 -> -1 */
    assert_int_equal(pos_of(&j, 3), 52);
    assert_int_equal(pos_of(&j, -3), 48);
    /* 0..3 over 1 cdeg: a third of a cdeg a unit */
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, 3, 1), 0);
    assert_int_equal(j.zero, 1); /* the middle, rounded down */
    assert_int_equal(cdeg_of(&j, 0), 0);  /* -0.33 */
    assert_int_equal(cdeg_of(&j, 3), 1);  /* +0.67 */
    /* 0..2 over 3 cdeg: 1.5 cdeg a unit, zero 1: positions at -1.5 and +1.5 */
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, 2, 3), 0);
    assert_int_equal(cdeg_of(&j, 0), -2);
    assert_int_equal(cdeg_of(&j, 2), 2);
}

static void test_direction_and_offset(void **state)
{
    (void)state;
    lsc_joint j;
    assert_int_equal(lsc_joint_init(&j, 2, LSC_JOINT_BUS), 0);
    j.direction = -1;
    j.zero = 520; /* the joint reads 0 at 520 */
    assert_int_equal(cdeg_of(&j, 520), 0);
    assert_int_equal(cdeg_of(&j, 521), -24);
    assert_int_equal(cdeg_of(&j, 0), 12480);
    assert_int_equal(cdeg_of(&j, 1000), -11520);
    assert_int_equal(pos_of(&j, 3000), 395);
    assert_int_equal(pos_of(&j, -3000), 645);
    assert_int_equal(pos_of(&j, 12480), 0);
    assert_int_equal(pos_of(&j, -11520), 1000);
    uint16_t p;
    assert_int_equal(lsc_joint_to_pos(&j, 12500, &p), LSC_EINVAL); /* would be -1 */
    assert_int_equal(lsc_joint_to_pos(&j, -11540, &p), LSC_EINVAL); /* 1001 */
}

static void test_limits(void **state)
{
    (void)state;
    lsc_joint j;
    assert_int_equal(lsc_joint_init(&j, 2, LSC_JOINT_BUS), 0);
    j.direction = -1;
    j.min_cdeg = -9000;
    j.max_cdeg = 4500;
    assert_true(lsc_joint_allows(&j, -9000));
    assert_true(lsc_joint_allows(&j, 4500));
    assert_true(lsc_joint_allows(&j, 0));
    assert_false(lsc_joint_allows(&j, -9001));
    assert_false(lsc_joint_allows(&j, 4501));
    /* positions: 4500 is 312.5 units below the zero (dir -1), -90 deg 375 above */
    assert_true(lsc_joint_allows_pos(&j, 875));
    assert_false(lsc_joint_allows_pos(&j, 876));
    assert_true(lsc_joint_allows_pos(&j, 313)); /* 4488 cdeg */
    assert_false(lsc_joint_allows_pos(&j, 312)); /* 4512: 4500.x would round to in */
    /* limits wider than the servo: the servo's range still bounds */
    j.min_cdeg = -LSC_UNITS_CDEG_MAX;
    j.max_cdeg = LSC_UNITS_CDEG_MAX;
    assert_true(lsc_joint_valid(&j));
    assert_false(lsc_joint_allows(&j, 13000));
    assert_true(lsc_joint_allows_pos(&j, 1000));
    assert_false(lsc_joint_allows_pos(&j, 1001));
    assert_false(lsc_joint_allows(NULL, 0));
    assert_false(lsc_joint_allows_pos(NULL, 500));
}

static void test_invalid_joints_and_arguments(void **state)
{
    (void)state;
    lsc_joint good, j;
    int32_t c = 5;
    uint16_t p = 5;
    assert_int_equal(lsc_joint_init(&good, 1, LSC_JOINT_PWM), 0);
    assert_true(lsc_joint_valid(&good));
    assert_false(lsc_joint_valid(NULL));
    j = good; j.direction = 0; assert_false(lsc_joint_valid(&j));
    j = good; j.direction = 2; assert_false(lsc_joint_valid(&j));
    j = good; j.pos_max = j.pos_min; assert_false(lsc_joint_valid(&j));
    j = good; j.pos_max = LSC_UNITS_POS_MAX + 1; assert_false(lsc_joint_valid(&j));
    j = good; j.span_cdeg = 0; assert_false(lsc_joint_valid(&j));
    j = good; j.span_cdeg = LSC_UNITS_CDEG_MAX + 1; assert_false(lsc_joint_valid(&j));
    j = good; j.zero = 499; assert_false(lsc_joint_valid(&j));
    j = good; j.zero = 2501; assert_false(lsc_joint_valid(&j));
    j = good; j.min_cdeg = -LSC_UNITS_CDEG_MAX - 1; assert_false(lsc_joint_valid(&j));
    j = good; j.max_cdeg = LSC_UNITS_CDEG_MAX + 1; assert_false(lsc_joint_valid(&j));
    j = good; j.min_cdeg = 1; j.max_cdeg = 0; assert_false(lsc_joint_valid(&j));
    j = good; j.direction = 0;
    assert_int_equal(lsc_joint_to_cdeg(&j, 1500, &c), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_pos(&j, 0, &p), LSC_EINVAL);
    assert_false(lsc_joint_allows(&j, 0));
    assert_false(lsc_joint_allows_pos(&j, 1500));
    assert_int_equal(lsc_joint_to_cdeg(&good, 499, &c), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_cdeg(&good, 2501, &c), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_cdeg(&good, 1500, NULL), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_pos(&good, 0, NULL), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_pos(&good, LSC_UNITS_CDEG_MAX + 1, &p), LSC_EINVAL);
    assert_int_equal(lsc_joint_to_pos(&good, -LSC_UNITS_CDEG_MAX - 1, &p), LSC_EINVAL);
    assert_int_equal(c, 5);
    assert_int_equal(p, 5);
    /* init_range refuses what would not be valid, and leaves *j alone */
    j = good;
    assert_int_equal(lsc_joint_init_range(&j, 1, 10, 10, 100), LSC_EINVAL);
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, LSC_UNITS_POS_MAX + 1, 100), LSC_EINVAL);
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, 100, 0), LSC_EINVAL);
    assert_int_equal(lsc_joint_init_range(NULL, 1, 0, 100, 100), LSC_EINVAL);
    /* (member by member: the struct's padding is not part of its value) */
    assert_int_equal(j.id, good.id);
    assert_int_equal(j.direction, good.direction);
    assert_int_equal(j.pos_min, good.pos_min);
    assert_int_equal(j.pos_max, good.pos_max);
    assert_int_equal(j.span_cdeg, good.span_cdeg);
    assert_int_equal(j.zero, good.zero);
    assert_int_equal(j.min_cdeg, good.min_cdeg);
    assert_int_equal(j.max_cdeg, good.max_cdeg);
}

static void test_extremes_do_not_overflow(void **state)
{
    (void)state;
    lsc_joint j;
    /* the largest range over the largest span, angles at the bounds */
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, LSC_UNITS_POS_MAX, LSC_UNITS_CDEG_MAX), 0);
    assert_int_equal(cdeg_of(&j, 0), -18000);
    assert_int_equal(cdeg_of(&j, LSC_UNITS_POS_MAX), 18000);
    j.zero = 0;
    j.max_cdeg = LSC_UNITS_CDEG_MAX;
    assert_int_equal(cdeg_of(&j, LSC_UNITS_POS_MAX), LSC_UNITS_CDEG_MAX);
    assert_int_equal(pos_of(&j, LSC_UNITS_CDEG_MAX), LSC_UNITS_POS_MAX);
    assert_true(lsc_joint_allows_pos(&j, LSC_UNITS_POS_MAX));
    j.direction = -1;
    j.zero = LSC_UNITS_POS_MAX;
    j.min_cdeg = -LSC_UNITS_CDEG_MAX;
    assert_int_equal(cdeg_of(&j, 0), LSC_UNITS_CDEG_MAX);
    assert_int_equal(pos_of(&j, LSC_UNITS_CDEG_MAX), 0);
    assert_int_equal(pos_of(&j, 0), LSC_UNITS_POS_MAX);
}

/* Every position of a joint -> angle -> position comes back within one unit
 * (exactly, for these kinds: each has at most one position per centidegree). */
static void round_trip_all(const lsc_joint *j)
{
    for (uint32_t p = j->pos_min; p <= j->pos_max; p++) {
        uint16_t back = 0;
        int32_t c = cdeg_of(j, (uint16_t)p);
        assert_int_equal(lsc_joint_to_pos(j, c, &back), 0);
        int32_t d = (int32_t)back - (int32_t)p;
        assert_true(d >= -1 && d <= 1);
        assert_int_equal(back, p);
    }
}

static void test_round_trip_every_position(void **state)
{
    (void)state;
    lsc_joint j;
    assert_int_equal(lsc_joint_init(&j, 1, LSC_JOINT_PWM), 0);
    round_trip_all(&j);
    j.direction = -1;
    j.zero = 1234;
    round_trip_all(&j);
    assert_int_equal(lsc_joint_init(&j, 1, LSC_JOINT_BUS), 0);
    round_trip_all(&j);
    j.direction = -1;
    j.zero = 980;
    round_trip_all(&j);
    /* explicit ranges: a 12-bit servo over 360 degrees, and one unit per cdeg */
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, 4095, 36000), 0);
    round_trip_all(&j);
    assert_int_equal(lsc_joint_init_range(&j, 1, 0, LSC_UNITS_POS_MAX, 10000), 0);
    round_trip_all(&j);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kinds_at_their_edges),
        cmocka_unit_test(test_rounding_halves_away_from_zero),
        cmocka_unit_test(test_direction_and_offset),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_invalid_joints_and_arguments),
        cmocka_unit_test(test_extremes_do_not_overflow),
        cmocka_unit_test(test_round_trip_every_position),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
