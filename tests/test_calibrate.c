/* Tests of calibration (include/lsc/calibrate.h, src/arm/calibrate.c): the
 * steps' names and servos, each step's settings written into the profile's
 * text (everything else kept byte for byte: comments, spacing, CRLF, a
 * byte-order mark, other steps' stamps), every refusal, and running out of
 * memory (malloc is interposed with the linker's --wrap). The arm is the
 * one of the done-when: zeros off by +23, -17, +30, -12, +5 positions
 * (base, shoulder, elbow, wrist, wrist roll), the elbow's servo reversed. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "lsc/calibrate.h"

void *__real_malloc(size_t n); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_malloc(size_t n); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int fail_malloc; /* > 0: the fail_malloc-th allocation from now fails */

void *__wrap_malloc(size_t n) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (fail_malloc > 0 && --fail_malloc == 0) {
        return NULL;
    }
    return __real_malloc(n);
}

/* An optimiser turns malloc then memset 0 into calloc: the same count. */
void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (fail_malloc > 0 && --fail_malloc == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

#define GEOMETRY                                                                           \
    "chain: base shoulder elbow wrist wrist-rotate gripper\n"                              \
    "links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm\n"

static const char shipped[] = "# a test arm\n"
                              "gripper       1  bus  limits=0..700 # the hand\n"
                              "wrist-rotate  2  bus  limits=-115deg..115deg  # roll\n"
                              "wrist         3  bus  dir=+1 limits=-115deg..115deg\n"
                              "elbow         4  bus  limits=-115deg..115deg\n"
                              "shoulder      5  bus  limits=100..900\n"
                              "base\t6\tbus\n" GEOMETRY;

static char why[LSC_ARM_MESSAGE_MAX];

/* the servos at (id, position) pairs, ended by id 0 */
static size_t servos(lsc_servo *out, const int *pairs)
{
    size_t n = 0;
    for (; pairs[2 * n] != 0; n++) {
        out[n].id = (uint8_t)pairs[2 * n];
        out[n].position = (uint16_t)pairs[2 * n + 1];
    }
    return n;
}

/* text after step with the readings (id, position...) and stamp: must be want */
static char *apply_ok(const char *text, lsc_calib_step step, const int *pairs, const char *stamp,
                      const char *want)
{
    lsc_servo s[8];
    size_t n = servos(s, pairs), len = 0;
    char *out = NULL;
    why[0] = '\0';
    int r = lsc_calib_apply(text, strlen(text), "t.conf", step, s, n, stamp, &out, &len, why,
                            sizeof why);
    if (r != 0) {
        fail_msg("step %s refused: %s", lsc_calib_step_name(step), why);
    }
    assert_non_null(out);
    assert_int_equal(len, strlen(out));
    if (want != NULL) {
        assert_string_equal(out, want);
    }
    return out;
}

static void apply_bad(const char *text, lsc_calib_step step, const int *pairs, int code,
                      const char *want)
{
    lsc_servo s[8];
    size_t n = servos(s, pairs), len = 7;
    char *out = (char *)&out;
    why[0] = '\0';
    assert_int_equal(lsc_calib_apply(text, strlen(text), "t.conf", step, s, n, "S", &out, &len,
                                     why, sizeof why),
                     code);
    assert_null(out);
    assert_string_equal(why, want);
}

static const int home[] = {6, 523, 5, 483, 4, 530, 3, 488, 2, 505, 1, 300, 0};
static const int lean[] = {2, 588, 3, 571, 4, 447, 5, 566, 6, 606, 0};

static void test_step_names(void **state)
{
    (void)state;
    static const char *const names[] = {"home", "lean", "gripper-closed", "gripper-open"};
    for (unsigned i = 0; i < LSC_CALIB_STEPS; i++) {
        lsc_calib_step step = LSC_CALIB_LEAN;
        assert_string_equal(lsc_calib_step_name((lsc_calib_step)i), names[i]);
        assert_int_equal(lsc_calib_step_parse(names[i], &step), 0);
        assert_int_equal(step, (lsc_calib_step)i);
    }
    lsc_calib_step step = LSC_CALIB_LEAN;
    assert_null(lsc_calib_step_name((lsc_calib_step)LSC_CALIB_STEPS));
    assert_null(lsc_calib_step_name((lsc_calib_step)-1));
    assert_int_equal(lsc_calib_step_parse("Home", &step), LSC_EINVAL);
    assert_int_equal(lsc_calib_step_parse(NULL, &step), LSC_EINVAL);
    assert_int_equal(lsc_calib_step_parse("home", NULL), LSC_EINVAL);
    assert_int_equal(step, LSC_CALIB_LEAN);
}

static lsc_arm *parse(const char *text)
{
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse(text, strlen(text), "t.conf", &arm, why, sizeof why), 0);
    return arm;
}

static void test_ids(void **state)
{
    (void)state;
    lsc_arm *arm = parse(shipped);
    uint8_t ids[6] = {0};
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_HOME, ids, 5, why, sizeof why), 5);
    assert_memory_equal(ids, "\x06\x05\x04\x03\x02", 5);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_LEAN, ids, 6, why, sizeof why), 5);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_GRIPPER_OPEN, ids, 1, why, sizeof why), 1);
    assert_int_equal(ids[0], 1);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_GRIPPER_CLOSED, ids, 1, why, sizeof why), 1);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_HOME, ids, 4, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "calibrate: room for 5 servo ids is needed");
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_HOME, NULL, 5, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_calib_ids(arm, (lsc_calib_step)9, ids, 6, why, sizeof why),
                     LSC_EINVAL);
    assert_string_equal(why, "calibrate: no arm profile, or an unknown step");
    assert_int_equal(lsc_calib_ids(NULL, LSC_CALIB_HOME, ids, 6, why, sizeof why), LSC_EINVAL);
    lsc_arm_free(arm);

    arm = parse("base 6 bus\n");
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_HOME, ids, 6, why, sizeof why), LSC_EINVAL);
    assert_non_null(strstr(why, "chain:"));
    lsc_arm_free(arm);

    arm = parse("a 1 bus\nb 2 bus\nc 3 bus\nd 4 bus\ne 5 bus\nchain: a b c d e\n"
                "links: height=1mm upper=1mm fore=1mm tool=1mm\n");
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_HOME, ids, 6, why, sizeof why), 5);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_GRIPPER_CLOSED, ids, 6, why, sizeof why),
                     LSC_EINVAL);
    assert_string_equal(why, "the profile's chain: line names no gripper: add the gripper's "
                             "joint at its end");
    /* a why of no room, or none */
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_GRIPPER_OPEN, ids, 6, why, 0), LSC_EINVAL);
    assert_int_equal(lsc_calib_ids(arm, LSC_CALIB_GRIPPER_OPEN, ids, 6, NULL, 9), LSC_EINVAL);
    lsc_arm_free(arm);
}

/* The whole calibration, step by step, each from the text the last one made. */
static void test_steps(void **state)
{
    (void)state;
    char *a = apply_ok(shipped, LSC_CALIB_HOME, home, "2026-11-29 10:00 UTC, from xarm.conf",
                       "# calibrate home: 2026-11-29 10:00 UTC, from xarm.conf\n"
                       "# a test arm\n"
                       "gripper       1  bus  limits=0..700 # the hand\n"
                       "wrist-rotate  2  bus offset=+5 limits=-115deg..115deg  # roll\n"
                       "wrist         3  bus dir=+1 offset=-12 limits=-115deg..115deg\n"
                       "elbow         4  bus offset=+30 limits=-115deg..115deg\n"
                       "shoulder      5  bus offset=-17 limits=100..900\n"
                       "base\t6\tbus offset=+23\n" GEOMETRY);
    char *b = apply_ok(a, LSC_CALIB_LEAN, lean, "L",
                       "# calibrate lean: L\n"
                       "# calibrate home: 2026-11-29 10:00 UTC, from xarm.conf\n"
                       "# a test arm\n"
                       "gripper       1  bus  limits=0..700 # the hand\n"
                       "wrist-rotate  2  bus dir=+1 offset=+5 limits=-115deg..115deg  # roll\n"
                       "wrist         3  bus dir=+1 offset=-12 limits=-115deg..115deg\n"
                       "elbow         4  bus dir=-1 offset=+30 limits=-115deg..115deg\n"
                       "shoulder      5  bus dir=+1 offset=-17 limits=100..900\n"
                       "base\t6\tbus dir=+1 offset=+23\n" GEOMETRY);
    static const int closed[] = {1, 650, 0}, open[] = {1, 120, 0};
    char *c = apply_ok(b, LSC_CALIB_GRIPPER_CLOSED, closed, "C", NULL);
    char *d = apply_ok(c, LSC_CALIB_GRIPPER_OPEN, open, "O", NULL);
    assert_non_null(strstr(c, "\ngripper       1  bus limits=0..700 closed=650  # the hand\n"));
    assert_non_null(strstr(d, "\ngripper       1  bus limits=120..650 open=120 closed=650  "
                              "# the hand\n"));
    assert_memory_equal(d, "# calibrate gripper-open: O\n# calibrate gripper-closed: C\n"
                           "# calibrate lean: L\n# calibrate home: 2026",
                        strlen("# calibrate gripper-open: O\n# calibrate gripper-closed: C\n"
                               "# calibrate lean: L\n# calibrate home: 2026"));
    /* home again: its stamp replaced, the offsets new, the directions kept */
    static const int home2[] = {6, 500, 5, 500, 4, 500, 3, 500, 2, 500, 0};
    char *e = apply_ok(d, LSC_CALIB_HOME, home2, "again", NULL);
    assert_memory_equal(e, "# calibrate home: again\n# calibrate gripper-open: O\n",
                        strlen("# calibrate home: again\n# calibrate gripper-open: O\n"));
    assert_null(strstr(e, "10:00 UTC"));
    assert_non_null(strstr(e, "\nelbow         4  bus dir=-1 offset=+0 limits=-115deg..115deg\n"));
    /* the result is the arm as built: the elbow's zero at 530, reversed */
    lsc_arm *arm = parse(d);
    const lsc_joint *elbow = lsc_arm_joint(arm, 3);
    assert_int_equal(elbow->zero, 530);
    assert_int_equal(elbow->direction, -1);
    uint16_t pos = 0;
    assert_int_equal(lsc_arm_end(arm, 0, LSC_ARM_OPEN, &pos), 0);
    assert_int_equal(pos, 120);
    lsc_arm_free(arm);
    free(a);
    free(b);
    free(c);
    free(d);
    free(e);
}

/* The gripper open first, then closed; limits widened to hold one end. */
static void test_gripper(void **state)
{
    (void)state;
    static const char text[] = "g 1 bus limits=200..700\n\nb 2 bus\nc 3 bus\nd 4 bus\ne 5 bus\n"
                               "f 6 bus\nchain: b c d e f g\n"
                               "links: height=1mm upper=1mm fore=1mm tool=1mm\n";
    static const int low[] = {1, 100, 0}, high[] = {1, 900, 0}, inside[] = {1, 300, 0},
                     near[] = {1, 120, 0};
    char *a = apply_ok(text, LSC_CALIB_GRIPPER_OPEN, low, "1", NULL);
    assert_non_null(strstr(a, "\ng 1 bus limits=100..700 open=100\n"));
    char *b = apply_ok(text, LSC_CALIB_GRIPPER_CLOSED, high, "2", NULL);
    assert_non_null(strstr(b, "\ng 1 bus limits=200..900 closed=900\n"));
    char *c = apply_ok(text, LSC_CALIB_GRIPPER_CLOSED, inside, "3", NULL);
    assert_non_null(strstr(c, "\ng 1 bus limits=200..700 closed=300\n"));
    char *d = apply_ok(a, LSC_CALIB_GRIPPER_CLOSED, high, "4", NULL);
    assert_non_null(strstr(d, "\ng 1 bus limits=100..900 open=100 closed=900\n"));
    /* open and closed too near: refused */
    apply_bad(a, LSC_CALIB_GRIPPER_CLOSED, near, LSC_EINVAL,
              "the gripper reads 100 open and 120 closed: close it further, then take this "
              "step again (at least 5 degrees apart)");
    apply_bad(c, LSC_CALIB_GRIPPER_OPEN, inside, LSC_EINVAL,
              "the gripper reads 300 open and 300 closed: open it wider, then take this step "
              "again (at least 5 degrees apart)");
    free(a);
    free(b);
    free(c);
    free(d);
}

/* CRLF lines, a byte-order mark, a last line without a newline. */
static void test_text_kept(void **state)
{
    (void)state;
    static const char text[] = "\xEF\xBB\xBF"
                               "b 2 bus # the base\r\n\r\nc 3 bus\r\nd 4 bus\r\ne 5 bus\r\n"
                               "f 6 bus\r\nchain: b c d e f\r\n"
                               "links: height=1mm upper=1mm fore=1mm tool=1mm";
    static const int at[] = {2, 510, 3, 490, 4, 500, 5, 500, 6, 500, 0};
    free(apply_ok(text, LSC_CALIB_HOME, at, "S",
             "\xEF\xBB\xBF# calibrate home: S\n"
             "b 2 bus offset=+10  # the base\r\n\r\nc 3 bus offset=-10\r\nd 4 bus offset=+0\r\n"
             "e 5 bus offset=+0\r\nf 6 bus offset=+0\r\nchain: b c d e f\r\n"
             "links: height=1mm upper=1mm fore=1mm tool=1mm"));
}

static void test_refused(void **state)
{
    (void)state;
    /* a joint not leaned far enough: each named, nothing written */
    static const int small[] = {2, 588, 3, 571, 4, 518, 5, 566, 6, 520, 0};
    apply_bad(shipped, LSC_CALIB_LEAN, small, LSC_EINVAL,
              "lean further, then take this step again: base 4.80 degrees, elbow 4.32 degrees "
              "from the zero (at least 5 each)");
    /* a servo not read, or outside its range */
    static const int some[] = {6, 523, 0};
    apply_bad(shipped, LSC_CALIB_HOME, some, LSC_EINVAL, "no reading of servo 5 (joint shoulder)");
    static const int far[] = {6, 1200, 0};
    apply_bad(shipped, LSC_CALIB_HOME, far, LSC_EINVAL,
              "servo 6 (joint base) reads 1200, outside its range 0..1000: is this the arm's "
              "profile?");
    static const char pwm[] = "b 2 pwm\nc 3 bus\nd 4 bus\ne 5 bus\nf 6 bus\nchain: b c d e f\n"
                              "links: height=1mm upper=1mm fore=1mm tool=1mm\n";
    static const int low[] = {2, 400, 0};
    apply_bad(pwm, LSC_CALIB_LEAN, low, LSC_EINVAL,
              "servo 2 (joint b) reads 400, outside its range 500..2500: is this the arm's "
              "profile?");
    static const int none[] = {0};
    apply_bad(pwm, LSC_CALIB_GRIPPER_OPEN, none, LSC_EINVAL,
              "the profile's chain: line names no gripper: add the gripper's joint at its end");
    apply_bad(shipped, LSC_CALIB_GRIPPER_OPEN, none, LSC_EINVAL,
              "no reading of servo 1 (joint gripper)");
    apply_bad("base 6 bus\nbase 7 bus\n", LSC_CALIB_HOME, none, LSC_EINVAL,
              "t.conf:2:1: joint base is named twice");
    /* a result the parser refuses: limits that hold no position from the new zero */
    static const char narrow[] = "b 2 bus limits=100deg..110deg\nc 3 bus\nd 4 bus\ne 5 bus\n"
                                 "f 6 bus\nchain: b c d e f\n"
                                 "links: height=1mm upper=1mm fore=1mm tool=1mm\n";
    static const int high[] = {2, 900, 3, 500, 4, 500, 5, 500, 6, 500, 0};
    apply_bad(narrow, LSC_CALIB_HOME, high, LSC_EINVAL,
              "the calibrated profile would be refused (t.conf:2:28: limits: 100.00deg..110.00deg "
              "hold no position of the servo: widen them): is the arm in the step's pose?");
}

static void test_arguments(void **state)
{
    (void)state;
    lsc_servo s[8];
    size_t n = servos(s, home), len = 0;
    char *out = (char *)&out;
    char longer[LSC_CALIB_STAMP_MAX + 2];
    memset(longer, 'x', sizeof longer - 1u);
    longer[sizeof longer - 1u] = '\0';
#define APPLY(text, len_, readings, n_, stamp, o, l)                                           \
    lsc_calib_apply(text, len_, NULL, LSC_CALIB_HOME, readings, n_, stamp, o, l, why, sizeof why)
    assert_int_equal(APPLY(NULL, 3, s, n, "S", &out, &len), LSC_EINVAL);
    assert_null(out);
    assert_string_equal(why, "calibrate: a NULL argument");
    assert_int_equal(APPLY(shipped, strlen(shipped), NULL, 1, "S", &out, &len), LSC_EINVAL);
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, NULL, &out, &len), LSC_EINVAL);
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, "S", NULL, &len), LSC_EINVAL);
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, "S", &out, NULL), LSC_EINVAL);
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, "a\nb", &out, &len), LSC_EINVAL);
    assert_string_equal(why, "calibrate: the stamp is one line of printable ASCII, at most 200 "
                             "bytes");
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, "\xC3\xA4", &out, &len), LSC_EINVAL);
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, longer, &out, &len), LSC_EINVAL);
    longer[LSC_CALIB_STAMP_MAX] = '\0';
    assert_int_equal(APPLY(shipped, strlen(shipped), s, n, longer, &out, &len), 0);
    free(out);
    /* no text, no readings: the parser's reason, then the step's */
    assert_int_equal(APPLY(NULL, 0, s, n, "S", &out, &len), LSC_EINVAL);
    assert_string_equal(why, "profile: no joints: a profile names at least one (see "
                             "docs/arm-profile.md)");
    assert_int_equal(APPLY(shipped, strlen(shipped), NULL, 0, "S", &out, &len), LSC_EINVAL);
    assert_string_equal(why, "no reading of servo 6 (joint base)");
    assert_int_equal(lsc_calib_apply(shipped, strlen(shipped), NULL, (lsc_calib_step)7, s, n, "S",
                                     &out, &len, why, sizeof why),
                     LSC_EINVAL);
#undef APPLY
}

static void test_out_of_memory(void **state)
{
    (void)state;
    lsc_servo s[8];
    size_t n = servos(s, home), len = 0;
    /* the profile, the text, the result's check */
    for (int k = 1; k <= 3; k++) {
        char *out = (char *)&out;
        fail_malloc = k;
        assert_int_equal(lsc_calib_apply(shipped, strlen(shipped), NULL, LSC_CALIB_HOME, s, n,
                                         "S", &out, &len, why, sizeof why),
                         LSC_ENOSPC);
        assert_null(out);
        assert_int_equal(len, 0);
    }
    fail_malloc = 0;
    assert_string_equal(why, "calibrate: out of memory");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_names), cmocka_unit_test(test_ids),
        cmocka_unit_test(test_steps),      cmocka_unit_test(test_gripper),
        cmocka_unit_test(test_text_kept),  cmocka_unit_test(test_refused),
        cmocka_unit_test(test_arguments),  cmocka_unit_test(test_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
