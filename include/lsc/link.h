/*
 * lsc link: what a program that passes frames on (as lscd does) and a
 * front end that gets its controller back after LSC_ENODEV (as lscd and
 * lsc-panel do) need beyond lsc/device.h: a hook on every frame received,
 * a frame sent as it is, reopening a lost controller into the same handle,
 * the link's counters and a batch read of notifications.
 *
 * Host only. Errors as lsc/device.h says: 0 or a negative LSC_E... code,
 * lsc_device_error(d) its line.
 */
#ifndef LSC_LINK_H
#define LSC_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Called with every whole, valid frame received from the controller, during
 * whichever call read it (a request's reply too, before the request returns
 * it), in the order they arrived; frame[0..n) is valid only during the call.
 * It must not call back into d. While a hook is set, notifications go to it
 * and are not queued (lsc_device_notification and lsc_device_wait_group see
 * none of them; lsc_device_next_event_ms does not wait for them): the hook's
 * owner routes them itself. Independent of the trace (lsc_device_set_trace),
 * which stays for people. */
typedef void (*lsc_device_frame_fn)(void *user, const uint8_t *frame, size_t n);
/* Sets the frame hook (NULL: none, notifications are queued again). */
LSC_API void lsc_device_set_frame_hook(lsc_device *d, lsc_device_frame_fn fn, void *user);

/* Sends frame[0..n), a whole frame encoded by someone else (a client of the
 * program that forwards it), as it is: the header 0x55 0x55 and a length byte
 * that matches n (LSC_FRAME_MIN..LSC_FRAME_MAX bytes) are checked, nothing
 * else (any command, 8 and 27 included: the frame's author decided). Written
 * as every frame is (traced, signals held off: see lsc/device.h). Returns 0,
 * LSC_EINVAL (not a frame; nothing sent; d, frame NULL) or the link's error. */
LSC_API int lsc_device_send_frame(lsc_device *d, const uint8_t *frame, size_t n);

/* Opens d's controller again after it went away (LSC_ENODEV, LSC_EIO): closes
 * its transport and opens the same name (the one lsc_device_name gives: the
 * one discovery chose for a NULL name) with the same settings (baud rate,
 * HID ids), into the same handle. What survives: the handle, its timeout, arm
 * profile, trace, frame hook and last-word callback, the dropped count, the
 * last known positions (lsc_device_last_position), a pending
 * lsc_device_interrupt. What starts again: the notification queue (emptied)
 * and the wait for a group (as after the open), the error. "sim" starts
 * again as a fresh virtual controller on the real clock. The descriptor
 * (lsc_device_fileno) may change: take it again. Returns 0, or the open's
 * error and message (lsc_device_error(d), lsc_device_error_cause(d)); then
 * the transport stays closed: every call that talks to the controller is
 * LSC_ENODEV, lsc_device_fileno is -1, until a reopen succeeds. Also for a
 * device that did not go away (it is opened afresh). NULL: LSC_EINVAL. */
LSC_API int lsc_device_reopen(lsc_device *d);

/* Closes d's port (the descriptor, its lock; "sim": its controller) and
 * leaves d as a failed reopen does: every call that talks to the controller
 * is LSC_ENODEV until lsc_device_reopen. For a front end that lost its
 * controller and tries again later: the port is free meanwhile (a USB serial
 * adapter plugged in again gets its old name back, another program may open
 * it). What survives is what survives a reopen. NULL: nothing. */
LSC_API void lsc_device_close_port(lsc_device *d);

/* What went over the link since the open (reopens included): for a front end
 * that shows the line's health (lscd's status). The caller sets size to
 * sizeof(lsc_device_counters) of its headers: fields are only ever added at
 * the end, and those beyond size are not written. */
typedef struct lsc_device_counters {
    size_t size;
    uint64_t frames_sent;     /* frames written to the controller */
    uint64_t frames_received; /* valid frames from it: replies, notifications, others */
    uint64_t notifications;   /* of those, notifications (6, 7, 8) */
    uint64_t bad_frames;      /* malformed or oversized frames received */
    uint64_t bytes_discarded; /* received bytes that formed no frame (noise, bad
                                 frames, a frame cut off by silence) */
    uint64_t timeouts;        /* requests unanswered within the timeout (each try) */
    uint64_t reopens;         /* lsc_device_reopen calls that succeeded */
} lsc_device_counters;
/* Fills out up to out->size bytes. Returns 0, or LSC_EINVAL (d or out NULL,
 * out->size smaller than the size field and the first counter). */
LSC_API int lsc_device_get_counters(const lsc_device *d, lsc_device_counters *out);

/* Takes up to cap queued notifications at once, oldest first, into
 * out[0..cap), without waiting or reading (lsc_device_poll reads): the
 * number taken (0: none queued), or LSC_EINVAL (d NULL, out NULL with cap >
 * 0). What lsc_device_notification(d, 0, ...) does, in one call. */
LSC_API int lsc_device_notifications(lsc_device *d, lsc_notification *out, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* LSC_LINK_H */
