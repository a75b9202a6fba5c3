/* lsc device: what a program's own event loop waits on: the device's
 * descriptor and its next deadline, and the read of what has arrived
 * (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

int lsc_device_fileno(const lsc_device *d)
{
    return d == NULL ? -1 : d->t->fileno(d);
}

uint32_t lsc_device_next_event_ms(const lsc_device *d)
{
    if (d == NULL) {
        return LSC_DEVICE_FOREVER;
    }
    if (d->count > 0 || d->more || (d->t->held != NULL && d->t->held(d))) {
        return 0;
    }
    /* else the descriptor tells when something comes, unless the entry knows */
    return d->t->next_event_ms != NULL ? d->t->next_event_ms(d) : LSC_DEVICE_FOREVER;
}

int lsc_dev_read_ready(lsc_device *d)
{
    if (d->t->before_ready != NULL) {
        d->t->before_ready(d);
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
