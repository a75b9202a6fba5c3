/* lscctl convert: an action file into another format, and with --from-arm
 * and --to-arm for another arm (the library's lsc_action_to_arm in
 * lsc/device.h; the formats in lsc/files.h): here are the arguments and
 * what is printed. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/convert.h"
#include "lscctl.h"
#include "lscctl_teach.h"

const char lscctl_help_convert[] =
    "Converts an action file: the extensions choose the formats (.txt .csv .rob\n"
    ".d6a to read; those and .h to write). The keyframes are the same; a format\n"
    "that cannot hold them (.rob: servos 1..6, positions 0..1000) is refused.\n"
    "The .h is a C header for firmware (examples/arduino/PlayKeyframes).\n"
    "With --from-arm and --to-arm (arm profiles: docs/arm-profile.md) the\n"
    "positions are converted through joint angles: each servo is a joint of the\n"
    "first profile, and goes to the joint of the same name in the second at the\n"
    "same angle; a keyframe outside the second's limits is refused (exit 2,\n"
    "nothing written). With -n, says what it would write and writes nothing.\n"
    "\nOptions:\n  --group N    read group N of a .txt file of several groups\n"
    "  --from-arm FILE  the arm profile IN was made for\n"
    "  --to-arm FILE    the arm profile to convert it for\n"
    "\nExamples:\n  lscctl convert arm.rob arm.csv\n  lscctl convert arm.d6a arm.h\n"
    "  lscctl convert wave.csv wave.rob --from-arm examples/arms/learm.conf \\\n"
    "                 --to-arm examples/arms/xarm.conf\n"
    "  lscctl convert examples/groups/arm-demo.txt wave.csv --group 1\n";

/* What convert writes (or, with -n, would write) to path: its format,
 * keyframes, servos and size. */
static void print_written(const lscctl_opts *o, const char *path, lsc_file_format f,
                          const lsc_action *a, size_t bytes)
{
    if (o->json) {
        printf("{\"file\":");
        lscctl_json_string(stdout, path);
        printf(",\"format\":\"%s\",\"keyframes\":%lu,\"servos\":[", lsc_file_format_name(f),
               (unsigned long)a->count);
        for (size_t i = 0; i < a->nservos; i++) {
            printf("%s%u", i ? "," : "", a->ids[i]);
        }
        printf("],\"bytes\":%lu,\"written\":%s}\n", (unsigned long)bytes,
               o->dry_run ? "false" : "true");
        return;
    }
    printf("%s: %s file, %lu keyframe%s of %u servo%s (", path, lsc_file_format_name(f),
           (unsigned long)a->count, a->count == 1u ? "" : "s", a->nservos,
           a->nservos == 1u ? "" : "s");
    for (size_t i = 0; i < a->nservos; i++) {
        printf("%s%u", i ? " " : "", a->ids[i]);
    }
    printf("), %lu byte%s; not written (-n)\n", (unsigned long)bytes, bytes == 1u ? "" : "s");
}

/* --from-arm and --to-arm (both or neither): a's positions through joint
 * angles (the library's lsc_action_to_arm); a is replaced. Returns 0 or the
 * exit code after saying why. */
static int convert_arms(const lscctl_opts *o, const char *path, lsc_action *a)
{
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *from = NULL, *to = NULL;
    lsc_action b;
    if (o->from_arm == NULL) {
        return 0;
    }
    int r = lsc_arm_open(o->from_arm, &from, why, sizeof why);
    if (r == 0) {
        r = lsc_arm_open(o->to_arm, &to, why, sizeof why);
    }
    int code = 0;
    if (r != 0) {
        code = lscctl_fail(o, r == LSC_ENOSPC ? LSCCTL_EXIT_FAIL : LSCCTL_EXIT_USAGE, "%s", why);
    } else if ((r = lsc_action_to_arm(a, from, to, &b, why, sizeof why)) != 0) {
        code = lscctl_fail(o, r == LSC_ENOSPC ? LSCCTL_EXIT_FAIL : LSCCTL_EXIT_USAGE, "%s: %s",
                           path, why);
    } else {
        lsc_action_free(a);
        *a = b;
    }
    lsc_arm_free(from);
    lsc_arm_free(to);
    return code;
}

/* Whether a holds a position beyond a .rob file's range. */
static bool beyond_rob(const lsc_action *a)
{
    size_t n = (size_t)a->count * (1u + a->nservos);
    for (size_t w = 0; w < n; w++) {
        if (w % (1u + a->nservos) != 0u && a->words[w] > LSC_FILE_ROB_POSITION_MAX) {
            return true;
        }
    }
    return false;
}

int lscctl_cmd_convert(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    lsc_action a;
    lsc_file_error err = {.size = sizeof err};
    lscctl_shown out;
    (void)lscctl_show(&out, argv[1]);
    lsc_file_format f = lsc_file_format_of(argv[1]);
    if (f == LSC_FILE_UNKNOWN) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s: unknown file type: lsc writes .txt, .csv, .rob, .d6a and .h",
                           out.text);
    }
    if ((o->from_arm == NULL) != (o->to_arm == NULL)) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "--from-arm and --to-arm go together: the profile the file was made "
                           "for and the one to convert it for");
    }
    int code = lscctl_load_action(o, argv[0], &a);
    if (code == 0) {
        code = convert_arms(o, argv[0], &a);
    }
    if (code != 0) {
        lsc_action_free(&a);
        return code;
    }
    /* -n and --json say what is written: the bytes, made once to count them */
    uint8_t *bytes = NULL;
    size_t len = 0;
    int r = o->dry_run || o->json ? lsc_action_format(f, &a, argv[1], &bytes, &len, &err) : 0;
    free(bytes);
    if (r == 0 && !o->dry_run) {
        r = lsc_action_write(argv[1], &a, &err);
    }
    if (r == 0 && (o->dry_run || o->json)) {
        print_written(o, argv[1], f, &a, len);
    }
    /* PWM positions (500..2500) are no .rob positions (0..1000): angles are */
    bool hint = r == LSC_EINVAL && f == LSC_FILE_ROB && o->to_arm == NULL && beyond_rob(&a);
    lsc_action_free(&a);
    if (r == LSC_EINVAL) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s%s", out.text, err.message,
                           hint ? "; positions of another arm convert through joint angles "
                                  "with --from-arm and --to-arm"
                                : "");
    }
    if (r != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: %s", out.text, err.message);
    }
    return LSCCTL_EXIT_OK;
}
