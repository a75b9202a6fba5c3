/*
 * lsc lxclient: the host side of the bus-servo protocol (lsc/lx.h) over a
 * caller-supplied byte transport (lsc/io.h): a BusLinker or any USB-serial
 * adapter at 115200 baud, a microcontroller's UART wired to the servos'
 * one-wire bus, or the in-process virtual bus (lsc/lxbus.h). It stands beside
 * the controller's client (lsc/client.h) and follows its contracts.
 *
 * Portable C99: no OS calls, no malloc, no global or static mutable state.
 * The client struct is the caller's (the parser inside it). Stack, as gcc
 * -Os -fstack-usage counts it along the deepest call chain (the transport's
 * own not included): a typed read about 200 bytes on AVR and 330 on a
 * Cortex-M0+, lsc_lxclient_scan about 290 and 460, lsc_lxclient_set_id_alone
 * (the deepest) about 390 and 570. A client is not thread-safe: call it from
 * one thread at a time (the trace callback runs on that thread).
 *
 * Return values: 0 (or a count) on success, a negative LSC_E... code of
 * lsc/core.h on failure:
 *   LSC_EINVAL   an argument is outside the document's ranges (or NULL):
 *                NOTHING was sent. The safe operations below also return it
 *                when they refuse (see lsc_lx_refusal): nothing was written.
 *   LSC_ETIMEOUT no reply within the timeout, and nothing but silence (or
 *                other servos' frames, or the host's own echo) came.
 *   LSC_EREPLY   no reply was believed, but bytes came that formed no good
 *                frame: a reply whose checksum failed (a flipped bit; two
 *                servos that share an id answering at once), or noise.
 *   other        what the transport returned (LSC_EIO, LSC_ENODEV, ...),
 *                unchanged; a transport that returns an impossible count
 *                gives LSC_EIO.
 *
 * What is believed: a frame only when its checksum holds (the parser's rule,
 * counted in parser.bad_checksums otherwise); of those, only the reply of the
 * command asked, from the id asked. A good frame from another id or of
 * another command (a late answer to an earlier request) is counted in
 * strays, never taken. A frame shaped as a request is the host's own echo (a
 * one-wire bus heard from a microcontroller's pin, or an adapter that
 * echoes): after each frame it sends, the client tells the parser to expect
 * its echo (lsc_lx_parser_expect_echo), so the echo is skipped whether or not
 * the line echoes; request-shaped frames that come anyway are counted in
 * echoes and never taken.
 *
 * Before each request the client reads what has already arrived (at most
 * LSC_LXCLIENT_DRAIN_READS reads and LSC_LXCLIENT_DRAIN_MS of io.now_ms) so
 * that a late answer to an earlier request is not taken for this one's (one
 * still arriving completes later and is counted, never taken); then it
 * sends the request and waits for the reply at
 * most the client's timeout (lsc_lxclient_set_timeout), in io.read calls each
 * given the time that is left. A wait of T ms makes at most
 * LSC_LXCLIENT_WAIT_READS_MIN + LSC_LXCLIENT_READS_PER_MS * T reads, so a
 * transport whose clock stands still while bytes keep coming cannot hang it.
 * While a partial frame is pending and the line stays silent for
 * LSC_LXCLIENT_GAP_MS, the partial frame is dropped (a torn frame never
 * swallows the start of the next reply).
 *
 * Writes (a move, a setting) send one frame and do not read. Reads to
 * LSC_LX_BROADCAST are refused (no servo answers them) but for
 * lsc_lxclient_whois. ID_WRITE to LSC_LX_BROADCAST is refused: it would give
 * every servo on the bus the same id.
 */
#ifndef LSC_LXCLIENT_H
#define LSC_LXCLIENT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/client.h" /* lsc_trace_fn, lsc_trace_dir */
#include "lsc/core.h"   /* LSC_API, error codes, lsc_servo */
#include "lsc/io.h"
#include "lsc/lx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The default wait for a reply, ms. A reply is 7..10 bytes (0.9 ms at
 * 115200 baud); USB-serial adapters deliver it within a few USB frames (FTDI
 * chips up to their 16 ms latency timer). 100 ms covers a busy host too. */
#define LSC_LXCLIENT_TIMEOUT_MS 100u

/* The default wait for each id of a scan, ms: short enough that a scan of
 * every id 0..253 takes under 3 s (254 x 8 ms = 2.03 s, absent ids costing
 * their whole wait, leaving about 1 s for the host's own work: a poll and a
 * write per id), long enough for an answer at 115200 baud: the request, its
 * echo and the 7-byte answer are 19 bytes, 1.7 ms on the wire, plus the
 * servo's turnaround, which the document does not give (allow 1 ms), and a
 * CH340/CP210x adapter's USB polling (1 ms each way): about 4 ms, so 8 ms
 * leaves a margin of 2. An answer that comes later still (an FTDI adapter's
 * 16 ms latency timer, a busy host) is not lost: it arrives while a later id
 * is asked, is recognised by its id, and that id is asked again with the
 * client's timeout at the end of the scan. */
#define LSC_LXCLIENT_SCAN_TIMEOUT_MS 8u

/* Silence, ms, after which a partial frame is dropped. */
#define LSC_LXCLIENT_GAP_MS 20u

/* Input read before a request (see above). */
#define LSC_LXCLIENT_DRAIN_MS 20u
#define LSC_LXCLIENT_DRAIN_READS 64u

/* The read budget of a wait (see above). */
#define LSC_LXCLIENT_WAIT_READS_MIN 64u
#define LSC_LXCLIENT_READS_PER_MS 32u

/* The client. Initialise with lsc_lxclient_init; fields are the caller's to
 * read (the counters are for diagnostics), never to write. */
typedef struct lsc_lxclient {
    lsc_io io;
    lsc_lx_parser parser; /* its counters: frames, bad_checksums, errors, echoes */
    uint32_t timeout_ms;  /* the wait for a reply */
    uint32_t last_rx_ms;  /* io.now_ms when a read last brought bytes */
    lsc_trace_fn trace;
    void *trace_user;
    uint32_t replies; /* replies taken */
    uint32_t strays;  /* good replies not taken: another id, another command, late */
    uint32_t echoes;  /* request-shaped frames seen (the parser drops most echoes itself) */
} lsc_lxclient;

/* Prepares c to talk through io (copied; io.write, io.read and io.now_ms must
 * all be set). Timeout LSC_LXCLIENT_TIMEOUT_MS, no trace. Sends and reads
 * nothing. Returns 0, or LSC_EINVAL if c is NULL or io is incomplete (c is
 * then unusable: every other call returns LSC_EINVAL). */
LSC_API int lsc_lxclient_init(lsc_lxclient *c, const lsc_io *io);

/* Sets the wait for a reply, ms (0: only what has already arrived). */
LSC_API void lsc_lxclient_set_timeout(lsc_lxclient *c, uint32_t timeout_ms);

/* Sets (fn non-NULL) or clears the frame trace: every frame sent (TX) and
 * every good frame received (RX), as its bytes on the wire. It must not call
 * back into the same client. */
LSC_API void lsc_lxclient_set_trace(lsc_lxclient *c, lsc_trace_fn fn, void *user);

/* ---- Writes: each sends one frame (id 0..253 or LSC_LX_BROADCAST) and
 * returns 0, LSC_EINVAL (a value outside the document's ranges: nothing
 * sent) or the transport's error. They do not read. ------------------------ */

/* MOVE_TIME_WRITE: to position 0..1000 over time_ms 0..30000, at once. */
LSC_API int lsc_lxclient_move(lsc_lxclient *c, uint8_t id, uint16_t position, uint16_t time_ms);
/* MOVE_TIME_WAIT_WRITE: the same, preset until MOVE_START. */
LSC_API int lsc_lxclient_move_preset(lsc_lxclient *c, uint8_t id, uint16_t position,
                                     uint16_t time_ms);
/* MOVE_START (what MOVE_TIME_WAIT_WRITE preset) and MOVE_STOP. */
LSC_API int lsc_lxclient_move_start(lsc_lxclient *c, uint8_t id);
LSC_API int lsc_lxclient_move_stop(lsc_lxclient *c, uint8_t id);
/* ID_WRITE: servo id (0..253, never LSC_LX_BROADCAST) takes new_id 0..253.
 * Kept at power-off. Unchecked: lsc_lxclient_change_id is the safe way. */
LSC_API int lsc_lxclient_write_id(lsc_lxclient *c, uint8_t id, uint8_t new_id);
/* OFFSET_ADJUST: offset -125..125, in effect at once, lost at power-off;
 * OFFSET_WRITE saves the adjusted offset (kept). */
LSC_API int lsc_lxclient_adjust_offset(lsc_lxclient *c, uint8_t id, int8_t offset);
LSC_API int lsc_lxclient_save_offset(lsc_lxclient *c, uint8_t id);
/* ANGLE_LIMIT_WRITE: 0 <= min < max <= 1000 (kept). */
LSC_API int lsc_lxclient_write_limits(lsc_lxclient *c, uint8_t id, uint16_t min, uint16_t max);
/* VIN_LIMIT_WRITE: 4500 <= min < max <= 12000 mV (kept). */
LSC_API int lsc_lxclient_write_vin_limits(lsc_lxclient *c, uint8_t id, uint16_t min_mv,
                                          uint16_t max_mv);
/* TEMP_MAX_LIMIT_WRITE: 50..100 degrees C (kept). */
LSC_API int lsc_lxclient_write_temp_limit(lsc_lxclient *c, uint8_t id, uint8_t celsius);
/* OR_MOTOR_MODE_WRITE: LSC_LX_MODE_SERVO or LSC_LX_MODE_MOTOR at speed
 * -1000..1000. */
LSC_API int lsc_lxclient_write_mode(lsc_lxclient *c, uint8_t id, uint8_t mode, int16_t speed);
/* LOAD_OR_UNLOAD_WRITE: torque on or off. */
LSC_API int lsc_lxclient_write_torque(lsc_lxclient *c, uint8_t id, bool on);
/* LED_CTRL_WRITE: the LED on or off (kept). */
LSC_API int lsc_lxclient_write_led(lsc_lxclient *c, uint8_t id, bool on);
/* LED_ERROR_WRITE: the faults that flash the LED, a mask 0..7 (LSC_LX_ALARM_...). */
LSC_API int lsc_lxclient_write_alarms(lsc_lxclient *c, uint8_t id, uint8_t mask);

/* ---- Reads: each asks servo id (0..253) and waits for its reply. Returns 0
 * and fills the outputs, or an error (outputs written only on success); a
 * reply whose values lie outside the document's ranges is LSC_EREPLY. ------ */

/* POS_READ: the shaft's position (int16, negative too). */
LSC_API int lsc_lxclient_read_position(lsc_lxclient *c, uint8_t id, int16_t *position);
/* MOVE_TIME_READ (preset false) or MOVE_TIME_WAIT_READ (true). */
LSC_API int lsc_lxclient_read_move(lsc_lxclient *c, uint8_t id, bool preset, uint16_t *position,
                                   uint16_t *time_ms);
/* ID_READ to one id: it answers with its id (a servo is there). */
LSC_API int lsc_lxclient_read_id(lsc_lxclient *c, uint8_t id);
LSC_API int lsc_lxclient_read_offset(lsc_lxclient *c, uint8_t id, int8_t *offset);
LSC_API int lsc_lxclient_read_limits(lsc_lxclient *c, uint8_t id, uint16_t *min, uint16_t *max);
LSC_API int lsc_lxclient_read_vin_limits(lsc_lxclient *c, uint8_t id, uint16_t *min_mv,
                                         uint16_t *max_mv);
LSC_API int lsc_lxclient_read_temp_limit(lsc_lxclient *c, uint8_t id, uint8_t *celsius);
LSC_API int lsc_lxclient_read_temp(lsc_lxclient *c, uint8_t id, uint8_t *celsius);
LSC_API int lsc_lxclient_read_vin(lsc_lxclient *c, uint8_t id, uint16_t *millivolts);
LSC_API int lsc_lxclient_read_mode(lsc_lxclient *c, uint8_t id, uint8_t *mode, int16_t *speed);
LSC_API int lsc_lxclient_read_torque(lsc_lxclient *c, uint8_t id, bool *on);
LSC_API int lsc_lxclient_read_led(lsc_lxclient *c, uint8_t id, bool *on);
LSC_API int lsc_lxclient_read_alarms(lsc_lxclient *c, uint8_t id, uint8_t *mask);

/* ---- Who is there ------------------------------------------------------------ */

/* What answered ID_READ sent to LSC_LX_BROADCAST. */
typedef struct lsc_lx_whois {
    uint8_t id;        /* the first good answer's id (when answers > 0) */
    uint8_t answers;   /* good answers heard (saturates at 255) */
    bool garbled;      /* bytes came that formed no good frame: answers that collided */
} lsc_lx_whois;

/* ID_READ to LSC_LX_BROADCAST, which every servo answers: waits the whole
 * timeout (more answers may come). Returns 0 when exactly one good answer came
 * and nothing else (out->id is the servo's id), LSC_ETIMEOUT when nothing
 * came, LSC_EREPLY when the answers collided: two or more, or bytes that formed
 * no good frame (several servos answering at once AND their bytes together on
 * the wire; the checksum then fails, or worse, holds for an id none has: so
 * this alone never proves a servo is alone, see lsc_lxclient_set_id_alone).
 * out (may be NULL) is filled in every case but LSC_EINVAL. */
LSC_API int lsc_lxclient_whois(lsc_lxclient *c, lsc_lx_whois *out);

/* A scan's findings: bit (id % 8) of found[id / 8] is set when id answered. */
typedef struct lsc_lx_scan {
    uint8_t found[32];   /* ids that answered with a good frame */
    uint8_t garbled[32]; /* ids where something answered, but no good frame: two
                            servos sharing the id (their answers collide), noise */
    uint16_t count;      /* ids found */
    uint16_t asked;      /* ids asked */
} lsc_lx_scan;

/* Whether the scan found id (garbled: whether id answered garbled). */
LSC_API bool lsc_lx_scan_found(const lsc_lx_scan *s, uint8_t id);
LSC_API bool lsc_lx_scan_garbled(const lsc_lx_scan *s, uint8_t id);

/* ID_READ to each of ids[0..n) (0..253), or, ids NULL, to every id 0..253,
 * each waiting at most per_id_ms (0: LSC_LXCLIENT_SCAN_TIMEOUT_MS); when the
 * last id asked did not answer, it then listens for answers still on their
 * way, for the client's timeout but at most LSC_LXCLIENT_TIMEOUT_MS; ids
 * whose good answer came late (while another id was asked, or then) are
 * asked again with the client's timeout. Returns the number of ids found
 * (out filled), LSC_EINVAL (an id > 253; out NULL; ids NULL means every id,
 * whatever n) or the transport's error. A whole bus takes about 254 x
 * per_id_ms, plus at most 0.1 s when 253 is not there (at the defaults
 * 2.03 s + 0.1 s, whatever the client's timeout). */
LSC_API int lsc_lxclient_scan(lsc_lxclient *c, const uint8_t *ids, size_t n, uint32_t per_id_ms,
                              lsc_lx_scan *out);

/* ---- The safe operations ---------------------------------------------------- */

/* Everything a servo tells. */
typedef struct lsc_lx_info {
    uint8_t id;
    int16_t position;           /* POS_READ */
    uint8_t temp_c;             /* TEMP_READ */
    uint16_t vin_mv;            /* VIN_READ */
    int8_t offset;              /* ANGLE_OFFSET_READ */
    uint16_t limit_min, limit_max;   /* ANGLE_LIMIT_READ */
    uint16_t vin_min_mv, vin_max_mv; /* VIN_LIMIT_READ */
    uint8_t temp_limit_c;       /* TEMP_MAX_LIMIT_READ */
    uint8_t mode;               /* lsc_lx_mode */
    int16_t speed;              /* motor mode's speed */
    bool torque;                /* LOAD_OR_UNLOAD_READ: torque on */
    bool led;                   /* LED_CTRL_READ: the LED on */
    uint8_t alarms;             /* LED_ERROR_READ: the alarm mask */
} lsc_lx_info;

/* Reads all of servo id's settings and readings (12 requests). Returns 0 with
 * *out filled, or the first error (out untouched). */
LSC_API int lsc_lxclient_info(lsc_lxclient *c, uint8_t id, lsc_lx_info *out);

/* Why a safe operation refused (its LSC_EINVAL) or what failed. */
typedef enum lsc_lx_refusal {
    LSC_LX_DONE = 0,        /* not refused */
    LSC_LX_BAD_ARGUMENT,    /* an argument outside its range: nothing sent */
    LSC_LX_ID_TAKEN,        /* the new id already answers: two servos would share it */
    LSC_LX_ID_ABSENT,       /* the old id does not answer */
    LSC_LX_ID_GARBLED,      /* the old id answers garbled: several servos share it */
    LSC_LX_NO_SERVO,        /* no servo answers */
    LSC_LX_NOT_ALONE,       /* more than one servo answers (or answers collide) */
    LSC_LX_NOT_READ_BACK,   /* written, but the servo did not answer at its new id or value */
    LSC_LX_OUT_OF_RANGE     /* the result would leave the document's range */
} lsc_lx_refusal;

/* A one-line English text for people (never parsed by programs): what was
 * refused and what to do. (On AVR its texts, about 600 B, are in RAM, as
 * every constant not marked PROGMEM: only in a program that calls it.) */
LSC_API const char *lsc_lx_refusal_str(lsc_lx_refusal why);

/* Gives servo old_id the id new_id (both 0..253, different): refused
 * (LSC_EINVAL, nothing written) when new_id already answers (LSC_LX_ID_TAKEN,
 * a garbled answer counts), when old_id does not answer (LSC_LX_ID_ABSENT) or
 * answers garbled (LSC_LX_ID_GARBLED: its ID_READ, or its POS_READ, since
 * servos that share an id answer ID_READ with the same bytes, which collide
 * into one good answer, while their positions usually differ; servos sharing
 * an id at the same position cannot be told from one); else ID_WRITE, then new_id is read
 * back: 0, or the read's error with LSC_LX_NOT_READ_BACK. why (may be NULL)
 * says which; a transport error leaves LSC_LX_DONE. */
LSC_API int lsc_lxclient_change_id(lsc_lxclient *c, uint8_t old_id, uint8_t new_id,
                                   lsc_lx_refusal *why);

/* Gives the one servo on the bus, whatever its id, the id new_id (0..253).
 * Only when exactly one servo is there, proven twice: the broadcast ID_READ
 * gets exactly one good answer, and a scan of every id 0..253 (per_id_ms as
 * lsc_lxclient_scan) finds that id and no other, nothing garbled. Otherwise
 * refused, nothing written: LSC_LX_NO_SERVO, LSC_LX_NOT_ALONE. Then ID_WRITE
 * to that servo's id (nothing when it has new_id already) and new_id read
 * back (LSC_LX_NOT_READ_BACK). *old_id (may be NULL) gets the id it had. */
LSC_API int lsc_lxclient_set_id_alone(lsc_lxclient *c, uint8_t new_id, uint32_t per_id_ms,
                                      uint8_t *old_id, lsc_lx_refusal *why);

/* Adds delta to servo id's offset: reads it, refuses (LSC_EINVAL,
 * LSC_LX_OUT_OF_RANGE, nothing written) when the sum leaves -125..125,
 * else ANGLE_OFFSET_ADJUST (in effect at once, lost at power-off), with save
 * also ANGLE_OFFSET_WRITE (kept), then reads it back (LSC_LX_NOT_READ_BACK if
 * it differs: LSC_EREPLY). delta 0 with save saves the offset in effect.
 * *offset (may be NULL) gets the offset now in effect. */
LSC_API int lsc_lxclient_offset_change(lsc_lxclient *c, uint8_t id, int delta, bool save,
                                       int8_t *offset, lsc_lx_refusal *why);

/* Moves n servos together: every id 0..253, distinct, position 0..1000,
 * time_ms 0..30000 checked first (LSC_EINVAL, nothing sent), then
 * MOVE_TIME_WAIT_WRITE to each and one MOVE_START to LSC_LX_BROADCAST. */
LSC_API int lsc_lxclient_move_together(lsc_lxclient *c, const lsc_servo *servos, size_t n,
                                       uint16_t time_ms);

#ifdef __cplusplus
}
#endif

#endif /* LSC_LXCLIENT_H */
