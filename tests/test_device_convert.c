/* lsc_action_to_arm (src/device/convert.c): an action's positions from one
 * arm profile to another through joint angles; joints matched by name; every
 * refusal names the keyframe and the joint. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/device.h"
#include "lsc/convert.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/player.h"

/* realloc, wrapped by the linker (--wrap=realloc): out of memory on demand */
void *__real_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_realloc(void *p, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
static int realloc_fails_in; /* 0: never; N: the Nth call from now fails */

void *__wrap_realloc(void *p, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (realloc_fails_in > 0 && --realloc_fails_in == 0) {
        return NULL;
    }
    return __real_realloc(p, size);
}

/* A PWM arm (500..2500 over 180 degrees) and a bus-servo arm (0..1000 over
 * 240 degrees) with their joints on other servos, in another order. */
static const char pwm_text[] = "gripper 1 pwm limits=1500..2500\n"
                               "wrist   3 pwm limits=-85deg..85deg\n"
                               "base    6 pwm limits=-85deg..85deg\n"
                               "spare   9 pwm\n";
static const char bus_text[] = "base    16 bus limits=-115deg..115deg\n"
                               "gripper 11 bus limits=0..700\n"
                               "wrist   13 bus dir=-1 offset=10deg\n";

static lsc_arm *arm(const char *text)
{
    lsc_arm *a = NULL;
    char why[LSC_ARM_MESSAGE_MAX];
    if (lsc_arm_parse(text, strlen(text), "test", &a, why, sizeof why) != 0) {
        fail_msg("profile: %s", why);
    }
    return a;
}

static void action(lsc_action *a, const uint8_t *ids, size_t n, const uint16_t *rows,
                   size_t count)
{
    assert_int_equal(lsc_action_init(a, ids, n), 0);
    for (size_t k = 0; k < count; k++) {
        assert_int_equal(lsc_action_append(a, rows[k * (1 + n)], &rows[k * (1 + n) + 1]), 0);
    }
}

static void assert_why(const char *why, const char *want)
{
    if (strcmp(why, want) != 0) {
        fail_msg("why '%s', want '%s'", why, want);
    }
}

static void test_pwm_to_bus(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text), *bus = arm(bus_text);
    static const uint8_t ids[] = {6, 1, 3};
    /* base 0deg, 45deg; gripper 0deg, 45deg; wrist 0deg, -45deg */
    static const uint16_t rows[] = {700, 1500, 1500, 1500, 250, 2000, 2000, 1000};
    lsc_action in, out;
    char why[LSC_ARM_MESSAGE_MAX];
    action(&in, ids, 3, rows, 2);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), 0);
    assert_string_equal(why, "");
    assert_int_equal(out.nservos, 3);
    static const uint8_t want_ids[] = {16, 11, 13};
    assert_memory_equal(out.ids, want_ids, sizeof want_ids);
    assert_int_equal(out.count, 2);
    /* bus: 1000 over 240deg; base zero 500; gripper zero 500; wrist zero at
     * 10deg (500 + 41.67 -> 542) and turning the other way */
    static const uint16_t want[] = {700, 500, 500, 542, 250, 688, 688, 730};
    assert_memory_equal(out.words, want, sizeof want);
    /* and back: the same angles, to the nearest position */
    lsc_action back;
    assert_int_equal(lsc_action_to_arm(&out, bus, pwm, &back, why, sizeof why), 0);
    assert_memory_equal(back.ids, ids, sizeof ids);
    static const uint16_t want_back[] = {700, 1500, 1500, 1500, 250, 2001, 2001, 999};
    assert_memory_equal(back.words, want_back, sizeof want_back);
    lsc_action_free(&back);
    lsc_action_free(&out);
    lsc_action_free(&in);
    lsc_arm_free(pwm);
    lsc_arm_free(bus);
}

static void test_refusals(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text), *bus = arm(bus_text);
    lsc_action in, out;
    char why[LSC_ARM_MESSAGE_MAX];
    /* outside the target's limits: keyframe and joint named */
    static const uint8_t ids[] = {1, 6};
    static const uint16_t far[] = {100, 1500, 1500, 100, 2400, 1500, 100, 1600, 2400};
    action(&in, ids, 2, far, 3);
    /* gripper 2400 on the PWM arm: 81deg, past the xArm gripper's 0..700
     * (-120deg..48deg); it comes in keyframe 2 */
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "keyframe 2: joint gripper: 81.00deg (position 2400) is outside the "
                    "target's limits of joint gripper (servo 11): -120.00deg..48.00deg");
    assert_int_equal(out.count, 0);
    assert_null(out.words);
    lsc_action_free(&in);
    /* the base at 130deg on the bus arm is past the PWM base's -85..85 */
    static const uint8_t bids[] = {16};
    static const uint16_t brows[] = {100, 500, 100, 1000};
    action(&in, bids, 1, brows, 2);
    assert_int_equal(lsc_action_to_arm(&in, bus, pwm, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "keyframe 2: joint base: 120.00deg (position 1000) is outside the "
                    "target's limits of joint base (servo 6): -85.00deg..85.00deg");
    lsc_action_free(&in);
    /* a position outside the source servo's range */
    static const uint16_t wide[] = {100, 1200};
    action(&in, bids, 1, wide, 1);
    assert_int_equal(lsc_action_to_arm(&in, bus, pwm, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "keyframe 1: joint base (servo 16): position 1200 is outside its servo's "
                    "range 0..1000 in the source profile");
    lsc_action_free(&in);
    /* a servo on no joint of the source; a joint the target lacks */
    static const uint8_t nids[] = {1, 7};
    static const uint16_t nrows[] = {100, 1500, 1500};
    action(&in, nids, 2, nrows, 1);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "servo 7 is on no joint of the source profile: its angle is not known");
    lsc_action_free(&in);
    static const uint8_t sids[] = {9};
    action(&in, sids, 1, nrows, 1);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "joint spare (servo 9) has no joint of that name in the target profile");
    /* bad arguments */
    assert_int_equal(lsc_action_to_arm(NULL, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_action_to_arm(&in, NULL, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_action_to_arm(&in, pwm, NULL, &out, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, NULL, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &in, NULL, 0), LSC_EINVAL);
    lsc_action_free(&in);
    lsc_action empty;
    memset(&empty, 0, sizeof empty);
    assert_int_equal(lsc_action_to_arm(&empty, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "the action has no servos (lsc_action_init gives them)");
    /* a short why is cut, never overrun */
    char small[8];
    action(&in, nids, 2, nrows, 1);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, small, sizeof small), LSC_EINVAL);
    assert_string_equal(small, "servo 7");
    lsc_action_free(&in);
    lsc_arm_free(pwm);
    lsc_arm_free(bus);
}

/* A file with no keyframes converts to one with none. */
static void test_empty(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text), *bus = arm(bus_text);
    static const uint8_t ids[] = {3};
    lsc_action in, out;
    assert_int_equal(lsc_action_init(&in, ids, 1), 0);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, NULL, 0), 0);
    assert_int_equal(out.count, 0);
    assert_int_equal(out.ids[0], 13);
    lsc_action_free(&out);
    lsc_arm_free(pwm);
    lsc_arm_free(bus);
}

/* An angle within the target's limits whose nearest position is past them
 * (rounding) is refused too: the move would be. */
static void test_rounded_past_limits(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text);
    lsc_arm *narrow = arm("wrist 13 bus limits=-10deg..10deg\n");
    static const uint8_t ids[] = {3};
    /* 1611: 9.99deg on the PWM wrist; on the bus servo 542 (10.08deg) is the nearest */
    static const uint16_t rows[] = {100, 1611};
    lsc_action in, out;
    char why[LSC_ARM_MESSAGE_MAX];
    action(&in, ids, 1, rows, 1);
    assert_int_equal(lsc_action_to_arm(&in, pwm, narrow, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "keyframe 1: joint wrist: 9.99deg (position 1611) is outside the target's "
                    "limits of joint wrist (servo 13): -10.00deg..10.00deg");
    /* 1610 (9.90deg) is 541 (9.84deg): inside */
    in.words[1] = 1610;
    assert_int_equal(lsc_action_to_arm(&in, pwm, narrow, &out, why, sizeof why), 0);
    assert_int_equal(out.words[1], 541);
    lsc_action_free(&out);
    lsc_action_free(&in);
    lsc_arm_free(pwm);
    lsc_arm_free(narrow);
}

/* Actions not made by lsc_action_init: each refused with its reason; a why
 * without room is left alone. */
static void test_malformed_actions(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text), *bus = arm(bus_text);
    lsc_action in, out;
    char why[LSC_ARM_MESSAGE_MAX] = "untouched";
    memset(&in, 0, sizeof in);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, 0), LSC_EINVAL);
    assert_string_equal(why, "untouched");
    /* more servos than an action holds */
    in.nservos = LSC_PLAYER_SERVOS_MAX + 1u;
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "the action has no servos (lsc_action_init gives them)");
    /* keyframes counted but none held */
    in.nservos = 1;
    in.ids[0] = 3;
    in.count = 2;
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "the action has no servos (lsc_action_init gives them)");
    /* one servo twice */
    in.nservos = 2;
    in.ids[1] = 3;
    in.count = 0;
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_EINVAL);
    assert_why(why, "the action gives a servo twice (lsc_action_init refuses that)");
    assert_null(out.words);
    lsc_arm_free(pwm);
    lsc_arm_free(bus);
}

/* Out of memory for the converted keyframes: nothing is kept. */
static void test_out_of_memory(void **state)
{
    (void)state;
    lsc_arm *pwm = arm(pwm_text), *bus = arm(bus_text);
    static const uint8_t ids[] = {6};
    static const uint16_t rows[] = {100, 1500};
    lsc_action in, out;
    char why[LSC_ARM_MESSAGE_MAX];
    action(&in, ids, 1, rows, 1);
    realloc_fails_in = 1;
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), LSC_ENOSPC);
    assert_why(why, "out of memory");
    assert_int_equal(out.count, 0);
    assert_null(out.words);
    assert_int_equal(lsc_action_to_arm(&in, pwm, bus, &out, why, sizeof why), 0);
    assert_int_equal(out.count, 1);
    lsc_action_free(&out);
    lsc_action_free(&in);
    lsc_arm_free(pwm);
    lsc_arm_free(bus);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pwm_to_bus),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_rounded_past_limits),
        cmocka_unit_test(test_malformed_actions),
        cmocka_unit_test(test_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
