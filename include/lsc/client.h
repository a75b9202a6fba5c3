/*
 * lsc client: the host side of the LSC protocol over a caller-supplied byte
 * transport (lsc/io.h): a serial port, an Arduino Stream, an STM32 UART or
 * the in-process simulator.
 *
 * Portable C99: no OS calls, no malloc, no static mutable state. The client
 * struct is the caller's (it holds the parser and its buffer inline); every
 * function uses at most ~LSC_FRAME_MAX + 100 bytes of stack (the frame being
 * sent is encoded on the stack). One client per transport; a client is not
 * thread-safe: call it from one thread at a time (callbacks run on that
 * thread, from inside the client call that read the bytes).
 *
 * Return values: 0 (or a count) on success, a negative LSC_E... code from
 * lsc/core.h on failure:
 *   LSC_EINVAL   an argument is invalid; NOTHING was sent (every frame is
 *                built by the core encoders, which validate, before any byte
 *                goes out).
 *   LSC_ETIMEOUT no reply (or, for lsc_client_wait_group, no end of group)
 *                within the timeout, and no wrong-shape reply was seen.
 *   LSC_EREPLY   the timeout passed and the controller did send something for
 *                this request, but of the wrong shape: a frame with the reply's
 *                command that does not answer the request (other length, other
 *                ids) or a malformed frame (LSC_EFRAME/LSC_ETOOBIG from the
 *                parser). Wrong-shape frames never end the wait early.
 *   LSC_ENOSPC   (raw request only) the reply is longer than the caller's buffer.
 *   other        what the transport returned (LSC_EIO, LSC_ENODEV, ...),
 *                passed through unchanged; a transport that returns an
 *                impossible value (more bytes than asked, a positive write
 *                count other than n) gives LSC_EIO.
 *
 * Timeouts: a call with a reply waits at most timeout_ms from its start, as
 * measured by io.now_ms, in one or more io.read calls each given the time
 * that is left. timeout_ms 0 means: read only what has already arrived.
 *
 * Notifications: the controller sends action_group_run (6, a group started),
 * action_group_stop (7, a group was stopped) and action_group_complete (8, a
 * group ran to its end) whenever they happen: before a reply, between its
 * bytes, after it. Every frame the client parses, in any call that reads
 * (replies, lsc_client_poll, lsc_client_wait_group), is checked first: a 6, 7
 * or 8 frame is a notification, never a reply. Each is handed to the
 * notification callback (lsc_client_set_notify) at once, in the order the
 * frames arrived, from inside that call. A call that reads processes every
 * byte of each chunk the transport returned, so notifications that came in the
 * same chunk as a reply are delivered before that call returns. Calls that only
 * send (move, run, stop, speed, unload, raw send) never read. Between calls,
 * call lsc_client_poll to read and dispatch what has arrived. With no callback
 * set, notifications are counted (lsc_client.notifications) and dropped.
 *
 * Frame gap: while the parser holds part of a frame, and the client, reading,
 * sees the line silent for gap_ms (an io.read returns nothing gap_ms or more
 * after the last bytes arrived), the partial frame is dropped (lsc_parser_reset),
 * so a frame torn by a reset, a plug-in or noise never swallows the start of
 * the next reply. Only silence the client observes counts: bytes found by a
 * read that comes late (a caller polling 100 ms apart) continue the frame,
 * however long ago the previous read was. While a partial frame is pending,
 * a longer wait is split so that one read ends when the gap is reached.
 * The default is LSC_CLIENT_GAP_MS = 50 ms: a controller sends each frame in one burst (at
 * 9600 baud a byte is 1.04 ms, a whole 257-byte frame 268 ms but its bytes
 * follow back to back), yet USB serial adapters deliver data in USB packets
 * (FTDI's latency timer is 16 ms by default, CH340/CP210x similar) and a busy
 * host can be scheduled late by a few ms, so a gap shorter than ~20 ms would
 * tear real frames. 50 ms is well above that and still far below the time a
 * human or script waits between a torn frame and the next request. Change it
 * with lsc_client_set_gap (0 disables the reset).
 */
#ifndef LSC_CLIENT_H
#define LSC_CLIENT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The longest frame the client can receive, in bytes (its receive buffer,
 * inside lsc_client). The default takes any frame. Small targets may choose a
 * smaller value, at least 7 (a battery reply, a notification), by defining it
 * the same for the library and every file that includes this header; longer
 * replies are then refused as LSC_EREPLY. A position reply for n servos is
 * 3n + 5 bytes. On AVR (an Uno has 2 KiB of RAM) the default is 32: position
 * reads of up to 9 servos at a time. */
#ifndef LSC_CLIENT_RX_MAX
#if defined(__AVR__)
#define LSC_CLIENT_RX_MAX 32u
#else
#define LSC_CLIENT_RX_MAX LSC_FRAME_MAX
#endif
#endif

/* Default silence, in ms, after which a partial frame is dropped (see above). */
#define LSC_CLIENT_GAP_MS 50u

/* Before sending a request, the client reads and processes what has already
 * arrived (a late reply to an earlier request must not be taken for this
 * one's; notifications in it are delivered): until a read returns nothing, but
 * for at most this many ms of io.now_ms, so input that never stops cannot hold
 * the request back. */
#define LSC_CLIENT_DRAIN_MS 50u

/* ... and for at most this many io.read calls (4 KiB in 32-byte reads, a
 * Linux tty's whole input buffer), so that input that never stops cannot hold
 * the request back even when io.now_ms does not advance (a broken clock). */
#define LSC_CLIENT_DRAIN_READS 128u

/* A call that waits (a request's reply, lsc_client_poll,
 * lsc_client_wait_group) for timeout_ms makes at most
 * LSC_CLIENT_WAIT_READS_MIN + LSC_CLIENT_READS_PER_MS * timeout_ms io.read
 * calls, then ends as if the time ran out: more reads than any line fills in
 * that time (at 230400 baud 23 bytes arrive per ms, and a read takes at least
 * one), so only a transport whose clock stands still while input keeps coming
 * meets the bound. */
#define LSC_CLIENT_WAIT_READS_MIN 64u
#define LSC_CLIENT_READS_PER_MS 32u

/* A controller notification. cmd is LSC_CMD_GROUP_RUN (6: group started),
 * LSC_CMD_GROUP_STOP (7: stopped; group and times are 0, the frame has none)
 * or LSC_CMD_GROUP_COMPLETE (8: ran to its end). */
typedef struct lsc_notification {
    uint8_t cmd;
    uint8_t group;
    uint16_t times;
} lsc_notification;

/* Called once per notification, in arrival order, from inside the client call
 * that parsed it. It must not call back into the same client. */
typedef void (*lsc_notify_fn)(void *user, const lsc_notification *n);

/* Direction of a traced frame. */
typedef enum lsc_trace_dir {
    LSC_TRACE_TX = 0, /* a whole frame the client is about to write */
    LSC_TRACE_RX = 1  /* a whole valid frame the parser returned (reply,
                         notification or anything else), before it is handled */
} lsc_trace_dir;

/* Called with the bytes of every frame sent and received (for lscctl -v).
 * Received frames are given as canonical bytes 55 55 LEN CMD params. Noise and
 * malformed input are not traced (see the parser's counters). It must not
 * call back into the same client. */
typedef void (*lsc_trace_fn)(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n);

/* The client. Initialise with lsc_client_init; fields are the caller's to
 * read (the counters are for diagnostics), never to write. */
typedef struct lsc_client {
    lsc_io io;
    lsc_parser parser;
    uint8_t rxbuf[LSC_CLIENT_RX_MAX];
    uint32_t gap_ms;
    uint32_t last_rx_ms; /* io.now_ms when a read last brought bytes */
    lsc_notify_fn notify;
    void *notify_user;
    lsc_trace_fn trace;
    void *trace_user;
    uint32_t notifications; /* notifications parsed (delivered or not) */
    uint32_t unexpected;    /* other frames discarded: stray or wrong-shape replies */
} lsc_client;

/* What the client has received since lsc_client_init, for diagnostics (the
 * same counts as the fields of lsc_client and its parser). Read them before
 * and after a call and subtract to see what arrived during it: after a
 * timeout, whether the line was silent (nothing), carried only noise (bytes
 * that formed no frame: often a wrong baud rate, or a reply whose bytes came
 * more than the frame gap apart), only notifications, or frames that answered
 * something else. Every received byte is in exactly one of: a frame, the
 * discarded bytes, the pending bytes. */
typedef struct lsc_client_counts {
    uint32_t frames;        /* valid frames: replies, notifications and any other */
    uint32_t notifications; /* of those, notifications (6, 7, 8) */
    uint32_t unexpected;    /* of those, frames that answered nothing waited for:
                               other commands, wrong-shape or late replies */
    uint32_t discarded;     /* bytes that formed no frame: noise, malformed frames,
                               partial frames dropped on the frame gap */
    uint32_t malformed;     /* malformed or oversized frames among those bytes */
    uint32_t pending;       /* bytes of a frame still incomplete */
} lsc_client_counts;

/* Fills *out with c's counts (all 0 if c is NULL). out may be NULL. */
LSC_API void lsc_client_get_counts(const lsc_client *c, lsc_client_counts *out);

/* Prepares c to talk through io (copied; io.write, io.read and io.now_ms must
 * all be set). No callbacks, gap LSC_CLIENT_GAP_MS. Sends and reads nothing.
 * Returns 0, or LSC_EINVAL if c is NULL or io is incomplete (c is then unusable:
 * every other call returns LSC_EINVAL). A macro: it passes the size of
 * lsc_client and LSC_CLIENT_RX_MAX as this file saw them, so that a program
 * built with another LSC_CLIENT_RX_MAX than the library is refused
 * (LSC_EINVAL, c unusable, nothing written past c->io) rather than
 * corrupting memory. */
#define lsc_client_init(c, io)                                                                \
    lsc_client_init_checked((c), (io), sizeof(lsc_client), (size_t)LSC_CLIENT_RX_MAX)

/* lsc_client_init's function: size and rx_max must be the library's own
 * sizeof(lsc_client) and LSC_CLIENT_RX_MAX, else LSC_EINVAL. */
LSC_API int lsc_client_init_checked(lsc_client *c, const lsc_io *io, size_t size,
                                    size_t rx_max);

/* Sets (fn non-NULL) or clears (fn NULL) the notification callback. */
LSC_API void lsc_client_set_notify(lsc_client *c, lsc_notify_fn fn, void *user);

/* Sets or clears the frame trace callback. */
LSC_API void lsc_client_set_trace(lsc_client *c, lsc_trace_fn fn, void *user);

/* Sets the frame gap in ms (0: never reset the parser on silence). */
LSC_API void lsc_client_set_gap(lsc_client *c, uint32_t gap_ms);

/* ---- Commands without a reply: each sends one frame and returns 0, or
 * LSC_EINVAL (nothing sent), or the transport's error. They do not read. ---- */

/* servo_move: n servos (1..LSC_MOVE_MAX, distinct ids) to their positions over time_ms. */
LSC_API int lsc_client_move(lsc_client *c, uint16_t time_ms, const lsc_servo *servos, size_t n);
/* servo_move of one servo. */
LSC_API int lsc_client_move_one(lsc_client *c, uint8_t id, uint16_t position, uint16_t time_ms);
/* action_group_run: run group `times` times (0 = forever). */
LSC_API int lsc_client_run_group(lsc_client *c, uint8_t group, uint16_t times);
/* action_group_stop: stop the running group (no effect on the board if none runs). */
LSC_API int lsc_client_stop_group(lsc_client *c);
/* action_group_speed: group (or LSC_GROUP_ALL) at percent of its original speed. */
LSC_API int lsc_client_set_group_speed(lsc_client *c, uint8_t group, uint16_t percent);
/* mult_servo_unload: power off n servos (1..LSC_UNLOAD_MAX distinct ids, n != 82). */
LSC_API int lsc_client_unload(lsc_client *c, const uint8_t *ids, size_t n);

/* ---- Commands with a reply ---------------------------------------------- */

/* get_battery_voltage: on success stores the millivolts in *mv and returns 0. */
LSC_API int lsc_client_get_battery(lsc_client *c, uint16_t *mv, uint32_t timeout_ms);

/* mult_servo_pos_read of n ids (1..LSC_READ_MAX distinct, n != 82). Only a
 * reply that carries exactly these ids in this order is taken; on success
 * out[i] = {ids[i], position} for every i and the return value is n. out
 * (n entries) is written only on success. */
LSC_API int lsc_client_read_positions(lsc_client *c, const uint8_t *ids, size_t n,
                                      lsc_servo *out, uint32_t timeout_ms);

/* xArm firmware only (commands 23 and 24, beyond the V1.2 document; LSC-6/16/32
 * boards may not answer: then LSC_ETIMEOUT). Servo offset read of n ids
 * (1..LSC_OFFSET_MAX distinct): only a reply with exactly these ids in this
 * order is taken; on success out[i] = {ids[i], offset} and the return value
 * is n (out written only on success). */
LSC_API int lsc_client_read_offsets(lsc_client *c, const uint8_t *ids, size_t n,
                                    lsc_servo_offset *out, uint32_t timeout_ms);
/* Servo offset adjust: sets servo id's offset (no reply). */
LSC_API int lsc_client_adjust_offset(lsc_client *c, uint8_t id, int8_t offset);

/* ---- Notifications ------------------------------------------------------- */

/* Reads what arrives within timeout_ms (0: only what is already there) and
 * dispatches every notification in it; returns the number of notifications
 * parsed (0 if none), or the transport's error. Other frames are discarded
 * (counted in c->unexpected). Returns as soon as one read brought bytes and
 * they were processed, or when the timeout passed. */
LSC_API int lsc_client_poll(lsc_client *c, uint32_t timeout_ms);

/* Waits until the running action group ends: an action_group_complete (8) or
 * action_group_stop (7) notification. Returns 0 and stores it in *out (cmd 8
 * with the group and times, or cmd 7), or LSC_ETIMEOUT if neither arrived
 * within timeout_ms. Only notifications arriving during this call count (one
 * that an earlier call already delivered is not seen again: track those with
 * the callback). Every notification, including the one that ends the wait, is
 * also delivered to the callback. Bytes after the ending notification in the
 * same chunk are processed too. out may be NULL. Reads only; sends nothing. */
LSC_API int lsc_client_wait_group(lsc_client *c, uint32_t timeout_ms, lsc_notification *out);

/* ---- Raw frames: any command the typed calls above do not cover (firmware
 * experiments, commands of other boards, a tool's "send" command). Command 8
 * is refused; a tool that must send it anyway encodes the frame itself
 * (lsc_encode_frame) and writes it through its transport. ---------------- */

/* Sends the frame cmd + n parameter bytes (n <= LSC_PARAMS_MAX, n != 83).
 * Refuses cmd 8 (LSC_EINVAL): on the xArm a host-sent 8 erases the action
 * groups. Returns 0 or an error; does not read. */
LSC_API int lsc_client_send_raw(lsc_client *c, uint8_t cmd, const uint8_t *params, size_t n);

/* Sends as lsc_client_send_raw, then waits for the next frame whose command
 * is reply_cmd (any length; reply_cmd 6, 7 and 8 are notifications and are
 * refused with LSC_EINVAL). Copies its parameter bytes to reply (cap bytes)
 * and returns how many, or LSC_ENOSPC (reply too long; nothing copied; the
 * frame is consumed), LSC_ETIMEOUT, LSC_EREPLY (only malformed input came). */
LSC_API int lsc_client_request_raw(lsc_client *c, uint8_t cmd, const uint8_t *params, size_t n,
                                   uint8_t reply_cmd, uint8_t *reply, size_t cap,
                                   uint32_t timeout_ms);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CLIENT_H */
