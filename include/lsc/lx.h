/*
 * lsc lx: the codec of Hiwonder/LewanSoul's bus-servo protocol (LX-16A,
 * LX-15D in the xArm, LX-224, HTS- and LD- bus servos), the protocol the
 * servos themselves speak on their one-wire bus (docs/protocol.md, "Servos on
 * a bus"). It stands beside the controller's codec (lsc/core.h) and follows
 * its contracts: encoders into caller buffers, a byte-at-a-time parser whose
 * state is all in the caller's struct, typed decoders.
 *
 * Portable C99, freestanding: no malloc, no stdio, no global or static
 * mutable state. Every function writes only into the caller's buffers and
 * never past the capacity it is given; each runs in a bounded number of steps
 * (a frame is at most LSC_LX_FRAME_MAX bytes) and uses a few dozen bytes of
 * stack.
 *
 * Frame on the wire (both directions):
 *     0x55 0x55 ID LEN CMD P1 ... Pn CHK
 * with LEN = n + 3 (it counts LEN, CMD, the parameters and CHK: the frame is
 * LEN + 3 bytes) and CHK = ~(ID + LEN + CMD + P1 + ... + Pn) & 0xFF. ID is a
 * servo's id 0..253, or 254 (LSC_LX_BROADCAST): every servo obeys it, and
 * none answers but to ID_READ. 16-bit values are little-endian. A reply
 * carries the read command's own value and the replying servo's id.
 *
 * Every command has exact lengths: a request of a read is LEN 3, its reply
 * the read's own LEN (lsc_lx_len). Ranges are the document's; encoders
 * refuse values outside them (LSC_EINVAL, nothing written), and decoders
 * refuse frames carrying them (LSC_EFRAME), so that decode(encode(x)) == x
 * and encode(decode(frame)) == frame (but for OR_MOTOR_MODE's unused byte,
 * which decoders ignore and encoders write as 0).
 *
 * Return values: 0 is success, a positive value is a byte count, a negative
 * value is an LSC_E... code of lsc/core.h.
 */
#ifndef LSC_LX_H
#define LSC_LX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h" /* LSC_API, error codes */

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Frame limits and ranges ---------------------------------------------- */

#define LSC_LX_HEADER_BYTE 0x55u
#define LSC_LX_FRAME_MIN 6u   /* 55 55 ID 03 CMD CHK */
#define LSC_LX_FRAME_MAX 10u  /* LEN 7 */
#define LSC_LX_LEN_MIN 3u
#define LSC_LX_LEN_MAX 7u
#define LSC_LX_PARAMS_MAX 4u  /* LSC_LX_LEN_MAX - 3 */

#define LSC_LX_ID_MAX 253u    /* servo ids 0..253 */
#define LSC_LX_BROADCAST 254u /* every servo: obeyed by all, answered only to ID_READ */
#define LSC_LX_ID_DEFAULT 1u  /* a new servo's id */

#define LSC_LX_POSITION_MAX 1000u /* positions 0..1000: 0..240 degrees, 0.24 degree a unit */
#define LSC_LX_TIME_MAX 30000u    /* a move's time, ms */
#define LSC_LX_OFFSET_MAX 125     /* offsets -125..125 (about -30..30 degrees) */
#define LSC_LX_VIN_MIN 4500u      /* supply voltage limits, mV: 4500..12000 */
#define LSC_LX_VIN_MAX 12000u
#define LSC_LX_TEMP_LIMIT_MIN 50u /* the temperature limit, degrees C: 50..100 */
#define LSC_LX_TEMP_LIMIT_MAX 100u
#define LSC_LX_TEMP_LIMIT_DEFAULT 85u
#define LSC_LX_SPEED_MAX 1000     /* motor mode's speed -1000..1000 */

/* The alarm bits of LED_ERROR (a mask 0..7): the faults that flash the LED. */
#define LSC_LX_ALARM_TEMP 1u    /* over temperature */
#define LSC_LX_ALARM_VOLTAGE 2u /* supply voltage outside its limits */
#define LSC_LX_ALARM_STALL 4u   /* stalled */
#define LSC_LX_ALARM_ALL 7u

/* ---- Commands --------------------------------------------------------------- *
 * Request LEN, and reply LEN for reads ("3 -> 7": a LEN 3 request answered by
 * a LEN 7 reply). Kept at power-off: ID, the saved offset, the limits, LED
 * ctrl. */
typedef enum lsc_lx_cmd {
    LSC_LX_MOVE_TIME_WRITE = 1,       /* 7: position, time ms; moves at once */
    LSC_LX_MOVE_TIME_READ = 2,        /* 3 -> 7: the last 1's position and time */
    LSC_LX_MOVE_TIME_WAIT_WRITE = 7,  /* 7: as 1, but waits for MOVE_START */
    LSC_LX_MOVE_TIME_WAIT_READ = 8,   /* 3 -> 7: the waiting position and time */
    LSC_LX_MOVE_START = 11,           /* 3: starts what 7 preset */
    LSC_LX_MOVE_STOP = 12,            /* 3: stops where it is */
    LSC_LX_ID_WRITE = 13,             /* 4: the new id 0..253 */
    LSC_LX_ID_READ = 14,              /* 3 -> 4: the id (answered even to 254) */
    LSC_LX_OFFSET_ADJUST = 17,        /* 4: int8 offset, at once, lost at power-off */
    LSC_LX_OFFSET_WRITE = 18,         /* 3: saves the adjusted offset */
    LSC_LX_OFFSET_READ = 19,          /* 3 -> 4: int8 offset */
    LSC_LX_ANGLE_LIMIT_WRITE = 20,    /* 7: min, max positions (min < max) */
    LSC_LX_ANGLE_LIMIT_READ = 21,     /* 3 -> 7 */
    LSC_LX_VIN_LIMIT_WRITE = 22,      /* 7: min, max mV (min < max) */
    LSC_LX_VIN_LIMIT_READ = 23,       /* 3 -> 7 */
    LSC_LX_TEMP_LIMIT_WRITE = 24,     /* 4: degrees C */
    LSC_LX_TEMP_LIMIT_READ = 25,      /* 3 -> 4 */
    LSC_LX_TEMP_READ = 26,            /* 3 -> 4: degrees C now */
    LSC_LX_VIN_READ = 27,             /* 3 -> 5: mV now */
    LSC_LX_POS_READ = 28,             /* 3 -> 5: int16 position, may be negative */
    LSC_LX_MOTOR_MODE_WRITE = 29,     /* 7: mode, 0, int16 speed */
    LSC_LX_MOTOR_MODE_READ = 30,      /* 3 -> 7 */
    LSC_LX_LOAD_WRITE = 31,           /* 4: torque 0 off, 1 on */
    LSC_LX_LOAD_READ = 32,            /* 3 -> 4 */
    LSC_LX_LED_CTRL_WRITE = 33,       /* 4: 0 LED on, 1 off */
    LSC_LX_LED_CTRL_READ = 34,        /* 3 -> 4 */
    LSC_LX_LED_ERROR_WRITE = 35,      /* 4: alarm mask 0..7 */
    LSC_LX_LED_ERROR_READ = 36        /* 3 -> 4 */
} lsc_lx_cmd;

/* OR_MOTOR_MODE's mode byte. */
typedef enum lsc_lx_mode {
    LSC_LX_MODE_SERVO = 0, /* position control */
    LSC_LX_MODE_MOTOR = 1  /* continuous rotation at a speed */
} lsc_lx_mode;

/* The LEN byte of cmd's request (reply false) or reply (reply true): 3..7,
 * or 0 when cmd is no command of the document, or (reply true) when it has
 * no reply (a write). */
LSC_API unsigned lsc_lx_len(uint8_t cmd, bool reply);

/* ---- Frames ------------------------------------------------------------------ */

/* A parsed frame. params points into the parser's buffer (or any buffer the
 * caller fills) and holds nparams = LEN - 3 bytes. reply: the frame has the
 * shape of a read's reply (its LEN is the reply's), not of a request. */
typedef struct lsc_lx_frame {
    uint8_t id;
    uint8_t cmd;
    uint8_t nparams;
    bool reply;
    const uint8_t *params;
} lsc_lx_frame;

/* ---- Encoders ------------------------------------------------------------------ *
 * Each writes one whole frame at buf and returns its length (6..10), or
 * LSC_EINVAL for arguments outside the document's ranges, or LSC_ENOSPC if
 * cap is smaller than the frame; on error nothing is written (buf may be NULL
 * only when cap is 0).
 *
 * The value encoders take cmd: a write command (the request), or the read
 * command of the same value (the servo's reply). id: a request's 0..253 or
 * LSC_LX_BROADCAST; a reply's 0..253. */

/* Any frame of the document's shapes: cmd with n parameter bytes, where
 * n + 3 is its request's LEN or (reply) its reply's; its id as above. Values
 * are not checked: the typed encoders below do that. */
LSC_API int lsc_lx_encode_frame(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                const uint8_t *params, size_t n);

/* A request without parameters (LEN 3): every read; MOVE_START, MOVE_STOP
 * and OFFSET_WRITE. A read to LSC_LX_BROADCAST is refused (none would
 * answer) but for ID_READ. */
LSC_API int lsc_lx_encode_request(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd);

/* MOVE_TIME_WRITE, MOVE_TIME_WAIT_WRITE (requests), MOVE_TIME_READ,
 * MOVE_TIME_WAIT_READ (replies): position 0..1000, time 0..30000 ms. */
LSC_API int lsc_lx_encode_move_time(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                    uint16_t position, uint16_t time_ms);
/* ID_WRITE: value is the new id 0..253. ID_READ's reply: value == id. */
LSC_API int lsc_lx_encode_id(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint8_t value);
/* OFFSET_ADJUST, OFFSET_READ: -125..125. */
LSC_API int lsc_lx_encode_offset(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                 int8_t offset);
/* ANGLE_LIMIT_WRITE, ANGLE_LIMIT_READ: 0 <= min < max <= 1000. */
LSC_API int lsc_lx_encode_angle_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                      uint16_t min, uint16_t max);
/* VIN_LIMIT_WRITE, VIN_LIMIT_READ: 4500 <= min < max <= 12000 mV. */
LSC_API int lsc_lx_encode_vin_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                    uint16_t min_mv, uint16_t max_mv);
/* TEMP_LIMIT_WRITE, TEMP_LIMIT_READ: 50..100 degrees C. */
LSC_API int lsc_lx_encode_temp_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                     uint8_t celsius);
/* TEMP_READ's reply: any degrees C. */
LSC_API int lsc_lx_encode_temp(uint8_t *buf, size_t cap, uint8_t id, uint8_t celsius);
/* VIN_READ's reply: any mV. */
LSC_API int lsc_lx_encode_vin(uint8_t *buf, size_t cap, uint8_t id, uint16_t millivolts);
/* POS_READ's reply: any position, negative too. */
LSC_API int lsc_lx_encode_position(uint8_t *buf, size_t cap, uint8_t id, int16_t position);
/* MOTOR_MODE_WRITE, MOTOR_MODE_READ: a mode of lsc_lx_mode, speed -1000..1000
 * (the servo ignores it in servo mode). */
LSC_API int lsc_lx_encode_motor_mode(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                     uint8_t mode, int16_t speed);
/* LOAD_WRITE, LOAD_READ: torque on (1 on the wire) or off (0). */
LSC_API int lsc_lx_encode_load(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool on);
/* LED_CTRL_WRITE, LED_CTRL_READ: the LED on (0 on the wire) or off (1). */
LSC_API int lsc_lx_encode_led_ctrl(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool on);
/* LED_ERROR_WRITE, LED_ERROR_READ: an alarm mask 0..7 (LSC_LX_ALARM_...). */
LSC_API int lsc_lx_encode_led_error(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd,
                                    uint8_t mask);

/* ---- Parser ---------------------------------------------------------------------- *
 * A byte-at-a-time state machine; its state and buffer are all in the
 * caller's struct (no pointers: it may be copied or moved between feeds).
 * Rules:
 *  - A frame is believed only when its checksum holds. A frame whose
 *    checksum fails is discarded and counted (bad_checksums, errors).
 *  - Every command has exact lengths: LEN must be its request's or its
 *    reply's (lsc_lx_len); a LEN of 3..7 that contradicts the command, a
 *    LEN outside 3..7, an id of 255 or an unknown command makes the frame
 *    malformed at that byte (LSC_EFRAME, counted in errors).
 *  - After a discard the parser rescans the bytes it held, so a frame that
 *    began inside them is still found.
 *  - The host's own echo (a one-wire bus heard from a microcontroller pin, or
 *    an adapter that echoes): after sending a frame, the host calls
 *    lsc_lx_parser_expect_echo with it. The next frame that completes, if
 *    it is exactly those bytes, is the echo: dropped (counted in echoes),
 *    not returned. Any frame that completes ends the expectation, so on a
 *    line that does not echo the reply is returned as usual, and a frame
 *    that comes later with the same bytes is never dropped.
 * Fields are the caller's to read, never to write. */
typedef struct lsc_lx_parser {
    uint8_t buf[LSC_LX_FRAME_MAX];  /* the frame being assembled, header included */
    uint8_t len;                    /* bytes of it held in buf */
    bool complete;                  /* buf holds the frame the last feed returned */
    uint8_t echo[LSC_LX_FRAME_MAX]; /* the frame the host sent */
    uint8_t echo_len;               /* its length; 0: no echo expected */
    uint32_t frames;                /* frames returned */
    uint32_t discarded;             /* bytes thrown away (noise, bad frames, resets) */
    uint32_t errors;                /* malformed frames and frames with a bad checksum */
    uint32_t bad_checksums;         /* of those, frames whose checksum failed */
    uint32_t echoes;                /* echoes recognised and dropped */
} lsc_lx_parser;

/* Empties p and zeroes its counters. Returns 0, or LSC_EINVAL (p NULL). */
LSC_API int lsc_lx_parser_init(lsc_lx_parser *p);

/* Feeds one byte. Returns 1 when a frame completed (*out valid until the next
 * feed or reset), 0 when more bytes are needed (or an echo was dropped), or
 * a negative code when input was discarded (the parser has already
 * resynchronised): LSC_ESYNC for bytes outside a frame, LSC_EFRAME for a
 * malformed frame or one whose checksum failed, LSC_EINVAL for p or out
 * NULL. At most LSC_LX_FRAME_MAX bytes are rescanned: a bounded number of
 * steps a byte. */
LSC_API int lsc_lx_parser_feed(lsc_lx_parser *p, uint8_t byte, lsc_lx_frame *out);

/* The frame[0..n) the host has just sent will come back as its echo (see
 * above). It must be a frame the parser would return (a valid frame of n
 * bytes), else LSC_EINVAL and nothing changes. Returns 0. A later call
 * replaces the expectation; lsc_lx_parser_reset and init end it. */
LSC_API int lsc_lx_parser_expect_echo(lsc_lx_parser *p, const uint8_t *frame, size_t n);

/* Forgets any partial frame (its bytes count as discarded) and any expected
 * echo. Counters stay. p may be NULL. */
LSC_API void lsc_lx_parser_reset(lsc_lx_parser *p);

/* ---- Typed decoders ---------------------------------------------------------------- *
 * Each checks the frame's command (either of the two named: the write's
 * request or the read's reply), its shape and its values (the ranges the
 * encoder checks), then fills the outputs. Returns 0, LSC_EFRAME if the
 * frame is another command, a request where a reply is needed (or the
 * reverse) or carries values outside the ranges, LSC_EINVAL for NULL
 * arguments. Outputs are written only on success. The frame's id is f->id. */

/* MOVE_TIME_WRITE, MOVE_TIME_WAIT_WRITE requests; MOVE_TIME_READ,
 * MOVE_TIME_WAIT_READ replies. */
LSC_API int lsc_lx_decode_move_time(const lsc_lx_frame *f, uint16_t *position,
                                    uint16_t *time_ms);
/* ID_WRITE (the new id), ID_READ's reply (its id, equal to f->id). */
LSC_API int lsc_lx_decode_id(const lsc_lx_frame *f, uint8_t *value);
/* OFFSET_ADJUST, OFFSET_READ's reply. */
LSC_API int lsc_lx_decode_offset(const lsc_lx_frame *f, int8_t *offset);
/* ANGLE_LIMIT_WRITE, ANGLE_LIMIT_READ's reply. */
LSC_API int lsc_lx_decode_angle_limit(const lsc_lx_frame *f, uint16_t *min, uint16_t *max);
/* VIN_LIMIT_WRITE, VIN_LIMIT_READ's reply. */
LSC_API int lsc_lx_decode_vin_limit(const lsc_lx_frame *f, uint16_t *min_mv, uint16_t *max_mv);
/* TEMP_LIMIT_WRITE, TEMP_LIMIT_READ's reply. */
LSC_API int lsc_lx_decode_temp_limit(const lsc_lx_frame *f, uint8_t *celsius);
/* TEMP_READ's reply. */
LSC_API int lsc_lx_decode_temp(const lsc_lx_frame *f, uint8_t *celsius);
/* VIN_READ's reply. */
LSC_API int lsc_lx_decode_vin(const lsc_lx_frame *f, uint16_t *millivolts);
/* POS_READ's reply. */
LSC_API int lsc_lx_decode_position(const lsc_lx_frame *f, int16_t *position);
/* MOTOR_MODE_WRITE, MOTOR_MODE_READ's reply (the unused byte is ignored). */
LSC_API int lsc_lx_decode_motor_mode(const lsc_lx_frame *f, uint8_t *mode, int16_t *speed);
/* LOAD_WRITE, LOAD_READ's reply: torque on. */
LSC_API int lsc_lx_decode_load(const lsc_lx_frame *f, bool *on);
/* LED_CTRL_WRITE, LED_CTRL_READ's reply: the LED on. */
LSC_API int lsc_lx_decode_led_ctrl(const lsc_lx_frame *f, bool *on);
/* LED_ERROR_WRITE, LED_ERROR_READ's reply. */
LSC_API int lsc_lx_decode_led_error(const lsc_lx_frame *f, uint8_t *mask);

#ifdef __cplusplus
}
#endif

#endif /* LSC_LX_H */
