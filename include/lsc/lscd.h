/*
 * lsc lscd client: the transport to a controller that the lscd daemon owns.
 *
 * lscd (lscd(8)) opens one controller and serves it on a Unix stream socket
 * to any number of programs at once. This is the client side: it connects to
 * that socket and gives an lsc_io (lsc/io.h), so lsc_client (lsc/client.h)
 * and everything above it work through the daemon unchanged. The device
 * layer (lsc/device.h) selects it for the names "lscd:NAME" and "lscd:PATH".
 * The wire protocol is docs/lscd-protocol.md; the constants below are its
 * numbers, for programs that speak it themselves.
 *
 * What the daemon guarantees a client (lscd(8) has the whole contract):
 *  - frames of all clients reach the controller one at a time, in arrival
 *    order; the reply to a request goes only to the client that sent it;
 *  - controller notifications (6, 7, 8) go to every subscribed client (this
 *    transport subscribes unless told not to), in the order they arrived;
 *  - a frame that cannot be handled within the client's timeout (another
 *    client's lease, a queue of other clients' requests) is dropped, never
 *    sent late.
 *
 * What this transport does with it: every frame written through the io is
 * confirmed by the daemon (its verdict): write returns n once the frame went
 * to the controller (for a request: once its reply is here, ready to read),
 * or the error it met:
 *   LSC_ETIMEOUT  a request got no reply, or the frame could not be sent within
 *                 the timeout (lsc_lscd_set_timeout)
 *   LSC_EBUSY     another client holds the lease and this client refuses to wait
 *                 (options.refuse_busy), or waited its whole timeout for it
 *   LSC_ENODEV    the controller is gone (unplugged; the daemon reopens it when
 *                 it is back), or the daemon closed the connection (stopped,
 *                 killed, restarted: the handle must be reopened)
 *   LSC_EREPLY, LSC_EIO, LSC_EINVAL  what the daemon's own request met
 * read returns replies and notifications, and LSC_ENODEV once when the
 * controller goes away (a monitor learns of it), or for ever after the
 * daemon closed the connection. No call waits longer than its timeout plus
 * LSC_LSCD_SLACK_MS; none hangs when the daemon dies (its socket closes).
 *
 * Host only (POSIX sockets). A handle is an opaque heap object; one thread at
 * a time per handle; handles are independent (no global state). SIGPIPE is
 * never raised (sends use MSG_NOSIGNAL).
 */
#ifndef LSC_LSCD_H
#define LSC_LSCD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Names ------------------------------------------------------------------ */

/* Where lscd's sockets are, unless $LSC_LSCD_DIR names another directory. */
#define LSC_LSCD_DIR "/run/lsc"
/* The prefix of device names that select this transport ("lscd:ttyUSB0"). */
#define LSC_LSCD_PREFIX "lscd:"
/* Room for a socket path (the OS's limit, sun_path, is 108 on Linux). */
#define LSC_LSCD_PATH_MAX 108u
/* Room for a NAME (lsc_lscd_name). */
#define LSC_LSCD_NAME_MAX 64u

/* The NAME lscd serves a port under (its socket is DIR/NAME.sock, its systemd
 * instance lscd@NAME): "sim" -> "sim", "hid" -> "hid", "hid:SERIAL" ->
 * "hid-SERIAL", a path -> its last component ("/dev/ttyUSB0" -> "ttyUSB0"),
 * a bus "lx:PATH" -> "lx-" and its path's ("lx:/dev/ttyUSB0" -> "lx-ttyUSB0",
 * "lx:sim" -> "lx-sim");
 * every byte outside [A-Za-z0-9_.-] becomes '_'. Writes it NUL-terminated to
 * out (cap bytes) and returns its length, or LSC_EINVAL (port NULL or empty,
 * nothing after its last '/' or after "lx:", a name "." or "..") or LSC_ENOSPC (longer than cap - 1,
 * or than LSC_LSCD_NAME_MAX - 1). */
LSC_API int lsc_lscd_name(const char *port, char *out, size_t cap);

/* The port a NAME stands for (the inverse, for systemd's lscd@NAME): "sim",
 * "hid", "hid-SERIAL" -> "hid:SERIAL", "lx-sim" -> "lx:sim", "lx-NAME" ->
 * "lx:/dev/NAME", anything else -> "/dev/NAME". Returns
 * the length written to out, or LSC_EINVAL (empty, or containing '/'), or
 * LSC_ENOSPC. */
LSC_API int lsc_lscd_port_of_name(const char *name, char *out, size_t cap);

/* The socket path of a daemon name: "lscd:" is skipped if present; what is
 * left is a path if it contains a '/', else a NAME, whose socket is
 * DIR/NAME.sock with DIR $LSC_LSCD_DIR when set and not empty, else
 * LSC_LSCD_DIR. Returns the length written to out, or LSC_EINVAL (NULL or
 * empty) or LSC_ENOSPC (longer than cap - 1 or LSC_LSCD_PATH_MAX - 1). */
LSC_API int lsc_lscd_socket_path(const char *name, char *out, size_t cap);

/* ---- Which socket serves which port: lscd's records ---------------------------- *
 * lscd (lscd(8)) records the serial port it holds and the socket it serves it
 * on in DIR/NAME.record (DIR and NAME as for its sockets above), so that a
 * program that opens the port itself is sent to the socket wherever it is
 * (lscd --socket PATH). A record is text, one "key value" line each: "pid N",
 * "port PATH", "socket PATH" (both absolute). lscd writes it atomically
 * (a temporary file renamed) and removes it when it stops; one left by an
 * lscd that was killed names a process that is gone, and is ignored. */
#define LSC_LSCD_RECORD_SUFFIX ".record"

/* The socket that lscd's record says serves port (a serial port's path):
 * reads DIR/NAME.record for port's NAME; the record counts when it names the
 * same file as port (stat(2): the same device node, through links) and its
 * process is alive. Writes the socket's path to out[cap], *pid (may be NULL)
 * the lscd's process, and returns the path's length; or LSC_ENODEV (no
 * record, another port of the same NAME, its lscd is gone), LSC_EINVAL (port
 * or out NULL, a port without a NAME, a file there that is not a record),
 * LSC_ENOSPC (longer than cap - 1). It does not connect: lsc_lscd_open tells
 * whether lscd answers there. */
LSC_API int lsc_lscd_recorded_socket(const char *port, char *out, size_t cap, long *pid);

/* The daemon's side of the records. lsc_lscd_record_path: DIR/NAME.record
 * of port, into out[cap]; returns its length, or lsc_lscd_name's and
 * lsc_lscd_socket_path's errors. lsc_lscd_record_write: writes the record of
 * port (this process serves it on socket_path; both made absolute)
 * atomically, making DIR if missing (its last component), and its path to
 * record[cap]; returns 0, or LSC_EACCES (DIR not writable), LSC_EINVAL (a
 * path with a newline), LSC_ENOSPC, LSC_EIO. The caller removes it (unlink)
 * when it stops. */
LSC_API int lsc_lscd_record_path(const char *port, char *out, size_t cap);
LSC_API int lsc_lscd_record_write(const char *port, const char *socket_path, char *record,
                                  size_t cap);

/* ---- The connection ----------------------------------------------------------- */

typedef struct lsc_lscd lsc_lscd;

#define LSC_LSCD_CONNECT_TIMEOUT 5000u /* ms, default of options.connect_timeout_ms */
/* How long past its own timeout a call waits for the daemon's answer before
 * it gives up with LSC_EIO (the daemon is stuck). */
#define LSC_LSCD_SLACK_MS 5000u

/* How to connect; a NULL options pointer means all defaults. The caller
 * sets size to sizeof(lsc_lscd_options) of its headers: fields are only ever
 * added at the end, and those beyond size take their default, as if 0 (a
 * size smaller than the size field and timeout_ms is LSC_EINVAL). In C99:
 *     lsc_lscd_options o = { .size = sizeof o, .no_notifications = true }; */
typedef struct lsc_lscd_options {
    size_t size;
    /* The most a frame may take at the daemon, from its arrival to its end
     * (for a request: its reply): 0 means 1000 ms. */
    uint32_t timeout_ms;
    /* How long the open waits for the daemon's greeting (a socket-activated
     * daemon starts and opens its controller first): 0 means
     * LSC_LSCD_CONNECT_TIMEOUT. */
    uint32_t connect_timeout_ms;
    /* While another client holds the lease: false (default) waits, up to the
     * timeout; true refuses at once with LSC_EBUSY. */
    bool refuse_busy;
    /* true: do not subscribe to notifications (replies only). */
    bool no_notifications;
} lsc_lscd_options;

/* Connects to the daemon `name` (lsc_lscd_socket_path), tells it the
 * options, and waits for its greeting. Returns 0, or LSC_EINVAL (a bad name,
 * opt->size too small: nothing is sent),
 * LSC_ENODEV (no daemon there: no socket, or nobody listening), LSC_EACCES
 * (permission denied: the message says which group), LSC_ETIMEOUT (no
 * greeting within the connect timeout), LSC_EREPLY (what answered is not lscd,
 * or speaks another protocol version), LSC_ENOSPC (out of memory). On return
 * *out is a handle even when the open failed (NULL only when memory ran out),
 * so that lsc_lscd_error can say why: close it in every case. A failed handle
 * refuses every call with the open's error. Nothing reaches the controller. */
LSC_API int lsc_lscd_open(const char *name, const lsc_lscd_options *opt, lsc_lscd **out);

/* Closes the connection (a lease held ends) and frees s (NULL is fine). */
LSC_API void lsc_lscd_close(lsc_lscd *s);

/* The last error as one line, no newline ("" if none); never NULL. For a NULL
 * s: "out of memory". Valid until the next call on s. */
LSC_API const char *lsc_lscd_error(const lsc_lscd *s);

/* Fills *io with the transport (see the top): write, read and now_ms
 * (CLOCK_MONOTONIC). Valid while s is open. */
LSC_API void lsc_lscd_get_io(lsc_lscd *s, lsc_io *io);

/* The same functions, for callers that wrap them (ctx is the lsc_lscd *). */
LSC_API int lsc_lscd_write(void *ctx, const uint8_t *data, size_t n);
LSC_API int lsc_lscd_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms);
LSC_API uint32_t lsc_lscd_now_ms(void *ctx);

/* Sets the per-frame timeout (as options.timeout_ms; 0 means 1000 ms) for
 * frames written from now on. Returns 0 or the connection's error. */
LSC_API int lsc_lscd_set_timeout(lsc_lscd *s, uint32_t timeout_ms);

/* ---- Lease: one client has the controller to itself for a while ------------ */

/* Takes (or, when held, renews) the lease for ms milliseconds (0: the
 * daemon's longest, lscd --lease-max; longer requests are cut to it). While
 * it is held only this client's frames reach the controller; others wait or
 * are refused (their choice). If another client holds it, waits up to
 * wait_ms (0: not at all) for it. Returns 0 (held; lsc_lscd_lease_ms says
 * for how long), LSC_EBUSY (another client kept it), or the connection's
 * error. It ends at lsc_lscd_release, at lsc_lscd_close or the process's
 * end (however it ends), or when its time runs out. */
LSC_API int lsc_lscd_lease(lsc_lscd *s, uint32_t ms, uint32_t wait_ms);
/* The time the last granted lease was given, in ms (0: none granted). */
LSC_API uint32_t lsc_lscd_lease_ms(const lsc_lscd *s);
/* Ends this client's lease. Returns 0 (ended), LSC_EINVAL (none was held,
 * e.g. its time had run out) or the connection's error. */
LSC_API int lsc_lscd_release(lsc_lscd *s);

/* ---- Halt: stop everything, whoever holds the lease ------------------------------ */

/* Halts the controller (lsc_device_halt through lscd; lscctl halt), never
 * refused for a lease: lscd, as soon as it reads the request, ends the lease
 * (its holder is told: LEASE with state LSC_LSCD_LEASE_HALTED), drops every
 * client's frames that wait for the controller (their verdicts: LSC_EBUSY),
 * and then, ahead of anything queued after it, stops the running action
 * group and holds every servo where it is (lsc_device_halt on its own
 * controller: every id of its kind). Every client is told when it is done
 * (HALTED: the result and lscd's message; lsc_lscd_halts counts them).
 * Returns the halt's result: 0, LSC_HOLD_BEYOND, or its error (e.g.
 * LSC_ETIMEOUT: positions not read), lsc_lscd_error saying it; or the
 * connection's error (LSC_EIO when no answer came within twice the timeout
 * plus LSC_LSCD_SLACK_MS). */
LSC_API int lsc_lscd_halt(lsc_lscd *s);
/* How many halts (by any client) lscd has told this client of. */
LSC_API uint32_t lsc_lscd_halts(const lsc_lscd *s);

/* ---- Status --------------------------------------------------------------------- */

/* Called once per status item: key and value are NUL-terminated text, valid
 * during the call. */
typedef void (*lsc_lscd_status_fn)(void *user, const char *key, const char *value);

/* Asks the daemon for its status and calls fn for each item, in the daemon's
 * order (lscd(8) lists the keys: the port, the controller, the clients, the
 * lease, the counters). Returns the number of items, or the connection's
 * error, or LSC_ETIMEOUT (no complete answer within timeout_ms, 0 meaning
 * 1000). Notifications that arrive meanwhile are kept for read. */
LSC_API int lsc_lscd_status(lsc_lscd *s, lsc_lscd_status_fn fn, void *user, uint32_t timeout_ms);

/* Whether the daemon has its controller open (as last heard from it). */
LSC_API bool lsc_lscd_controller_present(const lsc_lscd *s);
/* Frames meant for this client that were dropped because it did not read
 * them in time (the daemon's count, as last heard, plus this transport's
 * own while a call waited). */
LSC_API uint32_t lsc_lscd_dropped(const lsc_lscd *s);

/* For a program's own event loop: the connection's socket, else -1 (a
 * failed open, or s NULL). It polls readable when the daemon sent something
 * (a frame, the news that the controller went), and POLLHUP when the daemon
 * went away. Read through lsc_lscd_read, never on it: a call that waited
 * (a write, a status) may have taken frames off the socket already, which
 * lsc_lscd_input_pending then says. */
LSC_API int lsc_lscd_fileno(const lsc_lscd *s);
/* True when what the daemon sent waits in s for lsc_lscd_read (frames, or
 * the controller's loss), with no byte of it left on the socket to tell. */
LSC_API bool lsc_lscd_input_pending(const lsc_lscd *s);

/* ---- The wire protocol's numbers (docs/lscd-protocol.md) -------------------- */

#define LSC_LSCD_PROTOCOL 1u /* the version in HELLO */
/* Control frames: 55 55 LEN LSC_LSCD_CMD OP ARGS... both ways. lscd never
 * forwards this command to a controller. */
#define LSC_LSCD_CMD 0xCDu
/* Most argument bytes a control frame carries (after its op byte). */
#define LSC_LSCD_ARGS_MAX (LSC_PARAMS_MAX - 1u)

/* The wire's 32-bit numbers (timeouts, lease lengths, counters) are
 * little-endian (docs/lscd-protocol.md): these put and get one, for lscd and
 * for programs that speak the protocol themselves. */
static inline void lsc_lscd_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)((v >> 24) & 0xFFu);
}
static inline uint32_t lsc_lscd_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}
/* Longest a client may ask for as its per-frame timeout (ms, OP_TIMEOUT). */
#define LSC_LSCD_TIMEOUT_MAX 600000u

/* Writes the control frame 55 55 LEN CD OP ARGS[0..n) at buf[cap] (either
 * way: a client's request or lscd's event); returns its length, or
 * LSC_EINVAL (n > LSC_LSCD_ARGS_MAX, args NULL with n > 0, or n == 82: LEN
 * would be 0x55) or LSC_ENOSPC. */
LSC_API int lsc_lscd_encode_ctl(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *args,
                                size_t n);

/* Client -> lscd. */
typedef enum lsc_lscd_op {
    LSC_LSCD_OP_SUBSCRIBE = 0x01, /* on (u8 0/1): notifications (default on) */
    LSC_LSCD_OP_MODE = 0x02,      /* flags (u8): LSC_LSCD_MODE_* (default 0) */
    LSC_LSCD_OP_TIMEOUT = 0x03,   /* ms (u32): per-frame timeout, 0 = lscd's */
    LSC_LSCD_OP_LEASE = 0x04,     /* ms (u32), wait_ms (u32) */
    LSC_LSCD_OP_RELEASE = 0x05,   /* - */
    LSC_LSCD_OP_STATUS = 0x06,    /* - */
    LSC_LSCD_OP_PING = 0x07,      /* token (u32): answered by PONG */
    LSC_LSCD_OP_HALT = 0x08       /* -: stop everything (lsc_lscd_halt) */
} lsc_lscd_op;

/* MODE flags. */
#define LSC_LSCD_MODE_ACK 0x01u    /* a VERDICT for every frame */
#define LSC_LSCD_MODE_REFUSE 0x02u /* refuse frames while another client leases */

/* lscd -> client. */
typedef enum lsc_lscd_event {
    LSC_LSCD_EV_HELLO = 0x80,      /* version (u8), controller present (u8) */
    LSC_LSCD_EV_VERDICT = 0x81,    /* cmd (u8), result (i8: 0 or LSC_E...) */
    LSC_LSCD_EV_LEASE = 0x82,      /* state (u8: LSC_LSCD_LEASE_*), ms (u32) */
    LSC_LSCD_EV_CONTROLLER = 0x83, /* present (u8), text: why it went */
    LSC_LSCD_EV_DROPPED = 0x84,    /* count (u32): frames dropped so far */
    LSC_LSCD_EV_STATUS = 0x85,     /* text "key=value" */
    LSC_LSCD_EV_STATUS_END = 0x86, /* - */
    LSC_LSCD_EV_PONG = 0x87,       /* token (u32) */
    LSC_LSCD_EV_ERROR = 0x88,      /* op (u8), text: a control frame refused */
    LSC_LSCD_EV_HALTED = 0x89      /* result (i8: 0, 1 or LSC_E...), text: a halt is done */
} lsc_lscd_event;

/* LEASE states. */
#define LSC_LSCD_LEASE_GRANTED 1u
#define LSC_LSCD_LEASE_BUSY 2u     /* another client kept it for wait_ms */
#define LSC_LSCD_LEASE_RELEASED 3u
#define LSC_LSCD_LEASE_EXPIRED 4u  /* its time ran out */
#define LSC_LSCD_LEASE_NONE 5u     /* RELEASE without a lease */
#define LSC_LSCD_LEASE_HALTED 6u   /* a halt (by any client) ended it */

#ifdef __cplusplus
}
#endif

#endif /* LSC_LSCD_H */
