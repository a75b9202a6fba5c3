/* lsc device: recording keyframes over a device (lsc_device_take_keyframe,
 * lsc_device_record), over the public lsc_device_* calls. Only the error
 * message is set through the device's internal setter. Host only: compiles
 * to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)

#include "lsc/device.h"

#include "device_internal.h" /* lsc_dev_begin, lsc_dev_fail */

#define RECORD_ATTEMPTS_DEFAULT 5u
#define RECORD_SLICE_MS 100u /* the callback is called at least this often */
#define KEYFRAME_TIME_MAX 65535u
#define EVERY_MAX 65535u

/* Takes one keyframe. Before each retry of a read that timed out, fn (when
 * not NULL) is called with taken false; when it returns false, *stop is set
 * and nothing is taken (0). */
static int take(lsc_device *d, lsc_action *a, uint32_t since_ms, unsigned attempts,
                lsc_record_fn fn, void *user, bool *stop)
{
    if (a == NULL || a->nservos == 0 || a->nservos > LSC_PLAYER_SERVOS_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "no servos to read (lsc_action_init gives them); nothing was sent");
    }
    if (a->count >= LSC_ACTION_KEYFRAMES_MAX) {
        return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE,
                            "%lu keyframes, the most an action file holds; nothing was sent",
                            (unsigned long)a->count);
    }
    if (attempts == 0) {
        attempts = RECORD_ATTEMPTS_DEFAULT;
    }
    lsc_servo got[LSC_PLAYER_SERVOS_MAX];
    int r;
    for (unsigned i = 1;; i++) {
        r = lsc_device_read(d, a->ids, a->nservos, got);
        if (r != LSC_ETIMEOUT || i >= attempts) {
            break;
        }
        if (fn != NULL && !fn(user, a, false)) {
            *stop = true;
            return 0;
        }
    }
    if (r < 0) {
        return r; /* the read's message */
    }
    uint16_t pos[LSC_PLAYER_SERVOS_MAX];
    for (size_t i = 0; i < a->nservos; i++) {
        pos[i] = got[i].position;
    }
    uint16_t time = (uint16_t)(since_ms == 0                   ? 1u
                               : since_ms > KEYFRAME_TIME_MAX ? KEYFRAME_TIME_MAX
                                                              : since_ms);
    if (lsc_action_append(a, time, pos) != 0) { /* the count was checked: memory */
        return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE,
                            "out of memory after %lu keyframes", (unsigned long)a->count);
    }
    return 0;
}

int lsc_device_take_keyframe(lsc_device *d, lsc_action *a, uint32_t since_ms, unsigned attempts)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    int r = lsc_dev_begin(d);
    if (r != 0) {
        return r;
    }
    bool stop = false;
    return take(d, a, since_ms, attempts, NULL, NULL, &stop);
}

int lsc_device_record(lsc_device *d, lsc_action *a, uint32_t every_ms, uint32_t count,
                      lsc_record_fn fn, void *user)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    int r = lsc_dev_begin(d);
    if (r != 0) {
        return r;
    }
    if (every_ms == 0 || every_ms > EVERY_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "a keyframe every %lu ms: give 1..65535; nothing was sent",
                            (unsigned long)every_ms);
    }
    if (a == NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE, "no action to record into; nothing was sent");
    }
    /* the first keyframe comes every_ms after a virtual one at the start */
    uint32_t start = lsc_device_now_ms(d);
    uint32_t last = start - every_ms;
    uint32_t due = start;
    while (count == 0 || a->count < count) {
        uint32_t now = lsc_device_now_ms(d);
        if ((int32_t)(due - now) > 0) {
            uint32_t wait = due - now;
            r = lsc_device_poll(d, wait < RECORD_SLICE_MS ? wait : RECORD_SLICE_MS);
            if (r < 0) {
                return r;
            }
            if (fn != NULL && !fn(user, a, false)) {
                return 0;
            }
            continue;
        }
        bool stop = false;
        r = take(d, a, now - last, 0, fn, user, &stop);
        if (r != 0 || stop) {
            return r;
        }
        last = now;
        due += every_ms;
        if (fn != NULL && !fn(user, a, true)) {
            return 0;
        }
    }
    return 0;
}

#endif
