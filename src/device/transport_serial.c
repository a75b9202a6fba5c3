/* lsc device: the entry of a serial port (lsc/serial.h), the kind every
 * name no other entry claims is; a busy port that lscd holds is reached
 * through lscd's socket (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <string.h>

#include "device_internal.h"

static lsc_serial *st(const lsc_device *d)
{
    return d->state;
}

static bool claims(const char *name)
{
    (void)name;
    return true;
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

static int open_serial(lsc_device *d, const char *name)
{
    if (strlen(name) >= LSC_SERIAL_PATH_MAX) {
        return lsc_dev_too_long(d, name, "a serial port's path", LSC_SERIAL_PATH_MAX - 1u);
    }
    lsc_serial *s = NULL;
    int r = lsc_serial_open(name, d->baud, LSC_SERIAL_AUTO, &s);
    d->state = s;
    if (r == LSC_EBUSY) {
        int via = busy_through_lscd(d, name);
        if (via <= 0) {
            return via;
        }
    }
    if (r != 0) {
        /* the serial layer's message (every failed open sets one) names the
         * path and what failed */
        return lsc_dev_fail_text(d, r, lsc_dev_open_cause(r), "",
                                 lsc_serial_error_message(NULL));
    }
    lsc_serial_get_io(st(d), &d->port);
    return 0;
}

static void close_serial(lsc_device *d)
{
    lsc_serial_close(st(d));
    d->state = NULL;
}

static int serial_fileno(const lsc_device *d)
{
    return lsc_serial_fileno(st(d));
}

static const char *message(const lsc_device *d)
{
    return lsc_serial_error_message(st(d));
}

static size_t all_ids(const char *name)
{
    (void)name;
    return DEVICE_BOARD_IDS;
}

const lsc_dev_transport lsc_dev_transport_serial = {
    .kind = LSC_DEVICE_SERIAL,
    .claims = claims,
    .open = open_serial,
    .close = close_serial,
    .fileno = serial_fileno,
    .message = message, /* a serial port keeps nothing of its own: no held */
    .all_ids = all_ids,
    .ops = &lsc_dev_board_ops,
    .restart_grace_ms = DEVICE_RESTART_GRACE_MS,
    .line_baud = true,
    .name = "a serial port",
};

#endif
