/* lsc device: opening a controller by name, closing it, its settings and
 * accessors (contract in lsc/device.h). Host only: compiles to nothing
 * elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"

/* The action groups of the built-in virtual controller ("sim"). */
static const char sim_groups_text[] = "# lsc device \"sim\": demo action groups\n"
                                      "group 1\n"
                                      "step 500 1:1000 2:2000\n"
                                      "step 500 1:1500 2:1500\n"
                                      "group 2\n"
                                      "step 300 1:1200\n"
                                      "step 300 1:1800\n"
                                      "group 8\n"
                                      "step 1000 1:2000 2:1200 3:1500\n"
                                      "step 1000 1:1000 2:1800 3:1500\n"
                                      "step 500 1:1500 2:1500 3:1500\n";

/* The calling thread's last lsc_device_open, for a NULL handle: what
 * lsc_device_error, lsc_device_error_cause, lsc_device_name and
 * lsc_device_kind_of say of NULL (empty, LSC_DEVICE_SERIAL, after one that
 * succeeded). Per thread: opens in other threads do not touch it. */
typedef struct last_open {
    char message[DEVICE_MESSAGE_MAX];
    char name[LSC_DEVICE_NAME_MAX];
    lsc_device_cause cause;
    lsc_device_kind kind;
} last_open;

static __thread last_open last;

/* What name selects (the one place that decides): sim; lscd:NAME or
 * lscd:PATH; hid, hid:SERIAL or a hidraw node; else a serial port. */
static lsc_device_kind kind_of_name(const char *name)
{
    const char *base = strrchr(name, '/');
    if (strcmp(name, "sim") == 0) {
        return LSC_DEVICE_SIM;
    }
    if (strncmp(name, LSC_LSCD_PREFIX, sizeof LSC_LSCD_PREFIX - 1u) == 0) {
        return LSC_DEVICE_LSCD;
    }
    return strcmp(name, "hid") == 0 || strncmp(name, "hid:", 4) == 0 ||
                   (base != NULL && strncmp(base + 1, "hidraw", 6) == 0)
               ? LSC_DEVICE_HID
               : LSC_DEVICE_SERIAL;
}

int lsc_device_kind_of_name(const char *name, lsc_device_kind *kind)
{
    if (kind == NULL) {
        return LSC_EINVAL;
    }
    if (name == NULL) {
        name = lsc_dev_env_port(); /* as lsc_device_open(NULL) takes it */
        if (name == NULL) {
            return LSC_ENODEV; /* discovery decides */
        }
    }
    *kind = kind_of_name(name);
    return 0;
}

static void open_sim(lsc_device *d)
{
    d->kind = LSC_DEVICE_SIM;
    (void)lsc_sim_init(&d->sim);
    (void)lsc_sim_groups_init(&d->groups, d->steps, DEVICE_SIM_STEPS, d->targets,
                              DEVICE_SIM_TARGETS);
    (void)lsc_sim_groups_parse(&d->groups, sim_groups_text, sizeof sim_groups_text - 1u, NULL);
    lsc_sim_set_groups(&d->sim, &d->groups);
    lsc_dev_sim_clock_open(d);
}

/* The cause of a transport's failed open r: its message says how to get
 * access when it was denied (lsc_port's hints). */
static lsc_device_cause open_cause(int r)
{
    return r == LSC_EACCES ? LSC_DEVICE_CAUSE_ACCESS : LSC_DEVICE_CAUSE_NONE;
}

/* Opens the HID controller name: hid (the only one), hid:SERIAL or a path. */
static int open_hid(lsc_device *d, const char *name)
{
    int r;
    d->kind = LSC_DEVICE_HID;
    if (strcmp(name, "hid") == 0) {
        r = lsc_hid_open_serial_extra(&d->hid, NULL, d->hid_vid, d->hid_pid);
    } else if (strncmp(name, "hid:", 4) == 0) {
        if (name[4] == '\0') {
            return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                "hid: needs a serial number after the colon (hid:SERIAL), or "
                                "name hid for the only controller present");
        }
        r = lsc_hid_open_serial_extra(&d->hid, name + 4, d->hid_vid, d->hid_pid);
    } else {
        r = lsc_hid_open_path_extra(&d->hid, name, d->hid_vid, d->hid_pid);
    }
    if (r != 0) {
        /* the HID layer's message names the device and what failed (or, for
         * several controllers and none chosen, their serial numbers) */
        bool several = r == LSC_EINVAL && strcmp(name, "hid") == 0 && lsc_hid_available();
        return lsc_dev_fail_text(d, r, several ? LSC_DEVICE_CAUSE_SEVERAL : open_cause(r), "",
                                 lsc_hid_error_message(&d->hid));
    }
    lsc_hid_get_io(&d->hid, &d->port);
    return 0;
}

/* "lscd:NAME" or "lscd:PATH": the controller that lscd serves there. */
static int open_lscd(lsc_device *d, const char *name)
{
    lsc_lscd_options o = {d->timeout_ms, 0, false, false};
    d->kind = LSC_DEVICE_LSCD;
    int r = lsc_lscd_open(name, &o, &d->lscd);
    if (r != 0) {
        /* its message names the socket (escaped: a name from outside) */
        return lsc_dev_fail_text(d, r, LSC_DEVICE_CAUSE_NONE, "", lsc_lscd_error(d->lscd));
    }
    lsc_lscd_get_io(d->lscd, &d->port);
    return 0;
}

/* Opens lscd at sock (a name or path) for d: 0, or the open's error; its
 * message goes to why[cap] unless it is LSC_ENODEV (nobody there). */
static int via_lscd(lsc_device *d, const char *sock, char *why, size_t cap)
{
    lsc_lscd_options o = {d->timeout_ms, 0, false, false};
    int r = lsc_lscd_open(sock, &o, &d->lscd);
    if (r != 0) {
        if (r != LSC_ENODEV) {
            (void)snprintf(why, cap, "%s", lsc_lscd_error(d->lscd));
        }
        lsc_lscd_close(d->lscd);
        d->lscd = NULL;
        return r;
    }
    d->kind = LSC_DEVICE_LSCD;
    lsc_lscd_get_io(d->lscd, &d->port);
    return 0;
}

/* A serial port that is busy may be held by lscd: then its socket is the way
 * in, the one of its NAME in lscd's directory or the one its record names
 * (lsc_lscd_recorded_socket). Returns 0 (through lscd), 1 (not lscd's, as far
 * as can be told: the port's own message stands) or LSC_EBUSY after saying
 * which lscd holds it and why its socket cannot be used. */
static int busy_through_lscd(lsc_device *d, const char *port)
{
    char name[LSC_LSCD_NAME_MAX], lscd[LSC_LSCD_NAME_MAX + 8u], sock[LSC_LSCD_PATH_MAX];
    char why[DEVICE_MESSAGE_MAX], prefix[LSC_DEVICE_NAME_MAX * 4u + 96u];
    long pid = 0;
    if (lsc_lscd_name(port, name, sizeof name) < 0) {
        return 1;
    }
    why[0] = '\0';
    (void)snprintf(lscd, sizeof lscd, "%s%s", LSC_LSCD_PREFIX, name); /* fits: 5 + 63 < 72 */
    if (via_lscd(d, lscd, why, sizeof why) == 0) {
        return 0;
    }
    if (lsc_lscd_recorded_socket(port, sock, sizeof sock, &pid) >= 0 &&
        via_lscd(d, sock, why, sizeof why) == 0) {
        return 0;
    }
    if (why[0] == '\0') {
        return 1;
    }
    (void)snprintf(prefix, sizeof prefix,
                   "%s: port busy: lscd holds it and serves it on a socket this program "
                   "cannot use: ",
                   d->shown);
    return lsc_dev_fail_text(d, LSC_EBUSY, LSC_DEVICE_CAUSE_NONE, prefix, why);
}

/* name is longer than most bytes: its start, escaped, and the limit. */
static int too_long(lsc_device *d, const char *name, const char *what, unsigned most)
{
    char start[4u * 40u + 1u];
    (void)lsc_escape_text(start, sizeof start, name, 40u);
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NAME_TOO_LONG,
                        "%s '%s...' is too long: at most %u bytes", what, start, most);
}

static int open_serial(lsc_device *d, const char *name)
{
    d->kind = LSC_DEVICE_SERIAL;
    if (strlen(name) >= LSC_SERIAL_PATH_MAX) {
        return too_long(d, name, "a serial port's path", LSC_SERIAL_PATH_MAX - 1u);
    }
    int r = lsc_serial_open(&d->serial, name, d->baud, LSC_SERIAL_AUTO);
    if (r == LSC_EBUSY) {
        int via = busy_through_lscd(d, name);
        if (via <= 0) {
            return via;
        }
    }
    if (r != 0) {
        /* the serial layer's message (every failed open sets one) names the
         * path and what failed */
        return lsc_dev_fail_text(d, r, open_cause(r), "",
                                 lsc_serial_error_message(&d->serial));
    }
    lsc_serial_get_io(&d->serial, &d->port);
    return 0;
}

int lsc_dev_open_name(lsc_device *d, const char *name)
{
    size_t len = strlen(name);
    if (len >= sizeof d->name) {
        return too_long(d, name, "the name", LSC_DEVICE_NAME_MAX - 1u);
    }
    memcpy(d->name, name, len + 1u);
    (void)lsc_escape_text(d->shown, sizeof d->shown, name, len);
    switch (kind_of_name(name)) {
    case LSC_DEVICE_SIM: open_sim(d); return 0;
    case LSC_DEVICE_LSCD: return open_lscd(d, name);
    case LSC_DEVICE_HID: return open_hid(d, name);
    default: return open_serial(d, name);
    }
}

int lsc_device_open(const char *name, const lsc_device_config *cfg, lsc_device **out)
{
    if (out == NULL) {
        return LSC_EINVAL;
    }
    memset(&last, 0, sizeof last);
    lsc_device *d = calloc(1, sizeof *d);
    *out = NULL;
    if (d == NULL) {
        (void)snprintf(last.message, sizeof last.message, "out of memory");
        return LSC_ENOSPC;
    }
    lsc_serial_init(&d->serial);
    lsc_hid_init(&d->hid);
    d->sim_timer = -1;
    d->rx_other = -1;
    d->timeout_ms = cfg != NULL && cfg->timeout_ms != 0 ? cfg->timeout_ms
                                                        : LSC_DEVICE_TIMEOUT_DEFAULT;
    d->baud = cfg != NULL && cfg->baud != 0 ? cfg->baud : LSC_SERIAL_BAUD_DEFAULT;
    if (cfg != NULL) {
        d->hid_vid = cfg->hid_vid;
        d->hid_pid = cfg->hid_pid;
    }
    char found[LSC_DEVICE_NAME_MAX];
    int r = 0;
    if (name == NULL) {
        r = lsc_dev_find(d, found, sizeof found);
        name = found;
    }
    if (r == 0) {
        r = lsc_dev_open_name(d, name);
    }
    if (r != 0) { /* what it says stays readable without a handle */
        memcpy(last.message, d->message, sizeof last.message);
        memcpy(last.name, d->name, sizeof last.name);
        last.cause = d->cause;
        last.kind = d->kind;
        lsc_device_close(d);
        return r;
    }
    lsc_dev_io_init(d);
    *out = d;
    return 0;
}

void lsc_device_close(lsc_device *d)
{
    if (d == NULL) {
        return;
    }
    lsc_serial_close(&d->serial);
    lsc_hid_close(&d->hid);
    lsc_lscd_close(d->lscd);
    lsc_dev_sim_clock_close(d);
    lsc_dev_arm_free(d);
    free(d);
}

const char *lsc_device_error(const lsc_device *d)
{
    return d == NULL ? last.message : d->message;
}

lsc_device_cause lsc_device_error_cause(const lsc_device *d)
{
    return d == NULL ? last.cause : d->cause;
}

const char *lsc_device_name(const lsc_device *d)
{
    return d == NULL ? last.name : d->name;
}

lsc_device_kind lsc_device_kind_of(const lsc_device *d)
{
    return d == NULL ? last.kind : d->kind;
}

size_t lsc_device_groups(const lsc_device *d, uint8_t *out, size_t cap)
{
    size_t n = 0;
    if (d == NULL || d->kind != LSC_DEVICE_SIM) { /* (kind SIM: its open never fails) */
        return 0;
    }
    for (size_t g = 0; g < LSC_SIM_GROUPS; g++) {
        if (d->groups.group_steps[g] != 0) {
            if (out != NULL && n < cap) {
                out[n] = (uint8_t)g;
            }
            n++;
        }
    }
    return n;
}

void lsc_device_set_timeout(lsc_device *d, uint32_t timeout_ms)
{
    if (d != NULL) {
        d->timeout_ms = timeout_ms != 0 ? timeout_ms : LSC_DEVICE_TIMEOUT_DEFAULT;
        if (d->lscd != NULL) {
            (void)lsc_lscd_set_timeout(d->lscd, d->timeout_ms);
        }
    }
}

uint32_t lsc_device_timeout(const lsc_device *d)
{
    return d == NULL ? LSC_DEVICE_TIMEOUT_DEFAULT : d->timeout_ms;
}

void lsc_device_set_trace(lsc_device *d, lsc_trace_fn fn, void *user)
{
    if (d != NULL) {
        d->trace = fn;
        d->trace_user = user;
    }
}

void lsc_device_set_last_word(lsc_device *d, lsc_device_last_word_fn fn, void *user)
{
    if (d != NULL) {
        d->last_word = fn;
        d->last_word_user = user;
    }
}

uint32_t lsc_device_now_ms(lsc_device *d)
{
    return d == NULL ? 0u : d->io.now_ms(d->io.ctx);
}

#endif
