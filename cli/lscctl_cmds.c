/* lscctl: the commands that build a frame and talk to a controller. Each
 * checks every argument before it opens a port: bad input exits 2 with
 * nothing sent. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/motion.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lscctl.h"
#include "lscctl_parse.h"
#include "lscctl_port.h"

/* What a command does after sending its frame. */
typedef enum after {
    AFTER_NOTHING,
    AFTER_BATTERY,   /* print the battery voltage */
    AFTER_READ,      /* print the positions of ids[] */
    AFTER_GROUP_END, /* wait for the end of a group */
    AFTER_MONITOR,   /* print notifications */
    AFTER_SETTLE,    /* move --wait: wait for the servos to reach their targets */
    AFTER_OFFSETS    /* print the offsets of ids[] */
} after;

typedef struct job job;
struct job {
    uint8_t frame[LSC_FRAME_MAX]; /* as the client will send it (dry run, --json) */
    size_t n;          /* 0: nothing to send */
    /* sends it through the link; NULL when nothing is sent or what follows
     * sends the request itself (battery, read) */
    int (*send)(lscctl_link *l, const job *j);
    after then;
    bool any_group;    /* AFTER_GROUP_END: the end of any group ends it */
    uint8_t group;     /* run, speed; else the group whose end ends it */
    uint16_t value;    /* move time, run times, speed percent */
    uint8_t cmd;       /* send */
    bool force;        /* send --force */
    lsc_servo servos[LSC_MOVE_MAX]; /* move */
    size_t nservos;
    uint8_t bytes[LSC_PARAMS_MAX]; /* ids (unload, read), parameters (send) */
    size_t nbytes;
    const lsc_arm *arm; /* --arm: read prints degrees */
};

/* The arm profile of --arm or $LSC_ARM into *out (NULL without one; free it
 * with lsc_arm_free). Returns 0 or the exit code after saying why. */
static int load_arm(const lscctl_opts *o, lsc_arm **out)
{
    char why[LSC_ARM_MESSAGE_MAX];
    *out = NULL;
    if (o->arm != NULL && lsc_arm_open(o->arm, out, why, sizeof why) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    return 0;
}

/* A servo's line of read: ID:POSITION, or with --arm JOINT:ANGLEdeg for a
 * joint (the forms move takes). */
static void print_read(const lsc_arm *arm, const lsc_servo *s)
{
    char deg[LSC_ARM_DEGREES_MAX];
    int i = lsc_arm_degrees(arm, s, deg, sizeof deg);
    if (deg[0] != '\0') {
        printf("%s:%sdeg\n", lsc_arm_name(arm, (size_t)i), deg);
    } else {
        printf("%u:%u\n", s->id, s->position);
    }
}

static int send_move(lscctl_link *l, const job *j)
{
    return lscctl_link_check(l, lsc_device_move(lscctl_link_device(l), j->value, j->servos,
                                                j->nservos));
}

static int send_run(lscctl_link *l, const job *j)
{
    return lscctl_link_run(l, j->group, j->value);
}

static int send_stop(lscctl_link *l, const job *j)
{
    (void)j;
    return lscctl_link_check(l, lsc_device_stop(lscctl_link_device(l)));
}

static int send_speed(lscctl_link *l, const job *j)
{
    return lscctl_link_check(l, lsc_device_speed(lscctl_link_device(l), j->group, j->value));
}

static int send_unload(lscctl_link *l, const job *j)
{
    return lscctl_link_check(l, lsc_device_unload(lscctl_link_device(l), j->bytes, j->nbytes));
}

static int send_offset(lscctl_link *l, const job *j)
{
    return lscctl_link_check(
        l, lsc_device_adjust_offset(lscctl_link_device(l), j->bytes[0], (int8_t)j->bytes[1]));
}

/* send 8 and 27 go out only with --force (checked before the port opened) */
static int send_raw(lscctl_link *l, const job *j)
{
    return lscctl_link_check(l, lsc_device_send(lscctl_link_device(l), j->cmd, j->bytes,
                                                j->nbytes, j->force));
}

static int usage(const lscctl_opts *o, const char *why)
{
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s (see 'lscctl help %s')", why, o->cmd);
}

/* usage(why) for an argument refused by the arm profile's rules; when it
 * was refused without a profile (arg non-NULL) for want of one
 * (lsc_arm_needs_profile), with the option that gives one: after `joint`
 * for a joint's name (the words of why do not say it: "; a joint name needs
 * an arm profile"; they do: ""). */
static int usage_arm(const lscctl_opts *o, const char *why, const char *arg, const char *joint)
{
    lsc_arm_need need = arg != NULL ? lsc_arm_needs_profile(arg) : LSC_ARM_NEEDS_NONE;
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s%s%s (see 'lscctl help %s')", why,
                       need == LSC_ARM_NEEDS_JOINT     ? joint
                       : need == LSC_ARM_NEEDS_DEGREES ? "; or give an arm profile"
                                                       : "",
                       need != LSC_ARM_NEEDS_NONE ? " (--arm FILE)" : "", o->cmd);
}

/* A notification as a message line (text or JSON). */
static void print_notification(const lscctl_opts *o, const lsc_notification *n)
{
    uint8_t frame[LSC_FRAME_MAX];
    lscctl_msg m;
    char why[96];
    int len = n->cmd == LSC_CMD_GROUP_STOP
                  ? lsc_encode_group_stop(frame, sizeof frame)
              : n->cmd == LSC_CMD_GROUP_RUN
                  ? lsc_encode_group_run(frame, sizeof frame, n->group, n->times)
                  : lsc_encode_group_complete(frame, sizeof frame, n->group, n->times);
    lsc_frame f = {frame[3], (uint8_t)(len - 4), &frame[4]};
    if (lscctl_msg_decode(&m, &f, LSCCTL_DIR_CONTROLLER, why, sizeof why) == 0) {
        lscctl_msg_print(stdout, &m, o->json, false, NULL);
    }
    fflush(stdout);
}

typedef struct monitor_count {
    const lscctl_opts *o;
    unsigned long seen;
} monitor_count;

static bool on_notification(void *user, const lsc_notification *n)
{
    monitor_count *c = user;
    print_notification(c->o, n);
    return c->o->count == 0 || ++c->seen < c->o->count;
}

/* After the frame went out: read and print what the command asks for. */
static int follow_up(const lscctl_opts *o, const job *j, lscctl_link *l)
{
    lscctl_msg m;
    lsc_notification n;
    monitor_count count = {o, 0};
    int r;
    memset(&m, 0, sizeof m);
    m.dir = LSCCTL_DIR_CONTROLLER;
    m.reply = true;
    switch (j->then) {
    case AFTER_BATTERY:
        r = lscctl_link_check(l, lsc_device_battery(lscctl_link_device(l), &m.millivolts));
        if (r == 0 && !o->json) {
            printf("%u.%03u V (%u mV)\n", m.millivolts / 1000u, m.millivolts % 1000u,
                   m.millivolts);
        }
        m.cmd = LSC_CMD_BATTERY;
        break;
    case AFTER_READ:
        r = lscctl_link_check(l, lsc_device_read(lscctl_link_device(l), j->bytes, j->nbytes,
                                                 m.servos));
        m.nservos = j->nbytes;
        m.arm = j->arm; /* JSON: joints and angles beside the positions */
        for (size_t i = 0; r == 0 && !o->json && i < j->nbytes; i++) {
            print_read(j->arm, &m.servos[i]);
        }
        m.cmd = LSC_CMD_POS_READ;
        break;
    case AFTER_GROUP_END:
        r = lscctl_link_wait_group(l, j->any_group, j->group, &n);
        if (r == 0) {
            print_notification(o, &n);
        }
        return r;
    case AFTER_MONITOR: return lscctl_link_monitor(l, on_notification, &count);
    case AFTER_OFFSETS:
        r = lscctl_link_check(l, lsc_device_read_offsets(lscctl_link_device(l), j->bytes,
                                                         j->nbytes, m.offsets));
        m.noffsets = j->nbytes;
        for (size_t i = 0; r == 0 && !o->json && i < j->nbytes; i++) {
            printf("%u:%d\n", m.offsets[i].id, m.offsets[i].offset);
        }
        m.cmd = LSC_CMD_OFFSET_READ;
        break;
    case AFTER_SETTLE:
        if (o->json) {
            lscctl_frame_print(stdout, j->frame, j->n, true, false);
        }
        return lscctl_link_settle(l, j->servos, j->nservos, j->value, (uint16_t)o->tolerance);
    default:
        if (o->json) {
            lscctl_frame_print(stdout, j->frame, j->n, true, false);
        }
        return 0;
    }
    if (r == 0 && o->json) {
        m.name = lsc_device_cmd_name(m.cmd);
        lscctl_msg_print(stdout, &m, true, false, NULL);
    }
    return r;
}

/* Dry run: print the frame. Else open the port, send it, then what follows. */
static int finish(const lscctl_opts *o, const job *j)
{
    lsc_device_kind kind;
    if (o->dry_run && lsc_device_kind_of_name(o->port, &kind) == 0 && kind == LSC_DEVICE_LX) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "--dry-run prints a board's frames; a bus of servos (lx:PATH) gets "
                           "others: -v shows the frames sent");
    }
    if (o->dry_run) {
        if (j->n > 0) {
            lscctl_dry_run_print(stdout, j->frame, j->n, o->json);
        }
        return LSCCTL_EXIT_OK;
    }
    lscctl_link *l;
    int r = lscctl_link_open(o, &l);
    if (r != 0) {
        return r;
    }
    if (j->send != NULL) {
        r = j->send(l, j);
    }
    if (r == 0) {
        r = follow_up(o, j, l);
    }
    lscctl_link_close(l);
    return r;
}

/* Encoder result check: the command's own checks come first, so a failure
 * here means a combination they did not foresee. */
static int encoded(const lscctl_opts *o, job *j, int n)
{
    if (n < 0) {
        return usage(o, lsc_strerror(n));
    }
    j->n = (size_t)n;
    return finish(o, j);
}

/* Whether arg is a list of servos rather than one: "all", commas, a range. */
static bool id_list(const char *arg)
{
    return strcmp(arg, "all") == 0 || strchr(arg, ',') != NULL ||
           (arg[0] != '-' && strchr(arg, '-') != NULL);
}

/* The servos of argv[0..argc): each an id or a joint's name, or a list of
 * them (lsc_device_parse_ids_all: "all", "1-6", "1,3-5", "base,2"), into
 * ids[0..max); *n their number. */
static int parse_ids(const lscctl_opts *o, int argc, char **argv, uint8_t *ids, size_t max,
                     const lsc_arm *arm, size_t *n)
{
    char why[LSC_ARM_MESSAGE_MAX];
    uint8_t some[LSC_UNLOAD_MAX];
    size_t count = 0;
    for (int i = 0; i < argc; i++) {
        if (!id_list(argv[i])) {
            if (lsc_arm_servo_id(arm, argv[i], &some[0], why, sizeof why) != 0) {
                return usage_arm(o, why, arm == NULL ? argv[i] : NULL,
                                 "; a joint name needs an arm profile");
            }
            if (count < max) {
                ids[count] = some[0];
            }
            count++;
            continue;
        }
        int got = lsc_device_parse_ids_all(arm, o->port, argv[i], some, sizeof some, why,
                                           sizeof why);
        if (got == LSC_ENODEV) {
            return usage(o, "'all' stands for the controller's servos, which its kind tells: "
                            "name it with --port (or $LSC_PORT), or give --arm FILE");
        }
        if (got < 0) {
            return usage(o, why);
        }
        for (size_t k = 0; k < (size_t)got; k++, count++) {
            if (count < max) {
                ids[count] = some[k];
            }
        }
    }
    if (count > max || count == 82) {
        snprintf(why, sizeof why,
                 count == 82 ? "82 ids cannot be sent in one frame (its length byte would be "
                               "0x55): split them over two commands"
                             : "too many ids for one frame: at most %zu",
                 max);
        return usage(o, why);
    }
    size_t rep = lsc_ids_first_repeat(ids, 1, count);
    if (rep < count) {
        snprintf(why, sizeof why, "id %u is given twice: give each id once", ids[rep]);
        return usage(o, why);
    }
    *n = count;
    return 0;
}

int lscctl_cmd_move(const lscctl_opts *o, int argc, char **argv)
{
    char why[LSC_ARM_MESSAGE_MAX];
    job j = {.then = o->wait ? AFTER_SETTLE : AFTER_NOTHING, .send = send_move,
             .value = (uint16_t)o->time_ms, .nservos = (size_t)argc};
    lsc_servo *servos = j.servos;
    lsc_arm *a;
    int r = load_arm(o, &a);
    if (r != 0) {
        return r;
    }
    if (argc > (int)LSC_MOVE_MAX) {
        lsc_arm_free(a);
        snprintf(why, sizeof why, "%d servos do not fit in one frame: at most %u per move", argc,
                 LSC_MOVE_MAX);
        return usage(o, why);
    }
    int failed = 0;
    for (int i = 0; i < argc && r == 0; i++) {
        r = lsc_arm_target(a, argv[i], &servos[i], why, sizeof why);
        failed = i;
    }
    bool without = a == NULL;
    lsc_arm_free(a);
    if (r != 0) {
        return usage_arm(o, why, without ? argv[failed] : NULL, "");
    }
    size_t rep = lsc_ids_first_repeat(&servos[0].id, sizeof servos[0], (size_t)argc);
    if (rep < (size_t)argc) {
        snprintf(why, sizeof why, "servo %u is given twice: give each id once", servos[rep].id);
        return usage(o, why);
    }
    r = lscctl_hid_move_bound(o, j.nservos, "");
    if (r != 0) {
        return r;
    }
    if (o->deg_speed > 0) { /* the time from where the servos are: lscctl_reach.c */
        return lscctl_move_at_speed(o, servos, j.nservos);
    }
    return encoded(o, &j,
                   lsc_encode_servo_move(j.frame, sizeof j.frame, j.value, servos, j.nservos));
}

static int parse_group(const lscctl_opts *o, const char *s, bool all_ok, uint8_t *group)
{
    unsigned long v;
    char why[160];
    if (all_ok && strcmp(s, "all") == 0) {
        *group = LSC_GROUP_ALL;
        return 0;
    }
    if (lscctl_parse_uint(s, 255, "group", &v, why, sizeof why) != 0) {
        return usage(o, why);
    }
    *group = (uint8_t)v;
    return 0;
}

int lscctl_cmd_run(const lscctl_opts *o, int argc, char **argv)
{
    job j = {.then = o->wait ? AFTER_GROUP_END : AFTER_NOTHING, .send = send_run,
             .value = (uint16_t)o->times};
    (void)argc;
    int r = parse_group(o, argv[0], false, &j.group);
    if (r != 0) {
        return r;
    }
    return encoded(o, &j, lsc_encode_group_run(j.frame, sizeof j.frame, j.group, j.value));
}

/* A command without arguments: its frame's encoder (NULL: it sends nothing)
 * and what follows. */
static int plain(const lscctl_opts *o, after then, int (*encode)(uint8_t *buf, size_t cap),
                 int (*send)(lscctl_link *l, const job *j))
{
    job j = {.then = then, .any_group = true, .send = send};
    return encode != NULL ? encoded(o, &j, encode(j.frame, sizeof j.frame)) : finish(o, &j);
}

int lscctl_cmd_stop(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return plain(o, AFTER_NOTHING, lsc_encode_group_stop, send_stop);
}

/* halt and hold: LSC_HOLD_BEYOND (a joint held beyond its limits) is said
 * on stderr, and is no failure. */
static int held(lscctl_link *l, int r)
{
    if (r == LSC_HOLD_BEYOND) {
        fflush(stdout);
        fprintf(stderr, "lscctl: %s: %s\n", lscctl_link_opts(l)->cmd,
                lsc_device_error(lscctl_link_device(l)));
        return 0;
    }
    return lscctl_link_check(l, r);
}

/* The device knows --arm's profile (its joints' limits: which one is held
 * beyond them); "sim" was given it at the open. */
static int with_arm(lscctl_link *l)
{
    lsc_device *d = lscctl_link_device(l);
    return lsc_device_arm(d) != NULL ? 0 : lscctl_set_arm(lscctl_link_opts(l), d);
}

static int send_halt(lscctl_link *l, const job *j)
{
    (void)j;
    int r = with_arm(l);
    return r != 0 ? r : held(l, lsc_device_halt(lscctl_link_device(l)));
}

static int send_hold(lscctl_link *l, const job *j)
{
    int r = with_arm(l);
    return r != 0 ? r
                  : held(l, lsc_device_hold(lscctl_link_device(l), j->bytes, j->nbytes, NULL));
}

int lscctl_cmd_halt(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return plain(o, AFTER_NOTHING, lsc_encode_group_stop, send_halt);
}

int lscctl_cmd_hold(const lscctl_opts *o, int argc, char **argv)
{
    job j = {.then = AFTER_NOTHING, .send = send_hold};
    lsc_arm *arm;
    int r = load_arm(o, &arm);
    if (r == 0 && argc == 0) { /* without ids: all */
        static char all[] = "all";
        char *every[] = {all};
        r = parse_ids(o, 1, every, j.bytes, LSC_MOVE_MAX, arm, &j.nbytes);
    } else if (r == 0) {
        r = parse_ids(o, argc, argv, j.bytes, LSC_MOVE_MAX, arm, &j.nbytes);
    }
    lsc_arm_free(arm);
    if (r != 0) {
        return r;
    }
    r = lscctl_hid_move_bound(o, j.nbytes, "");
    /* nothing to show for -n: the move holds positions it reads first */
    return r != 0 ? r : finish(o, &j);
}

int lscctl_cmd_battery(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return plain(o, AFTER_BATTERY, lsc_encode_battery_request, NULL);
}

int lscctl_cmd_wait(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return plain(o, AFTER_GROUP_END, NULL, NULL);
}

int lscctl_cmd_monitor(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return plain(o, AFTER_MONITOR, NULL, NULL);
}

int lscctl_cmd_speed(const lscctl_opts *o, int argc, char **argv)
{
    job j = {.then = AFTER_NOTHING, .send = send_speed};
    unsigned long percent;
    char why[160];
    (void)argc;
    int r = parse_group(o, argv[0], true, &j.group);
    if (r != 0) {
        return r;
    }
    if (lscctl_parse_uint(argv[1], 65535, "percent", &percent, why, sizeof why) != 0) {
        return usage(o, why);
    }
    if (percent == 0) { /* a step's time is divided by the percent */
        return usage(o, "speed 0 is no speed: use 1..65535 percent (100 = original speed)");
    }
    j.value = (uint16_t)percent;
    return encoded(o, &j, lsc_encode_group_speed(j.frame, sizeof j.frame, j.group, j.value));
}

int lscctl_cmd_unload(const lscctl_opts *o, int argc, char **argv)
{
    job j = {.then = AFTER_NOTHING, .send = send_unload};
    lsc_arm *arm;
    int r = load_arm(o, &arm);
    if (r == 0) {
        r = parse_ids(o, argc, argv, j.bytes, LSC_UNLOAD_MAX, arm, &j.nbytes);
    }
    lsc_arm_free(arm);
    if (r != 0) {
        return r;
    }
    return encoded(o, &j, lsc_encode_unload(j.frame, sizeof j.frame, j.bytes, j.nbytes));
}

int lscctl_cmd_read(const lscctl_opts *o, int argc, char **argv)
{
    job j = {.then = AFTER_READ};
    lsc_arm *arm;
    int r = load_arm(o, &arm);
    j.arm = arm;
    if (r == 0) {
        r = parse_ids(o, argc, argv, j.bytes, LSC_READ_MAX, j.arm, &j.nbytes);
    }
    if (r == 0) {
        r = encoded(o, &j, lsc_encode_pos_request(j.frame, sizeof j.frame, j.bytes, j.nbytes));
    }
    lsc_arm_free(arm);
    return r;
}

int lscctl_cmd_send(const lscctl_opts *o, int argc, char **argv)
{
    unsigned long cmd, v;
    char why[160];
    job j = {.then = AFTER_NOTHING, .send = send_raw};
    if (lscctl_parse_uint(argv[0], 255, "command", &cmd, why, sizeof why) != 0) {
        return usage(o, why);
    }
    if (cmd == LSC_CMD_GROUP_COMPLETE && !o->force) {
        return usage(o, "command 8 erases the action groups on xArm firmware; add --force "
                        "if that is what you want");
    }
    if (cmd == LSCCTL_CMD_WRITE_ALL && !o->force) {
        return usage(o, "command 27 writes a setting (such as the servo id) to every servo on "
                        "the bus at once on xArm firmware; add --force if that is what you want");
    }
    size_t n = (size_t)argc - 1u;
    if (n > LSC_PARAMS_MAX || n == 83) {
        snprintf(why, sizeof why,
                 n == 83 ? "83 bytes cannot be sent in one frame (its length byte would be "
                           "0x55)"
                         : "too many bytes for one frame: at most %u",
                 LSC_PARAMS_MAX);
        return usage(o, why);
    }
    for (size_t i = 0; i < n; i++) {
        if (lscctl_parse_uint(argv[i + 1], 255, "byte", &v, why, sizeof why) != 0) {
            return usage(o, why);
        }
        j.bytes[i] = (uint8_t)v;
    }
    j.cmd = (uint8_t)cmd;
    j.force = o->force;
    j.nbytes = n;
    return encoded(o, &j, lsc_encode_frame(j.frame, sizeof j.frame, j.cmd, j.bytes, n));
}

int lscctl_cmd_ports(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return o->dry_run ? LSCCTL_EXIT_OK : lscctl_list_ports(o);
}

/* offset read ID... | offset set ID VALUE: the xArm's servo offsets (23, 24).
 * With --arm, ID may be a joint's name. */
static int offset_read(const lscctl_opts *o, const lsc_arm *arm, int argc, char **argv)
{
    job j = {.then = AFTER_OFFSETS};
    if (argc == 0) {
        return usage(o, "offset read needs the servos: offset read ID...");
    }
    if (argc > (int)LSC_OFFSET_MAX) {
        char why[80];
        snprintf(why, sizeof why, "too many ids for one offset read: at most %u",
                 LSC_OFFSET_MAX);
        return usage(o, why);
    }
    int r = parse_ids(o, argc, argv, j.bytes, LSC_OFFSET_MAX, arm, &j.nbytes);
    if (r != 0) {
        return r;
    }
    return encoded(o, &j, lsc_encode_offset_request(j.frame, sizeof j.frame, j.bytes, j.nbytes));
}

static int offset_set(const lscctl_opts *o, const lsc_arm *arm, int argc, char **argv)
{
    char why[LSC_ARM_MESSAGE_MAX];
    unsigned long v;
    job j = {.then = AFTER_NOTHING, .send = send_offset, .nbytes = 2};
    if (argc != 2) {
        return usage(o, "offset set takes ID VALUE");
    }
    if (lsc_arm_servo_id(arm, argv[0], &j.bytes[0], why, sizeof why) != 0) {
        return usage_arm(o, why, arm == NULL ? argv[0] : NULL,
                         "; a joint name needs an arm profile");
    }
    bool neg = argv[1][0] == '-';
    if (lscctl_parse_uint(argv[1] + neg, neg ? 128 : 127, "offset", &v, why, sizeof why) != 0) {
        char value[4u * 40u + 1u];
        (void)lsc_escape_text(value, sizeof value, argv[1], strlen(argv[1]));
        snprintf(why, sizeof why, "offset '%s': use -128..127", value);
        return usage(o, why);
    }
    long signed_value = neg ? -(long)v : (long)v; /* -128..127 */
    int8_t offset = (int8_t)signed_value;
    j.bytes[1] = (uint8_t)offset;
    return encoded(o, &j, lsc_encode_offset_adjust(j.frame, sizeof j.frame, j.bytes[0], offset));
}

int lscctl_cmd_offset(const lscctl_opts *o, int argc, char **argv)
{
    bool read = strcmp(argv[0], "read") == 0;
    if (!read && strcmp(argv[0], "set") != 0) {
        char what[4u * 40u + 1u], why[300];
        (void)lsc_escape_text(what, sizeof what, argv[0], strlen(argv[0]));
        snprintf(why, sizeof why,
                 "'%s' is neither read nor set: use 'offset read ID...' or 'offset set ID "
                 "VALUE'",
                 what);
        return usage(o, why);
    }
    lsc_arm *arm;
    int r = load_arm(o, &arm);
    if (r == 0) {
        r = read ? offset_read(o, arm, argc - 1, argv + 1) : offset_set(o, arm, argc - 1, argv + 1);
    }
    lsc_arm_free(arm);
    return r;
}
