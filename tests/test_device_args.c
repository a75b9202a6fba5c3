/* What front ends read from people, through the device layer (src/device,
 * lsc/device.h): lists of servos (ids, ranges and joint names) and the
 * environment. No wraps. */
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
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "../src/device/device_internal.h" /* the config's fields */


/* ---- Lists of servos ------------------------------------------------------------------ */

/* Parses list into ids[0..cap): the count, which must be want. */
static int ids_of(const lsc_arm *arm, const char *list, uint8_t *ids, size_t cap, char *why,
                  size_t whylen)
{
    memset(ids, 0xEE, cap);
    if (why != NULL && whylen > 0) {
        why[0] = '\0';
    }
    return lsc_device_parse_ids(arm, list, ids, cap, why, whylen);
}

/* lsc_device_parse_ids: ids, ranges and joint names; every refusal says why. */
static void id_lists(void **state)
{
    (void)state;
    static const char profile[] = "base 6 bus\nshoulder 5 bus\nwrist-roll 2 bus\n";
    lsc_arm *arm = NULL;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX + 1];
    char why[200];
    assert_int_equal(lsc_arm_parse(profile, sizeof profile - 1u, "t.conf", &arm, why, sizeof why),
                     0);
    /* ids and ranges, with or without a profile */
    for (int with = 0; with < 2; with++) {
        const lsc_arm *a = with ? arm : NULL;
        assert_int_equal(ids_of(a, "1-6", ids, 32, why, sizeof why), 6);
        for (uint8_t i = 0; i < 6; i++) {
            assert_int_equal(ids[i], i + 1);
        }
        assert_int_equal(ids_of(a, "1-3,8", ids, 32, why, sizeof why), 4);
        assert_int_equal(ids[3], 8);
        assert_int_equal(ids_of(a, "0x10,7,0-0,255", ids, 32, why, sizeof why), 4);
        assert_int_equal(ids[0], 16);
        assert_int_equal(ids[1], 7);
        assert_int_equal(ids[2], 0);
        assert_int_equal(ids[3], 255);
        assert_int_equal(ids_of(a, "0xfe-0xff", ids, 32, why, sizeof why), 2);
        assert_int_equal(ids[1], 255);
        assert_int_equal(ids_of(a, "9", ids, 1, why, sizeof why), 1); /* exactly cap */
        /* a negative id is said to be one (not "id ''") */
        assert_int_equal(ids_of(a, "-5", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "id '-5' is negative: use 0..255");
        assert_int_equal(ids_of(a, "1,-", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "id '-' is negative: use 0..255");
        assert_int_equal(ids_of(a, "5-3", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range 5-3 is empty: write the lower id first");
        assert_int_equal(ids_of(a, "1-", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-' has no end: write LO-HI, like 1-6");
        assert_int_equal(ids_of(a, "1-x", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-x': id 'x' is not a number: write it in decimal "
                                 "or 0x-hex");
        assert_int_equal(ids_of(a, "256-300", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '256-300': id 256 is out of range: use 0..255");
        assert_int_equal(ids_of(a, "1-3-5", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_has(why, "the range '1-3-5': id '3-5' is not a number");
        assert_int_equal(ids_of(a, "1,1", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "servo 1 listed twice");
        assert_int_equal(ids_of(a, "1-4,3", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "servo 3 listed twice");
        assert_int_equal(ids_of(a, "0-40", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "more than 32 servos");
        assert_int_equal(ids_of(a, "", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "no servos listed: give ids like 1-6, 1,2,5 or joint names");
        for (size_t k = 0; k < 4; k++) {
            static const char *const empty[] = {",", "1,", ",1", "1,,2"};
            assert_int_equal(ids_of(a, empty[k], ids, 32, why, sizeof why), LSC_EINVAL);
            assert_string_equal(why, "an empty item (two commas, or one at an end): give ids "
                                     "like 1-6, 1,2,5 or joint names");
        }
        /* text from outside stays one line */
        assert_int_equal(ids_of(a, "1,2\n\033[31m", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_has(why, "2\\x0A\\x1B[31m");
        assert_null(strchr(why, '\n'));
        assert_null(strchr(why, '\033'));
        assert_int_equal(ids_of(a, "1-\n", ids, 32, why, sizeof why), LSC_EINVAL);
        assert_string_equal(why, "the range '1-\\x0A': id '\\x0A' is not a number: write it in "
                                 "decimal or 0x-hex");
    }
    /* joint names, mixed with ids and ranges */
    assert_int_equal(ids_of(arm, "base,shoulder,3-4", ids, 32, why, sizeof why), 4);
    assert_int_equal(ids[0], 6);
    assert_int_equal(ids[1], 5);
    assert_int_equal(ids[2], 3);
    assert_int_equal(ids[3], 4);
    assert_int_equal(ids_of(arm, "wrist-roll,1", ids, 32, why, sizeof why), 2);
    assert_int_equal(ids[0], 2);
    assert_int_equal(ids_of(arm, "base,6", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "servo 6 listed twice");
    assert_int_equal(ids_of(arm, "4-6,base", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "servo 6 listed twice");
    assert_int_equal(ids_of(arm, "elbow", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'elbow' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(ids_of(arm, "base-3", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'base-3' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(ids_of(NULL, "base", ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id 'base' is not a number: write it in decimal or 0x-hex");
    /* an item longer than any name or id: its start, escaped */
    char longer[64];
    memset(longer, 'a', sizeof longer - 1u);
    longer[sizeof longer - 1u] = '\0';
    longer[1] = '\t';
    assert_int_equal(ids_of(arm, longer, ids, 32, why, sizeof why), LSC_EINVAL);
    assert_has(why, "'a\\x09aaaa");
    assert_has(why, "...' is neither a joint nor a servo id");
    /* the most there can be: every id once */
    uint8_t all[256];
    assert_int_equal(lsc_device_parse_ids(NULL, "0-255", all, sizeof all, why, sizeof why), 256);
    assert_int_equal(all[255], 255);
    /* arguments */
    assert_int_equal(lsc_device_parse_ids(arm, NULL, ids, 32, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_device_parse_ids: no list, or no room for ids");
    assert_int_equal(lsc_device_parse_ids(arm, "1", NULL, 32, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1", ids, 0, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1,1", ids, 32, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids(arm, "1,1", ids, 32, why, 0), LSC_EINVAL);
    lsc_arm_free(arm);
}

/* ---- The environment, as every front end reads it ------------------------------------ */

static void env_vars(void **state)
{
    (void)state;
    char why[160];
    uint16_t vid = 7, pid = 7;
    (void)unsetenv("LSC_ARM");
    assert_null(lsc_device_env_arm());
    assert_int_equal(setenv("LSC_ARM", "", 1), 0);
    assert_null(lsc_device_env_arm());
    assert_int_equal(setenv("LSC_ARM", "arm.conf", 1), 0);
    assert_string_equal(lsc_device_env_arm(), "arm.conf");
    (void)unsetenv("LSC_ARM");
    assert_null(lsc_device_env_port());
    assert_int_equal(setenv("LSC_PORT", "sim", 1), 0);
    assert_string_equal(lsc_device_env_port(), "sim");
    (void)unsetenv("LSC_PORT");
    /* VID:PID */
    assert_int_equal(lsc_device_parse_hid_id("0483:5750", &vid, &pid), 0);
    assert_int_equal(vid, 0x0483);
    assert_int_equal(pid, 0x5750);
    assert_int_equal(lsc_device_parse_hid_id("aBcD:Ef", &vid, &pid), 0);
    assert_int_equal(vid, 0xABCD);
    assert_int_equal(pid, 0xEF);
    assert_int_equal(lsc_device_parse_hid_id("0:1", &vid, &pid), 0);
    static const char *const bad[] = {"",    ":1",   "1:",  "12345:1", "123456:1", "1:12345",
                                      "1:2x", "12",   "0:0", "g:1",     "G:1",      "1/2",
                                      "1:2:3", "1 :2", "0x1:2"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        vid = pid = 7;
        assert_int_equal(lsc_device_parse_hid_id(bad[i], &vid, &pid), LSC_EINVAL);
        assert_int_equal(vid, 7);
        assert_int_equal(pid, 7);
    }
    assert_int_equal(lsc_device_parse_hid_id(NULL, &vid, &pid), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_hid_id("1:2", NULL, &pid), LSC_EINVAL);
    assert_int_equal(lsc_device_parse_hid_id("1:2", &vid, NULL), LSC_EINVAL);
    /* $LSC_HID_ID into the config, unless it names ids */
    lsc_device_config *opt = lsc_device_config_new();
    assert_non_null(opt);
    (void)unsetenv("LSC_HID_ID");
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), 0);
    assert_string_equal(why, "");
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(setenv("LSC_HID_ID", "046d:c52b", 1), 0);
    assert_int_equal(lsc_device_config_from_env(opt, NULL, 0), 0);
    assert_int_equal(opt->hid_vid, 0x046d);
    assert_int_equal(opt->hid_pid, 0xc52b);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 1, 2), 0);
    assert_int_equal(lsc_device_config_from_env(opt, why, 0), 0);
    assert_int_equal(opt->hid_vid, 1);
    assert_int_equal(opt->hid_pid, 2);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 0, 2), 0); /* a pid alone */
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), 0);
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(opt->hid_pid, 2);
    assert_int_equal(setenv("LSC_HID_ID", "usb", 1), 0);
    assert_int_equal(lsc_device_config_set_hid_id(opt, 0, 0), 0);
    assert_int_equal(lsc_device_config_from_env(opt, why, sizeof why), LSC_EINVAL);
    assert_has(why, "$LSC_HID_ID needs a USB VID:PID in hex");
    assert_int_equal(opt->hid_vid, 0);
    assert_int_equal(opt->hid_pid, 0);
    assert_int_equal(lsc_device_config_from_env(NULL, why, sizeof why), LSC_EINVAL);
    lsc_device_config_free(opt);
    (void)unsetenv("LSC_HID_ID");
}

/* Each kind's short name, the one lscd's status and the panel show. */
static void kind_names(void **state)
{
    (void)state;
    assert_string_equal(lsc_device_kind_name(LSC_DEVICE_SERIAL), "serial");
    assert_string_equal(lsc_device_kind_name(LSC_DEVICE_HID), "hid");
    assert_string_equal(lsc_device_kind_name(LSC_DEVICE_SIM), "sim");
    assert_string_equal(lsc_device_kind_name(LSC_DEVICE_LSCD), "lscd");
    assert_string_equal(lsc_device_kind_name(LSC_DEVICE_LX), "lx");
    assert_string_equal(lsc_device_kind_name((lsc_device_kind)99), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(id_lists, device_setup, device_teardown),
        cmocka_unit_test_setup_teardown(env_vars, device_setup, device_teardown),
        cmocka_unit_test(kind_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
