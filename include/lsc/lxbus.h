/*
 * lsc lxbus: a virtual bus of serial bus servos (Hiwonder/LewanSoul LX-16A,
 * LX-15D, LX-224...), speaking the bus-servo protocol of lsc/lx.h, driven by
 * bytes and virtual time like the virtual controller (lsc/sim.h).
 *
 * Portable C99: no OS calls, no malloc, no stdio, no global or static
 * mutable state. The bus lives in a caller-owned lsc_lxbus (about 4.2 KiB). It
 * is deterministic: the same bytes fed at the same virtual times give the
 * same output bytes at the same times.
 *
 * How it is driven: lsc_lxbus_feed() hands it the host's bytes at the current
 * virtual time; lsc_lxbus_advance_us() moves the clock on; lsc_lxbus_read()
 * drains what the servos sent; lsc_lxbus_next_event_us() says how long until
 * more can be read; lsc_lxbus_io_init() wraps it as an lsc_io.
 *
 * What the model does (the document's behaviour; docs/protocol.md):
 *  - Up to LSC_LXBUS_SERVOS servos, each with an id 0..253. Two servos may
 *    share an id (a bus wired from servos fresh from the box, all id 1):
 *    both obey what is sent to it, and both answer.
 *  - A frame to an id is obeyed by every servo with that id; to 254
 *    (broadcast) by every servo. Reads are answered by every servo they
 *    reach, but a broadcast is answered by none except ID_READ. Answers sent
 *    at the same time collide on the wire: a UART line idles high and a 0
 *    wins, so the bytes AND together (stats.collisions counts it); the
 *    checksum then fails, or worse, looks right.
 *  - A frame whose checksum fails, or that is malformed, is ignored
 *    (stats.bad_frames); so is a frame left unfinished for more than
 *    LSC_LXBUS_FRAME_GAP_MS before its next byte. A well-formed frame whose
 *    values lie outside the document's ranges changes nothing
 *    (stats.ignored), as is a move while in motor mode or while a fault
 *    (over temperature, supply voltage outside the limits) holds the torque
 *    off.
 *  - Positions: the shaft of a servo at rest sits at its commanded position
 *    plus its offset, so that POS_READ (the shaft's position) and where the
 *    servo actually is both move with the offset; POS_READ can be negative.
 *    (The document does not say whether POS_READ counts the offset: this is
 *    the model's reading. A peer that reports the shaft less the offset reads
 *    the commanded position instead.)
 *    MOVE_TIME_WRITE goes from where the servo is, linearly, to the target
 *    held within the angle limits, over the time (0: at once), and turns the
 *    torque on. MOVE_TIME_WAIT_WRITE presets the same, started by
 *    MOVE_START (broadcast: every servo at once); MOVE_STOP stops where it
 *    is. A position read mid-move answers the interpolated value, rounded
 *    towards the start. Each servo starts at 500.
 *  - OFFSET_ADJUST moves the shaft at once by the new offset; OFFSET_WRITE
 *    saves it. Only saved offsets survive a power cycle.
 *  - Motor mode (OR_MOTOR_MODE_WRITE, mode 1): the shaft turns at `speed`
 *    position units a second (this model's choice; the document gives no
 *    unit), its position wrapping at LSC_LXBUS_TURN (1500 units, a whole
 *    turn at 0.24 degree a unit); torque on. Mode 0 stops it where it is.
 *  - LOAD_OR_UNLOAD_WRITE 0: torque off, the shaft stays where it is; 1:
 *    torque on, holding where it is. Servos power on with the torque off.
 *  - Temperature (lsc_lxbus_set_temp, default LSC_LXBUS_TEMP_DEFAULT) above
 *    the servo's limit, or the supply voltage (lsc_lxbus_set_vin, shared by
 *    the bus, default LSC_LXBUS_VIN_DEFAULT) outside its limits: a fault;
 *    the torque goes off and stays off until the fault clears. A stall
 *    (lsc_lxbus_set_stall) is a fault too but leaves the torque alone.
 *    LED_ERROR_WRITE's mask says which faults flash the LED
 *    (lsc_lxbus_led_alarm); its default is LSC_LX_ALARM_ALL.
 *  - Kept at power-off (lsc_lxbus_power_cycle; the text of
 *    lsc_lxbus_save): the id, the saved offset, the angle limits, the
 *    voltage limits, the temperature limit, the LED ctrl (and, as a shaft
 *    without power does not move, where it is). Lost: the adjusted offset
 *    (the saved one comes back), motor mode, the torque, presets, the
 *    alarm mask (the document does not say it is kept).
 *
 * Output queue: at most LSC_LXBUS_OUT_BYTES bytes wait to be read; a reply
 * that does not fit is dropped whole (stats.overflow).
 *
 * Wire time (optional): with lsc_lxbus_set_baud(bus, 115200) each byte a
 * servo sends becomes readable one byte time (10 bits / baud) after the one
 * before, and replies wait for the line to be free. Baud 0 (the default) is
 * instant. Echo (lsc_lxbus_set_echo): every byte the host feeds is first sent
 * back at once, as a one-wire bus heard from the host's own pin.
 *
 * Fault injection (for tests of hosts): drop the next N replies; delay every
 * reply by N ms; XOR one byte of the next N replies.
 *
 * Thread safety: none; one lsc_lxbus is used by one thread at a time.
 * Costs: feed is O(servos) per frame; read O(bytes returned).
 */
#ifndef LSC_LXBUS_H
#define LSC_LXBUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"
#include "lsc/lx.h"
#include "lsc/sim.h" /* lsc_sim_event, lsc_sim_log_fn, lsc_sim_parse_error */

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_LXBUS_SERVOS 32u             /* servos on one bus */
#define LSC_LXBUS_OUT_BYTES 256u         /* output queue, bytes */
#define LSC_LXBUS_POSITION_DEFAULT 500u  /* each servo's position when added */
#define LSC_LXBUS_VIN_DEFAULT 7500u      /* the supply, mV */
#define LSC_LXBUS_TEMP_DEFAULT 30u       /* each servo's temperature, degrees C */
#define LSC_LXBUS_FRAME_GAP_MS 50u       /* a partial frame older than this is dropped */
#define LSC_LXBUS_TURN 1500              /* position units in a turn (motor mode) */
#define LSC_LXBUS_TIME_NEVER UINT64_MAX  /* lsc_lxbus_next_event_us(): nothing pending */
/* Room lsc_lxbus_save needs at most (a line of at most 128 bytes a servo). */
#define LSC_LXBUS_STATE_MAX (128u * LSC_LXBUS_SERVOS + 128u)

/* One servo. Fields are the caller's to read, never to write. */
typedef struct lsc_lxbus_servo {
    /* kept at power-off */
    uint8_t id;
    int8_t offset_saved;
    uint16_t limit_min, limit_max;  /* angle limits, positions */
    uint16_t vin_min, vin_max;      /* voltage limits, mV */
    uint8_t temp_limit;             /* degrees C */
    bool led_on;                    /* LED ctrl: the LED is on (0 on the wire) */
    /* lost at power-off */
    int8_t offset;                  /* the offset in effect (adjusted) */
    uint8_t mode;                   /* lsc_lx_mode */
    int16_t speed;                  /* motor mode's speed */
    bool torque;
    uint8_t alarm_mask;             /* LED_ERROR: the faults that flash the LED */
    uint16_t move_pos, move_time;   /* the last MOVE_TIME_WRITE (MOVE_TIME_READ) */
    uint16_t wait_pos, wait_time;   /* the preset (MOVE_TIME_WAIT_READ) */
    bool waiting;                   /* a preset waits for MOVE_START */
    /* the shaft: commanded position from -> to over dur_us from start_us (in
     * servo mode; the shaft is there plus the offset); in motor mode it
     * turns from `from` (a shaft position) at speed from start_us */
    int32_t from, to;
    uint64_t start_us;
    uint32_t dur_us;
    /* its surroundings */
    uint8_t temp_c;
    bool stalled;
} lsc_lxbus_servo;

/* Counters since init. */
typedef struct lsc_lxbus_stats {
    uint32_t frames_in;   /* well-formed frames from the host */
    uint32_t frames_out;  /* replies queued (a collision counts once) */
    uint32_t bad_frames;  /* frames discarded: bad checksum, malformed, unfinished */
    uint32_t ignored;     /* well-formed frames that changed nothing */
    uint32_t noise_bytes; /* bytes outside any frame */
    uint32_t collisions;  /* replies of two or more servos at once */
    uint32_t dropped;     /* replies dropped by fault injection */
    uint32_t overflow;    /* replies dropped: the output queue was full */
} lsc_lxbus_stats;

/* The bus. Fields are internal, but stats, servo[0..nservos) and changes,
 * which the caller may read. */
typedef struct lsc_lxbus {
    lsc_lxbus_stats stats;
    uint32_t changes; /* grows whenever what survives power-off changes */
    uint64_t now_us;
    uint32_t baud;    /* 0: instant */
    bool echo;
    uint16_t vin_mv;  /* the supply */
    lsc_sim_log_fn log;
    void *log_ctx;
    lsc_lx_parser parser;
    uint64_t last_byte_us;
    size_t nservos;
    lsc_lxbus_servo servo[LSC_LXBUS_SERVOS];
    /* output: a ring of bytes, each readable from its time on */
    uint8_t out[LSC_LXBUS_OUT_BYTES];
    uint64_t out_at[LSC_LXBUS_OUT_BYTES];
    size_t out_head, out_len;
    uint64_t line_free_us;
    /* fault injection */
    uint32_t fault_drop, fault_delay_ms, fault_corrupt;
    uint8_t fault_corrupt_offset, fault_corrupt_xor;
} lsc_lxbus;

/* An empty bus at virtual time 0: no servos, supply LSC_LXBUS_VIN_DEFAULT,
 * baud 0, no echo, no log, no faults. Returns 0, or LSC_EINVAL (bus NULL). */
LSC_API int lsc_lxbus_init(lsc_lxbus *bus);

/* Adds a servo fresh from the box but for its id (0..253): offsets 0, angle
 * limits 0..1000, voltage limits 4500..12000 mV, temperature limit 85, LED
 * on, servo mode, torque off, at LSC_LXBUS_POSITION_DEFAULT. An id already
 * on the bus is allowed (they collide). Returns its index (the servo keeps
 * it), LSC_EINVAL (bus NULL, id > 253) or LSC_ENOSPC (bus full). */
LSC_API int lsc_lxbus_add(lsc_lxbus *bus, uint8_t id);

/* The index of the first servo with this id, or -1 (bus NULL too). */
LSC_API int lsc_lxbus_find(const lsc_lxbus *bus, uint8_t id);

/* Servo i's shaft position now (interpolated; with the offset; in motor
 * mode turning), as POS_READ answers it. 0 for a bad bus or i. */
LSC_API int16_t lsc_lxbus_position(const lsc_lxbus *bus, size_t i);
/* True while servo i is moving (a move not finished, or motor mode with a
 * speed). */
LSC_API bool lsc_lxbus_moving(const lsc_lxbus *bus, size_t i);
/* Servo i's faults now (LSC_LX_ALARM_... bits), and whether its LED flashes
 * (faults & alarm mask). 0 / false for a bad bus or i. */
LSC_API uint8_t lsc_lxbus_faults(const lsc_lxbus *bus, size_t i);
LSC_API bool lsc_lxbus_led_alarm(const lsc_lxbus *bus, size_t i);

/* The surroundings: servo i's temperature; the supply of the whole bus;
 * servo i stalled or not. A fault that begins turns the torque off (the
 * shaft stops where it is). Return 0, or LSC_EINVAL (bus NULL, i out of
 * range). */
LSC_API int lsc_lxbus_set_temp(lsc_lxbus *bus, size_t i, uint8_t celsius);
LSC_API int lsc_lxbus_set_vin(lsc_lxbus *bus, uint16_t millivolts);
LSC_API int lsc_lxbus_set_stall(lsc_lxbus *bus, size_t i, bool stalled);

/* Every servo loses power and gets it back now: what is kept at power-off
 * stays, the rest is as at power-on (see above). Output not yet read is
 * lost, as is a partial frame. */
LSC_API void lsc_lxbus_power_cycle(lsc_lxbus *bus);

/* Writes what survives power-off as text into buf[cap] (NUL-terminated), one
 * line a servo in index order, with comment lines first:
 *     servo id=1 offset=0 limits=0,1000 vin-limits=4500,12000 temp-limit=85 led=on position=500
 * Returns its length (without the NUL), or LSC_EINVAL (bus or buf NULL), or
 * LSC_ENOSPC (cap too small: LSC_LXBUS_STATE_MAX always suffices; buf then
 * holds a truncated, NUL-terminated text when cap > 0). */
LSC_API int lsc_lxbus_save(const lsc_lxbus *bus, char *buf, size_t cap);

/* Replaces the bus's servos by those of text[0..len) (the form above; no
 * NUL needed): a line per servo, blank lines and lines starting with '#'
 * skipped; each line "servo" and keys in any order, each at most once, a
 * missing key taking the value of a servo fresh from the box (id 1); values
 * in the document's ranges (position, where the shaft rests: -1000..2000).
 * The servos come up as after a power cycle. Returns the number of servos,
 * or LSC_EINVAL (bad text: err says the line, the column and why; also bus
 * NULL, text NULL with len > 0) or LSC_ENOSPC (more than LSC_LXBUS_SERVOS
 * servos); on error the bus is unchanged. err may be NULL. O(len). */
LSC_API int lsc_lxbus_load(lsc_lxbus *bus, const char *text, size_t len,
                           lsc_sim_parse_error *err);

LSC_API void lsc_lxbus_set_baud(lsc_lxbus *bus, uint32_t baud);
LSC_API void lsc_lxbus_set_echo(lsc_lxbus *bus, bool echo);
/* The log callback (lsc/sim.h's events: RX a frame in, TX a reply, BEEP a
 * frame discarded with text saying why, IGNORED, DROPPED, NOISE). */
LSC_API void lsc_lxbus_set_log(lsc_lxbus *bus, lsc_sim_log_fn fn, void *ctx);
/* Fault injection; each call replaces that fault's setting. Offset past a
 * reply's end: its last byte. */
LSC_API void lsc_lxbus_fault_drop(lsc_lxbus *bus, uint32_t n);
LSC_API void lsc_lxbus_fault_delay(lsc_lxbus *bus, uint32_t ms);
LSC_API void lsc_lxbus_fault_corrupt(lsc_lxbus *bus, uint32_t n, uint8_t offset,
                                     uint8_t xor_mask);

/* Feeds n bytes from the host at the current virtual time. Returns n, or
 * LSC_EINVAL (bus NULL, data NULL with n > 0, n > INT_MAX: nothing fed). */
LSC_API int lsc_lxbus_feed(lsc_lxbus *bus, const uint8_t *data, size_t n);
/* Moves the virtual clock on (saturating). */
LSC_API void lsc_lxbus_advance_us(lsc_lxbus *bus, uint64_t us);
LSC_API uint64_t lsc_lxbus_now_us(const lsc_lxbus *bus);
/* Bytes readable now; reading them (up to cap) removes them. */
LSC_API size_t lsc_lxbus_available(const lsc_lxbus *bus);
LSC_API size_t lsc_lxbus_read(lsc_lxbus *bus, uint8_t *buf, size_t cap);
/* Microseconds until the next output byte is readable (0: now), or
 * LSC_LXBUS_TIME_NEVER when none waits. */
LSC_API uint64_t lsc_lxbus_next_event_us(const lsc_lxbus *bus);

/* Fills io so that a host talks to the bus through it, as lsc_sim_io_init
 * does for the controller: write feeds (with a baud set, the clock first
 * advances a byte time per byte), read returns what is readable, advancing
 * the virtual clock up to the timeout, now_ms is the virtual time. Returns 0,
 * or LSC_EINVAL (an argument NULL). */
LSC_API int lsc_lxbus_io_init(lsc_lxbus *bus, lsc_io *io);

#ifdef __cplusplus
}
#endif

#endif /* LSC_LXBUS_H */
