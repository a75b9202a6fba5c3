/*
 * lsc play: playing an action (lsc/files.h) over a device (lsc/device.h) on
 * the schedule of lsc/player.h, and recording one from the servos' positions.
 *
 * Host only. Errors as lsc/device.h says.
 */
#ifndef LSC_PLAY_H
#define LSC_PLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"
#include "lsc/files.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Play and record ------------------------------------------------------------- */

/* Called by lsc_device_play after each frame it sent (step non-NULL) and at
 * least every 100 ms while it waits (step NULL), with the ms since the start.
 * Returning false stops the play after the frame being sent: the servos stay
 * where they are. May be NULL. */
typedef bool (*lsc_play_fn)(void *user, const lsc_player_step *step, uint32_t elapsed_ms);

/* What a play did. The caller sets size to sizeof(lsc_play_result) of its
 * headers: fields are only ever added at the end, and those beyond size are
 * not written (a size smaller than the size field and frames is LSC_EINVAL,
 * nothing sent). */
typedef struct lsc_play_result {
    size_t size;
    uint32_t frames;       /* frames sent */
    uint32_t dropped;      /* keyframes dropped: faster than the line carries */
    uint32_t keyframe;     /* 1-based keyframe of the last frame sent (0: none) */
    uint32_t max_late_ms;  /* the latest a frame went out after its due time */
    uint32_t total_ms;     /* the whole schedule: the end of the last move after
                              the start (lsc_player_total_ms) */
    bool stopped;          /* the callback stopped it */
} lsc_play_result;

/* Plays a over d on a schedule fixed from one start (lsc/player.h): cfg's
 * speed, times and lead; baud 0 means the device's line (its baud; HID and
 * sim: 9600 as the model). Returns when the last move has ended (0), when the
 * callback stopped it (0, result->stopped), or at the first error of a send
 * or a wait (what was sent stays sent).
 * Refused before anything is sent (LSC_EINVAL): no keyframes, speed or times
 * 0, a schedule longer than 2^32 - 1 ms, more than LSC_DEVICE_HID_MOVE_MAX
 * servos over HID, and, with an arm profile, any keyframe outside its limits
 * (every keyframe is checked first; the message names the keyframe, 1-based,
 * and the joint), result->size too small. result may be NULL; else it is
 * kept up to date (up to result->size bytes) as the play
 * goes (total_ms is set before the first frame), so that the callback may
 * read it. On "sim" on its virtual clock the play takes no real time.
 * Through lscd, a halt (lsc_lscd_halt, by any client) ends the play at once:
 * LSC_EBUSY, cause LSC_DEVICE_CAUSE_HALTED (what was sent stays sent). */
LSC_API int lsc_device_play(lsc_device *d, const lsc_action *a, const lsc_player_config *cfg,
                            lsc_play_fn fn, void *user, lsc_play_result *result);

/* ---- Record ------------------------------------------------------------------- */


/* Record: lsc_device_unload the servos of a (its ids) so that they can be
 * posed by hand, then take keyframes. */

/* Reads the positions of a's servos (a timeout is retried, up to `attempts`
 * reads; 0 means 5; each waits the device's timeout) and appends them to a
 * as a keyframe since_ms after the one before (0 becomes 1, more than 65535
 * becomes 65535). Returns 0, LSC_EINVAL (a NULL, or without servos),
 * LSC_ETIMEOUT (no read was answered), LSC_ENOSPC (the action is full:
 * LSC_ACTION_KEYFRAMES_MAX, checked before anything is sent; or out of
 * memory) or the link's error; a is unchanged on error. */
LSC_API int lsc_device_take_keyframe(lsc_device *d, lsc_action *a, uint32_t since_ms,
                                     unsigned attempts);

/* Called by lsc_device_record after each keyframe it took (a->count is its
 * 1-based number) and at least every 100 ms while it waits (taken false;
 * lsc_device_error(d) is then ""). Also, with taken false, after a position
 * read that timed out and before it is retried: lsc_device_error(d) then
 * holds the timeout's line (a front end may say that it retries).
 * Returning false ends the recording. May be NULL. */
typedef bool (*lsc_record_fn)(void *user, const lsc_action *a, bool taken);

/* Takes a keyframe every every_ms ms (1..65535, else LSC_EINVAL) on the
 * device's clock, on a schedule fixed from one start: keyframe k is due
 * (k - 1) * every_ms after it, and its time is the ms since the one before
 * (the first's: every_ms); one that is late (a read retried) is taken at once
 * and the schedule keeps its times. Goes on until count keyframes (0: no
 * limit) are in a or the callback says stop. Does not unload. Returns 0 (the
 * end was reached, or the callback ended it), or lsc_device_take_keyframe's
 * error (LSC_ENOSPC when a is full: a->count is then
 * LSC_ACTION_KEYFRAMES_MAX) or a wait's; what was taken stays in a either
 * way. On "sim" on its virtual clock it takes no real time. */
LSC_API int lsc_device_record(lsc_device *d, lsc_action *a, uint32_t every_ms, uint32_t count,
                              lsc_record_fn fn, void *user);

#ifdef __cplusplus
}
#endif

#endif /* LSC_PLAY_H */
