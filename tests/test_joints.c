/* Tests of joint angles as numbers (include/lsc/device.h's lsc_arm_target_deg
 * and lsc_arm_angle, src/arm/arm_deg.c): an angle is taken as given, not
 * rounded to hundredths of a degree, and checked against the joint's limits
 * as lsc_arm_target checks one written as text. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/arm.h"

/* base: a PWM joint (500..2500 over 180 degrees: 0.09 degree a position)
 * with limits; elbow: reversed and offset; gripper: limits in positions;
 * wrist: an upper limit between two positions (29.96 degrees: 332.9
 * positions from the middle). */
static const char profile[] = "base     6  pwm  limits=-30deg..30deg\n"
                              "elbow    4  pwm  dir=-1  offset=10deg\n"
                              "gripper  1  bus  limits=0..700\n"
                              "wrist    3  pwm  limits=-30deg..29.96deg\n";

static lsc_arm *load(void)
{
    lsc_arm *arm = NULL;
    char why[LSC_ARM_MESSAGE_MAX];
    assert_int_equal(lsc_arm_parse(profile, strlen(profile), "t.conf", &arm, why, sizeof why),
                     0);
    return arm;
}

/* The position lsc_arm_target gives for text, to compare with. */
static uint16_t by_text(const lsc_arm *arm, const char *arg)
{
    lsc_servo s;
    char why[LSC_ARM_MESSAGE_MAX];
    assert_int_equal(lsc_arm_target(arm, arg, &s, why, sizeof why), 0);
    return s.position;
}

static void test_target_as_text_gives_it(void **state)
{
    (void)state;
    lsc_arm *arm = load();
    lsc_servo s = {0, 0};
    char why[LSC_ARM_MESSAGE_MAX];
    const double angles[] = {0, 12.5, -12.5, 29.99, -30};
    for (size_t i = 0; i < sizeof angles / sizeof angles[0]; i++) {
        char arg[32];
        (void)snprintf(arg, sizeof arg, "base:%.2fdeg", angles[i]);
        assert_int_equal(lsc_arm_target_deg(arm, "base", angles[i], &s, why, sizeof why), 0);
        assert_int_equal(s.id, 6);
        assert_int_equal(s.position, by_text(arm, arg));
        (void)snprintf(arg, sizeof arg, "elbow:%.2fdeg", angles[i]);
        assert_int_equal(lsc_arm_target_deg(arm, "4", angles[i], &s, why, sizeof why), 0);
        assert_int_equal(s.id, 4);
        assert_int_equal(s.position, by_text(arm, arg));
    }
    lsc_arm_free(arm);
}

/* 30.004 degrees is not 30.00: beyond base's upper limit, where text (two
 * decimals at most) could only say 30.00; and 0.0451 degrees is past the
 * half position (0.045) that 0.05 and 0.04 fall either side of. */
static void test_no_rounding_to_hundredths(void **state)
{
    (void)state;
    lsc_arm *arm = load();
    lsc_servo s = {9, 9};
    char why[LSC_ARM_MESSAGE_MAX] = "";
    assert_int_equal(lsc_arm_target_deg(arm, "base", 30.0, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 1833);
    assert_int_equal(lsc_arm_target_deg(arm, "base", 30.004, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "base: 30.004deg is outside the limits of joint base (servo 6): "
                             "-30.00deg..30.00deg");
    assert_int_equal(s.position, 1833); /* untouched */
    assert_int_equal(lsc_arm_target_deg(arm, "base", 0.0449, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 1500);
    assert_int_equal(lsc_arm_target_deg(arm, "base", 0.0451, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 1501);
    assert_int_equal(lsc_arm_target_deg(arm, "base", -0.0451, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 1499);
    lsc_arm_free(arm);
}

static void test_refused(void **state)
{
    (void)state;
    lsc_arm *arm = load();
    lsc_servo s;
    char why[LSC_ARM_MESSAGE_MAX] = "";
    assert_int_equal(lsc_arm_target_deg(arm, "base", -30.01, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "base: -30.01deg is outside the limits of joint base (servo 6): "
                             "-30.00deg..30.00deg");
    assert_int_equal(lsc_arm_target_deg(arm, "base", (double)NAN, &s, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_arm_target_deg(arm, "base", (double)INFINITY, &s, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_arm_target_deg(arm, "hand", 1, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'hand' is not a joint of the arm profile");
    assert_int_equal(lsc_arm_target_deg(arm, NULL, 1, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'(none)' is not a joint of the arm profile");
    assert_int_equal(lsc_arm_target_deg(NULL, "base", 1, &s, why, 0), LSC_EINVAL);
    assert_int_equal(lsc_arm_target_deg(arm, "base", 1, NULL, why, sizeof why), LSC_EINVAL);
    /* the gripper's limit 700 is 48.00deg exactly */
    assert_int_equal(lsc_arm_target_deg(arm, "gripper", 48.0, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 700);
    assert_int_equal(lsc_arm_target_deg(arm, "gripper", 48.0 + 0.001, &s, why, sizeof why),
                     LSC_EINVAL);
    /* an angle within the (rounded) limits whose position is beyond them */
    assert_int_equal(lsc_arm_target_deg(arm, "wrist", 29.9, &s, why, sizeof why), 0);
    assert_int_equal(s.position, 1832);
    assert_int_equal(lsc_arm_target_deg(arm, "wrist", 29.96, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "wrist: 29.96deg (position 1833) is outside the limits of joint "
                             "wrist (servo 3): -30.00deg..29.96deg");
    assert_int_equal(lsc_arm_target(arm, "wrist:29.96deg", &s, why, sizeof why), LSC_EINVAL);
    lsc_arm_free(arm);
}

static void test_angle(void **state)
{
    (void)state;
    lsc_arm *arm = load();
    double deg = 99;
    lsc_servo s = {6, 1501};
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), 0);
    assert_true(fabs(deg - 0.09) < 1e-9); /* lsc_arm_degrees: "0.09" */
    s.position = 1833;
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), 0);
    assert_true(fabs(deg - 29.97) < 1e-9);
    s = (lsc_servo){4, 1500};
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), 1);
    char text[LSC_ARM_DEGREES_MAX]; /* reversed and offset: as lsc_arm_degrees, unrounded */
    assert_int_equal(lsc_arm_degrees(arm, &s, text, sizeof text), 1);
    assert_true(fabs(deg - strtod(text, NULL)) <= 0.005);
    assert_true(fabs(deg) > 1);
    deg = 99;
    s = (lsc_servo){6, 499}; /* outside the servo's range */
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), -1);
    s.position = 2501;
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), -1);
    s = (lsc_servo){7, 1500}; /* no joint */
    assert_int_equal(lsc_arm_angle(arm, &s, &deg), -1);
    assert_int_equal(lsc_arm_angle(arm, NULL, &deg), -1);
    assert_int_equal(lsc_arm_angle(arm, &s, NULL), -1);
    assert_true(deg > 98.5 && deg < 99.5); /* untouched */
    lsc_arm_free(arm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_target_as_text_gives_it),
        cmocka_unit_test(test_no_rounding_to_hundredths),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_angle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
