/* lsc device: what the files of src/device share (private). */
#ifndef LSC_DEVICE_INTERNAL_H
#define LSC_DEVICE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/arm.h"
#include "lsc/convert.h"
#include "lsc/device.h"
#include "lsc/env.h"
#include "lsc/discovery.h"
#include "lsc/files.h"
#include "lsc/link.h"
#include "../util/sized.h" /* structs that grow */
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/text.h"
#include "lsc/hid.h"
#include "lsc/lscd.h"
#include "lsc/serial.h"
#include "lsc/sim.h"
#include "device_sim.h" /* the sim hooks, not public */

#include "transport.h"

#define DEVICE_MESSAGE_MAX 640u
#define DEVICE_WAIT_CHUNK_MS 1000u /* a wait without limit reads in chunks */
#define DEVICE_SHOWN_MAX 320u /* the name as messages show it (escaped), with its NUL */
#define DEVICE_READY_READS 64u /* lsc_device_poll(d, 0): at most this many reads */
/* How soon after a stop (7) the controller's start (6) of the group it
 * stopped for comes: back to back on the wire (7 bytes, 7.3 ms at 9600 baud),
 * plus a USB-serial adapter's latency (up to 16 ms), with room to spare
 * (wait.c's restarts_at_once; an entry's restart_grace_ms). */
#define DEVICE_RESTART_GRACE_MS 50u
#define DEVICE_INTERRUPT_SLICE_MS 50u /* a read waits this long at most between looks at
                                         lsc_device_interrupt's flag */

/* A queued notification and its sequence number (notifications queued
 * before it since the open). */
typedef struct device_note {
    lsc_notification n;
    uint32_t seq;
} device_note;

/* A controller found by a listing (lsc/discovery.h: read through accessors,
 * info.c). Strings are NUL-terminated, "" when unknown. */
struct lsc_device_info {
    char name[LSC_DEVICE_NAME_MAX]; /* what lsc_device_open takes for it */
    char path[LSC_DEVICE_NAME_MAX]; /* the device node */
    char description[128];          /* the port's or the HID product's */
    char serial[128];               /* USB serial number */
    char manufacturer[128];
    lsc_device_kind kind;           /* LSC_DEVICE_SERIAL or LSC_DEVICE_HID */
    uint16_t vid, pid;              /* USB ids (0 when not USB) */
    bool usb;                       /* vid, pid and serial are known */
    bool controller;                /* a known controller (HID) or adapter (serial) */
};

/* lsc_device_config (config.c): 0 means not set (the default). */
struct lsc_device_config {
    uint32_t baud;
    uint32_t timeout_ms;
    uint16_t hid_vid, hid_pid;
};

struct lsc_device {
    const lsc_dev_transport *t; /* the kind's entry (transport.h), or `closed` */
    void *state;                /* the kind's own, allocated by its entry */
    lsc_dev_transport closed;   /* the entry while the port is closed (reopen.c) */
    int interrupted; /* lsc_device_interrupt was called (atomic: __atomic builtins) */
    char name[LSC_DEVICE_NAME_MAX];
    char shown[DEVICE_SHOWN_MAX]; /* name for messages: control characters escaped */
    char message[DEVICE_MESSAGE_MAX];
    lsc_device_cause cause;
    uint32_t timeout_ms;
    uint32_t baud;
    uint16_t hid_vid, hid_pid; /* another HID controller's ids to accept (0:0 none) */

    lsc_client client;
    lsc_io io;   /* what the client talks through: port with guarded writes */
    lsc_io port; /* the transport's own */

    lsc_trace_fn trace;
    void *trace_user;
    lsc_device_frame_fn frame_hook; /* every received frame (frames.c) */
    void *frame_user;
    /* the link's counters (base.c, frames.c) beyond the client's own: */
    uint64_t n_sent, n_received, n_notes, n_timeouts, n_reopens;
    uint64_t n_discarded, n_malformed; /* of the clients before the last reopen */
    lsc_device_last_word_fn last_word;
    void *last_word_user;

    /* for the messages */
    uint8_t tx_cmd; /* the frame the last failed write was sending */
    size_t tx_len;
    bool tx_failed;
    int rx_other;   /* command of the last received frame that is no notification, or -1 */
    uint8_t asked;  /* command of the last frame sent */
    lsc_client_counts before; /* the counts when the request began */
    bool answered;  /* a request was answered since the open (first_retries) */
    bool got;       /* the last read of the port brought bytes */
    bool more;      /* lsc_device_poll(d, 0) stopped at its bound with bytes left */

    lsc_arm *arm;
    uint16_t last_pos[256];  /* each servo's last commanded or read position ... */
    uint8_t last_known[32];  /* ... where its bit is set (base.c) */

    /* notifications */
    device_note queue[LSC_DEVICE_QUEUE];
    size_t head, count;
    uint32_t seq;     /* notifications queued since the open */
    uint32_t dropped; /* dropped from a full queue */

    /* the group lsc_device_wait_group waits for */
    bool ran;          /* lsc_device_run was called */
    uint8_t run_group; /* ... of this group */
    bool run_forever;  /* ... with times 0 */
    bool waiting;      /* a wait for `wait_group`'s start and end is under way */
    uint8_t wait_group;
    uint32_t wait_seq; /* notifications from this sequence number on count */
    bool started;      /* wait_group's start was seen */
    bool start_due;    /* ... and is due within lsc_device_start_ms of the run: */
    uint32_t run_at;   /* the device's clock when the run was sent */
};

/* The base (base.c), under the link and everything on it: keeps
 * servos[0..n)'s positions as the last known; the client's notification
 * callback (queues n); takes the oldest queued notification into *out
 * (false if none). */
void lsc_dev_remember(lsc_device *d, const lsc_servo *servos, size_t n);
void lsc_dev_queue(void *user, const lsc_notification *n);
bool lsc_dev_take(lsc_device *d, device_note *out);

/* Sets d's message (printf-style) and cause; returns err. */
int lsc_dev_fail(lsc_device *d, int err, lsc_device_cause cause, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Sets d's message to prefix followed by text, a transport's message that
 * may carry names from outside (a path, a USB serial number): escaped with
 * lsc_escape_text so that the line stays one line. Returns err. */
/* For calls that report into a caller's why[whylen] (NULL or 0: nothing
 * written) rather than the device: writes the reason, returns LSC_EINVAL. */
int lsc_dev_refuse(char *why, size_t whylen, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;

int lsc_dev_fail_text(lsc_device *d, int err, lsc_device_cause cause, const char *prefix,
                      const char *text);

/* The one line for an error err of the transport or client (timeouts say
 * what did arrive); returns err. */
int lsc_dev_link_fail(lsc_device *d, int err);

/* A struct that grows (src/util/sized.h) given by the caller: 0 when s is
 * NULL or its size is at least least (LSC_SIZED_MIN), else LSC_EINVAL after
 * the line "what.size is N, less than M: ...; nothing was sent". */
int lsc_dev_sized(lsc_device *d, const void *s, size_t least, const char *what);

/* Clears the last error (at the start of each call). */
void lsc_dev_begin(lsc_device *d);


/* Discovery (discovery.c): the name NULL stands for: $LSC_PORT, else the one
 * controller present. Writes it to name[cap]; 0, or an error after
 * lsc_dev_fail. */
int lsc_dev_find(lsc_device *d, char *name, size_t cap);

/* $LSC_PORT when it is set and not empty, else NULL (env.c). */
const char *lsc_dev_env_port(void);

/* The serial ports and HID controllers present into out[0..cap) (out may
 * be NULL when cap is 0; lsc_device_list's order and names), with HID
 * controllers of the ids vid:pid too (0:0: the known ones only): how many
 * exist (may exceed cap), or an error, why in message. */
int lsc_dev_list(lsc_device_info *out, size_t cap, char *message, size_t msgcap, uint16_t vid,
                 uint16_t pid);

/* Whether a serial port's USB ids are a known adapter's. */
bool lsc_dev_known_adapter(bool usb, uint16_t vid, uint16_t pid);
/* The calibration key of the serial port at path (lsc_calibrated_key):
 * "port-" and the name of the link path is, else of the link in dir that points at the same
 * file. 0 and key[cap], LSC_ENODEV (none), LSC_EINVAL (cap too small). */
int lsc_dev_port_key(const char *dir, const char *path, char *key, size_t cap);

/* Sets up d->io (the port's, with guarded writes) and the client over it
 * (link.c). */
void lsc_dev_io_init(lsc_device *d);

/* The entry's bound (its `bound`) for `what` of n servos (a move, a hold,
 * keyframes): 0, or LSC_EINVAL after its line ("what of N servos on PORT:
 * ...advice; nothing was sent") (link.c). */
int lsc_dev_bound(lsc_device *d, size_t n, const char *what, const char *advice);

/* A position read (the device's timeout, the HID retry); n or an error after
 * its line (link.c). */
int lsc_dev_read_positions(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out);

/* The arm profile (device_arm.c): frees it; checks servos[0..n) against it
 * (0, or LSC_EINVAL after lsc_dev_fail). */
void lsc_dev_arm_free(lsc_device *d);
int lsc_dev_arm_check(lsc_device *d, const lsc_servo *servos, size_t n);

/* lsc_device_poll(d, 0): reads what has arrived until a read brings
 * nothing (at most DEVICE_READY_READS reads; then d->more), queueing
 * notifications; 0 or the link's error after its line (events.c). */
int lsc_dev_read_ready(lsc_device *d);

/* Lets timeout_ms pass on d's clock, reading (notifications are queued):
 * 0 or the link's error after its line (wait.c). */
int lsc_dev_pass(lsc_device *d, uint32_t timeout_ms);

/* Every frame sent or received goes here first (link.c's trace): counted,
 * a received one to the frame hook, if any (base.c). */
void lsc_dev_frame_seen(lsc_device *d, lsc_trace_dir dir, const uint8_t *frame, size_t n);

/* Writes the whole frame[0..n) as it is, traced (link.c): 0 or the link's
 * error after its line. */
int lsc_dev_write_frame(lsc_device *d, const uint8_t *frame, size_t n);

/* Opens into d, whose settings are set, the entry that name selects
 * (lsc_dev_transport_of) (device.c): 0, or an error after its line (d->t
 * is that entry, d->state what its open left). */
int lsc_dev_open_name(lsc_device *d, const char *name);

#endif
