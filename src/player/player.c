/* The keyframe player (include/lsc/player.h): due times from one start,
 * a model of the line, and the "cannot keep up" rule. */
#include "lsc/player.h"

#include "../core/internal.h" /* lsc_ids_distinct */

#define LINE_BAUD_MAX 100000000u /* keeps line_rem + one frame's bits in 32 bits */
#define BITS_PER_BYTE_MS 10000u  /* 10 bits a byte, times 1000 ms a second */
#define MOVE_TIME_MAX 65535u

static uint16_t word(const lsc_track *t, size_t i)
{
    return t->read != NULL ? t->read(t->data, i) : ((const uint16_t *)t->data)[i];
}

/* Time of keyframe k (the first word of its row). */
static uint16_t keyframe_time(const lsc_track *t, uint32_t k)
{
    return word(t, (size_t)k * (1u + (size_t)t->nservos));
}

/* floor(x * 100 / pct) into *out; false if it does not fit in 32 bits. */
static bool scale(uint32_t x, uint16_t pct, uint32_t *out)
{
    uint32_t whole = x / pct;
    uint32_t part = (x % pct) * 100u / pct; /* (pct - 1) * 100 fits */
    if (whole > (UINT32_MAX - part) / 100u) {
        return false;
    }
    *out = whole * 100u + part;
    return true;
}

/* Scaling a value the init checked (every prefix of the total fits). */
static uint32_t scaled(const lsc_player *p, uint32_t x)
{
    uint32_t r = 0;
    (void)scale(x, p->cfg.speed_pct, &r);
    return r;
}

/* Time of frame f (0 is the lead-in, which comes before the unscaled sum). */
static uint32_t frame_time(const lsc_player *p, uint32_t f)
{
    return f == 0 ? 0u : keyframe_time(p->track, f % p->track->count);
}

int lsc_player_init(lsc_player *p, const lsc_track *track, const lsc_player_config *cfg)
{
    if (p == NULL || track == NULL || cfg == NULL || track->ids == NULL || track->data == NULL ||
        track->count == 0 || track->nservos == 0 || track->nservos > LSC_PLAYER_SERVOS_MAX ||
        cfg->speed_pct == 0 || cfg->times == 0 || cfg->baud == 0 ||
        cfg->baud > LINE_BAUD_MAX || !lsc_ids_distinct(track->ids, 1, track->nservos) ||
        track->count > UINT32_MAX / cfg->times) {
        return LSC_EINVAL;
    }
    uint32_t rep = 0;
    for (uint32_t k = 0; k < track->count; k++) {
        uint16_t t = keyframe_time(track, k);
        if (rep > UINT32_MAX - t) {
            return LSC_EINVAL;
        }
        rep += t;
    }
    /* the unscaled time of every frame after the lead-in: each repetition
     * but the first includes keyframe 0's time. Every due time is at most
     * this scaled, plus the lead: the check makes all of them fit. */
    uint32_t all = 0;
    if ((rep != 0 && cfg->times > UINT32_MAX / rep) ||
        !scale(rep * cfg->times - keyframe_time(track, 0), cfg->speed_pct, &all) ||
        all > UINT32_MAX - cfg->lead_ms) {
        return LSC_EINVAL;
    }
    *p = (lsc_player){0};
    p->track = track;
    p->cfg = *cfg;
    p->total = track->count * cfg->times;
    p->end_ms = cfg->lead_ms + all;
    return 0;
}

/* Is the line still busy el ms after the start? For how long, in *wait.
 * Free to within a millisecond: a frame may go out while the last fraction of
 * a millisecond of the one before is still on the line (the UART's buffer
 * holds it); the remainder carries on, so the model never drifts. */
static bool line_busy(const lsc_player *p, uint32_t el, uint32_t *wait)
{
    if (el >= p->line_ms) {
        return false;
    }
    *wait = p->line_ms - el;
    return true;
}

/* A frame of n servos goes out at el: the line is busy for its bytes. */
static void line_send(lsc_player *p, uint32_t el, size_t nservos)
{
    uint32_t bytes = 3u * (uint32_t)nservos + 7u;
    if (el > p->line_ms || (el == p->line_ms && p->line_rem == 0)) {
        p->line_ms = el; /* the line was idle: it starts now */
        p->line_rem = 0;
    }
    p->line_rem += bytes * BITS_PER_BYTE_MS;
    p->line_ms += p->line_rem / p->cfg.baud;
    p->line_rem %= p->cfg.baud;
}

/* Fills out with the servos of frame f that changed since the last frame
 * sent (every servo if none was) and takes their positions as the last sent:
 * the caller sends them when there are any. Returns how many. */
static uint8_t take_changed_servos(lsc_player *p, uint32_t f, lsc_player_step *out)
{
    const lsc_track *t = p->track;
    size_t row = (size_t)(f % t->count) * (1u + (size_t)t->nservos);
    uint8_t n = 0;
    for (uint8_t i = 0; i < t->nservos; i++) {
        uint16_t pos = word(t, row + 1u + i);
        if (!p->sent_any || pos != p->last[i]) {
            out->servos[n].id = t->ids[i];
            out->servos[n].position = pos;
            p->last[i] = pos;
            n++;
        }
    }
    p->sent_any = true; /* n > 0 when nothing was sent yet: every servo */
    return n;
}

/* Due time of frame next (ms after the start). */
static uint32_t due(const lsc_player *p, uint32_t f, uint32_t cum)
{
    return f == 0 ? 0u : p->cfg.lead_ms + scaled(p, cum);
}

int lsc_player_next(lsc_player *p, uint32_t now_ms, lsc_player_step *out)
{
    if (p == NULL || out == NULL || p->track == NULL) {
        return LSC_EINVAL;
    }
    if (!p->begun) {
        p->begun = true;
        p->start_ms = now_ms;
    }
    uint32_t el = now_ms - p->start_ms; /* modulo 2^32: wraps with the clock */
    uint32_t dropped = 0;
    for (;;) {
        if (p->next == p->total) {
            if (el >= p->end_ms) {
                return LSC_PLAYER_DONE;
            }
            out->wait_ms = p->end_ms - el;
            return LSC_PLAYER_WAIT;
        }
        uint32_t d = due(p, p->next, p->cum_ms);
        if (el < d) {
            out->wait_ms = d - el;
            return LSC_PLAYER_WAIT;
        }
        if (line_busy(p, el, &out->wait_ms)) {
            return LSC_PLAYER_WAIT;
        }
        /* the latest frame due goes out; those due before it are dropped.
         * Never the lead-in: it brings the servos to keyframe 0, and with
         * lead_ms 0 keyframe 1 is due with it (a late first call cannot
         * happen: it fixes the start). */
        while (p->next != 0 && p->next + 1u < p->total) {
            uint32_t cum = p->cum_ms + frame_time(p, p->next);
            uint32_t d_next = due(p, p->next + 1u, cum);
            if (d_next > el) {
                break;
            }
            p->next++;
            p->cum_ms = cum;
            p->dropped++;
            dropped++;
            d = d_next;
        }
        uint32_t f = p->next;
        uint32_t cum = p->cum_ms + frame_time(p, f);
        uint8_t n = take_changed_servos(p, f, out);
        p->next++;
        p->cum_ms = cum;
        if (n == 0) {
            continue; /* nothing moves: a pause */
        }
        uint32_t time = f == 0 ? p->cfg.lead_ms : scaled(p, cum) - (d - p->cfg.lead_ms);
        out->keyframe = f % p->track->count;
        out->repetition = (uint16_t)(f / p->track->count);
        out->lead_in = f == 0;
        out->due_ms = d;
        out->time_ms = (uint16_t)(time < MOVE_TIME_MAX ? time : MOVE_TIME_MAX);
        out->nservos = n;
        out->dropped = dropped;
        line_send(p, el, n);
        return LSC_PLAYER_SEND;
    }
}

uint32_t lsc_player_frames(const lsc_player *p)
{
    return p != NULL ? p->total : 0u;
}

uint32_t lsc_player_dropped(const lsc_player *p)
{
    return p != NULL ? p->dropped : 0u;
}

uint32_t lsc_player_total_ms(const lsc_player *p)
{
    return p != NULL ? p->end_ms : 0u;
}

uint32_t lsc_player_line_us(size_t nservos, uint32_t baud)
{
    if (baud == 0) {
        return UINT32_MAX;
    }
    uint32_t bits = (3u * (uint32_t)nservos + 7u) * 10u;
    return (uint32_t)(((uint64_t)bits * 1000000u + baud - 1u) / baud);
}
