/* Tests of the action group text format (docs/action-groups.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "lsc/lsc.h"

static lsc_sim_groups g;
static lsc_sim_step steps[64];
static lsc_servo targets[256];

static int setup(void **state)
{
    (void)state;
    assert_int_equal(lsc_sim_groups_init(&g, steps, 64, targets, 256), 0);
    return 0;
}

static int parse(const char *text, lsc_sim_parse_error *err)
{
    return lsc_sim_groups_parse(&g, text, strlen(text), err);
}

static void test_valid_text(void **state)
{
    (void)state;
    lsc_sim_parse_error err;
    const char *text = "# a comment line\n"
                       "\n"
                       "group 0   # trailing comment\n"
                       "  step 1000 1:1500 2:2000\t32:500\r\n"
                       "\tstep 20\n"            /* a pause */
                       "group 254\n"
                       "step 65535 0:0 255:65535#comment\n"
                       "   \n"
                       "group 17";              /* last line, no newline, no steps */
    int r = parse(text, &err);
    assert_int_equal(r, LSC_EINVAL);            /* group 17 has no steps */
    assert_int_equal(err.line, 9);
    assert_int_equal(err.column, 1);
    assert_string_equal(err.message, "group has no steps");
    assert_int_equal(g.nsteps, 0);              /* left empty on error */
    assert_int_equal(g.group_steps[0], 0);

    text = "# a comment line\n"
           "\n"
           "group 0   # trailing comment\n"
           "  step 1000 1:1500 2:2000\t32:500\r\n"
           "\tstep 20\n"
           "group 254\n"
           "step 65535 0:0 255:65535#comment\n"
           "group 17\n"
           "step 1 5:5";
    r = parse(text, &err);
    assert_int_equal(r, 3);
    assert_int_equal(err.line, 0);
    assert_int_equal(g.nsteps, 4);
    assert_int_equal(g.ntargets, 6);
    assert_int_equal(g.group_steps[0], 2);
    assert_int_equal(g.group_steps[254], 1);
    assert_int_equal(g.group_steps[17], 1);
    assert_int_equal(g.group_steps[1], 0);
    const lsc_sim_step *s = &g.steps[g.first_step[0]];
    assert_int_equal(s[0].time_ms, 1000);
    assert_int_equal(s[0].ntargets, 3);
    assert_int_equal(g.targets[s[0].first + 2].id, 32);
    assert_int_equal(g.targets[s[0].first + 2].position, 500);
    assert_int_equal(s[1].time_ms, 20);
    assert_int_equal(s[1].ntargets, 0);
    s = &g.steps[g.first_step[254]];
    assert_int_equal(s->time_ms, 65535);
    assert_int_equal(g.targets[s->first + 1].id, 255);
    assert_int_equal(g.targets[s->first + 1].position, 65535);
}

static void test_empty_text(void **state)
{
    (void)state;
    lsc_sim_parse_error err;
    assert_int_equal(parse("", &err), 0);
    assert_int_equal(parse("# nothing\n\n  \n", &err), 0);
    assert_int_equal(lsc_sim_groups_parse(&g, NULL, 0, NULL), 0);
}

typedef struct bad_text {
    const char *text;
    uint32_t line;
    uint32_t column;
    const char *message;
    int code;
} bad_text;

static void test_every_error(void **state)
{
    (void)state;
    static const bad_text cases[] = {
        {"grup 1\n", 1, 1, "expected 'group N' or 'step MS ID:POS...'", LSC_EINVAL},
        {"group 1\nstep 10 1:1\nmove 1\n", 3, 1, "expected 'group N' or 'step MS ID:POS...'", LSC_EINVAL},
        {"GROUP 1\n", 1, 1, "expected 'group N' or 'step MS ID:POS...'", LSC_EINVAL},
        {"step 100 1:1500\n", 1, 1, "step before any group line", LSC_EINVAL},
        {"group\n", 1, 6, "group number must be 0..254", LSC_EINVAL},
        {"group x\n", 1, 7, "group number must be 0..254", LSC_EINVAL},
        {"group 255\n", 1, 7, "group number must be 0..254", LSC_EINVAL},
        {"group 99999999999\n", 1, 7, "group number must be 0..254", LSC_EINVAL},
        {"group -1\n", 1, 7, "group number must be 0..254", LSC_EINVAL},
        {"group 1x\n", 1, 7, "group number must be 0..254", LSC_EINVAL},
        {"group 1 2\nstep 1\n", 1, 9, "unexpected text at end of line", LSC_EINVAL},
        {"group 1\nstep 5\ngroup 1\nstep 5\n", 3, 7, "group defined twice", LSC_EINVAL},
        {"group 1\ngroup 2\nstep 5\n", 1, 1, "group has no steps", LSC_EINVAL},
        {"  group 3\n", 1, 3, "group has no steps", LSC_EINVAL},
        {"group 1\nstep\n", 2, 5, "step needs a time in ms (1..65535)", LSC_EINVAL},
        {"group 1\nstep # no time\n", 2, 6, "step needs a time in ms (1..65535)", LSC_EINVAL},
        {"group 1\nstep 0 1:1500\n", 2, 6, "step time must be 1..65535 ms", LSC_EINVAL},
        {"group 1\nstep 65536\n", 2, 6, "step time must be 1..65535 ms", LSC_EINVAL},
        {"group 1\nstep 1.5\n", 2, 6, "step time must be 1..65535 ms", LSC_EINVAL},
        {"group 1\nstep 1:1500\n", 2, 6, "step time must be 1..65535 ms", LSC_EINVAL},
        {"group 1\nstep 100 1\n", 2, 10, "target must be ID:POSITION (id 0..255)", LSC_EINVAL},
        {"group 1\nstep 100 1=1500\n", 2, 10, "target must be ID:POSITION (id 0..255)", LSC_EINVAL},
        {"group 1\nstep 100 256:1500\n", 2, 10, "target must be ID:POSITION (id 0..255)", LSC_EINVAL},
        {"group 1\nstep 100 :1500\n", 2, 10, "target must be ID:POSITION (id 0..255)", LSC_EINVAL},
        {"group 1\nstep 100 1:\n", 2, 12, "position must be 0..65535", LSC_EINVAL},
        {"group 1\nstep 100 1:65536\n", 2, 12, "position must be 0..65535", LSC_EINVAL},
        {"group 1\nstep 100 1:15x0\n", 2, 12, "position must be 0..65535", LSC_EINVAL},
        {"group 1\nstep 100 1:1:1\n", 2, 12, "position must be 0..65535", LSC_EINVAL},
        {"group 1\nstep 100 2:1 3:1 2:5\n", 2, 18, "servo listed twice in one step", LSC_EINVAL},
        {"group 1\nstep 100 1:1\n\x01\n", 3, 1, "expected 'group N' or 'step MS ID:POS...'", LSC_EINVAL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        lsc_sim_parse_error err;
        int r = parse(cases[i].text, &err);
        if (r != cases[i].code || err.line != cases[i].line || err.column != cases[i].column ||
            strcmp(err.message, cases[i].message) != 0) {
            fail_msg("case %zu \"%s\": got %d line %u col %u \"%s\"", i, cases[i].text, r,
                     (unsigned)err.line, (unsigned)err.column, err.message);
        }
        assert_int_equal(g.nsteps, 0);
        assert_int_equal(g.ntargets, 0);
        for (unsigned k = 0; k < LSC_SIM_GROUPS; k++) {
            assert_int_equal(g.group_steps[k], 0);
        }
    }
}

static void test_storage_limits(void **state)
{
    (void)state;
    lsc_sim_step few_steps[2];
    lsc_servo few_targets[3];
    lsc_sim_parse_error err;
    assert_int_equal(lsc_sim_groups_init(&g, few_steps, 2, few_targets, 3), 0);
    assert_int_equal(parse("group 1\nstep 1 1:1 2:2\nstep 1 3:3\n", &err), 1);
    assert_int_equal(parse("group 1\nstep 1\nstep 1\nstep 1\n", &err), LSC_ENOSPC);
    assert_int_equal(err.line, 4);
    assert_int_equal(err.column, 1);
    assert_string_equal(err.message, "too many steps for the storage given");
    assert_int_equal(parse("group 1\nstep 1 1:1 2:2\nstep 1 3:3 4:4\n", &err), LSC_ENOSPC);
    assert_int_equal(err.line, 3);
    assert_int_equal(err.column, 12);
    assert_string_equal(err.message, "too many targets for the storage given");
    assert_int_equal(g.nsteps, 0);
    /* no storage at all: only empty texts fit */
    assert_int_equal(lsc_sim_groups_init(&g, NULL, 0, NULL, 0), 0);
    assert_int_equal(parse("# empty\n", &err), 0);
    assert_int_equal(parse("group 1\nstep 1\n", &err), LSC_ENOSPC);
}

static void test_invalid_arguments(void **state)
{
    (void)state;
    lsc_sim_parse_error err;
    assert_int_equal(lsc_sim_groups_init(NULL, steps, 1, targets, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_groups_init(&g, NULL, 1, targets, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_groups_init(&g, steps, 1, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_sim_groups_parse(NULL, "", 0, &err), LSC_EINVAL);
    assert_string_equal(err.message, "invalid argument");
    assert_int_equal(lsc_sim_groups_parse(&g, NULL, 3, &err), LSC_EINVAL);
    assert_int_equal(lsc_sim_groups_parse(&g, "group 1\n", 8, NULL), LSC_EINVAL);
    /* text need not be NUL-terminated: only len bytes are read */
    assert_int_equal(lsc_sim_groups_parse(&g, "group 1\nstep 5 1:1junk", 18, &err), 1);
    assert_int_equal(g.targets[0].position, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_valid_text, setup),
        cmocka_unit_test_setup(test_empty_text, setup),
        cmocka_unit_test_setup(test_every_error, setup),
        cmocka_unit_test_setup(test_storage_limits, setup),
        cmocka_unit_test_setup(test_invalid_arguments, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
