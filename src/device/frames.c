/* lsc device: a forwarder's data path: the frame hook that sees every
 * received frame, and a whole frame sent as it is (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

void lsc_device_set_frame_hook(lsc_device *d, lsc_device_frame_fn fn, void *user)
{
    if (d != NULL) {
        d->frame_hook = fn;
        d->frame_user = user;
    }
}

void lsc_dev_frame_rx(lsc_device *d, const uint8_t *frame, size_t n)
{
    if (d->frame_hook != NULL) {
        d->frame_hook(d->frame_user, frame, n);
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
    return lsc_dev_write_frame(d, frame, n);
}

#endif
