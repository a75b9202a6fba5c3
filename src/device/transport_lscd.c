/* lsc device: the entry of "lscd:NAME" or "lscd:PATH", the controller that
 * the lscd daemon serves there (lsc/lscd.h), also the way in to a serial
 * port lscd holds; its halt (lscd halts its controller, whoever leases it),
 * the halts a play ends at, and its lines (lscd opened the port, at its own
 * baud rate) (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <string.h>

#include "device_internal.h"

static lsc_lscd *st(const lsc_device *d)
{
    return d->state;
}

static bool claims(const char *name)
{
    return strncmp(name, LSC_LSCD_PREFIX, sizeof LSC_LSCD_PREFIX - 1u) == 0;
}

static int open_lscd(lsc_device *d, const char *name)
{
    lsc_lscd_options o = {.size = sizeof o, .timeout_ms = d->timeout_ms};
    lsc_lscd *l = NULL;
    int r = lsc_lscd_open(name, &o, &l);
    d->state = l; /* a failed handle too: it says why */
    if (r != 0) {
        /* its message names the socket (escaped: a name from outside) */
        return lsc_dev_fail_text(d, r, LSC_DEVICE_CAUSE_NONE, "", lsc_lscd_error(l));
    }
    lsc_lscd_get_io(l, &d->port);
    return 0;
}

int lsc_dev_lscd_take_over(lsc_device *d, const char *sock, char *why, size_t cap)
{
    lsc_lscd_options o = {.size = sizeof o, .timeout_ms = d->timeout_ms};
    lsc_lscd *l = NULL;
    int r = lsc_lscd_open(sock, &o, &l);
    if (r != 0) {
        if (r != LSC_ENODEV) {
            (void)snprintf(why, cap, "%s", lsc_lscd_error(l));
        }
        lsc_lscd_close(l);
        return r;
    }
    d->t->close(d);
    d->t = &lsc_dev_transport_lscd;
    d->state = l;
    lsc_lscd_get_io(l, &d->port);
    return 0;
}

/* A busy port held by lscd: 0 (d taken over), 1 (not lscd's, as far as can
 * be told) or LSC_EBUSY with why its socket cannot be used. */
static int lscd_busy(lsc_device *d, const char *port)
{
    char name[LSC_LSCD_NAME_MAX], lscd[LSC_LSCD_NAME_MAX + 8u], sock[LSC_LSCD_PATH_MAX];
    char why[DEVICE_MESSAGE_MAX], prefix[LSC_DEVICE_NAME_MAX * 4u + 96u];
    long pid = 0;
    if (lsc_lscd_name(port, name, sizeof name) < 0) {
        return 1;
    }
    why[0] = '\0';
    (void)snprintf(lscd, sizeof lscd, "%s%s", LSC_LSCD_PREFIX, name); /* fits: 5 + 63 < 72 */
    if (lsc_dev_lscd_take_over(d, lscd, why, sizeof why) == 0) {
        return 0;
    }
    if (lsc_lscd_recorded_socket(port, sock, sizeof sock, &pid) >= 0 &&
        lsc_dev_lscd_take_over(d, sock, why, sizeof why) == 0) {
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

int lsc_dev_serial_open_failed(lsc_device *d, int r, const char *name)
{
    if (r == LSC_EBUSY) {
        int via = lscd_busy(d, name);
        if (via <= 0) {
            return via;
        }
    }
    /* the serial layer's message (every failed open sets one) names the
     * path and what failed */
    return lsc_dev_fail_text(d, r, lsc_dev_open_cause(r), "", lsc_serial_error_message(NULL));
}

static void close_lscd(lsc_device *d)
{
    lsc_lscd_close(st(d));
    d->state = NULL;
}

static int lscd_fileno(const lsc_device *d)
{
    return lsc_lscd_fileno(st(d));
}

static const char *message(const lsc_device *d)
{
    return lsc_lscd_error(st(d));
}

static bool held(const lsc_device *d)
{
    return lsc_lscd_input_pending(st(d));
}

static int silence(lsc_device *d)
{
    return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_LSCD_NO_REPLY,
                        "no reply from the controller behind %s within %lu ms: nothing "
                        "arrived; check that it is powered and connected, and the port "
                        "and baud rate lscd serves (its --port and --baud); the time "
                        "includes the wait behind other programs' requests; or raise the "
                        "timeout",
                        d->shown, (unsigned long)d->timeout_ms);
}

static void set_timeout(lsc_device *d, uint32_t timeout_ms)
{
    (void)lsc_lscd_set_timeout(st(d), timeout_ms);
}

static uint32_t halts(const lsc_device *d)
{
    return lsc_lscd_halts(st(d));
}

static int halt(lsc_device *d)
{
    int r = lsc_lscd_halt(st(d));
    return r == 0 ? 0 : lsc_dev_fail_text(d, r, LSC_DEVICE_CAUSE_NONE, "", lsc_lscd_error(st(d)));
}

lsc_lscd *lsc_device_lscd(lsc_device *d)
{
    return d != NULL && d->t == &lsc_dev_transport_lscd ? st(d) : NULL;
}

/* As the controller behind it: HID ("lscd:hid", "lscd:hid-SERIAL":
 * lsc_lscd_name's names for them), else a serial board. */
static size_t all_ids(const char *name)
{
    const char *sock = name + sizeof LSC_LSCD_PREFIX - 1u;
    if (strncmp(sock, "lx-", 3) == 0) { /* a bus (lsc_lscd_name) */
        return DEVICE_LX_IDS;
    }
    return strncmp(sock, "hid", 3) == 0 && (sock[3] == '\0' || sock[3] == '-') ? DEVICE_HID_IDS
                                                                             : DEVICE_BOARD_IDS;
}

/* The board's commands, through lscd, but its own halt. */
static const lsc_dev_ops ops = LSC_DEV_BOARD_OPS(halt);

const lsc_dev_transport lsc_dev_transport_lscd = {
    .kind = LSC_DEVICE_LSCD,
    .claims = claims,
    .open = open_lscd,
    .close = close_lscd,
    .fileno = lscd_fileno,
    .message = message,
    .held = held,
    .silence = silence,
    .set_timeout = set_timeout,
    .halts = halts,
    .all_ids = all_ids,
    .ops = &ops,
    .restart_grace_ms = DEVICE_RESTART_GRACE_MS,
    .name = "lscd",
};

#endif
