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

static int open_serial(lsc_device *d, const char *name)
{
    if (strlen(name) >= LSC_SERIAL_PATH_MAX) {
        return lsc_dev_too_long(d, name, "a serial port's path", LSC_SERIAL_PATH_MAX - 1u);
    }
    lsc_serial *s = NULL;
    int r = lsc_serial_open(name, d->baud, LSC_SERIAL_AUTO, &s);
    d->state = s;
    if (r != 0) {
        return lsc_dev_serial_open_failed(d, r, name);
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
