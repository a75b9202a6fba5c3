/* lsc device: playing an action file over a device (lsc_device_play) with
 * the keyframe player (lsc/player.h), over the public lsc_device_* calls.
 * Only the error message is set through the device's internal setter. Host
 * only: compiles to nothing elsewhere (the Arduino IDE builds every .c under
 * src/). */
#include "lsc/host.h"
#if LSC_HOST

#include "lsc/device.h"
#include "lsc/play.h"

#include "device_internal.h" /* lsc_dev_begin, lsc_dev_fail, the serial baud */

#define PLAY_SLICE_MS 100u /* the callback is called at least this often */
#define PLAY_MODEL_BAUD 9600u

/* The line the player models: cfg's baud, else the serial port's, else 9600
 * (HID and sim). */
static uint32_t line_baud(const lsc_device *d, const lsc_player_config *cfg)
{
    if (cfg->baud != 0) {
        return cfg->baud;
    }
    if (d->t->line_baud) {
        return d->baud; /* the open's, never 0 */
    }
    return PLAY_MODEL_BAUD;
}

/* Keyframe k of a as servos: out[0..a->nservos). */
static void keyframe_servos(const lsc_action *a, uint32_t k, lsc_servo *out)
{
    const uint16_t *row = &a->words[(size_t)k * (1u + (size_t)a->nservos)];
    for (size_t i = 0; i < a->nservos; i++) {
        out[i].id = a->ids[i];
        out[i].position = row[1u + i];
    }
}

/* Everything refused before a frame is sent: 0, or the error after
 * lsc_dev_fail. */
static int check(lsc_device *d, const lsc_action *a, const lsc_player_config *cfg,
                 lsc_player *p, lsc_track *t)
{
    if (a == NULL || cfg == NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "no action or no configuration to play; nothing was sent");
    }
    if (a->count == 0 || a->words == NULL || a->nservos == 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE, "no keyframes to play; nothing was sent");
    }
    int bound = lsc_dev_bound(d, a->nservos, "keyframes", "");
    if (bound != 0) {
        return bound;
    }
    if (cfg->speed_pct == 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "speed 0 %%: give 1..65535 (100 plays as recorded); nothing was "
                            "sent");
    }
    if (cfg->times == 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "times 0: give 1..65535; nothing was sent");
    }
    lsc_player_config c = *cfg;
    c.baud = line_baud(d, cfg);
    lsc_action_track(a, t);
    if (lsc_player_init(p, t, &c) != 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "too long to play: more than 2^32 - 1 ms (49 days) at this speed "
                            "and number of times; nothing was sent");
    }
    const lsc_arm *arm = lsc_device_arm(d);
    if (arm != NULL) {
        lsc_servo servos[LSC_PLAYER_SERVOS_MAX];
        char why[LSC_ARM_MESSAGE_MAX];
        for (uint32_t k = 0; k < a->count; k++) {
            keyframe_servos(a, k, servos);
            if (lsc_arm_check(arm, servos, a->nservos, why, sizeof why) != 0) {
                return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                    "keyframe %lu: %s; nothing was sent",
                                    (unsigned long)k + 1u, why);
            }
        }
    }
    return 0;
}

/* Whether a halt was told (through lscd) since there were `halts` (then the
 * play ends: LSC_EBUSY after its line); else 0. */
static int halted(lsc_device *d, uint32_t halts, const lsc_play_result *out)
{
    if (d->t->halts == NULL || d->t->halts(d) == halts) {
        return 0;
    }
    return lsc_dev_fail(d, LSC_EBUSY, LSC_DEVICE_CAUSE_HALTED,
                        "the play was stopped after keyframe %lu: the controller was halted "
                        "through lscd (lscctl halt, or another program's halt)",
                        (unsigned long)out->keyframe);
}

/* lsc_device_play after its size check: *out kept whole, result (the
 * caller's, may be NULL) given a copy whenever it changes. */
static int play(lsc_device *d, const lsc_action *a, const lsc_player_config *cfg,
                lsc_play_fn fn, void *user, lsc_play_result *out, lsc_play_result *result)
{
    lsc_player p;
    lsc_track t;
    int r = check(d, a, cfg, &p, &t);
    if (r != 0) {
        return r;
    }
    out->total_ms = lsc_player_total_ms(&p);
    lsc_sized_give(result, out, sizeof *out);
    uint32_t halts = d->t->halts != NULL ? d->t->halts(d) : 0u; /* (through lscd) */
    uint32_t start = lsc_device_now_ms(d); /* the player's start too: its first call */
    for (uint32_t now = start;; now = lsc_device_now_ms(d)) {
        lsc_player_step s;
        r = halted(d, halts, out);
        if (r != 0) {
            return r;
        }
        int act = lsc_player_next(&p, now, &s);
        if (act == LSC_PLAYER_DONE) {
            return 0;
        }
        if (act == LSC_PLAYER_WAIT) {
            r = lsc_device_poll(d, s.wait_ms < PLAY_SLICE_MS ? s.wait_ms : PLAY_SLICE_MS);
            if (r < 0) {
                return r;
            }
            if (fn != NULL && !fn(user, NULL, lsc_device_now_ms(d) - start)) {
                out->stopped = true;
                return 0;
            }
            continue;
        }
        r = lsc_device_move(d, s.time_ms, s.servos, s.nservos);
        if (r < 0) {
            return r;
        }
        uint32_t el = now - start;
        uint32_t late = el - s.due_ms;
        out->frames++;
        out->keyframe = s.keyframe + 1u;
        out->dropped = lsc_player_dropped(&p);
        out->max_late_ms = late > out->max_late_ms ? late : out->max_late_ms;
        lsc_sized_give(result, out, sizeof *out); /* (the callback may read it) */
        if (fn != NULL && !fn(user, &s, el)) {
            out->stopped = true;
            return 0;
        }
    }
}

int lsc_device_play(lsc_device *d, const lsc_action *a, const lsc_player_config *cfg,
                    lsc_play_fn fn, void *user, lsc_play_result *result)
{
    lsc_play_result all = {0};
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = lsc_dev_sized(d, result, LSC_SIZED_MIN(lsc_play_result, frames), "lsc_play_result");
    if (r != 0) {
        return r;
    }
    all.size = sizeof all;
    r = play(d, a, cfg, fn, user, &all, result);
    lsc_sized_give(result, &all, sizeof all);
    return r;
}

#endif
