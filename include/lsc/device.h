/*
 * lsc device: a controller by name, over whichever transport the name
 * selects, with everything a program needs around the client (lsc/client.h):
 * discovery, the retry and waiting rules, settling a move, arm profiles
 * (lsc/arm.h), playing and recording action files (lsc/files.h), and errors
 * as one line that says what to do. lscctl, the Python bindings and lscd are
 * front ends of this layer.
 *
 * Names (lsc_device_open):
 *   "sim"             the built-in virtual controller (lsc/sim.h) with demo
 *                     groups 1, 2 and 8, on the real clock (a group takes its
 *                     time; lsc_device_fileno polls readable when it sends
 *                     something), or on a virtual clock where waits take no
 *                     time (lsc_device_set_virtual_clock)
 *   "hid"             the one USB HID controller present (xArm, LeArm, Bus
 *                     Servo Controller; lsc/hid.h)
 *   "hid:SERIAL"      the HID controller with that USB serial number
 *   ".../hidrawN"     a hidraw node
 *   "lscd:NAME"       the controller lscd (lscd(8)) serves as NAME in its
 *   "lscd:PATH"       directory, or on the socket PATH (lsc/lscd.h)
 *   "lx:PATH"         a bus of serial bus servos on the serial port PATH (a
 *                     BusLinker, lsc-sim --lx), 115200 baud unless the options
 *                     give another: see "A bus of servos" below
 *   any other path    a serial port (lsc/serial.h), e.g. /dev/ttyUSB0; when
 *                     another program holds it and that program is lscd, its
 *                     socket is used instead (kind LSC_DEVICE_LSCD)
 *   NULL              $LSC_PORT if set and not empty, else the one controller
 *                     present: a serial port with a known USB adapter's
 *                     VID:PID (CH340 1a86:7523, CP210x 10c4:ea60, FT232
 *                     0403:6001) or a HID controller (none: LSC_ENODEV;
 *                     several: LSC_EINVAL, the message lists them; see
 *                     lsc_device_error_cause)
 *
 * Host only (not in the Arduino library). A device is an opaque heap object:
 * it can grow without breaking the ABI and other languages hold only a
 * pointer. One thread at a time per device; different devices are
 * independent. No global state.
 *
 * Errors: every call returns 0 (or a count) on success, or a negative
 * LSC_E... code; then lsc_device_error gives one line (no newline) that names
 * the port and says what failed and what to check, in words any front end
 * can show ("the timeout", "the baud rate"; a front end may add its own
 * hints, and lsc_device_error_cause says which of the situations it may want
 * to word itself this was). A NULL d is LSC_EINVAL.
 *   LSC_EINVAL   an argument is refused (nothing was sent): a servo outside
 *                the arm profile's limits, too many servos for one frame or
 *                one HID report (19), a name that selects nothing
 *   LSC_ETIMEOUT no reply (or no notification) within the timeout
 *   LSC_EREPLY   something arrived, but not a valid reply
 *   LSC_EBUSY    another program holds the port (nothing was sent)
 *   LSC_ENODEV   no such device, no controller present, or it went away
 *   LSC_EACCES   permission denied (the message says how to get access)
 *   LSC_EIO      any other failure of the transport
 *   LSC_ENOSPC   out of memory, or a raw reply longer than the buffer
 *   LSC_EINTR    lsc_device_interrupt ended the call (or the next one)
 *
 * Time: every request waits at most the device's timeout (options, or
 * lsc_device_set_timeout) for its reply. Calls that wait for the controller
 * to do something (notifications, a group's end) take their own timeout;
 * LSC_DEVICE_FOREVER waits without limit (never on "sim" when nothing there
 * can happen: that is LSC_ETIMEOUT at once).
 *
 * Signals: a frame is written with SIGINT, SIGTERM and SIGHUP blocked in
 * the calling thread (pthread_sigmask, around the transport's write only), so
 * a signal never leaves part of a frame on the line; a pending signal takes
 * effect when the write is done (a serial write gives up after 1 s plus twice
 * a frame's time: lsc/serial.h). When such a signal will end the process and
 * the write failed, lsc_device_set_last_word's callback is told first.
 */
#ifndef LSC_DEVICE_H
#define LSC_DEVICE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/arm.h"
#include "lsc/client.h"
#include "lsc/core.h"
#include "lsc/files.h"
#include "lsc/lscd.h"
#include "lsc/player.h"
#include "lsc/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_DEVICE_TIMEOUT_DEFAULT 1000u /* ms a request waits for its reply */
#define LSC_DEVICE_FOREVER UINT32_MAX    /* a wait without limit */
#define LSC_DEVICE_NAME_MAX 272u         /* room for a name: a path, or hid:SERIAL */
#define LSC_DEVICE_QUEUE 64u             /* notifications kept until read */
#define LSC_DEVICE_TOLERANCE_DEFAULT 10u /* positions, for lsc_device_settle */
#define LSC_DEVICE_HID_MOVE_MAX 19u      /* servos in one move over HID (a 64-byte report) */

typedef struct lsc_device lsc_device;

/* How to open a device; a NULL options pointer means all defaults. */
typedef struct lsc_device_options {
    uint32_t baud;       /* serial ports: 0 means LSC_SERIAL_BAUD_DEFAULT (9600); a bus
                            of servos (lx:PATH): 0 means 115200 */
    uint32_t timeout_ms; /* each request's reply: 0 means LSC_DEVICE_TIMEOUT_DEFAULT */
    uint16_t hid_vid;    /* HID: another controller's USB ids to accept besides the */
    uint16_t hid_pid;    /* known ones (lsc/hid.h, lsc_hid_open_path_extra), when a
                            HID name is opened and when NULL looks for the one
                            controller present; 0:0 means none */
} lsc_device_options;

/* What a name selected. */
typedef enum lsc_device_kind {
    LSC_DEVICE_SERIAL = 0,
    LSC_DEVICE_HID = 1,
    LSC_DEVICE_SIM = 2,
    LSC_DEVICE_LSCD = 3, /* a controller that lscd owns, through its socket (lsc/lscd.h) */
    LSC_DEVICE_LX = 4    /* a bus of serial bus servos, "lx:PATH" (lsc/lxclient.h) */
} lsc_device_kind;

/* A controller found by lsc_device_list. Strings are NUL-terminated, "" when
 * unknown. */
typedef struct lsc_device_info { /* NOLINT(clang-analyzer-optin.performance.Padding): 6 bytes
                                   of 940; the order is the bindings' (ABI) */
    char name[LSC_DEVICE_NAME_MAX]; /* what lsc_device_open takes for it */
    char path[LSC_DEVICE_NAME_MAX]; /* the device node */
    char description[128];          /* the port's or the HID product's */
    char serial[128];               /* USB serial number */
    char manufacturer[128];
    uint16_t vid, pid;              /* USB ids (0 when not USB) */
    bool usb;                       /* vid, pid and serial are known */
    lsc_device_kind kind;           /* LSC_DEVICE_SERIAL or LSC_DEVICE_HID */
    bool controller;                /* a known controller (HID) or adapter (serial) */
} lsc_device_info;

/* ---- Opening and closing ---------------------------------------------------- */

/* Opens the controller `name` (see the top) with opt (NULL: defaults). On
 * success *out is the handle (close it with lsc_device_close); on failure
 * *out is NULL and nothing needs closing: why stays readable without a
 * handle, through NULL, in the thread that called the open, until its next
 * lsc_device_open (the calling thread's last open: thread-local, so opens
 * in other threads do not touch it): lsc_device_error(NULL) is its one
 * line, lsc_device_error_cause(NULL) its cause, lsc_device_name(NULL) the
 * name tried ("" when discovery found none) and lsc_device_kind_of(NULL)
 * its kind. After an open that succeeded they say "", LSC_DEVICE_CAUSE_NONE,
 * "" and LSC_DEVICE_SERIAL. Nothing is sent by the open. Returns 0, or: LSC_EINVAL (a name longer than
 * LSC_DEVICE_NAME_MAX - 1 bytes, "hid:" without a serial number, several
 * controllers and none chosen, a baud rate the port does not take, a build
 * without HID support for a HID name), LSC_ENODEV (no such device, none
 * present), LSC_EBUSY, LSC_EACCES, LSC_EIO (the transport's), LSC_ENOSPC.
 * out NULL: LSC_EINVAL. */
LSC_API int lsc_device_open(const char *name, const lsc_device_options *opt,
                            lsc_device **out);

/* ---- The environment --------------------------------------------------------------- */

/* What every front end (lscctl, lscd, the Python bindings) takes from the
 * environment, read here the same way for all (a variable set to "" is
 * unset):
 *   LSC_PORT      the controller when none is named: lsc_device_open(NULL),
 *                 lsc_device_kind_of_name(NULL)
 *   LSC_ARM       the path of an arm profile (lsc/arm.h) when none is given:
 *                 joint names, degrees and limits
 *   LSC_HID_ID    VID:PID in hex: another HID controller's USB ids to accept
 *                 (lsc_device_options' hid_vid, hid_pid)
 *   LSC_LSCD_DIR  where the names lscd:NAME are (lsc/lscd.h; default
 *                 LSC_LSCD_DIR)
 * $LSC_PORT's value, or NULL. */
LSC_API const char *lsc_device_env_port(void);
/* $LSC_ARM's value, or NULL. */
LSC_API const char *lsc_device_env_arm(void);
/* $LSC_HID_ID into opt's hid_vid and hid_pid, when it is set and they are
 * 0:0 (a value the front end was given wins). Returns 0, or LSC_EINVAL with
 * opt unchanged and why[whylen] (may be NULL) saying so when it is no
 * VID:PID, or opt is NULL. */
LSC_API int lsc_device_options_from_env(lsc_device_options *opt, char *why, size_t whylen);
/* USB ids as "VID:PID": 1..4 hex digits each, not 0:0 (what --hid-id and
 * $LSC_HID_ID take). Returns 0 and *vid, *pid, or LSC_EINVAL (they are
 * unchanged; any argument NULL too). */
LSC_API int lsc_device_parse_hid_id(const char *s, uint16_t *vid, uint16_t *pid);

/* The kind of controller name selects, by the rules lsc_device_open follows
 * (the same code decides), without opening or checking anything:
 * LSC_DEVICE_SIM for "sim"; LSC_DEVICE_LSCD for "lscd:..."; LSC_DEVICE_HID
 * for "hid", "hid:..." and a path whose last component begins with
 * "hidraw"; else LSC_DEVICE_SERIAL (a serial port that lscd holds turns out
 * LSC_DEVICE_LSCD when it is opened: lsc_device_kind_of). NULL stands for
 * $LSC_PORT when it is set and not empty, as in lsc_device_open. For a front
 * end that checks its arguments before it opens a port (at most
 * LSC_DEVICE_HID_MOVE_MAX servos in one move over HID). The open may still
 * refuse the name. Returns 0 and *kind, or LSC_EINVAL (kind NULL), or
 * LSC_ENODEV (name NULL and $LSC_PORT unset or empty: the controller that
 * discovery finds decides; lsc_device_kind_of tells after the open). */
LSC_API int lsc_device_kind_of_name(const char *name, lsc_device_kind *kind);

/* Closes the port and frees d (NULL is fine). */
LSC_API void lsc_device_close(lsc_device *d);

/* The last error as one line ("" after a call that succeeded); never NULL,
 * valid until the next call on d. For a NULL d: the calling thread's last
 * lsc_device_open's ("" when it succeeded), valid until that thread's next
 * open. */
LSC_API const char *lsc_device_error(const lsc_device *d);

/* What the last error was about, beyond its code: what a front end branches
 * on (never the message's words), e.g. to name its own option for a remedy
 * (lsc_device_error says it in general words: "the timeout"). Values are
 * only ever added. */
typedef enum lsc_device_cause {
    LSC_DEVICE_CAUSE_NONE = 0,       /* none of those below (or no error) */
    LSC_DEVICE_CAUSE_NO_CONTROLLER,  /* open(NULL): no controller present, or none
                                        could be listed (LSC_ENODEV) */
    LSC_DEVICE_CAUSE_SEVERAL,        /* open(NULL) or open("hid"): several present and
                                        none chosen (LSC_EINVAL) */
    LSC_DEVICE_CAUSE_WAIT_TIMEOUT,   /* a wait (lsc_device_notification,
                                        lsc_device_wait_group) ran out of its timeout */
    LSC_DEVICE_CAUSE_SIM_IDLE,       /* a wait on "sim" while nothing runs there:
                                        nothing can arrive (LSC_ETIMEOUT at once) */
    LSC_DEVICE_CAUSE_SIM_NO_GROUP,   /* ... after a run of a group "sim" does not
                                        have (lsc_device_groups lists those it has) */
    LSC_DEVICE_CAUSE_SIM_FOREVER,    /* a wait without limit while the group run on
                                        "sim" loops for ever (times 0): after its
                                        start it sends nothing, so nothing can come */
    LSC_DEVICE_CAUSE_STOPPED_SHORT,  /* lsc_device_settle_ex with LSC_SETTLE_STRICT (and
                                        lsc_device_settle): a servo stopped short of
                                        its target (LSC_ETIMEOUT) */
    LSC_DEVICE_CAUSE_NAME_TOO_LONG,  /* open: the name, or the serial port's path, is
                                        longer than the message says (LSC_EINVAL) */
    LSC_DEVICE_CAUSE_NO_REPLY,       /* a request got no reply within the device's
                                        timeout and nothing at all arrived
                                        (LSC_ETIMEOUT): check the power, the cable,
                                        the port; a longer timeout may help (the
                                        message ends so). The other things that may
                                        have come instead have their own causes:
                                        _NOISE, _OTHER_FRAMES, _ONLY_NOTIFICATIONS,
                                        and through lscd _LSCD_NO_REPLY */
    LSC_DEVICE_CAUSE_NOT_SETTLED,    /* lsc_device_settle: a servo not within the
                                        tolerance of its target within the timeout
                                        (LSC_ETIMEOUT): a longer timeout or a larger
                                        tolerance may help */
    LSC_DEVICE_CAUSE_ACCESS,         /* the open was denied (LSC_EACCES); the
                                        message says how to get access (the udev
                                        rule, the group to join) */
    LSC_DEVICE_CAUSE_NEVER_STARTED,  /* lsc_device_wait_group after lsc_device_run:
                                        no start of the group was heard within
                                        lsc_device_start_ms (LSC_ETIMEOUT): the
                                        board has no such group ("sim" says so
                                        at once: LSC_DEVICE_CAUSE_SIM_NO_GROUP) */
    LSC_DEVICE_CAUSE_HALTED,         /* lsc_device_play through lscd: a halt (this
                                        program's or another's, lsc_lscd_halt)
                                        stopped the controller (LSC_EBUSY) */
    LSC_DEVICE_CAUSE_NOISE,          /* no reply (LSC_ETIMEOUT): only bytes that
                                        formed no frame arrived, most likely a wrong
                                        baud rate (or noise on the line) */
    LSC_DEVICE_CAUSE_OTHER_FRAMES,   /* no reply (LSC_ETIMEOUT): frames answering
                                        something else came instead (another program
                                        on the line, or a request the controller does
                                        not know) */
    LSC_DEVICE_CAUSE_ONLY_NOTIFICATIONS, /* no reply (LSC_ETIMEOUT): only
                                        notifications came: the controller is there
                                        but did not answer */
    LSC_DEVICE_CAUSE_LSCD_NO_REPLY,  /* no reply through lscd (LSC_ETIMEOUT),
                                        nothing arrived: check lscd's port and baud
                                        rate (its --port, --baud) */
    LSC_DEVICE_CAUSE_INTERRUPTED     /* lsc_device_interrupt ended the call
                                        (LSC_EINTR) */
} lsc_device_cause;

/* The cause of the last error (LSC_DEVICE_CAUSE_NONE after success). NULL
 * d: the calling thread's last lsc_device_open's. */
LSC_API lsc_device_cause lsc_device_error_cause(const lsc_device *d);

/* The name the device was opened as ("hid" stays "hid"), or for a NULL name
 * the one discovery chose (e.g. "/dev/ttyUSB0", "hid:1A2B"); and its kind.
 * NULL d: those of the calling thread's last lsc_device_open when it failed
 * (the name tried, "" when discovery found none), else "" and
 * LSC_DEVICE_SERIAL. */
LSC_API const char *lsc_device_name(const lsc_device *d);
LSC_API lsc_device_kind lsc_device_kind_of(const lsc_device *d);

/* The action groups the device is known to hold, ascending, into
 * out[0..cap): "sim" has its demo groups (1, 2, 8); a real controller does
 * not say (0). Returns how many there are (may exceed cap). */
LSC_API size_t lsc_device_groups(const lsc_device *d, uint8_t *out, size_t cap);

/* Lists the serial ports and HID controllers present into out[0..cap)
 * (out may be NULL when cap is 0): serial ports first, then HID
 * controllers with known USB ids (lsc_hid_known_ids), each with the name lsc_device_open takes for it (a HID
 * controller: hid:SERIAL, or its path without a serial number). Returns how
 * many exist (may exceed cap), or an error: neither kind can be listed (the
 * serial listing's error; a build without libserialport and hidapi has
 * neither), LSC_ENOSPC (out of memory), LSC_EINVAL (out NULL, cap > 0).
 * message (msgcap bytes, may be NULL) receives why, "" on success. */
LSC_API int lsc_device_list(lsc_device_info *out, size_t cap, char *message, size_t msgcap);

/* ---- Settings ---------------------------------------------------------------- */

/* The reply timeout of every request (0 means LSC_DEVICE_TIMEOUT_DEFAULT). */
LSC_API void lsc_device_set_timeout(lsc_device *d, uint32_t timeout_ms);
LSC_API uint32_t lsc_device_timeout(const lsc_device *d);

/* Every frame sent and received (as lsc_client_set_trace), or none (NULL). */
LSC_API void lsc_device_set_trace(lsc_device *d, lsc_trace_fn fn, void *user);

/* Called when a write failed while a signal that ends the process is
 * pending (SIGINT, SIGTERM or SIGHUP, not blocked before the call and at its
 * default action): the process ends as soon as the write unblocks it, before
 * the call can return its error, so this is the last moment to report
 * lsc_device_error(d), which already holds the failure's line. It must not
 * call back into d. NULL: none. */
typedef void (*lsc_device_last_word_fn)(void *user, const lsc_device *d);
LSC_API void lsc_device_set_last_word(lsc_device *d, lsc_device_last_word_fn fn, void *user);

/* Gives d a copy of an arm profile (NULL: none): from then on moves and
 * play are checked against its limits before anything is sent. On "sim" the
 * virtual controller then stands in for that arm (lsc_arm_stand_in): each
 * joint's servo is put at the joint's 0 degrees, and moves beyond its
 * servo's range stop at the range's end. Returns 0 or LSC_ENOSPC. */
LSC_API int lsc_device_set_arm(lsc_device *d, const lsc_arm *arm);
/* The device's profile, or NULL. */
LSC_API const lsc_arm *lsc_device_arm(const lsc_device *d);

/* The connection to lscd of a device that goes through lscd (kind
 * LSC_DEVICE_LSCD: "lscd:NAME", or a port lscd holds), for what only lscd
 * does: its status, a lease (lsc/lscd.h). NULL for other devices and a NULL
 * d. Owned by d: valid until lsc_device_close; not to be closed. */
LSC_API lsc_lscd *lsc_device_lscd(lsc_device *d);

/* "sim" only: on true, its clock becomes virtual: it moves only while the
 * device waits or reads, by as much as the wait (waits, plays and records
 * take no real time; lsc_device_fileno is -1 and lsc_device_next_event_ms
 * says how long on that clock; tests, and lscctl's one-shot --port sim); on
 * false (as opened), it follows the real clock again from where it is.
 * Returns 0, or LSC_EINVAL for another kind or NULL. */
LSC_API int lsc_device_set_virtual_clock(lsc_device *d, bool on);

/* Ends the call on d that is waiting for the controller, from another
 * thread or from a signal handler (it only stores a flag, lock-free, and
 * calls nothing: async-signal-safe): within 50 ms the call returns
 * LSC_EINTR, cause LSC_DEVICE_CAUSE_INTERRUPTED ("interrupted ... while
 * waiting for the controller on PORT"). When no call waits, the next one
 * that would wait returns LSC_EINTR at once; one interrupt ends one call.
 * What waits: a request's wait for its reply (lsc_device_battery,
 * lsc_device_read, ...), lsc_device_notification and lsc_device_poll with a
 * timeout, lsc_device_wait_group, lsc_device_settle(_ex), lsc_device_play,
 * lsc_device_take_keyframe, lsc_device_record, lsc_device_reach with a wait.
 * Calls that only send (lsc_device_move, lsc_device_stop, ...) or take what
 * has arrived (timeout 0) neither wait nor take the interrupt: a program
 * that interrupted a play can stop the servos at once. A frame being
 * written is finished first (a write is never cut). What was sent stays
 * sent; a reply that comes later is passed over by the next request. d must
 * stay open during the call (do not race it with lsc_device_close); NULL
 * does nothing. */
LSC_API void lsc_device_interrupt(lsc_device *d);

/* The device's monotonic clock in ms (the virtual controller's own for
 * "sim", which follows the real clock, or on its virtual clock moves only
 * while the device waits or reads). 0 for NULL. */
LSC_API uint32_t lsc_device_now_ms(lsc_device *d);

/* ---- In a program's own event loop (poll, epoll, asyncio, a GUI's) ---------------- */

/* The device's descriptor, to wait on for reading: it polls readable
 * (POLLIN) when the controller (or lscd) sent something, and POLLHUP or
 * POLLERR when it went away. Serial: the port's (lsc_serial_fileno); HID:
 * the node's descriptor that the open locks, which the kernel's hidraw
 * driver gives a copy of every input report (lsc_hid_fileno); lscd: the
 * socket (lsc_lscd_fileno); "sim": a timer (Linux: a timerfd) that polls
 * readable when the virtual controller is due to send something. -1 for
 * "sim" on its virtual clock (lsc_device_set_virtual_clock: nothing comes
 * by itself, lsc_device_next_event_ms says when it is due on that clock),
 * on systems without timerfd, and NULL. It stays the same while d is open
 * (and "sim" keeps its clock). Never read, write or close it: the device
 * does that.
 *
 * The loop: take what is queued, sleep in poll() until the descriptor is
 * readable or the next deadline comes, then let the device read:
 *
 *     for (;;) {
 *         lsc_notification n;
 *         while (lsc_device_notification(d, 0, &n) == 0)
 *             handle(&n);                     (what is queued, no waiting)
 *         uint32_t next = lsc_device_next_event_ms(d);
 *         int ms = next == LSC_DEVICE_FOREVER ? -1 : next > INT_MAX ? INT_MAX : (int)next;
 *         struct pollfd p = {lsc_device_fileno(d), POLLIN, 0};
 *         if (poll(&p, 1, ms) < 0 && errno != EINTR)
 *             break;
 *         (a descriptor: what arrived, without waiting; none ("sim" on
 *          its virtual clock): the time that passed, on that clock)
 *         if (lsc_device_poll(d, p.fd >= 0 ? 0u : next) < 0)
 *             break;                          (lsc_device_error says why)
 *     }
 *
 * (poll() ignores a negative descriptor: then it only sleeps.) A program
 * with other descriptors adds them to the same poll(); with "sim" on its
 * virtual clock it passes the time that really passed, at most `next`
 * (lsc_device_poll with more runs the virtual controller on). Requests (lsc_device_battery,
 * ...) may be made between rounds: notifications that arrive meanwhile are
 * queued, and next is then 0. */
LSC_API int lsc_device_fileno(const lsc_device *d);

/* How many ms until the device needs lsc_device_poll without its
 * descriptor saying so: 0 when a notification is queued
 * (lsc_device_notification takes it at once), when the last
 * lsc_device_poll(d, 0) left input unread (it reads at most 64 chunks), or
 * when the transport holds input already taken from its descriptor (HID: a
 * frame read in part; lscd: frames a request took off the socket); for
 * "sim" the ms until it sends something of its own accord (a running
 * group's next step, its end: real ms, or on its virtual clock that
 * clock's); else LSC_DEVICE_FOREVER (also for NULL). */
LSC_API uint32_t lsc_device_next_event_ms(const lsc_device *d);

/* For "sim" only: how many ms on its clock until it sends something of its
 * own accord, 0 when that is due now; LSC_DEVICE_FOREVER when nothing is
 * scheduled (only a frame sent to it can make it send anything), for the
 * other kinds and NULL. lsc_device_next_event_ms says it for every kind, in
 * real ms. */
LSC_API uint32_t lsc_device_sim_next_event_ms(const lsc_device *d);

/* ---- Commands without a reply (each sends one frame) -------------------------- */

/* servo_move of n servos over time_ms. Refused (LSC_EINVAL, nothing sent;
 * the message says which rule): n outside 1..LSC_MOVE_MAX, more than
 * LSC_DEVICE_HID_MOVE_MAX over HID ("at most 19 servos in one move over
 * HID"), a repeated id, a servo outside the arm profile's limits (the
 * profile's message: the joint, its limits). */
LSC_API int lsc_device_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos,
                            size_t n);
/* action_group_run (times 0: for ever). What has arrived is read (and
 * queued) first: notifications that arrived before the run are never taken
 * for its start (lsc_device_wait_group). */
LSC_API int lsc_device_run(lsc_device *d, uint8_t group, uint16_t times);
LSC_API int lsc_device_stop(lsc_device *d);
LSC_API int lsc_device_speed(lsc_device *d, uint8_t group, uint16_t percent);
LSC_API int lsc_device_unload(lsc_device *d, const uint8_t *ids, size_t n);
/* The xArm's servo offset adjust (command 24). */
LSC_API int lsc_device_adjust_offset(lsc_device *d, uint8_t id, int8_t offset);

/* A raw frame: cmd with n parameter bytes (n <= LSC_PARAMS_MAX, n != 83),
 * sent as it is (a raw frame need not be a valid message). Commands 8
 * (erases the action groups on xArm firmware) and 27 (writes a setting to
 * every servo on the bus) are refused (LSC_EINVAL) unless force is true; a
 * forced 8, which the client refuses, goes out directly, traced the same
 * way. */
LSC_API int lsc_device_send(lsc_device *d, uint8_t cmd, const uint8_t *params, size_t n,
                            bool force);

/* ---- Requests (each waits at most the device's timeout) ------------------------ */

/* Over HID the first request after the open is sent again, LSC_HID_FIRST_RETRIES
 * times, when it timed out (real arms may leave it unanswered); from the first
 * request that got anything but a timeout on, never. Arguments a frame cannot
 * carry (n 0, too many ids, repeated ids) are LSC_EINVAL with nothing sent. */

/* get_battery_voltage: millivolts. */
LSC_API int lsc_device_battery(lsc_device *d, uint16_t *millivolts);
/* Positions of n servos: out[i] = {ids[i], position}; returns n. */
LSC_API int lsc_device_read(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out);
/* The xArm's servo offsets (command 23; LSC boards may not answer: then the
 * timeout's message says so); returns n. */
LSC_API int lsc_device_read_offsets(lsc_device *d, const uint8_t *ids, size_t n,
                                    lsc_servo_offset *out);
/* A raw request: sends cmd, waits for a frame whose command is reply_cmd and
 * copies its parameters to reply[0..cap); returns their number, or
 * LSC_ENOSPC (the reply is longer than cap; it is consumed). Refused
 * (LSC_EINVAL): reply_cmd 6, 7 or 8 (notifications), cmd 8 or 27 (no
 * requests: lsc_device_send with force). */
LSC_API int lsc_device_request(lsc_device *d, uint8_t cmd, const uint8_t *params, size_t n,
                               uint8_t reply_cmd, uint8_t *reply, size_t cap);

/* ---- Waiting ------------------------------------------------------------------ */

/* A move's wait: lets time_ms pass (queueing what arrives), then reads the
 * positions of targets[0..n) (n 1..LSC_READ_MAX), every 20 ms, until each is
 * within tolerance of its target, or has stopped short of it (see
 * lsc_device_settle_ex, of which this is the strict form). Returns 0 when they are; 1 when the
 * controller does not answer position reads (some LSC boards: the move's
 * time has passed, which is all there is to wait for; lsc_device_error then
 * says so); LSC_ETIMEOUT (the message names the first servo outside, where
 * it is and its target) when they are not within the device's timeout after
 * time_ms, or at once when one stopped short (cause
 * LSC_DEVICE_CAUSE_STOPPED_SHORT); or a request's error. */
LSC_API int lsc_device_settle(lsc_device *d, const lsc_servo *targets, size_t n,
                              uint16_t time_ms, uint16_t tolerance);

/* A servo stops short of its target when, outside the tolerance, its
 * position reads stay within LSC_SETTLE_STILL of each other for
 * LSC_SETTLE_STILL_MS (a gripper closed on an object, a joint against an
 * obstacle): waiting longer cannot bring it there. */
#define LSC_SETTLE_STILL_MS 200u
#define LSC_SETTLE_STILL 3u /* positions */
#define LSC_SETTLE_STRICT 1u /* lsc_device_settle_ex flag: a servo stopping short is an error */
/* lsc_device_settle_ex's positive outcomes (0: every servo arrived). */
#define LSC_SETTLE_NO_READS 1 /* the controller does not answer position reads */
#define LSC_SETTLE_STOPPED 2  /* some servos stopped short (listed in the result) */

/* A servo that stopped short: where, and its target. */
typedef struct lsc_settle_stop {
    uint8_t id;
    uint16_t position;
    uint16_t target;
} lsc_settle_stop;

/* What lsc_device_settle_ex saw: the servos that stopped short, in the
 * order of targets. */
typedef struct lsc_settle_result {
    size_t nstopped;
    lsc_settle_stop stopped[LSC_READ_MAX];
} lsc_settle_result;

/* lsc_device_settle that understands a servo held short of its target: the
 * wait ends as soon as every servo is within tolerance or has stopped short
 * (LSC_SETTLE_STILL_MS after it stopped), not after the timeout. Returns 0
 * (all arrived), LSC_SETTLE_NO_READS (as lsc_device_settle's 1),
 * LSC_SETTLE_STOPPED (some stopped short: *out lists them, and
 * lsc_device_error says "servo 1 stopped at 600, 100 short of its target
 * 700"); with flags LSC_SETTLE_STRICT a stop short is LSC_ETIMEOUT (cause
 * LSC_DEVICE_CAUSE_STOPPED_SHORT, the same message) instead; LSC_ETIMEOUT
 * (cause LSC_DEVICE_CAUSE_NOT_SETTLED) when a servo still moving is not
 * there within the device's timeout after time_ms; LSC_EINVAL (n not 1..LSC_READ_MAX, an unknown flag);
 * or a request's error. out may be NULL; it is filled on every return after
 * the reads began (nstopped 0 otherwise). lsc_device_settle is this with
 * LSC_SETTLE_STRICT. */
LSC_API int lsc_device_settle_ex(lsc_device *d, const lsc_servo *targets, size_t n,
                                 uint16_t time_ms, uint16_t tolerance, unsigned flags,
                                 lsc_settle_result *out);

/* The virtual controller of a "sim" device (NULL for any other, or NULL d):
 * for tests and demonstrations that act on it as the world would (hold a
 * servo with lsc_sim_block, run a group as its handle would). Valid until
 * lsc_device_close. */
LSC_API lsc_sim *lsc_device_sim(lsc_device *d);

/* ---- A bus of servos (lx:PATH) --------------------------------------------------- *
 * What works on a board works on a bus with the same calls: lsc_device_move
 * (positions 0..1000, times 0..30000 ms; the servos start together:
 * MOVE_TIME_WAIT_WRITE to each, then one broadcast MOVE_START),
 * lsc_device_read (POS_READ to each; the ids must be given), lsc_device_unload
 * (torque off; no ids: every servo), the offsets, settle, hold and halt, arm
 * profiles, play and record. A bus has no action groups and no board's
 * battery: lsc_device_run, _stop, _speed and _battery are refused (LSC_EINVAL,
 * nothing sent, the line says where a servo's supply voltage is), and waits
 * for notifications end at once (LSC_ETIMEOUT). lsc_device_kind_of_name says
 * LSC_DEVICE_LX for "lx:...". */
struct lsc_lxclient;
/* The bus client of an lx:PATH device, for what only a bus has (lsc/lxclient.h:
 * scan, info, the safe id change, offsets, limits, modes); NULL for any other
 * kind, or NULL d. Its timeout is the device's. Valid until lsc_device_close;
 * use it from the device's thread only. */
LSC_API struct lsc_lxclient *lsc_device_lxclient(lsc_device *d);
/* The outcome r of a call of that bus client (why: its lsc_lx_refusal, or
 * LSC_LX_DONE for the calls without one) made for `what` ("servo id 1 3"),
 * asking servo id, as d's error: "" when r >= 0; a refusal (LSC_EINVAL,
 * nothing written) in the client's words; no reply, or a bad one, from servo
 * id; a value written but not read back; else the port's line. Returns r, or
 * LSC_EINVAL when d is no lx:PATH device (or what is NULL). */
LSC_API int lsc_device_lx_result(lsc_device *d, int r, const char *what, uint8_t id, int why);
/* A new servo for joint `joint` (its name, or its servo's id) of arm on the
 * bus d: it must be alone on the bus (lsc_lxclient_set_id_alone: else
 * refused, nothing written); it gets the joint's id, then the joint's limits
 * as its angle limits, read back. *old_id (may be NULL) gets the id it had.
 * Returns 0, or an error after d's line (LSC_EINVAL: no such joint, limits no
 * bus servo takes, not alone; d no lx:PATH device or NULL arguments). */
LSC_API int lsc_device_lx_replace(lsc_device *d, const lsc_arm *arm, const char *joint,
                                  uint8_t *old_id);
/* Whether every joint of arm answers on the bus d, once: a scan of their ids.
 * Returns the number of joints, or an error after d's line: LSC_ETIMEOUT (a
 * joint's servo does not answer), LSC_EREPLY (its answers collide: two
 * servos share the id), LSC_EINVAL (an id no bus servo has; d no lx:PATH
 * device, arm NULL). */
LSC_API int lsc_device_lx_check_arm(lsc_device *d, const lsc_arm *arm);

/* Reads what arrives until timeout_ms has passed on the device's clock,
 * queueing notifications; returns how many were queued (at most
 * LSC_DEVICE_QUEUE), or the link's error. The way to let time pass while the
 * controller talks. timeout_ms 0: only what is there, without waiting: read
 * until a read brings nothing (at most 64 reads of up to 32 bytes; if input
 * is left, lsc_device_next_event_ms says 0), as an event loop does when
 * lsc_device_fileno polled readable. */
LSC_API int lsc_device_poll(lsc_device *d, uint32_t timeout_ms);

/* Takes the oldest queued notification, waiting up to timeout_ms for one if
 * none is queued (0: only what has arrived): 0 and *out (out may be NULL),
 * or LSC_ETIMEOUT (cause LSC_DEVICE_CAUSE_WAIT_TIMEOUT, "nothing arrived
 * within N ms"; on "sim" with nothing running, at once: cause
 * LSC_DEVICE_CAUSE_SIM_IDLE or _SIM_NO_GROUP). Notifications that arrive
 * during any call are queued (at most LSC_DEVICE_QUEUE: beyond, the oldest is
 * dropped and counted, lsc_device_dropped_notifications). */
LSC_API int lsc_device_notification(lsc_device *d, uint32_t timeout_ms,
                                    lsc_notification *out);
LSC_API uint32_t lsc_device_dropped_notifications(const lsc_device *d);

/* The end of an action group, taking queued notifications as it goes:
 * group LSC_GROUP_ALL waits for any group's end (a stop, 7, or a completion,
 * 8), queued or new; else for `group`'s start (6) after the last
 * lsc_device_run of it on d (or, without one, from now: queued notifications
 * are passed over), then a stop or its completion: a start that was already
 * taken by an earlier wait counts, so a wait can be resumed after a timeout.
 * A stop followed at once (within 50 ms) by `group`'s start is the
 * controller switching to a new run of it, not an end: the wait goes on
 * (the start it had taken may have been an earlier run's whose notice came
 * late); so an end by a stop comes 50 ms after the stop (on "sim" at once).
 * 0 and *out (may be NULL), or LSC_ETIMEOUT when that did not happen within
 * timeout_ms ("no action group ended within N ms"; on "sim" at once when it
 * cannot happen: the causes LSC_DEVICE_CAUSE_SIM_*; after lsc_device_run of
 * group, when its start has not come within lsc_device_start_ms of the run:
 * cause LSC_DEVICE_CAUSE_NEVER_STARTED). */
LSC_API int lsc_device_wait_group(lsc_device *d, uint8_t group, uint32_t timeout_ms,
                                  lsc_notification *out);
/* Whether the start of the group that lsc_device_wait_group waits (or last
 * waited) for has been seen (for a front end that says, after a while, that
 * it has not: a board ignores a run of a group it does not have). */
LSC_API bool lsc_device_group_started(const lsc_device *d);

/* How long a board takes at most to announce the start of a group after a
 * run (lsc_device_run): a board that has the group sends its start (6) as
 * soon as it has read the run, so the wait is the run's frame and the start's
 * on the line (7 bytes each at the device's baud rate; HID, lscd and "sim":
 * 9600), plus the margin a request's reply gets: the device's timeout, at
 * most LSC_DEVICE_TIMEOUT_DEFAULT (1015 ms by default). A group whose start
 * has not come by then was never started (a board ignores a run of a group
 * it does not have): lsc_device_wait_group of the group run last says so
 * then (LSC_ETIMEOUT, cause LSC_DEVICE_CAUSE_NEVER_STARTED: "group 9 never
 * started: ..."), unless its own timeout ends first. NULL d:
 * LSC_DEVICE_TIMEOUT_DEFAULT. */
LSC_API uint32_t lsc_device_start_ms(const lsc_device *d);

/* ---- Halt and hold ---------------------------------------------------------------- */

/* The servos "all" stands for, into ids[0..cap): the arm profile's joints
 * (arm non-NULL), in the profile's order; else every id the board kind has:
 * 1..6 on a HID controller (the xArm, the LeArm: six servos; "hid",
 * "hid:SERIAL", a hidraw node, and lscd serving one: "lscd:hid",
 * "lscd:hid-SERIAL"), 1..32 on anything else (a serial port: the channels of
 * the largest LSC board, the LSC-32; "sim"; lscd serving a serial port).
 * name is the controller's name as lsc_device_open takes it (NULL: $LSC_PORT).
 * Returns how many (may exceed cap: then only cap are written), or
 * LSC_ENODEV when name is NULL, $LSC_PORT is unset and there is no arm
 * (discovery decides the kind: lsc_device_all_ids of lsc_device_name after
 * the open), LSC_EINVAL (ids NULL with cap > 0). */
LSC_API int lsc_device_all_ids(const lsc_arm *arm, const char *name, uint8_t *ids, size_t cap);

/* A list of servos as lsc_device_parse_ids takes it (arm may be NULL), or
 * "all" alone: lsc_device_all_ids(arm, name). Returns the count, or
 * LSC_EINVAL with why as lsc_device_parse_ids ("all" more than cap servos
 * too), or LSC_ENODEV for "all" when the kind is not known before the open
 * (name NULL, $LSC_PORT unset, no arm: parse it again with the name
 * lsc_device_name gives after the open). */
LSC_API int lsc_device_parse_ids_all(const lsc_arm *arm, const char *name, const char *list,
                                     uint8_t *ids, size_t cap, char *why, size_t whylen);

/* lsc_device_hold and lsc_device_halt: some servo was held where it is,
 * beyond its joint's limits in the arm profile (positive, not an error). */
#define LSC_HOLD_BEYOND 1
/* The time of the move that holds a servo where it was read (ms). */
#define LSC_HOLD_MS 20u

/* What lsc_device_hold did. */
typedef struct lsc_hold_result {
    size_t n;                      /* servos held: held[0..n), in the order of ids */
    lsc_servo held[LSC_READ_MAX];  /* each one's position as read, now its target */
    size_t nbeyond;                /* of them, beyond their joints' limits: */
    uint8_t beyond[LSC_READ_MAX];  /* their ids, in the order of ids */
} lsc_hold_result;

/* Holds servos ids[0..n) where they are: reads their positions, then moves
 * each to its own (LSC_HOLD_MS, which it lets pass: when it returns they
 * hold), which powers a servo that was unloaded and stops one that moves. A servo beyond its joint's limits in the arm profile
 * (opened by hand past a limit while limp) is held there too: holding where a
 * servo already is cannot break a limit (moving it anywhere but back within
 * its limits stays refused: lsc_device_move). Returns 0 (all within their
 * limits), LSC_HOLD_BEYOND (some beyond: res lists them, lsc_device_error
 * names the first: "joint gripper (servo 1) is held at 900, beyond its
 * limits ...: move it back within them"), LSC_EINVAL with nothing sent (ids
 * NULL, n not 1..LSC_READ_MAX, a repeated id, more than
 * LSC_DEVICE_HID_MOVE_MAX over HID), or the read's or move's error (nothing
 * was moved when the read failed). res may be NULL. */
LSC_API int lsc_device_hold(lsc_device *d, const uint8_t *ids, size_t n, lsc_hold_result *res);

/* Stops everything, promptly: sends action_group_stop (7) and then holds
 * every servo where it is (lsc_device_hold of lsc_device_all_ids: the arm
 * profile's joints, else every id of the board kind), so that a move under
 * way or a group's ends where the servos are. It takes the stop's frame, one
 * position read and its reply, and the hold's move and its LSC_HOLD_MS.
 * Returns as lsc_device_hold (LSC_HOLD_BEYOND: some joint beyond its limits,
 * held there); when the positions cannot be read (a board that does not
 * answer position reads) the stop was sent and the read's error is
 * returned, its message saying that the servos go on to their last targets.
 * Through lscd (kind LSC_DEVICE_LSCD) it is lsc_lscd_halt: lscd halts its
 * controller whoever holds the lease (every id of its controller's kind:
 * d's arm profile is not lscd's), and its result and message are d's. */
LSC_API int lsc_device_halt(lsc_device *d);

/* ---- Play and record ------------------------------------------------------------- */

/* Called by lsc_device_play after each frame it sent (step non-NULL) and at
 * least every 100 ms while it waits (step NULL), with the ms since the start.
 * Returning false stops the play after the frame being sent: the servos stay
 * where they are. May be NULL. */
typedef bool (*lsc_play_fn)(void *user, const lsc_player_step *step, uint32_t elapsed_ms);

/* What a play did. */
typedef struct lsc_play_result {
    uint32_t frames;       /* frames sent */
    uint32_t dropped;      /* keyframes dropped: faster than the line carries */
    uint32_t keyframe;     /* 1-based keyframe of the last frame sent (0: none) */
    uint32_t max_late_ms;  /* the latest a frame went out after its due time */
    uint32_t total_ms;     /* the whole schedule: the end of the last move after
                              the start (lsc_player_total_ms) */
    bool stopped;          /* the callback stopped it */
} lsc_play_result;

/* Plays a over d on a schedule fixed from one start (lsc/player.h): cfg's
 * speed, times and lead; baud 0 means the device's line (its baud; HID and
 * sim: 9600 as the model). Returns when the last move has ended (0), when the
 * callback stopped it (0, result->stopped), or at the first error of a send
 * or a wait (what was sent stays sent).
 * Refused before anything is sent (LSC_EINVAL): no keyframes, speed or times
 * 0, a schedule longer than 2^32 - 1 ms, more than LSC_DEVICE_HID_MOVE_MAX
 * servos over HID, and, with an arm profile, any keyframe outside its limits
 * (every keyframe is checked first; the message names the keyframe, 1-based,
 * and the joint). result may be NULL; else it is kept up to date as the play
 * goes (total_ms is set before the first frame), so that the callback may
 * read it. On "sim" on its virtual clock the play takes no real time.
 * Through lscd, a halt (lsc_lscd_halt, by any client) ends the play at once:
 * LSC_EBUSY, cause LSC_DEVICE_CAUSE_HALTED (what was sent stays sent). */
LSC_API int lsc_device_play(lsc_device *d, const lsc_action *a, const lsc_player_config *cfg,
                            lsc_play_fn fn, void *user, lsc_play_result *result);

/* ---- Converting between arms ---------------------------------------------------- */

/* Converts the positions of in, recorded on arm `from`, for arm `to`,
 * through joint angles: each servo of in is a joint of from (found by its
 * id); the joint of the same name in to (matched by name, never by id) gets
 * the position of the same angle (lsc_joint_to_cdeg, then lsc_joint_to_pos:
 * rounded to the nearest position). out gets to's servo ids, in in's order,
 * and in's times; it is initialised here (lsc_action_free it after success;
 * on error it is empty). Refused, LSC_EINVAL with why[whylen] saying which
 * and why (one line), nothing in out:
 *   - a servo of in on no joint of from ("servo 7 is on no joint of the
 *     source profile: ...");
 *   - a joint of from that to has no joint of that name ("joint wrist (servo
 *     3) has no joint of that name in the target profile");
 *   - a position outside its servo's range in from ("keyframe 2: joint
 *     gripper (servo 1): position 1200 is outside its servo's range 0..1000
 *     in the source profile");
 *   - an angle outside the limits of to's joint, or its servo's range
 *     ("keyframe 3: joint base: 100.08deg (position 917) is outside the
 *     target's limits of joint base (servo 6): -85.00deg..85.00deg"): the
 *     first keyframe, then the first joint, in in's order;
 *   - NULL arguments, or in the same as out.
 * LSC_ENOSPC: out of memory. No device is used. O(keyframes x servos). */
LSC_API int lsc_action_to_arm(const lsc_action *in, const lsc_arm *from, const lsc_arm *to,
                              lsc_action *out, char *why, size_t whylen);

/* Record: lsc_device_unload the servos of a (its ids) so that they can be
 * posed by hand, then take keyframes. */

/* Reads the positions of a's servos (a timeout is retried, up to `attempts`
 * reads; 0 means 5; each waits the device's timeout) and appends them to a
 * as a keyframe since_ms after the one before (0 becomes 1, more than 65535
 * becomes 65535). Returns 0, LSC_EINVAL (a NULL, or without servos),
 * LSC_ETIMEOUT (no read was answered), LSC_ENOSPC (the action is full:
 * LSC_ACTION_KEYFRAMES_MAX, checked before anything is sent; or out of
 * memory) or the link's error; a is unchanged on error. */
LSC_API int lsc_device_take_keyframe(lsc_device *d, lsc_action *a, uint32_t since_ms,
                                     unsigned attempts);

/* Called by lsc_device_record after each keyframe it took (a->count is its
 * 1-based number) and at least every 100 ms while it waits (taken false;
 * lsc_device_error(d) is then ""). Also, with taken false, after a position
 * read that timed out and before it is retried: lsc_device_error(d) then
 * holds the timeout's line (a front end may say that it retries).
 * Returning false ends the recording. May be NULL. */
typedef bool (*lsc_record_fn)(void *user, const lsc_action *a, bool taken);

/* Takes a keyframe every every_ms ms (1..65535, else LSC_EINVAL) on the
 * device's clock, on a schedule fixed from one start: keyframe k is due
 * (k - 1) * every_ms after it, and its time is the ms since the one before
 * (the first's: every_ms); one that is late (a read retried) is taken at once
 * and the schedule keeps its times. Goes on until count keyframes (0: no
 * limit) are in a or the callback says stop. Does not unload. Returns 0 (the
 * end was reached, or the callback ended it), or lsc_device_take_keyframe's
 * error (LSC_ENOSPC when a is full: a->count is then
 * LSC_ACTION_KEYFRAMES_MAX) or a wait's; what was taken stays in a either
 * way. On "sim" on its virtual clock it takes no real time. */
LSC_API int lsc_device_record(lsc_device *d, lsc_action *a, uint32_t every_ms, uint32_t count,
                              lsc_record_fn fn, void *user);

/* The servos of a list given in one argument (lscctl record --ids): items
 * separated by commas, each a joint's name of arm (lsc/arm.h; arm may be
 * NULL: ids only), a servo id 0..255 (decimal or 0x-hex) or a range of ids
 * LO-HI, both ends included: "1-6", "1-3,8", "base,shoulder,3-4". Writes the
 * ids, in the order listed, to ids[0..cap). Returns their number (1..cap), or
 * LSC_EINVAL with why (whylen bytes, may be NULL: one line, the text from
 * list escaped as lsc_escape_text does) naming the item and the reason: an
 * empty list or item, an item that is no joint and no id (a negative id:
 * "id '-5' is negative: use 0..255"), a range without an end or whose end is
 * below its start ("the range 5-3 is empty"), a servo listed twice (by its
 * joint's name or its id: "servo 6 listed twice"), more than cap servos
 * ("more than 32 servos"); list or ids NULL, or cap 0. Time: linear in the
 * list's length (each servo at most once). */
LSC_API int lsc_device_parse_ids(const lsc_arm *arm, const char *list, uint8_t *ids, size_t cap,
                                 char *why, size_t whylen);

/* ---- The hand: the arm profile's geometry (lsc/kinematics.h) ------------------- */

#define LSC_REACH_STEP_MM 5.0f     /* reach's line: waypoints at most this far apart */
#define LSC_REACH_WAYPOINTS_MAX 256u /* ... and at most this many (longer: wider apart) */

/* The position of servo id that d last commanded (lsc_device_move) or read
 * (lsc_device_read, lsc_device_settle): 0 and *pos, or LSC_EINVAL when there
 * is none yet (or d or pos NULL). */
LSC_API int lsc_device_last_position(const lsc_device *d, uint8_t id, uint16_t *pos);

/* The time of a move of servos[0..n) (n 1..LSC_MOVE_MAX) at speed_dps
 * degrees a second for the joint that turns the most: each servo's travel
 * from its last position (lsc_device_last_position; those not known are read
 * first), in degrees of its joint of the device's arm profile. Rounded up to
 * a whole ms, at least 1, at most 65535 (a longer one is LSC_EINVAL: "lower
 * the speed's travel..."). LSC_EINVAL (nothing sent): speed_dps not within
 * 0.01..100000, no arm profile, a servo that is no joint of it, n or servos
 * refused; or a read's error. */
LSC_API int lsc_device_move_time(lsc_device *d, const lsc_servo *servos, size_t n,
                                 float speed_dps, uint16_t *time_ms);

/* A move of servos[0..n) at speed_dps degrees a second for the joint that
 * turns the most: its time from lsc_device_move_time (the same rule and
 * checks), then lsc_device_move over that time; with wait, then the wait of
 * lsc_device_settle_ex with tolerance and flags (0 or LSC_SETTLE_STRICT).
 * *time_ms (may be NULL) is the move's time once it was sent, else 0;
 * settle (may be NULL) is filled as lsc_device_settle_ex fills it (nstopped
 * 0 without a wait). Returns 0, or with wait lsc_device_settle_ex's positive
 * outcomes (LSC_SETTLE_NO_READS, LSC_SETTLE_STOPPED); LSC_EINVAL with nothing
 * sent (lsc_device_move_time's refusals, lsc_device_move's, flags unknown);
 * or a read's, the move's or the wait's error. What lscctl move --speed
 * does. */
LSC_API int lsc_device_move_speed(lsc_device *d, const lsc_servo *servos, size_t n,
                                  float speed_dps, bool wait, uint16_t tolerance,
                                  unsigned flags, uint16_t *time_ms,
                                  lsc_settle_result *settle);

/* Where the hand is: reads the joints of the arm profile's chain (five, base
 * to wrist roll) and gives their angles q[LSC_KIN_JOINTS] (q may be NULL)
 * and the pose they put the grasp point in (lsc_kin_forward). LSC_EINVAL
 * without an arm profile or without its geometry (the message says what to
 * add); a read's error. */
LSC_API int lsc_device_where(lsc_device *d, float *q, lsc_kin_pose *pose);

/* Where the hand is, and which joints are near an end of their limits. */
typedef struct lsc_where {
    float q[LSC_KIN_JOINTS]; /* the chain's angles, base to wrist roll (degrees) */
    lsc_kin_pose pose;       /* where they put the grasp point (lsc_kin_forward) */
    unsigned near_end;       /* lsc_kin_near_ends(&chain, q, LSC_KIN_NEAR_END_DEG):
                              * LSC_KIN_NEAR_LOW(i) / LSC_KIN_NEAR_HIGH(i) bits */
    lsc_kin_chain chain;     /* the profile's chain: lengths and limits */
    int joint[LSC_KIN_JOINTS]; /* each chain joint's index in the profile (lsc_arm_name) */
} lsc_where;

/* lsc_device_where with the joints near an end of their limits (within
 * LSC_KIN_NEAR_END_DEG, 5 degrees) and the chain they are judged by: what
 * lscctl where prints, and a front end can show. Returns as
 * lsc_device_where does (w NULL: LSC_EINVAL). */
LSC_API int lsc_device_where_ex(lsc_device *d, lsc_where *w);

/* A move of the grasp point (lsc_device_reach). */
typedef struct lsc_reach {
    lsc_kin_target target; /* where, and the pitch and roll if given */
    uint16_t time_ms;      /* the whole move's time when speed_dps is 0 (0: 1000) */
    float speed_dps;       /* > 0: timed by the joint that turns the most, at this speed */
    bool line;             /* keep the grasp point on the straight segment */
    float step_mm;         /* line: waypoints at most this far apart (0: LSC_REACH_STEP_MM) */
    bool wait;             /* then wait as lsc_device_settle_ex does */
    uint16_t tolerance;    /* ... positions off target accepted */
    unsigned flags;        /* ... its flags: 0 or LSC_SETTLE_STRICT */
} lsc_reach;

/* What lsc_device_reach did, or why it did not. */
typedef struct lsc_reach_result {
    lsc_kin_result kin;  /* the inverse's outcome (kin.status: why refused) */
    size_t waypoints;    /* moves sent (planned, when refused by a limit) */
    uint32_t time_ms;    /* their times, together */
    lsc_settle_result settle; /* r->wait: the servos that stopped short */
} lsc_reach_result;

/* Moves the grasp point to r->target through the device's arm profile: the
 * current angles of its chain (last commanded or read; read when unknown)
 * choose the solution (lsc_kin_inverse: the base and the elbow as they are
 * first; the pitch chosen when none is given, over the whole circle); the joints' positions are checked against the limits.
 * With r->line, the grasp point moves along the straight segment from where
 * it is (lsc_kin_forward of the current angles): waypoints at most step_mm
 * apart (at most LSC_REACH_WAYPOINTS_MAX), the pitch and roll turning evenly
 * from the current ones, every one solved (each nearest the one before) and
 * checked before the first is sent, each sent when the one before has had
 * its time; equal times, so the grasp point moves at one speed. With
 * speed_dps, each move's time is that of the largest joint travel of any
 * waypoint at that speed (lsc_device_move_time's rule). With r->wait, the
 * last move is waited for as lsc_device_settle_ex does with r->flags (its
 * returns: LSC_SETTLE_NO_READS when the controller does not report
 * positions, LSC_SETTLE_STOPPED when a joint stopped short of its target,
 * res->settle listing them; with LSC_SETTLE_STRICT that is LSC_ETIMEOUT).
 * A target that no current angles could reach within the limits (any off
 * the base's axis) is refused before anything is sent, the read too.
 * Returns 0 (or settle_ex's LSC_SETTLE_NO_READS or LSC_SETTLE_STOPPED), res
 * (may be NULL) filled; LSC_EINVAL with
 * nothing sent: no arm profile or no geometry, a value refused (r->flags
 * not 0 or LSC_SETTLE_STRICT among them), the target
 * out of reach or reachable only beyond a joint's limit (res->kin says which,
 * the message too: "(x, y, z) is out of reach by N mm", "... needs joint
 * elbow (servo 4) at 131.2deg, beyond its limit 115.00deg"; at a given pitch
 * followed by the pitches that do reach it, "; pitches A..B reach it"; without
 * one the reason that holds at every pitch); an angle on a limit whose nearest
 * position lies beyond it is sent as the next position inside; or a read's,
 * move's or settle's error. */
LSC_API int lsc_device_reach(lsc_device *d, const lsc_reach *r, lsc_reach_result *res);

/* ---- Messages ----------------------------------------------------------------- */

/* Text from outside (a file's name, an argument, a device's serial number)
 * made safe to repeat in a one-line message, by the rules of the library's
 * own messages (those of lsc_device_error, lsc/arm.h and lsc/files.h): writes
 * s[0..n) (up to a NUL byte, if one comes first) into out[cap]: printable
 * ASCII as it is, a backslash as \\, any other byte (control characters,
 * DEL, bytes >= 0x80) as \xNN with upper-case hex digits. Cut to fit, never in
 * the middle of an escape; out is NUL-terminated when cap > 0 (4 * n + 1
 * bytes always suffice). s may be NULL when n is 0. Returns the length
 * written (without the NUL). Portable, no allocation. */
LSC_API size_t lsc_escape_text(char *out, size_t cap, const char *s, size_t n);

/* The name of command cmd as the messages use it, the protocol's own
 * ("servo_move", "get_battery_voltage", ...), or "unknown". Never NULL. */
LSC_API const char *lsc_device_cmd_name(uint8_t cmd);

#ifdef __cplusplus
}
#endif

#endif /* LSC_DEVICE_H */
