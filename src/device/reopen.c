/* lsc device: opening a lost controller again into the same handle, and
 * what every call says while it stays closed (contract in lsc/device.h).
 * Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _POSIX_C_SOURCE 200809L

#include <string.h>
#include <time.h>

#include "device_internal.h"

/* The port of a device whose reopen failed: nothing is there. */
static int gone_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    (void)data;
    (void)n;
    return LSC_ENODEV;
}

static int gone_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)buf;
    (void)cap;
    (void)timeout_ms;
    return LSC_ENODEV;
}

static uint32_t gone_now(void *ctx)
{
    (void)ctx;
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts); /* (cannot fail for this clock) */
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

int lsc_dev_gone_fail(lsc_device *d, int err)
{
    return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NONE,
                        "%s: the controller is gone and its port closed; nothing was sent "
                        "(lsc_device_reopen opens it again)",
                        d->shown);
}

/* Closes d's transport, whichever it was (or what a failed open left), and
 * starts again what starts again after an open; the client's counts are
 * kept. */
static void close_transport(lsc_device *d)
{
    lsc_client_counts counts; /* (the client starts again after this) */
    lsc_client_get_counts(&d->client, &counts);
    d->n_discarded += counts.discarded;
    d->n_malformed += counts.malformed;
    lsc_serial_close(&d->serial);
    lsc_hid_close(&d->hid);
    lsc_lscd_close(d->lscd);
    d->lscd = NULL;
    lsc_dev_sim_clock_close(d);
    lsc_serial_init(&d->serial);
    lsc_hid_init(&d->hid);
    d->sim_timer = -1;
    d->sim_virtual = false;
    memset(&d->port, 0, sizeof d->port);
    d->head = d->count = 0;
    d->more = d->got = d->answered = d->tx_failed = false;
    d->rx_other = -1;
    d->ran = d->run_forever = d->waiting = d->started = d->start_due = false;
}

/* d without a transport: every call finds nothing there. */
static void go_gone(lsc_device *d)
{
    d->gone = true;
    d->port.ctx = d;
    d->port.write = gone_write;
    d->port.read = gone_read;
    d->port.now_ms = gone_now;
    lsc_dev_io_init(d);
}

void lsc_device_close_port(lsc_device *d)
{
    if (d != NULL) {
        lsc_dev_begin(d);
        close_transport(d);
        go_gone(d);
    }
}

int lsc_device_reopen(lsc_device *d)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    close_transport(d);
    char name[LSC_DEVICE_NAME_MAX];
    memcpy(name, d->name, sizeof name); /* (the open writes d->name) */
    int r = lsc_dev_open_name(d, name);
    if (r != 0) { /* its message stays */
        go_gone(d);
        return r;
    }
    d->gone = false;
    lsc_dev_io_init(d); /* a fresh client over the new port */
    d->n_reopens++;
    return 0;
}

#endif
