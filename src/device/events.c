/* lsc device: what a program's own event loop waits on: the device's
 * descriptor and its next deadline, and the read of what has arrived
 * (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

int lsc_device_fileno(const lsc_device *d)
{
    if (d == NULL) {
        return -1;
    }
    switch (d->kind) {
    case LSC_DEVICE_SERIAL: return lsc_serial_fileno(&d->serial);
    case LSC_DEVICE_HID: return lsc_hid_fileno(&d->hid);
    case LSC_DEVICE_LSCD: return lsc_lscd_fileno(d->lscd);
    default: return lsc_dev_sim_fileno(d); /* its timer; -1 on its virtual clock */
    }
}

/* What the transport already holds, that no descriptor tells of. */
static bool held(const lsc_device *d)
{
    switch (d->kind) {
    case LSC_DEVICE_HID: return lsc_hid_input_pending(&d->hid);
    case LSC_DEVICE_LSCD: return lsc_lscd_input_pending(d->lscd);
    default: return false; /* a serial port keeps nothing of its own */
    }
}

/* "sim": ms on its clock until it sends something of its own accord. */
static uint32_t sim_next(const lsc_device *d)
{
    uint64_t us = lsc_sim_next_event_us(&d->sim);
    if (us == LSC_SIM_TIME_NEVER) {
        return LSC_DEVICE_FOREVER;
    }
    /* rounded up: at that time it is due. A step lasts at most 65535 ms
     * slowed 100 times (speed 1%): far below LSC_DEVICE_FOREVER ms */
    return (uint32_t)((us + 999u) / 1000u);
}

uint32_t lsc_device_sim_next_event_ms(const lsc_device *d)
{
    return d == NULL || d->kind != LSC_DEVICE_SIM ? LSC_DEVICE_FOREVER
                                                                       : sim_next(d);
}

uint32_t lsc_device_next_event_ms(const lsc_device *d)
{
    if (d == NULL) {
        return LSC_DEVICE_FOREVER;
    }
    if (d->count > 0 || d->more || held(d)) {
        return 0;
    }
    /* another kind: its descriptor tells when something comes */
    return d->kind == LSC_DEVICE_SIM ? lsc_dev_sim_next_ms(d) : LSC_DEVICE_FOREVER;
}

int lsc_dev_read_ready(lsc_device *d)
{
    /* HID: the copies on the descriptor go first, so that a report that
     * comes after the last read below finds it readable again */
    if (d->kind == LSC_DEVICE_HID) {
        (void)lsc_hid_fileno_drain(&d->hid);
    }
    d->more = false;
    for (unsigned i = 0; i < DEVICE_READY_READS; i++) {
        d->got = false;
        int r = lsc_client_poll(&d->client, 0);
        if (r < 0) {
            return lsc_dev_link_fail(d, r);
        }
        if (!d->got) {
            return 0;
        }
    }
    d->more = true; /* lsc_device_next_event_ms says 0: the loop comes back */
    return 0;
}

#endif
