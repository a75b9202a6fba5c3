/* lscctl: the port a command talks to, over the library's device layer
 * (lsc/device.h): opening it, -v tracing, the ports listing, and every error
 * of the device turned into one line on stderr, with lscctl's hints, and an
 * exit code. */
#include "lscctl_port.h"
#include "lsc/motion.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/discovery.h"
#include "lsc/env.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct lscctl_link {
    const lscctl_opts *o;
    lsc_device *d;
    uint8_t run_group; /* the group lscctl_link_run ran, for messages */
};


/* What to do when no port is given. */
static const char no_port_hint[] =
    "choose one with --port PATH (see 'lscctl ports') or set LSC_PORT (a HID controller: "
    "--port hid:SERIAL); --port sim is the built-in virtual controller";

/* The exit code of a device error. */
static int exit_code(int err)
{
    return err == LSC_EINVAL     ? LSCCTL_EXIT_USAGE
           : err == LSC_ETIMEOUT ? LSCCTL_EXIT_TIMEOUT
           : err == LSC_EBUSY    ? LSCCTL_EXIT_BUSY
                                 : LSCCTL_EXIT_FAIL;
}

/* Prints the device's error as it is, then the lscctl options that its
 * cause says would help (from the cause: never from the message's words),
 * then hint. Returns code. */
static int say(const lscctl_opts *o, int code, lsc_device_cause cause, const char *msg,
               const char *hint)
{
    const char *options = "";
    switch (cause) {
    case LSC_DEVICE_CAUSE_NO_REPLY:
    case LSC_DEVICE_CAUSE_OTHER_FRAMES:
    case LSC_DEVICE_CAUSE_ONLY_NOTIFICATIONS:
    case LSC_DEVICE_CAUSE_LSCD_NO_REPLY: options = " (--timeout MS)"; break;
    case LSC_DEVICE_CAUSE_NOISE: options = " (--baud N, --timeout MS)"; break;
    case LSC_DEVICE_CAUSE_NOT_SETTLED: options = " (--timeout MS, --tolerance N)"; break;
    default: break;
    }
    return lscctl_fail(o, code, "%s%s%s", msg, options, hint);
}

/* The virtual controller's groups as "1, 2 and 8". */
static void sim_groups(lsc_device *d, char *out, size_t cap)
{
    uint8_t groups[255];
    size_t total = lsc_device_groups(d, groups, sizeof groups), len = 0;
    out[0] = '\0';
    for (size_t i = 0; i < total && i < sizeof groups && len < cap; i++) {
        int w = snprintf(out + len, cap - len, "%s%u",
                         i == 0 ? "" : i + 1u == total ? " and " : ", ", groups[i]);
        len += w > 0 ? (size_t)w : 0u;
    }
}

int lscctl_link_check(lscctl_link *l, int r)
{
    const lscctl_opts *o = l->o;
    char groups[64];
    if (r >= 0) {
        return 0;
    }
    switch (lsc_device_error_cause(l->d)) {
    case LSC_DEVICE_CAUSE_SIM_FOREVER:
        return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                           "group %u loops forever (--times 0) and nothing else on the virtual "
                           "controller (--port sim) can stop it, so the wait would never end: "
                           "give --times N, or --timeout MS",
                           l->run_group);
    case LSC_DEVICE_CAUSE_NEVER_STARTED:
        return say(o, LSCCTL_EXIT_NEVER_STARTED, LSC_DEVICE_CAUSE_NEVER_STARTED,
                   lsc_device_error(l->d), "");
    case LSC_DEVICE_CAUSE_SIM_NO_GROUP:
        sim_groups(l->d, groups, sizeof groups);
        return lscctl_fail(o, LSCCTL_EXIT_NEVER_STARTED,
                           "the virtual controller (--port sim) has no group %u, so it never "
                           "starts: its groups are %s",
                           l->run_group, groups);
    case LSC_DEVICE_CAUSE_SIM_IDLE:
        sim_groups(l->d, groups, sizeof groups);
        return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                           "nothing runs on the virtual controller (--port sim, groups %s), so "
                           "nothing will arrive: start a group in the same command (run GROUP "
                           "--wait), or serve it with lsc-sim",
                           groups);
    default:
        return say(o, exit_code(r), lsc_device_error_cause(l->d), lsc_device_error(l->d), "");
    }
}

/* A wait's result r: its timeout said in lscctl's words (what within
 * --timeout), any other error as lscctl_link_check says it. */
static int waited(lscctl_link *l, int r, const char *what)
{
    if (r == LSC_ETIMEOUT && lsc_device_error_cause(l->d) == LSC_DEVICE_CAUSE_WAIT_TIMEOUT) {
        return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                           "%s within %lu ms; raise --timeout, or leave it out to wait without "
                           "limit",
                           what, l->o->timeout_ms);
    }
    return lscctl_link_check(l, r);
}

/* Every frame sent and received, with -v: on stderr, hex and meaning. */
static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    const lscctl_link *l = user;
    lsc_frame f = {frame[3], (uint8_t)(n - 4u), &frame[4]};
    lscctl_msg m;
    char why[96], hex[LSCCTL_HEX_MAX];
    lscctl_hex(hex, sizeof hex, frame, n);
    fputs(dir == LSC_TRACE_TX ? "lscctl: sent " : "lscctl: received ", stderr);
    if (lsc_device_kind_of(l->d) == LSC_DEVICE_LX) { /* 55 55 ID LEN CMD ...: a bus's frame */
        fprintf(stderr, "bus frame: servo %u, command %u (%s)\n", frame[2], frame[4], hex);
        return;
    }
    if (lscctl_msg_decode(&m, &f, dir == LSC_TRACE_TX ? LSCCTL_DIR_HOST : LSCCTL_DIR_CONTROLLER,
                          why, sizeof why) == 0) {
        lscctl_msg_print(stderr, &m, false, false, hex);
    } else {
        fprintf(stderr, "%s (%s)\n", why, hex);
    }
}

/* A write failed as a signal that ends lscctl came: say why now, the process
 * ends when the write returns. */
static void last_word(void *user, const lsc_device *d)
{
    lscctl_link *l = user;
    (void)d;
    (void)lscctl_link_check(l, LSC_EIO);
}

/* The controllers present, as "NAME (serial number S), ..." (for several
 * found without --port). */
static void controllers(char *out, size_t cap)
{
    lsc_device_info **all = NULL;
    size_t len = 0, found = 0;
    out[0] = '\0';
    (void)lsc_device_list(&all, NULL, 0); /* (none on an error) */
    for (size_t i = 0; all != NULL && all[i] != NULL && len < cap; i++) {
        if (lsc_device_info_controller(all[i])) {
            const char *n = lsc_device_info_name(all[i]), *sn = lsc_device_info_serial(all[i]);
            char name[4u * LSC_DEVICE_NAME_MAX], serial[4u * 128u];
            (void)lsc_escape_text(name, sizeof name, n, strlen(n));
            (void)lsc_escape_text(serial, sizeof serial, sn, strlen(sn));
            int w = snprintf(out + len, cap - len, "%s%s (serial number %s)",
                             found++ == 0 ? "" : ", ", name, *serial != '\0' ? serial : "none");
            len += w > 0 ? (size_t)w : 0u;
        }
    }
    lsc_device_list_free(all);
}

/* Why the open failed (r), with lscctl's hints; d is NULL: what the calling
 * thread's last open said. */
static int open_failed(const lscctl_opts *o, lsc_device *d, int r)
{
    lsc_device_cause cause = lsc_device_error_cause(d);
    const char *msg = lsc_device_error(d);
    if (cause == LSC_DEVICE_CAUSE_NO_CONTROLLER) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "no port given and none looks like a controller: %s", no_port_hint);
    }
    if (cause == LSC_DEVICE_CAUSE_SEVERAL && o->port == NULL) {
        char list[1024];
        controllers(list, sizeof list);
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "no port given and several look like a controller: %s; they are: %s",
                           no_port_hint, list);
    }
    if (o->port == NULL && *lsc_device_name(d) == '\0') { /* no listing */
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "no port given: %s; %s", msg, no_port_hint);
    }
    const char *hint = "";
    if (lsc_device_kind_of(d) == LSC_DEVICE_HID) {
        hint = cause == LSC_DEVICE_CAUSE_SEVERAL ? ": --port hid:SERIAL (see 'lscctl ports')"
               : r == LSC_ENODEV ? " ('lscctl ports' lists the controllers; --port sim is the "
                                   "built-in virtual controller)"
                                 : "";
    } else if (r == LSC_ENODEV) {
        hint = " ('lscctl ports' lists the serial ports; --port sim is the built-in virtual "
               "controller)";
    } else if (r == LSC_EINVAL && cause != LSC_DEVICE_CAUSE_NAME_TOO_LONG) {
        hint = " (check --port, and use a standard --baud such as 9600)";
    }
    return say(o, exit_code(r), cause, msg, hint);
}

/* The arm profile of --arm or $LSC_ARM on d (none without one). Returns 0
 * or the exit code after saying why. */
int lscctl_set_arm(const lscctl_opts *o, lsc_device *d)
{
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    if (o->arm == NULL) {
        return 0;
    }
    if (lsc_arm_open(o->arm, &arm, why, sizeof why) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    int r = lsc_device_set_arm(d, arm);
    lsc_arm_free(arm);
    return r == 0 ? 0 : lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
}

int lscctl_link_open(const lscctl_opts *o, lscctl_link **out)
{
    lsc_device_config *cfg = lsc_device_config_new();
    lscctl_link *l = calloc(1, sizeof *l);
    lsc_device *d = NULL;
    if (l == NULL || cfg == NULL) {
        free(l);
        lsc_device_config_free(cfg);
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
    }
    /* (the options' ranges are the setters': lscctl.c parses them so) */
    (void)lsc_device_config_set_baud(cfg, (uint32_t)o->baud);
    (void)lsc_device_config_set_timeout_ms(cfg, (uint32_t)o->timeout_ms);
    (void)lsc_device_config_set_hid_id(cfg, o->hid_vid, o->hid_pid);
    (void)lsc_device_config_from_env(cfg, NULL, 0); /* (checked by main) */
    int r = lsc_device_open(o->port, cfg, &d);
    lsc_device_config_free(cfg);
    if (r != 0) { /* no handle: lsc_device_error(NULL) and the rest say why */
        free(l);
        return open_failed(o, NULL, r);
    }
    /* the built-in virtual controller, fresh for each command, runs on its
     * virtual clock (waits take no time); --arm makes it that arm */
    (void)lsc_device_set_virtual_clock(d, true); /* (LSC_EINVAL for the other kinds) */
    if (lsc_device_kind_of(d) == LSC_DEVICE_SIM && (r = lscctl_set_arm(o, d)) != 0) {
        lsc_device_close(d);
        free(l);
        return r;
    }
    l->o = o;
    l->d = d;
    if (o->verbose) {
        lsc_device_set_trace(d, trace, l);
    }
    lsc_device_set_last_word(d, last_word, l);
    *out = l;
    return 0;
}

void lscctl_link_close(lscctl_link *l)
{
    lsc_device_close(l->d);
    free(l);
}

const lscctl_opts *lscctl_link_opts(const lscctl_link *l)
{
    return l->o;
}

lsc_device *lscctl_link_device(lscctl_link *l)
{
    return l->d;
}

int lscctl_link_run(lscctl_link *l, uint8_t group, uint16_t times)
{
    l->run_group = group;
    return lscctl_link_check(l, lsc_device_run(l->d, group, times));
}

int lscctl_link_unload(lscctl_link *l, const uint8_t *ids, size_t n)
{
    return lscctl_link_check(l, lsc_device_unload(l->d, ids, n));
}

int lscctl_link_settled(lscctl_link *l, int r, const lsc_settle_result *res)
{
    const lscctl_opts *o = l->o;
    if (r == LSC_SETTLE_NO_READS && o->verbose) { /* the controller does not report positions */
        (void)lscctl_fail(o, 0, "%s", lsc_device_error(l->d));
    }
    if (r == LSC_SETTLE_STOPPED || lsc_device_error_cause(l->d) == LSC_DEVICE_CAUSE_STOPPED_SHORT) {
        if (o->json) { /* {"stopped":[{"id":1,"position":600,"target":700,"short":100}]} */
            fputs("{\"stopped\":[", stdout);
            for (size_t i = 0; i < res->nstopped; i++) {
                const lsc_settle_stop *s = &res->stopped[i];
                printf("%s{\"id\":%u,\"position\":%u,\"target\":%u,\"short\":%d}",
                       i == 0 ? "" : ",", s->id, s->position, s->target,
                       s->position > s->target ? s->position - s->target
                                               : s->target - s->position);
            }
            fputs("]}\n", stdout);
        }
        return lscctl_fail(o, r < 0 ? LSCCTL_EXIT_TIMEOUT : LSCCTL_EXIT_OK, "%s%s",
                           lsc_device_error(l->d), r < 0 ? " (--strict)" : "");
    }
    return lscctl_link_check(l, r);
}

int lscctl_link_settle(lscctl_link *l, const lsc_servo *targets, size_t n, uint16_t time_ms,
                       uint16_t tolerance)
{
    lsc_settle_result res = {.size = sizeof res};
    int r = lsc_device_settle_ex(l->d, targets, n, time_ms, tolerance,
                                 l->o->strict ? LSC_SETTLE_STRICT : 0u, &res);
    return lscctl_link_settled(l, r, &res);
}

unsigned long lscctl_baud(const lscctl_opts *o)
{
    lsc_device_kind kind;
    if (o->baud != 0) {
        return o->baud;
    }
    return lsc_device_kind_of_name(o->port, &kind) == 0 && kind == LSC_DEVICE_LX ? 115200ul
                                                                                 : 9600ul;
}

int lscctl_hid_move_bound(const lscctl_opts *o, size_t n, const char *what)
{
    lsc_device_kind kind;
    if (n <= LSC_DEVICE_HID_MOVE_MAX || lsc_device_kind_of_name(o->port, &kind) != 0 ||
        kind != LSC_DEVICE_HID) {
        return 0;
    }
    lscctl_shown port;
    return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                       "%s%s%lu servos in one move on %s: at most %u servos in one move over "
                       "HID (a 64-byte report)%s",
                       what, *what != '\0' ? ": " : "", (unsigned long)n,
                       lscctl_show(&port, o->port), LSC_DEVICE_HID_MOVE_MAX,
                       *what != '\0' ? "" : ": split it over two moves");
}

int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out)
{
    const lscctl_opts *o = l->o;
    uint32_t limit = o->timeout_set ? (uint32_t)o->timeout_ms : LSC_DEVICE_FOREVER;
    /* after a run, a start that does not come within lsc_device_start_ms ends
     * the wait: the group never started (exit 5) */
    int r = lsc_device_wait_group(l->d, any ? LSC_GROUP_ALL : group, limit, out);
    return r == 0 ? 0 : waited(l, r, "no action group ended");
}

int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user)
{
    const lscctl_opts *o = l->o;
    uint32_t limit = o->timeout_set ? (uint32_t)o->timeout_ms : LSC_DEVICE_FOREVER;
    lsc_notification n;
    for (;;) {
        /* with --timeout: that long since the last notification */
        int r = lsc_device_notification(l->d, limit, &n);
        if (r != 0) {
            return waited(l, r, "nothing arrived");
        }
        if (!fn(user, &n)) {
            return 0;
        }
    }
}

/* What print_port shows of an info (lsc/discovery.h's accessors). */
typedef struct port_view {
    const char *name, *path, *description, *serial, *manufacturer;
    unsigned vid, pid;
    bool usb, controller;
} port_view;

static void print_port(const lscctl_opts *o, const lsc_device_info *info)
{
    const port_view port = {lsc_device_info_name(info), lsc_device_info_path(info),
              lsc_device_info_description(info), lsc_device_info_serial(info),
              lsc_device_info_manufacturer(info), lsc_device_info_vid(info),
              lsc_device_info_pid(info), lsc_device_info_usb(info),
              lsc_device_info_controller(info)};
    const port_view *p = &port;
    if (lsc_device_info_kind(info) == LSC_DEVICE_HID) {
        if (o->json) {
            /* the description the text shows: the product, and the link */
            char description[128 + 16];
            (void)snprintf(description, sizeof description, "%s (USB HID)",
                           *p->description ? p->description : "-");
            fputs("{\"path\":", stdout);
            lscctl_json_string(stdout, p->path);
            fputs(",\"description\":", stdout);
            lscctl_json_string(stdout, description);
            printf(",\"vid\":\"%04x\",\"pid\":\"%04x\",\"serial\":", p->vid, p->pid);
            lscctl_json_string(stdout, p->serial);
            fputs(",\"manufacturer\":", stdout);
            lscctl_json_string(stdout, p->manufacturer);
            fputs(",\"hid\":true,\"port\":", stdout);
            lscctl_json_string(stdout, p->name);
            puts(",\"controller\":true}");
        } else {
            printf("%s\t%s (USB HID)\t%04x:%04x\t%s\tcontroller (--port %s)\n", p->path,
                   *p->description ? p->description : "-", p->vid, p->pid,
                   *p->serial ? p->serial : "-", p->name);
        }
        return;
    }
    if (o->json) {
        fputs("{\"path\":", stdout);
        lscctl_json_string(stdout, p->path);
        fputs(",\"description\":", stdout);
        lscctl_json_string(stdout, p->description);
        if (p->usb) {
            printf(",\"vid\":\"%04x\",\"pid\":\"%04x\",\"serial\":", p->vid, p->pid);
            lscctl_json_string(stdout, p->serial);
        } else { /* the same keys on every line: none of them known */
            fputs(",\"vid\":null,\"pid\":null,\"serial\":null", stdout);
        }
        printf(",\"controller\":%s}\n", p->controller ? "true" : "false");
    } else {
        printf("%s\t%s", p->path, *p->description ? p->description : "-");
        if (p->usb) {
            printf("\t%04x:%04x\t%s", p->vid, p->pid, *p->serial ? p->serial : "-");
        } else {
            fputs("\t-\t-", stdout);
        }
        puts(p->controller ? "\tcontroller" : "");
    }
}

int lscctl_list_ports(const lscctl_opts *o)
{
    char why[512];
    lsc_device_info **all = NULL;
    int n = lsc_device_list(&all, why, sizeof why);
    if (n < 0) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s", why);
    }
    for (size_t i = 0; all[i] != NULL; i++) {
        print_port(o, all[i]);
    }
    if (n == 0 && !o->json) {
        fprintf(stderr, "lscctl: ports: no serial ports or HID controllers found (plug the "
                        "controller in; --port sim is the built-in virtual controller)\n");
    }
    lsc_device_list_free(all);
    return LSCCTL_EXIT_OK;
}
