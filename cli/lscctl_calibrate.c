/* lscctl calibrate: an arm profile made right for the arm in hand. The
 * steps' arithmetic and the profile's text are the library's
 * (lsc/calibrate.h), where the result is kept is lsc/calibrated.h's: this
 * file reads the servos, walks the owner through the poses, writes the file
 * and says what it found. */
#define _POSIX_C_SOURCE 200809L /* sigaction */

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lsc/arm.h"
#include "lsc/calibrate.h"
#include "lsc/calibrated.h"
#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/motion.h"
#include "lsc/kinematics.h"
#include "lscctl.h"
#include "lscctl_parse.h"
#include "lscctl_port.h"

#define PATH_MAX_ 4096u
#define CHECK_FAR_MM 10.0 /* --check: farther than this, a pose was held wrong */

static int usage(const lscctl_opts *o, const char *why)
{
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s (see 'lscctl help calibrate')", why);
}

/* The work of one calibration: the profile's text so far and where it goes. */
typedef struct calib {
    const lscctl_opts *o;
    char base[PATH_MAX_]; /* the profile the text came from */
    char out[PATH_MAX_];  /* where the result goes */
    char *text;           /* the profile so far (malloc) */
    size_t len;
    lsc_arm *arm; /* text parsed */
} calib;

static void calib_free(calib *c)
{
    free(c->text);
    lsc_arm_free(c->arm);
}

/* c->text (and c->arm) from the file at path. */
static int load_text(calib *c, const char *path)
{
    lsc_file_error err = {.size = sizeof err};
    uint8_t *data = NULL;
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    if (lsc_file_load(path, LSC_ARM_FILE_MAX, &data, &c->len, &err) != 0) {
        lscctl_shown shown;
        return lscctl_fail(c->o, LSCCTL_EXIT_USAGE, "cannot read the arm profile %s: %s",
                           lscctl_show(&shown, path), err.message);
    }
    if (lsc_arm_parse((const char *)data, c->len, path, &arm, why, sizeof why) != 0) {
        free(data);
        return lscctl_fail(c->o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    c->text = (char *)data;
    c->arm = arm;
    (void)snprintf(c->base, sizeof c->base, "%s", path);
    return 0;
}

/* Where the result goes (--out, else the controller's calibrated profile)
 * and the text it starts from (that file when it exists: the steps so far;
 * else the profile of --arm). */
static int calib_open(calib *c, const lscctl_opts *o)
{
    char key[LSC_CALIBRATED_KEY_MAX];
    struct stat st;
    memset(c, 0, sizeof *c);
    c->o = o;
    if (o->out != NULL) {
        (void)snprintf(c->out, sizeof c->out, "%s", o->out);
    } else if (lsc_calibrated_key(o->port, key, sizeof key) != 0 ||
               lsc_calibrated_path(key, c->out, sizeof c->out) != 0) {
        return usage(o, "this controller has no name to keep its arm's profile under (a HID "
                        "controller's serial number, a serial port's /dev/serial/by-id link): "
                        "give the file with --out FILE");
    }
    if (stat(c->out, &st) == 0) {
        if (o->arm != NULL && !o->arm_calibrated) {
            fprintf(stderr, "lscctl: calibrate: continuing %s (not --arm's profile: remove "
                            "the file to start over)\n",
                    c->out);
        }
        return load_text(c, c->out);
    }
    if (o->arm == NULL) {
        return usage(o, "calibration starts from the arm's profile: --arm NAME or FILE (e.g. "
                        "xarm)");
    }
    char path[PATH_MAX_], why[LSC_ARM_MESSAGE_MAX];
    if (lsc_arm_path(o->arm, path, sizeof path, why, sizeof why) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    return load_text(c, path);
}

/* Takes step on the servos (lsc_device_calibrate) into c->text: 0, an exit
 * code, or (retry not NULL) *retry true after saying why the readings were
 * refused, which the owner can put right by holding the pose better. */
static int take_step(calib *c, lscctl_link *l, lsc_calib_step step, bool *retry)
{
    char why[LSC_ARM_MESSAGE_MAX];
    char *text = NULL;
    size_t len = 0;
    lsc_arm *arm = NULL;
    lsc_device *d = lscctl_link_device(l);
    int r = lsc_device_calibrate(d, step, c->text, c->len, c->base, &text, &len);
    if (r == LSC_EINVAL && retry != NULL) {
        *retry = true;
        fprintf(stderr, "lscctl: calibrate: %s\n", lsc_device_error(d));
        return 0;
    }
    if (r != 0) {
        return lscctl_link_check(l, r);
    }
    if (lsc_arm_parse(text, len, c->out, &arm, why, sizeof why) != 0) { /* out of memory */
        free(text);
        return lscctl_fail(c->o, LSCCTL_EXIT_FAIL, "%s", why);
    }
    free(c->text);
    lsc_arm_free(c->arm);
    c->text = text;
    c->len = len;
    c->arm = arm;
    if (retry != NULL) {
        *retry = false;
    }
    return 0;
}

/* What a step found, on stdout: each joint's setting the step gave. */
static void say(const calib *c, lsc_calib_step step, bool written)
{
    uint8_t ids[LSC_ARM_CHAIN_MAX];
    int n = lsc_calib_ids(c->arm, step, ids, LSC_ARM_CHAIN_MAX, NULL, 0);
    if (c->o->json) {
        printf("{\"step\":\"%s\",", lsc_calib_step_name(step));
        if (written) {
            printf("\"profile\":");
            lscctl_json_string(stdout, c->out);
            printf(",");
        }
        printf("\"joints\":{");
    } else {
        printf("%s:", lsc_calib_step_name(step));
    }
    for (int k = 0; k < n; k++) {
        int i = lsc_arm_by_id(c->arm, ids[k]);
        const lsc_joint *j = lsc_arm_joint(c->arm, (size_t)i);
        long offset = (long)j->zero - ((long)j->pos_min + ((long)j->pos_max - (long)j->pos_min) / 2);
        uint16_t open = 0, closed = 0;
        bool has_open = lsc_arm_end(c->arm, (size_t)i, LSC_ARM_OPEN, &open) == 0;
        bool has_closed = lsc_arm_end(c->arm, (size_t)i, LSC_ARM_CLOSED, &closed) == 0;
        if (c->o->json) {
            printf("%s", k > 0 ? "," : "");
            lscctl_json_string(stdout, lsc_arm_name(c->arm, (size_t)i));
            if (step == LSC_CALIB_HOME) {
                printf(":{\"offset\":%ld}", offset);
            } else if (step == LSC_CALIB_LEAN) {
                printf(":{\"dir\":%d}", j->direction);
            } else {
                printf(":{\"open\":%d,\"closed\":%d}", has_open ? open : -1,
                       has_closed ? closed : -1);
            }
            continue;
        }
        printf(" %s ", lsc_arm_name(c->arm, (size_t)i));
        if (step == LSC_CALIB_HOME) {
            printf("offset=%+ld", offset);
        } else if (step == LSC_CALIB_LEAN) {
            printf("dir=%+d", j->direction);
        } else if (step == LSC_CALIB_GRIPPER_OPEN) {
            printf("open=%u", open);
        } else {
            printf("closed=%u", closed);
        }
    }
    if (c->o->json) {
        printf("}}\n");
    } else {
        printf(written ? " (written to %s)\n" : "\n", c->out);
    }
    fflush(stdout);
}

static int write_result(calib *c)
{
    char why[LSC_ARM_MESSAGE_MAX + 64];
    if (lsc_calibrated_write(c->out, c->text, c->len, why, sizeof why) != 0) {
        return lscctl_fail(c->o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    return 0;
}

/* Holds the servos where they are (lsc_device_hold). */
static int hold(lscctl_link *l, const uint8_t *ids, size_t n)
{
    lsc_hold_result res = {.size = sizeof res};
    int r = lsc_device_hold(lscctl_link_device(l), ids, n, &res);
    return r < 0 ? lscctl_link_check(l, r) : 0; /* (held beyond a limit: held all the same) */
}

/* The servos of the whole chain (the gripper's too, when it has one). */
static size_t chain_ids(const calib *c, uint8_t *ids)
{
    int n = lsc_calib_ids(c->arm, LSC_CALIB_HOME, ids, LSC_ARM_CHAIN_MAX, NULL, 0);
    int g = lsc_calib_ids(c->arm, LSC_CALIB_GRIPPER_OPEN, ids + (n > 0 ? n : 0), 1, NULL, 0);
    return (size_t)(n > 0 ? n : 0) + (size_t)(g > 0 ? g : 0);
}

static const char *const prompts[LSC_CALIB_STEPS] = {
    "Hold the arm straight up, every joint at 0 degrees (docs/kinematics.md: the base\n"
    "facing +x, the upper arm, forearm and hand in one vertical line, the wrist roll at\n"
    "its middle).",
    "Lean every joint its positive way by a good amount (20 degrees or more): the\n"
    "shoulder, elbow and wrist forward (toward +x), the base toward +y (counterclockwise\n"
    "seen from above), the wrist roll its positive way.",
    "Close the gripper.",
    "Open the gripper.",
};

/* SIGINT during the walk: it interrupts the prompt's read (no SA_RESTART),
 * which then quits as q does: the servos hold, nothing is written. */
static void on_interrupt(int sig)
{
    (void)sig;
}

/* One line from the owner: 0 (go on), 1 (quit: q, Ctrl-C, or the end of input). */
static int ask(const char *prompt)
{
    char line[64];
    fprintf(stderr, "\n%s\nPress Enter when it is there, or q then Enter to quit without "
                    "writing: ",
            prompt);
    fflush(stderr);
    if (fgets(line, sizeof line, stdin) == NULL) {
        fputc('\n', stderr);
        return 1;
    }
    return line[0] == 'q' || line[0] == 'Q';
}

static int walk(calib *c, lscctl_link *l)
{
    uint8_t ids[LSC_ARM_CHAIN_MAX];
    size_t n = chain_ids(c, ids);
    unsigned steps = n > LSC_KIN_JOINTS ? LSC_CALIB_STEPS : 2u;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt; /* (no SA_RESTART: the prompt's read ends) */
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGINT, &sa, NULL);
    int r = lscctl_link_unload(l, ids, n);
    if (r != 0) {
        return r;
    }
    fprintf(stderr, "The arm's servos are limp: move it by hand. The result goes to %s.\n",
            c->out);
    for (unsigned s = 0; s < steps && r == 0; s++) {
        bool retry = true;
        while (retry && r == 0) {
            if (ask(prompts[s]) != 0) {
                fprintf(stderr, "Nothing was written; the servos hold where they are.\n");
                r = hold(l, ids, n);
                return r != 0 ? r : LSCCTL_EXIT_USAGE;
            }
            r = take_step(c, l, (lsc_calib_step)s, &retry);
        }
        if (r == 0) {
            say(c, (lsc_calib_step)s, false);
        }
    }
    if (r == 0) {
        r = write_result(c);
    }
    if (r == 0) {
        fprintf(stderr, "Written to %s; the servos hold where they are.\n", c->out);
        r = hold(l, ids, n);
    }
    return r;
}

/* v with one decimal: never "-0.0" */
static double one_decimal(float v)
{
    return (double)v > -0.05 && (double)v < 0.05 ? 0.0 : (double)v;
}

/* --check X Y Z: how far where's grasp point is from a point the owner measured. */
static int check(const lscctl_opts *o, lscctl_link *l, char **argv)
{
    static const char *const axes[3] = {"X", "Y", "Z"};
    double v[3];
    char why[160];
    lsc_kin_pose p;
    for (int i = 0; i < 3; i++) {
        if (lscctl_parse_decimal(argv[i], -10000, 10000, axes[i], &v[i], why, sizeof why) != 0) {
            return usage(o, why);
        }
    }
    int r = lscctl_link_check(l, lsc_device_where(lscctl_link_device(l), NULL, &p));
    if (r != 0) {
        return r;
    }
    double dx = (double)p.x_mm - v[0], dy = (double)p.y_mm - v[1], dz = (double)p.z_mm - v[2];
    double off = sqrt(dx * dx + dy * dy + dz * dz);
    if (o->json) {
        printf("{\"x_mm\":%.2f,\"y_mm\":%.2f,\"z_mm\":%.2f,\"off_mm\":%.2f}\n", (double)p.x_mm,
               (double)p.y_mm, (double)p.z_mm, off);
    } else {
        printf("where: x %.1f y %.1f z %.1f mm, %.1f mm from the point measured%s\n",
               one_decimal(p.x_mm), one_decimal(p.y_mm), one_decimal(p.z_mm), off,
               off > CHECK_FAR_MM ? ": more than the servos and the links' lengths explain; "
                                    "calibrate again"
                                  : "");
    }
    return 0;
}

int lscctl_cmd_calibrate(const lscctl_opts *o, int argc, char **argv)
{
    calib c;
    lscctl_link *l = NULL;
    char why[LSC_ARM_MESSAGE_MAX], found[PATH_MAX_];
    lsc_calib_step step = LSC_CALIB_HOME;
    if (o->check != (argc == 3) || (!o->check && argc != 0)) {
        return usage(o, o->check ? "--check takes the point the grasp point is held on: X Y Z "
                                   "in millimetres"
                                 : "calibrate takes no arguments (X Y Z go with --check)");
    }
    if (o->calib_step != NULL && lsc_calib_step_parse(o->calib_step, &step) != 0) {
        lscctl_shown shown;
        char msg[160];
        (void)snprintf(msg, sizeof msg, "--step '%s': use home, lean, gripper-closed or "
                                        "gripper-open",
                       lscctl_show(&shown, o->calib_step));
        return usage(o, msg);
    }
    if (o->check && o->calib_step != NULL) {
        return usage(o, "--check and --step: one at a time");
    }
    if (o->dry_run) {
        return usage(o, "-n: calibration reads the servos, so it has no dry run");
    }
    if (o->check) {
        /* the profile where uses: --arm, else this controller's calibrated one */
        lsc_arm *arm = NULL;
        const char *path = o->arm;
        if (path == NULL && lsc_calibrated_find(o->port, found, sizeof found) == 0) {
            path = found;
        }
        if (path == NULL) {
            return usage(o, "--check needs the arm's profile: --arm FILE, or a calibrated one");
        }
        if (lsc_arm_open(path, &arm, why, sizeof why) != 0) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
        }
        int r = lscctl_link_open(o, &l);
        if (r == 0) {
            r = lscctl_link_check(l, lsc_device_set_arm(lscctl_link_device(l), arm));
        }
        if (r == 0) {
            r = check(o, l, argv);
        }
        lscctl_link_close(l);
        lsc_arm_free(arm);
        return r;
    }
    lsc_kin_chain chain;
    int r = 0;
    memset(&c, 0, sizeof c);
    if (o->out == NULL) { /* the place comes from the controller: its absence is said first */
        r = lscctl_link_open(o, &l);
    }
    if (r == 0) {
        r = calib_open(&c, o);
    }
    if (r == 0 && lsc_arm_chain(c.arm, &chain, NULL, why, sizeof why) != 0) {
        r = lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    if (r == 0 && l == NULL) {
        r = lscctl_link_open(o, &l);
    }
    if (r == 0 && o->calib_step != NULL) {
        r = take_step(&c, l, step, NULL);
        if (r == 0) {
            r = write_result(&c);
        }
        if (r == 0) {
            say(&c, step, true);
        }
    } else if (r == 0) {
        r = walk(&c, l);
    }
    if (l != NULL) {
        lscctl_link_close(l);
    }
    calib_free(&c);
    return r;
}
