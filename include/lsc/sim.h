/*
 * lsc sim: a virtual LSC servo controller, driven by bytes and virtual time.
 *
 * Portable C99: no OS calls, no malloc, no stdio, no global or static mutable
 * state. The model lives in a caller-owned lsc_sim (about 10 KiB; make it
 * static or put it on a roomy stack). It is deterministic: the same bytes fed
 * at the same virtual times give the same output bytes at the same times.
 *
 * How it is driven:
 *  - lsc_sim_feed() hands it bytes from the host, at the current virtual time;
 *  - lsc_sim_advance_us() / lsc_sim_advance_ms() move the virtual clock on
 *    (group steps and move interpolation follow it);
 *  - lsc_sim_read() drains the bytes the controller has sent by now (replies
 *    and notifications, whole frames in order);
 *  - lsc_sim_next_event_us() says how long until something changes, so a
 *    caller can sleep (lsc-sim) or jump the clock (the lsc_io adapter).
 *  - lsc_sim_io_init() wraps it all as an lsc_io, for clients (the `sim` port).
 *
 * What the model does (docs/action-groups.md has the group file format):
 *  - Servo channels for every id the protocol can address: 0..255. Each starts
 *    at position 1500, powered, at rest. Positions are stored as sent (no
 *    clamping to the 500..2500 a PWM board drives), unless the servo was
 *    given a range (lsc_sim_set_servo: the arm it stands in for).
 *  - servo_move (3): each listed servo goes linearly from its current
 *    (interpolated) position to the target over the frame's time; a position
 *    read mid-move answers the interpolated value, rounded towards the start
 *    position. Time 0 moves at once. A move powers the servo on.
 *    A servo can be held at a position (lsc_sim_block): a gripper closing
 *    on an object stops there while its move's time runs on.
 *  - mult_servo_unload (20): the servos stop where they are (mid-move: at the
 *    interpolated position) and are powered off; they keep that position.
 *  - mult_servo_pos_read (21): replies with the ids in the order asked.
 *  - get_battery_voltage (15): replies with the battery voltage (default
 *    7500 mV, lsc_sim_set_battery()).
 *  - servo offset read (23) and adjust (24), the xArm firmware's (no LSC-6/16/32
 *    board is known to answer them): each servo keeps an offset, 0 at power-on,
 *    that 24 sets and 23 reports in the order asked. It does not move the
 *    servo or change the positions read back.
 *  - action_group_run (6) from the host, or lsc_sim_group_run() (the board's
 *    handle, buttons or Bluetooth): the group's steps run in order, `times`
 *    times (0 = forever). The controller sends 6 (group, times) when it
 *    starts, 8 (group, times) when it ends by itself, 7 when it is stopped.
 *    Each step moves its servos over the step's time scaled by the speed:
 *    time x 100 / percent (computed in microseconds, truncated), but never
 *    less than 1 ms; the next step starts when that time is up.
 *  - Edges of groups (each well-formed: no beep, no reply):
 *      run of a group number with no group loaded: ignored (the running
 *        group, if any, carries on);
 *      run while a group runs: the running group is stopped (7 is sent, its
 *        servos stop where they are) and the new one starts (6);
 *      stop with nothing running: ignored;
 *      stop: the servos the group was moving stop where they are;
 *      speed 0: ignored (the board would divide by zero);
 *      speed for a group number with no group: kept, applies if one is
 *        loaded later; speed for 0xFF (LSC_GROUP_ALL): every group number;
 *      a speed change while a group runs applies from its next step;
 *      a host move of a servo the group also moves: the host's move applies
 *        until the group's next step moves that servo again.
 *    Every ignored command is counted (stats.ignored) and logged.
 *  - A malformed frame gets no reply and changes nothing: the board beeps
 *    twice. The model counts it (stats.beeps) and logs it. Malformed means:
 *    the parser rejected it (LEN contradicting the command, LSC_EFRAME); a
 *    frame that decodes badly (wrong shape, a repeated id); command 8 from
 *    the host (erase on xArm: never obeyed); a controller-only message (a
 *    battery or position reply) or an unknown command; a position request
 *    for more than LSC_READ_MAX ids (no reply frame can carry the answer);
 *    and a frame left unfinished (header and LEN received) for more than
 *    LSC_SIM_FRAME_GAP_MS before the next byte.
 *    Bytes outside any frame (noise) are counted (stats.noise_bytes) and
 *    logged, not beeped.
 *  - Speeds are not kept across power-off: lsc_sim_init() sets every group
 *    to 100 %.
 *
 * Output queue: at most LSC_SIM_OUT_FRAMES frames and LSC_SIM_OUT_BYTES bytes
 * wait to be read; a frame that does not fit is dropped whole (stats.overflow)
 * and logged: the output never holds part of a frame.
 *
 * Wire time (optional): with lsc_sim_set_baud(sim, 9600) each byte the
 * controller sends becomes readable one byte time (10 bits / baud, about
 * 1.04 ms) after the one before, and the lsc_io adapter's write spends the
 * same time per byte of the host's frame. Baud 0 (the default) is instant.
 *
 * Fault injection (for tests of clients): drop the next N replies; delay every
 * frame the controller sends by N ms; corrupt one byte of the next N replies.
 * "Replies" are the answers to battery and position requests; notifications
 * (6, 7, 8) are never dropped or corrupted, but are delayed like replies so
 * the order of frames on the line is kept.
 *
 * Thread safety: none; one lsc_sim is used by one thread at a time.
 * Costs: feed is O(1) per byte plus O(servos in the frame) per frame; advance
 * is O(targets) per group step passed; read is O(bytes returned).
 */
#ifndef LSC_SIM_H
#define LSC_SIM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Limits and defaults -------------------------------------------------- */

#define LSC_SIM_SERVOS 256u             /* servo ids 0..255 */
#define LSC_SIM_GROUPS 255u             /* group numbers 0..254 (255 is "all") */
#define LSC_SIM_POSITION_DEFAULT 1500u  /* every servo's position at init */
#define LSC_SIM_BATTERY_DEFAULT 7500u   /* millivolts at init */
#define LSC_SIM_SPEED_DEFAULT 100u      /* percent, every group at init */
#define LSC_SIM_FRAME_GAP_MS 100u       /* a partial frame older than this is dropped */
#define LSC_SIM_OUT_BYTES 2048u         /* output queue: bytes */
#define LSC_SIM_OUT_FRAMES 64u          /* output queue: frames */
#define LSC_SIM_STEP_MIN_US 1000u       /* shortest step after speed scaling */
#define LSC_SIM_TIME_NEVER UINT64_MAX   /* lsc_sim_next_event_us(): nothing pending */

/* ---- Action groups (caller-owned storage, filled from text) --------------- */

/* One step of a group: move `ntargets` servos (targets[first ..]) over time_ms
 * (at 100 %). A step with no targets is a pause. */
typedef struct lsc_sim_step {
    uint32_t first;    /* index of its first target in lsc_sim_groups.targets */
    uint16_t ntargets; /* 0..256 (ids in a step are distinct) */
    uint16_t time_ms;  /* 1..65535 */
} lsc_sim_step;

/* A set of action groups. Storage for steps and targets is the caller's;
 * lsc_sim_groups_init() hands it over, lsc_sim_groups_parse() fills it.
 * Fields are the caller's to read, never to write. */
typedef struct lsc_sim_groups {
    lsc_sim_step *steps;
    size_t steps_cap; /* at most 65535 are used */
    size_t nsteps;
    lsc_servo *targets;
    size_t targets_cap;
    size_t ntargets;
    uint16_t first_step[LSC_SIM_GROUPS]; /* group g: steps[first_step[g] ..] */
    uint16_t group_steps[LSC_SIM_GROUPS]; /* its step count; 0 = no such group */
} lsc_sim_groups;

/* Where and why a group text was refused. */
typedef struct lsc_sim_parse_error {
    uint32_t line;       /* 1-based line of the error (0: no error) */
    uint32_t column;     /* 1-based column of the offending token */
    const char *message; /* short English text, static; never NULL after a parse */
} lsc_sim_parse_error;

/* Prepares g to use the caller's arrays (either may be NULL with cap 0) and
 * empties it. Returns 0, or LSC_EINVAL if g is NULL or an array is NULL with a
 * non-zero cap. */
LSC_API int lsc_sim_groups_init(lsc_sim_groups *g, lsc_sim_step *steps, size_t steps_cap,
                                lsc_servo *targets, size_t targets_cap);

/* Parses `len` bytes of group text (docs/action-groups.md; need not be NUL
 * terminated) into g, replacing what it held. Returns the number of groups
 * defined (0..255), or: LSC_EINVAL for bad text (err says the line, the
 * column and why), LSC_ENOSPC when the steps or targets do not fit in g's
 * arrays (err says where), LSC_EINVAL for NULL g or text (with len > 0). On
 * error g is left empty. err may be NULL. O(len). */
LSC_API int lsc_sim_groups_parse(lsc_sim_groups *g, const char *text, size_t len,
                                 lsc_sim_parse_error *err);

/* ---- The model ------------------------------------------------------------ */

/* What the log callback is told. */
typedef enum lsc_sim_event_kind {
    LSC_SIM_EV_RX = 1,  /* a well-formed frame from the host: bytes/len */
    LSC_SIM_EV_TX,      /* a frame queued to send (as it goes out, after any
                           corruption): bytes/len; time = when queued */
    LSC_SIM_EV_BEEP,    /* a malformed frame: two beeps; text says why */
    LSC_SIM_EV_IGNORED, /* a well-formed command that changed nothing; text */
    LSC_SIM_EV_DROPPED, /* a frame not sent (fault injection or full queue): bytes/len, text */
    LSC_SIM_EV_NOISE    /* input discarded as noise: bytes/len = the byte just fed */
} lsc_sim_event_kind;

typedef struct lsc_sim_event {
    lsc_sim_event_kind kind;
    uint64_t time_us;     /* virtual time of the event */
    const uint8_t *bytes; /* the frame (RX, TX, DROPPED), the byte (NOISE), else NULL */
    size_t len;
    const char *text;     /* reason (BEEP, IGNORED, DROPPED), else NULL; static */
} lsc_sim_event;

/* Called synchronously from feed/advance/group_run/group_stop; the event and
 * its bytes are valid only during the call. It must not call back into the
 * same lsc_sim. */
typedef void (*lsc_sim_log_fn)(void *ctx, const lsc_sim_event *ev);

/* Counters since init. */
typedef struct lsc_sim_stats {
    uint32_t frames_in;   /* frames the parser delivered (a badly decoding one also beeps) */
    uint32_t frames_out;  /* frames queued to send */
    uint32_t beeps;       /* malformed frames (each one: "two beeps") */
    uint32_t ignored;     /* well-formed commands that changed nothing */
    uint32_t noise_bytes; /* bytes outside any frame */
    uint32_t dropped;     /* replies dropped by fault injection */
    uint32_t overflow;    /* frames dropped because the output queue was full */
} lsc_sim_stats;

/* Internal state of one servo channel (read it through the functions below). */
typedef struct lsc_sim_channel {
    uint64_t start_us; /* when the current move began */
    uint32_t dur_us;   /* its length (0: at rest at `to`) */
    uint16_t from;
    uint16_t to;
    bool powered;
    bool by_group; /* the current move was started by a group step */
    int8_t offset; /* the servo's offset (xArm commands 23, 24; in the padding) */
    /* the positions it can reach, lo .. hi_end - 1 (hi_end 0: no upper
     * end; both 0: anywhere), set by lsc_sim_set_servo or lsc_sim_block
     * (the last call wins; in the padding too) */
    uint16_t lo;
    uint16_t hi_end;
} lsc_sim_channel;

/* One frame waiting in the output queue (internal). */
typedef struct lsc_sim_out {
    uint64_t ready_us; /* when its first byte starts on the line */
    uint16_t len;
    uint16_t sent; /* bytes already read */
} lsc_sim_out;

/* The virtual controller. Every field is internal except `stats`, which the
 * caller may read. Set up with lsc_sim_init(). */
typedef struct lsc_sim {
    lsc_sim_stats stats;
    /* clock and configuration */
    uint64_t now_us;
    uint32_t baud; /* 0: instant */
    uint16_t battery_mv;
    lsc_sim_log_fn log;
    void *log_ctx;
    const lsc_sim_groups *groups;
    /* input */
    lsc_parser parser;
    uint8_t parser_buf[LSC_FRAME_MAX];
    uint64_t last_byte_us;
    /* servos and groups */
    lsc_sim_channel ch[LSC_SIM_SERVOS];
    uint16_t speed[LSC_SIM_GROUPS];
    bool running;
    uint8_t run_group;
    uint16_t run_times;    /* as commanded; 0 = forever */
    uint16_t run_done;     /* iterations finished */
    uint16_t run_step;     /* index within the group of the current step */
    uint64_t step_end_us;  /* when the current step ends */
    /* output queue: a byte ring and the frames in it */
    uint8_t out[LSC_SIM_OUT_BYTES];
    size_t out_head;  /* ring index of the first unread byte */
    size_t out_bytes; /* unread bytes in the ring */
    lsc_sim_out frames[LSC_SIM_OUT_FRAMES];
    size_t frame_head;
    size_t nframes;
    uint64_t line_free_us; /* when the line is free after the last queued frame */
    /* fault injection */
    uint32_t fault_drop;
    uint32_t fault_delay_ms;
    uint32_t fault_corrupt;
    uint8_t fault_corrupt_offset;
    uint8_t fault_corrupt_xor;
} lsc_sim;

/* Power-on state: virtual time 0, every servo at 1500 and powered, battery
 * 7500 mV, every group speed 100 %, no groups, baud 0, no log, no faults,
 * counters zero. Returns 0, or LSC_EINVAL if sim is NULL. */
LSC_API int lsc_sim_init(lsc_sim *sim);

/* Uses the groups in g from now on (NULL: none). g must stay valid and
 * unchanged while sim uses it. A running group is stopped first (7 is sent). */
LSC_API void lsc_sim_set_groups(lsc_sim *sim, const lsc_sim_groups *g);
/* Sets the battery voltage the controller reports. */
LSC_API void lsc_sim_set_battery(lsc_sim *sim, uint16_t millivolts);
/* Models wire time at this baud rate (10 bits a byte); 0 = instant. Applies
 * to frames queued from now on. */
LSC_API void lsc_sim_set_baud(lsc_sim *sim, uint32_t baud);
/* Sets (or with fn NULL, removes) the log callback. */
LSC_API void lsc_sim_set_log(lsc_sim *sim, lsc_sim_log_fn fn, void *ctx);

/* Feeds n bytes from the host at the current virtual time. Returns n, or
 * LSC_EINVAL (sim NULL, data NULL with n > 0, or n > INT_MAX: nothing is
 * fed). Bad input is never an error here: it beeps (see above). */
LSC_API int lsc_sim_feed(lsc_sim *sim, const uint8_t *data, size_t n);

/* Moves the virtual clock on by us (or ms) and runs what happens meanwhile
 * (group steps start and end at their exact times). Saturates at UINT64_MAX - 1. */
LSC_API void lsc_sim_advance_us(lsc_sim *sim, uint64_t us);
LSC_API void lsc_sim_advance_ms(lsc_sim *sim, uint32_t ms);
/* The virtual time in microseconds since init. */
LSC_API uint64_t lsc_sim_now_us(const lsc_sim *sim);

/* Bytes the controller has sent by now (readable without advancing). */
LSC_API size_t lsc_sim_available(const lsc_sim *sim);
/* Copies up to cap of them into buf and removes them; returns the count. */
LSC_API size_t lsc_sim_read(lsc_sim *sim, uint8_t *buf, size_t cap);
/* Microseconds from now until the next change a caller could observe: the
 * next output byte becoming readable, or the running group's next step
 * boundary. 0 if bytes are readable now; LSC_SIM_TIME_NEVER if nothing is
 * pending. */
LSC_API uint64_t lsc_sim_next_event_us(const lsc_sim *sim);

/* Makes servo id a servo with the position range pos_min..pos_max, such as
 * a bus servo's 0..1000 (or the range an arm profile gives it: lsc/arm.h,
 * lsc_arm_stand_in): it rests at position (read at the nearer end of the
 * range when outside it), and every move to it from then on, a host's or a
 * group's, stops at the nearer end of the range when its target lies
 * outside (its move's time runs on), as a bus servo's angle limits make it
 * stop there. pos_max 0 removes the range (the default: positions are kept
 * as sent). The range replaces a block (lsc_sim_block) and the reverse:
 * both are the positions the servo can reach. Its power is left as it is.
 * Returns 0, or
 * LSC_EINVAL (sim NULL, pos_min > pos_max: nothing changes). */
LSC_API int lsc_sim_set_servo(lsc_sim *sim, uint8_t id, uint16_t position, uint16_t pos_min,
                              uint16_t pos_max);

/* Servo id's position now (interpolated mid-move) and whether it is powered. */
LSC_API uint16_t lsc_sim_position(const lsc_sim *sim, uint8_t id);
LSC_API bool lsc_sim_powered(const lsc_sim *sim, uint8_t id);
/* True while servo id is moving (its move has not reached its target). */
LSC_API bool lsc_sim_moving(const lsc_sim *sim, uint8_t id);

/* Something in a servo's way (a gripper closing on an object it holds):
 * from now on servo id cannot go past position `at` on the given side
 * (ABOVE: no position above `at`; BELOW: none below). A move towards that
 * side stops at `at` and stays there, read back as `at`, until a move away
 * takes it back; a servo already past `at` is read at `at`. The move itself
 * is not changed (lsc_sim_moving is true until its time is up), as a real
 * servo keeps pushing. LSC_SIM_BLOCK_NONE removes the block. A block
 * replaces the servo's range (lsc_sim_set_servo) and the reverse. Returns 0,
 * or LSC_EINVAL (sim NULL, side not one of these: nothing changes). */
typedef enum lsc_sim_block_side {
    LSC_SIM_BLOCK_NONE = 0,
    LSC_SIM_BLOCK_ABOVE,
    LSC_SIM_BLOCK_BELOW
} lsc_sim_block_side;
LSC_API int lsc_sim_block(lsc_sim *sim, uint8_t id, uint16_t at, lsc_sim_block_side side);

/* Starts a group the way the board's handle or Bluetooth would (the same
 * rules as a host's run frame; 6 is sent). Returns 0, or LSC_EINVAL if no
 * such group is loaded (nothing changes). */
LSC_API int lsc_sim_group_run(lsc_sim *sim, uint8_t group, uint16_t times);
/* Stops the running group (7 is sent). Returns 0, or LSC_EINVAL if none runs. */
LSC_API int lsc_sim_group_stop(lsc_sim *sim);
/* The running group's number, or -1 if none runs. */
LSC_API int lsc_sim_group_running(const lsc_sim *sim);
/* The speed percent of a group number (LSC_GROUP_ALL: 0, not a group). */
LSC_API uint16_t lsc_sim_group_speed(const lsc_sim *sim, uint8_t group);

/* Fault injection. Each call replaces that fault's previous setting. */
/* Do not send the next n replies (they are counted in stats.dropped). */
LSC_API void lsc_sim_fault_drop(lsc_sim *sim, uint32_t n);
/* Send every frame (replies and notifications) ms later than due (0: off). */
LSC_API void lsc_sim_fault_delay(lsc_sim *sim, uint32_t ms);
/* XOR byte `offset` (past the end: the last byte) of the next n replies with
 * xor_mask. Offset 2 (the LEN byte) with mask 0xFF makes them malformed. */
LSC_API void lsc_sim_fault_corrupt(lsc_sim *sim, uint32_t n, uint8_t offset, uint8_t xor_mask);

/* ---- The lsc_io adapter (the `sim` port) ----------------------------------- *
 * Fills io so that a client talks to sim through it:
 *  - write feeds the bytes (with a baud set, the clock first advances one byte
 *    time per byte, as the bytes cross the line); returns n (LSC_EINVAL for
 *    data NULL with n > 0, or n > INT_MAX);
 *  - read returns the bytes readable now; if there are none it advances the
 *    virtual clock event by event until some are, or until timeout_ms has
 *    passed (then returns 0). No real time passes. LSC_EINVAL for buf NULL
 *    or cap 0; a cap above INT_MAX is treated as INT_MAX;
 *  - now_ms is the virtual time in ms (truncated, wrapping at 2^32).
 * Returns 0, or LSC_EINVAL if an argument is NULL. */
LSC_API int lsc_sim_io_init(lsc_sim *sim, lsc_io *io);

#ifdef __cplusplus
}
#endif

#endif /* LSC_SIM_H */
