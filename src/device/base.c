/* lsc device: the base under the link (link.c) and what is built on it
 * (wait, reach, play, record): the notification queue the client fills and
 * the servos' last known positions. It calls nothing of the device's own.
 * Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

void lsc_dev_queue(void *user, const lsc_notification *n)
{
    lsc_device *d = user;
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
