/* lsc device: recording keyframes over a device (lsc_device_take_keyframe,
 * lsc_device_record), over the public lsc_device_* calls. Only the error
 * message is set through the device's internal setter. Host only: compiles
 * to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include "lsc/device.h"
#include "lsc/play.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "device_internal.h" /* lsc_dev_begin, lsc_dev_fail, lsc_dev_refuse */

#define RECORD_ATTEMPTS_DEFAULT 5u
#define RECORD_SLICE_MS 100u /* the callback is called at least this often */
#define KEYFRAME_TIME_MAX 65535u
#define EVERY_MAX 65535u
#define ITEM_MAX 40u /* bytes of one item of an id list: a joint's name (31), an id, a range */

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
    lsc_dev_begin(d);
    bool stop = false;
    return take(d, a, since_ms, attempts, NULL, NULL, &stop);
}

int lsc_device_record(lsc_device *d, lsc_action *a, uint32_t every_ms, uint32_t count,
                      lsc_record_fn fn, void *user)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
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

/* ---- The servos of a list ("1-3,8", "base,shoulder,3-4") ---------------------- */


/* A servo id of a range's end: lsc_arm_servo_id's rules without joints, its
 * reason after "the range 'ITEM': ". */
static int range_end(const char *item, const char *text, uint8_t *id, char *why,
                     size_t whylen)
{
    char reason[160];
    if (lsc_arm_servo_id(NULL, text, id, reason, sizeof reason) != 0) {
        return lsc_dev_refuse(why, whylen, "the range '%s': %s", item, reason);
    }
    return 0;
}

/* The ids item[0..len) lists (a joint, an id, LO-HI): *lo..*hi. */
static int ids_item(const lsc_arm *arm, const char *item, size_t len, uint8_t *lo, uint8_t *hi,
                    char *why, size_t whylen)
{
    char text[ITEM_MAX + 1u], shown[4u * ITEM_MAX + 1u];
    (void)lsc_escape_text(shown, sizeof shown, item, len < ITEM_MAX ? len : ITEM_MAX);
    if (len == 0) {
        return lsc_dev_refuse(why, whylen,
                           "an empty item (two commas, or one at an end): give ids like 1-6, "
                           "1,2,5 or joint names");
    }
    if (len > ITEM_MAX) {
        return lsc_dev_refuse(why, whylen, "'%s...' is neither a joint nor a servo id", shown);
    }
    memcpy(text, item, len);
    text[len] = '\0';
    char *dash = text[0] >= '0' && text[0] <= '9' ? strchr(text, '-') : NULL;
    if (dash == NULL) { /* a joint or an id ("-5" is a negative id) */
        if (lsc_arm_servo_id(text[0] == '-' ? NULL : arm, text, lo, why, whylen) != 0) {
            return LSC_EINVAL;
        }
        *hi = *lo;
        return 0;
    }
    *dash = '\0';
    if (dash[1] == '\0') {
        return lsc_dev_refuse(why, whylen, "the range '%s' has no end: write LO-HI, like 1-6",
                           shown);
    }
    if (range_end(shown, text, lo, why, whylen) != 0 ||
        range_end(shown, dash + 1, hi, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    if (*hi < *lo) {
        return lsc_dev_refuse(why, whylen, "the range %u-%u is empty: write the lower id first",
                           *lo, *hi);
    }
    return 0;
}

int lsc_device_parse_ids(const lsc_arm *arm, const char *list, uint8_t *ids, size_t cap,
                         char *why, size_t whylen)
{
    bool seen[256] = {false};
    size_t n = 0;
    if (list == NULL || ids == NULL || cap == 0) {
        return lsc_dev_refuse(why, whylen, "lsc_device_parse_ids: no list, or no room for ids");
    }
    if (*list == '\0') {
        return lsc_dev_refuse(why, whylen, "no servos listed: give ids like 1-6, 1,2,5 or joint "
                                        "names");
    }
    for (const char *p = list;;) {
        const char *comma = strchr(p, ',');
        size_t len = comma != NULL ? (size_t)(comma - p) : strlen(p);
        uint8_t lo = 0, hi = 0;
        if (ids_item(arm, p, len, &lo, &hi, why, whylen) != 0) {
            return LSC_EINVAL;
        }
        for (unsigned id = lo; id <= hi; id++) {
            if (seen[id]) {
                return lsc_dev_refuse(why, whylen, "servo %u listed twice", id);
            }
            if (n == cap) {
                return lsc_dev_refuse(why, whylen, "more than %lu servos", (unsigned long)cap);
            }
            seen[id] = true;
            ids[n++] = (uint8_t)id;
        }
        if (comma == NULL) {
            return (int)n; /* at most 256 */
        }
        p = comma + 1;
    }
}

#endif
