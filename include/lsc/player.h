/* lsc player: plays a sequence of keyframes as servo_move frames, each at its
 * scheduled time. Portable C99 like the client: no allocation, no floating
 * point, no clock of its own (the caller passes the time in), no mutable
 * static state. Keyframes may live in RAM or in flash (an accessor reads them).
 *
 * A keyframe is the time since the previous keyframe (ms) and the positions
 * of the track's servos. Playing a track:
 *  - frame 0 (the lead-in) moves every servo to keyframe 0 over lead_ms; it
 *    is never dropped: with lead_ms 0 it goes out at once (a move of 0 ms)
 *    and keyframe 1, due then too, follows as soon as the line is free;
 *  - then each keyframe k (k >= 1, and every keyframe of the later
 *    repetitions, keyframe 0 included) is one move over its time, sent when
 *    the move before it ends. Its servos whose position did not change since
 *    the last frame sent are left out; a keyframe with no change sends nothing.
 *  - Times are scaled by 100 / speed_pct. Due times are computed from one start
 *    time as sums of the scaled times (no drift, however long the track).
 *  - The line is modelled at `baud` (10 bits a byte): a frame takes
 *    (3n + 7) * 10 / baud seconds. A frame goes out at its due time or, when
 *    the line is still busy, as soon as it is free (to within 1 ms: the
 *    fraction carries on to the next frame); when a later keyframe is
 *    due by then, the earlier ones are dropped (counted) and only the latest
 *    due is sent, so the player never falls behind its schedule.
 */
#ifndef LSC_PLAYER_H
#define LSC_PLAYER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_PLAYER_SERVOS_MAX 32u /* servos in one track */
#define LSC_PLAYER_BAUD_DEFAULT 9600u

/* Reads word i of a track's keyframe data (see lsc_track). For data in RAM
 * pass NULL; on AVR with the data in PROGMEM, a function calling
 * pgm_read_word(). */
typedef uint16_t (*lsc_track_read_fn)(const void *data, size_t i);

/* A sequence of keyframes: `count` rows of 1 + nservos words: the time since
 * the previous keyframe in ms, then the position of ids[0], ids[1], ...
 * Everything is the caller's and must outlive the player. */
typedef struct lsc_track {
    const uint8_t *ids;     /* nservos distinct servo ids (RAM) */
    uint8_t nservos;        /* 1..LSC_PLAYER_SERVOS_MAX */
    uint32_t count;         /* keyframes, >= 1 */
    const void *data;       /* count * (1 + nservos) uint16_t words */
    lsc_track_read_fn read; /* NULL: data is a uint16_t array in RAM */
} lsc_track;

/* How to play a track. */
typedef struct lsc_player_config {
    uint16_t speed_pct; /* 100 = as recorded, 200 = twice as fast (1..65535) */
    uint16_t times;     /* repetitions, 1..65535 */
    uint16_t lead_ms;   /* the move to the first keyframe (0..65535) */
    uint32_t baud;      /* line speed for the "cannot keep up" rule (>= 1) */
} lsc_player_config;

/* The player's state: the caller's, opaque in use (fields are private). */
typedef struct lsc_player {
    const lsc_track *track;
    lsc_player_config cfg;
    uint32_t start_ms;      /* the monotonic start every due time counts from */
    uint32_t next;          /* next frame: 0 is the lead-in, f is keyframe f % count */
    uint32_t total;         /* frames in all: times * count */
    uint32_t cum_ms;        /* unscaled time from the lead-in's end to frame next's start */
    uint32_t end_ms;        /* the end of the last move, ms after the start */
    uint32_t line_ms;       /* the line is busy until line_ms + line_rem / baud */
    uint32_t line_rem;
    uint32_t dropped;       /* frames dropped so far */
    uint16_t last[LSC_PLAYER_SERVOS_MAX]; /* positions last sent */
    bool begun;             /* start_ms is set */
    bool sent_any;          /* last[] holds what was sent */
} lsc_player;

/* What lsc_player_next() asks of the caller. */
typedef enum lsc_player_action {
    LSC_PLAYER_WAIT = 0, /* nothing to send yet: call again after wait_ms */
    LSC_PLAYER_SEND = 1, /* send servos[0..nservos) over time_ms now */
    LSC_PLAYER_DONE = 2  /* every frame was sent and the last move has ended */
} lsc_player_action;

typedef struct lsc_player_step {
    uint32_t wait_ms;      /* WAIT: how long until there is something to do */
    uint32_t keyframe;     /* SEND: which keyframe (0..count-1) */
    uint16_t repetition;   /* SEND: 0..times-1 */
    bool lead_in;          /* SEND: the move to keyframe 0 over lead_ms */
    uint32_t due_ms;       /* SEND: its due time, ms after the start */
    uint16_t time_ms;      /* SEND: the move's time */
    uint8_t nservos;       /* SEND: 1..nservos of the track */
    lsc_servo servos[LSC_PLAYER_SERVOS_MAX];
    uint32_t dropped;      /* frames dropped just now, to send this one in time */
} lsc_player_step;

/* Checks track and config and prepares p. Returns 0, or LSC_EINVAL (NULL
 * arguments, no keyframes, 0 or too many servos, repeated ids, speed, times or
 * baud 0, a track longer than 2^32 - 1 ms at this speed). Reads every
 * keyframe's time once: O(count). */
LSC_API int lsc_player_init(lsc_player *p, const lsc_track *track, const lsc_player_config *cfg);

/* What to do at now_ms (a monotonic clock in ms that may wrap around). The
 * first call fixes the start. Call it again after each SEND (having sent
 * the frame) or after waiting wait_ms. Returns an lsc_player_action, or
 * LSC_EINVAL for NULL arguments. O(frames dropped + nservos). */
LSC_API int lsc_player_next(lsc_player *p, uint32_t now_ms, lsc_player_step *out);

/* Frames the whole play has (lead-in included), frames dropped so far, and the
 * total time in ms (the end of the last move after the start). */
LSC_API uint32_t lsc_player_frames(const lsc_player *p);
LSC_API uint32_t lsc_player_dropped(const lsc_player *p);
LSC_API uint32_t lsc_player_total_ms(const lsc_player *p);

/* Line time of a move of n servos at baud, in microseconds (rounded up). */
LSC_API uint32_t lsc_player_line_us(size_t nservos, uint32_t baud);

#ifdef __cplusplus
}
#endif

#endif /* LSC_PLAYER_H */
