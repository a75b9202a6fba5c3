/* lsc device: a forwarder's data path: the frame hook that sees every
 * received frame (called by the base, base.c), a whole frame sent as it is,
 * the link's counters and the queued notifications at once (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <string.h>

#include "device_internal.h"

void lsc_device_set_frame_hook(lsc_device *d, lsc_device_frame_fn fn, void *user)
{
    if (d != NULL) {
        d->frame_hook = fn;
        d->frame_user = user;
    }
}

int lsc_device_send_frame(lsc_device *d, const uint8_t *frame, size_t n)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    /* a LEN of 0x55 would read as a third header byte: no frame carries it */
    if (frame == NULL || n < LSC_FRAME_MIN || n > LSC_FRAME_MAX ||
        frame[0] != LSC_HEADER_BYTE || frame[1] != LSC_HEADER_BYTE || (size_t)frame[2] != n - 2u ||
        frame[2] == LSC_HEADER_BYTE) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "%lu bytes that are no frame (55 55 LEN CMD ..., LEN = bytes - 2, "
                            "not 0x55); nothing was sent",
                            frame == NULL ? 0ul : (unsigned long)n);
    }
    if (d->t->send_frame != NULL) { /* a kind that speaks another protocol */
        return d->t->send_frame(d, frame, n);
    }
    return lsc_dev_write_frame(d, frame, n);
}

int lsc_device_get_counters(const lsc_device *d, lsc_device_counters *out)
{
    if (d == NULL || out == NULL ||
        out->size < LSC_SIZED_MIN(lsc_device_counters, frames_sent)) {
        return LSC_EINVAL;
    }
    lsc_client_counts now;
    lsc_client_get_counts(&d->client, &now);
    lsc_device_counters all;
    all.size = sizeof all;
    all.frames_sent = d->n_sent;
    all.frames_received = d->n_received;
    all.notifications = d->n_notes;
    all.bad_frames = d->n_malformed + now.malformed;
    all.bytes_discarded = d->n_discarded + now.discarded;
    all.timeouts = d->n_timeouts;
    all.reopens = d->n_reopens;
    lsc_sized_give(out, &all, sizeof all);
    return 0;
}

int lsc_device_notifications(lsc_device *d, lsc_notification *out, size_t cap)
{
    if (d == NULL || (out == NULL && cap > 0)) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    size_t n = 0;
    device_note note;
    while (n < cap && lsc_dev_take(d, &note)) {
        out[n++] = note.n;
    }
    return (int)n; /* (at most LSC_DEVICE_QUEUE) */
}

#endif
