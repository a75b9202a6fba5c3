/* lsc device: the base under the link (link.c) and what is built on it
 * (wait, reach, play, record, frames): the notification queue the client
 * fills, the frames the link saw (counted, and to the frame hook) and the
 * servos' last known positions. It calls nothing of the device's own.
 * Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

void lsc_dev_frame_seen(lsc_device *d, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    if (dir == LSC_TRACE_TX) {
        d->n_sent++;
        return;
    }
    d->n_received++;
    d->n_notes += frame[3] >= LSC_CMD_GROUP_RUN && frame[3] <= LSC_CMD_GROUP_COMPLETE ? 1u : 0u;
    if (d->frame_hook != NULL) {
        d->frame_hook(d->frame_user, frame, n);
    }
}

void lsc_dev_queue(void *user, const lsc_notification *n)
{
    lsc_device *d = user;
    if (d->frame_hook != NULL) { /* the hook had it: its owner routes it */
        return;
    }
    if (d->count == LSC_DEVICE_QUEUE) { /* full: the oldest goes */
        d->head = (d->head + 1u) % LSC_DEVICE_QUEUE;
        d->count--;
        d->dropped++;
    }
    device_note *at = &d->queue[(d->head + d->count) % LSC_DEVICE_QUEUE];
    at->n = *n;
    at->seq = d->seq++;
    d->count++;
}

bool lsc_dev_take(lsc_device *d, device_note *out)
{
    if (d->count == 0) {
        return false;
    }
    *out = d->queue[d->head];
    d->head = (d->head + 1u) % LSC_DEVICE_QUEUE;
    d->count--;
    return true;
}

void lsc_dev_remember(lsc_device *d, const lsc_servo *servos, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        d->last_pos[servos[i].id] = servos[i].position;
        d->last_known[servos[i].id >> 3] |= (uint8_t)(1u << (servos[i].id & 7u));
    }
}

int lsc_device_last_position(const lsc_device *d, uint8_t id, uint16_t *pos)
{
    if (d == NULL || pos == NULL || (d->last_known[id >> 3] & (1u << (id & 7u))) == 0) {
        return LSC_EINVAL;
    }
    *pos = d->last_pos[id];
    return 0;
}

#endif
