/*
 * lsc core: constants, frame encoders, the byte-at-a-time parser and typed
 * decoders of the LSC servo controller protocol.
 *
 * Portable C99, freestanding: no malloc, no stdio, no global or static
 * mutable state. Every function writes only into the caller's buffers and
 * never past the capacity it is given. Every function runs in time linear in
 * its input (the parser: a bounded number of steps per byte, see
 * lsc_parser_feed) and uses a few dozen bytes of stack.
 *
 * Frame on the wire:  0x55 0x55 LEN CMD P1 ... Pn   with LEN = n + 2.
 * 16-bit values are little-endian. There is no checksum.
 *
 * Return values: 0 is success, a positive value is a byte or item count, a
 * negative value is one of the LSC_E... codes below.
 */
#ifndef LSC_CORE_H
#define LSC_CORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Marks the public API; the shared library exports only what carries it. */
#ifndef LSC_API
#if defined(LSC_SHARED_BUILD) && defined(__GNUC__)
#define LSC_API __attribute__((visibility("default")))
#else
#define LSC_API
#endif
#endif

/* ---- Frame limits --------------------------------------------------------- */

#define LSC_HEADER_BYTE 0x55u
#define LSC_FRAME_MIN 4u   /* 55 55 02 CMD */
#define LSC_FRAME_MAX 257u /* LEN 255 + the two header bytes */
#define LSC_LEN_MIN 2u
#define LSC_LEN_MAX 255u
#define LSC_PARAMS_MAX 253u /* LSC_LEN_MAX - 2 */

/* Most servos (or ids) one frame can carry. A LEN of 0x55 cannot be sent (a
 * receiver reads it as one more header byte), so an unload or a position
 * request of exactly 82 ids is refused as well. */
#define LSC_MOVE_MAX 83u   /* 3*N + 5 <= 255 */
#define LSC_UNLOAD_MAX 252u /* N + 3 <= 255, N != 82 */
#define LSC_READ_MAX 84u   /* reply 3*N + 3 <= 255; request N != 82 */
/* Most servos one offset read (command 23) can ask for: the reply, 2*N + 3
 * bytes long, could not carry 41 (its LEN would be 0x55); an xArm has 6. */
#define LSC_OFFSET_MAX 40u

/* Group number meaning "every action group" in action_group_speed. */
#define LSC_GROUP_ALL 0xFFu

/* ---- Command values -------------------------------------------------------- */

typedef enum lsc_cmd {
    LSC_CMD_SERVO_MOVE = 3,
    LSC_CMD_GROUP_RUN = 6,      /* action_group_run (both directions) */
    LSC_CMD_GROUP_STOP = 7,     /* action_group_stop (both directions) */
    LSC_CMD_GROUP_COMPLETE = 8, /* controller -> host only: never send it */
    LSC_CMD_GROUP_SPEED = 11,
    LSC_CMD_BATTERY = 15,       /* get_battery_voltage: request and reply */
    LSC_CMD_UNLOAD = 20,        /* mult_servo_unload */
    LSC_CMD_POS_READ = 21,      /* mult_servo_pos_read: request and reply */
    /* xArm firmware, beyond the V1.2 document (seen by two projects; LSC-6/16/32
     * boards may not answer): */
    LSC_CMD_OFFSET_READ = 23,   /* servo offset read: count, ids -> count, (id, offset)... */
    LSC_CMD_OFFSET_ADJUST = 24  /* servo offset adjust: id, offset (int8) */
} lsc_cmd;

/* ---- Error codes ----------------------------------------------------------- */

typedef enum lsc_error {
    LSC_OK = 0,
    LSC_EINVAL = -1,   /* invalid argument (nothing was written or sent) */
    LSC_ENOSPC = -2,   /* the caller's buffer is too small */
    LSC_ESYNC = -3,    /* parser: a byte outside any frame was discarded */
    LSC_EFRAME = -4,   /* malformed frame: LEN or contents contradict the command */
    LSC_ETOOBIG = -5,  /* parser: frame longer than the parser's buffer */
    LSC_ETIMEOUT = -6, /* no reply within the timeout */
    LSC_EIO = -7,      /* I/O error on the transport */
    LSC_EREPLY = -8,   /* a reply arrived but not the one expected */
    LSC_EBUSY = -9,    /* port is in use by another process */
    LSC_ENODEV = -10,  /* no such device, or the device went away */
    LSC_EACCES = -11,  /* permission denied opening the device */
    LSC_EINTR = -12    /* the call was interrupted (lsc_device_interrupt) */
} lsc_error;

/* Short English text for any value above (and for unknown values). Never NULL. */
LSC_API const char *lsc_strerror(int err);

/* The version of the library the program runs with, "MAJOR.MINOR.PATCH"
 * (LSC_VERSION_STRING of its own headers: lsc/version.h). Never NULL. */
LSC_API const char *lsc_version(void);

/* ---- Frames --------------------------------------------------------------- */

/* A parsed frame. params points into the parser's buffer (or any buffer the
 * caller fills) and holds nparams = LEN - 2 bytes. */
typedef struct lsc_frame {
    uint8_t cmd;
    uint8_t nparams;
    const uint8_t *params;
} lsc_frame;

/* One servo's id and position (a move target, or a position read back). */
typedef struct lsc_servo {
    uint8_t id;
    uint16_t position;
} lsc_servo;

/* One servo's id and its offset (xArm commands 23 and 24): a signed
 * position correction the servo keeps (two's complement on the wire). */
typedef struct lsc_servo_offset {
    uint8_t id;
    int8_t offset;
} lsc_servo_offset;

/* ---- Encoders -------------------------------------------------------------- *
 * Each writes one whole frame at buf and returns its length in bytes (4..257),
 * or LSC_EINVAL for arguments the frame cannot carry, or LSC_ENOSPC if cap is
 * smaller than the frame. On error nothing is written. buf may be NULL only
 * when cap is 0. */

/* Any frame: cmd with n parameter bytes (n <= 253, n != 83). params may be
 * buf + 4, the parameters already in place. */
LSC_API int lsc_encode_frame(uint8_t *buf, size_t cap, uint8_t cmd, const uint8_t *params,
                             size_t n);

/* servo_move: n servos (1..LSC_MOVE_MAX, distinct ids) to their positions over time_ms. */
LSC_API int lsc_encode_servo_move(uint8_t *buf, size_t cap, uint16_t time_ms,
                                  const lsc_servo *servos, size_t n);
/* action_group_run: run group `times` times (0 = forever); from the controller:
 * the group started. */
LSC_API int lsc_encode_group_run(uint8_t *buf, size_t cap, uint8_t group, uint16_t times);
/* action_group_stop (either direction). */
LSC_API int lsc_encode_group_stop(uint8_t *buf, size_t cap);
/* action_group_complete (controller -> host; a host must never send it). */
LSC_API int lsc_encode_group_complete(uint8_t *buf, size_t cap, uint8_t group, uint16_t times);
/* action_group_speed: group (or LSC_GROUP_ALL) at percent of its original speed. */
LSC_API int lsc_encode_group_speed(uint8_t *buf, size_t cap, uint8_t group, uint16_t percent);
/* get_battery_voltage request and reply. */
LSC_API int lsc_encode_battery_request(uint8_t *buf, size_t cap);
LSC_API int lsc_encode_battery_reply(uint8_t *buf, size_t cap, uint16_t millivolts);
/* mult_servo_unload: n distinct ids (1..LSC_UNLOAD_MAX, n != 82). */
LSC_API int lsc_encode_unload(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n);
/* mult_servo_pos_read request: n distinct ids (1..LSC_READ_MAX, n != 82). */
LSC_API int lsc_encode_pos_request(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n);
/* mult_servo_pos_read reply: n servos (1..LSC_READ_MAX, distinct ids). */
LSC_API int lsc_encode_pos_reply(uint8_t *buf, size_t cap, const lsc_servo *servos, size_t n);
/* servo offset read (23) request: n distinct ids (1..LSC_OFFSET_MAX); and its
 * reply: n servos with their offsets (1..LSC_OFFSET_MAX, distinct ids). */
LSC_API int lsc_encode_offset_request(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n);
LSC_API int lsc_encode_offset_reply(uint8_t *buf, size_t cap, const lsc_servo_offset *servos,
                                    size_t n);
/* servo offset adjust (24): servo id's offset. */
LSC_API int lsc_encode_offset_adjust(uint8_t *buf, size_t cap, uint8_t id, int8_t offset);

/* ---- Parser ---------------------------------------------------------------- *
 * A byte-at-a-time state machine whose state and buffer are the caller's.
 * Rules:
 *  - Known commands have exact lengths; a LEN or count byte that contradicts
 *    the command makes the frame malformed (LSC_EFRAME). Commands 3, 20 and 21
 *    need at least one servo. Unknown commands take any LEN from 2 up to what
 *    the buffer holds (longer: LSC_ETOOBIG).
 *  - After malformed input the parser rescans the bytes it had buffered, so a
 *    frame that began inside them is still found.
 *  - A LEN byte of 0x55 is one more header byte.
 * Fields are the caller's to read, never to write. */
typedef struct lsc_parser {
    uint8_t *buf;       /* the frame being assembled, header included */
    size_t cap;         /* usable bytes of buf (at most LSC_FRAME_MAX used) */
    size_t len;         /* bytes of the current candidate held in buf */
    bool complete;      /* buf holds the frame the last feed returned */
    uint32_t frames;    /* frames returned */
    uint32_t discarded; /* bytes thrown away (noise, malformed frames, resets) */
    uint32_t errors;    /* malformed or oversized frames (LSC_EFRAME, LSC_ETOOBIG) */
} lsc_parser;

/* Prepares p to use buf (cap >= LSC_FRAME_MIN; LSC_FRAME_MAX holds any
 * frame). Returns 0, or LSC_EINVAL (p NULL, buf NULL, cap too small: the
 * parser then refuses every byte with LSC_EINVAL). */
LSC_API int lsc_parser_init(lsc_parser *p, uint8_t *buf, size_t cap);

/* Feeds one byte. Returns 1 when a frame completed (out->cmd, out->params and
 * out->nparams stay valid until the next feed or reset), 0 when more bytes are
 * needed, or a negative code when input was discarded (the parser has already
 * resynchronised): LSC_ESYNC for noise outside a frame, LSC_EFRAME for a
 * malformed frame, LSC_ETOOBIG for a frame longer than the buffer, LSC_EINVAL
 * for a NULL argument or an uninitialised parser. At most 5 buffered bytes
 * are ever rescanned, so a call costs a bounded number of steps. */
LSC_API int lsc_parser_feed(lsc_parser *p, uint8_t byte, lsc_frame *out);

/* The bulk path: feeds the bytes data[0..n) up to and including the first
 * one at which lsc_parser_feed would return nonzero, exactly as that many
 * calls of lsc_parser_feed would (same frames, counters and buffer
 * contents). Returns how many bytes it consumed, k (1..n when n > 0), and
 * stores in *result what lsc_parser_feed returned for data[k - 1]: 1 (a
 * frame completed: out is set as by lsc_parser_feed), a negative code (bytes
 * were discarded), or 0 (k == n: all consumed, no frame completed). Feed the
 * rest, data[k..n), with the next call. Between frames, a noise byte and a
 * whole valid frame at the start of data are each decided in one step (the
 * frame checked against its command and copied at once); otherwise
 * parameter bytes are copied in runs, so a frame costs a few steps per
 * header byte and about one per parameter byte. data must not lie inside
 * the parser's buffer. n = 0 consumes nothing and gives 0. What lsc_parser_feed refuses
 * (a NULL p or out, an uninitialised parser) is refused the same way: one
 * byte consumed, LSC_EINVAL. A NULL result, or data NULL with n > 0, reads
 * nothing and returns n (with LSC_EINVAL in *result if result is not NULL),
 * so that a caller's loop always ends. Stack and time: as lsc_parser_feed,
 * per byte. */
LSC_API size_t lsc_parser_feed_buf(lsc_parser *p, const uint8_t *data, size_t n, lsc_frame *out,
                                   int *result);

/* Forgets any partial frame (its bytes count as discarded). Counters stay. */
LSC_API void lsc_parser_reset(lsc_parser *p);

/* ---- Typed decoders ---------------------------------------------------------- *
 * Each checks the frame's command and that its contents fit that message,
 * then fills the outputs. Return 0 (or the servo/id count) on success,
 * LSC_EFRAME if the frame is another command or contradicts this one
 * (wrong length, count, a repeated id, or more ids or servos than its encoder
 * accepts, e.g. a position request of more than LSC_READ_MAX ids, which no
 * reply could answer), LSC_ENOSPC if the caller's array
 * holds fewer than the frame carries, LSC_EINVAL for NULL arguments. Outputs
 * are written only on success. */

LSC_API int lsc_decode_servo_move(const lsc_frame *f, uint16_t *time_ms, lsc_servo *servos,
                                  size_t cap);
LSC_API int lsc_decode_group_run(const lsc_frame *f, uint8_t *group, uint16_t *times);
LSC_API int lsc_decode_group_stop(const lsc_frame *f);
LSC_API int lsc_decode_group_complete(const lsc_frame *f, uint8_t *group, uint16_t *times);
LSC_API int lsc_decode_group_speed(const lsc_frame *f, uint8_t *group, uint16_t *percent);
LSC_API int lsc_decode_battery_request(const lsc_frame *f);
LSC_API int lsc_decode_battery_reply(const lsc_frame *f, uint16_t *millivolts);
LSC_API int lsc_decode_unload(const lsc_frame *f, uint8_t *ids, size_t cap);
LSC_API int lsc_decode_pos_request(const lsc_frame *f, uint8_t *ids, size_t cap);
LSC_API int lsc_decode_pos_reply(const lsc_frame *f, lsc_servo *servos, size_t cap);
LSC_API int lsc_decode_offset_request(const lsc_frame *f, uint8_t *ids, size_t cap);
LSC_API int lsc_decode_offset_reply(const lsc_frame *f, lsc_servo_offset *servos, size_t cap);
LSC_API int lsc_decode_offset_adjust(const lsc_frame *f, uint8_t *id, int8_t *offset);

/* The rule every message with a list of servos keeps (the encoders, the
 * device layer, lscctl and the Python bindings check it with this): each
 * servo at most once. Returns the index of the first of the n ids at ids[0],
 * ids[stride], ids[2 * stride]... (stride >= 1: an id field in an array of
 * structures) that repeats an earlier one, or n when they are distinct. At
 * most n * (n - 1) / 2 comparisons, no allocation; ids may be NULL when n is
 * 0. */
LSC_API size_t lsc_ids_first_repeat(const uint8_t *ids, size_t stride, size_t n);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CORE_H */
