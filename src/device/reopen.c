/* lsc device: opening a lost controller again into the same handle, and the
 * entry of a device whose port is closed (lsc_device_close_port, a failed
 * reopen): a table entry like the others (transport.h), on which every call
 * that talks to the controller finds nothing there (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _POSIX_C_SOURCE 200809L

#include <string.h>
#include <time.h>

#include "device_internal.h"

/* ---- The closed port's entry ------------------------------------------------------ */

/* Its port: nothing is there. */
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

static void close_none(lsc_device *d)
{
    (void)d; /* its entry's close took the state already */
}

static int no_fileno(const lsc_device *d)
{
    (void)d;
    return -1;
}

/* Every failure (the port's LSC_ENODEV, an interrupt taken) is the one
 * line: the controller is gone. */
static int gone_fail(lsc_device *d, int err)
{
    return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NONE,
                        "%s: the controller is gone and its port closed; nothing was sent "
                        "(lsc_device_reopen opens it again)",
                        d->shown);
}

/* No name selects it (claims, open: NULL): a device comes to it by
 * go_gone and leaves it by a reopen. The board's commands run over the
 * closed port (LSC_ENODEV), halt too (the shared one: its stop fails);
 * link_fail says every failure, so message is never asked. */
static const lsc_dev_transport closed_entry = {
    .close = close_none,
    .fileno = no_fileno,
    .link_fail = gone_fail,
    .ops = &lsc_dev_board_ops,
};

/* d on the closed port's entry, as the kind it was (its kind and name, for
 * lsc_device_kind_of and the lines; what "all" stands for), its state
 * closed already: every call finds nothing there. */
static void go_gone(lsc_device *d)
{
    const lsc_dev_transport *was = d->t;
    d->closed = closed_entry;
    d->closed.kind = was->kind;
    d->closed.name = was->name;
    d->closed.all_ids = was->all_ids;
    d->t = &d->closed;
    d->port.ctx = d;
    d->port.write = gone_write;
    d->port.read = gone_read;
    d->port.now_ms = gone_now;
    lsc_dev_io_init(d);
}

/* ---- Closing and reopening ------------------------------------------------------- */

/* Closes d's entry (its state: the transport, or what a failed open left;
 * nothing on the closed port's entry) and starts again what starts again
 * after an open; the client's counts are kept. */
static void close_transport(lsc_device *d)
{
    lsc_client_counts counts; /* (the client starts again after this) */
    lsc_client_get_counts(&d->client, &counts);
    d->n_discarded += counts.discarded;
    d->n_malformed += counts.malformed;
    d->t->close(d);
    memset(&d->port, 0, sizeof d->port);
    d->head = d->count = 0;
    d->more = d->got = d->answered = d->tx_failed = false;
    d->rx_other = -1;
    d->ran = d->run_forever = d->waiting = d->started = d->start_due = false;
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
    /* the entry the name selects, as at the open (a busy serial port may
     * be lscd's again, or no longer) */
    int r = lsc_dev_open_name(d, name);
    if (r != 0) { /* its message stays */
        d->t->close(d);
        go_gone(d);
        return r;
    }
    lsc_dev_io_init(d); /* a fresh client over the new port */
    d->n_reopens++;
    return 0;
}

#endif
