/*
 * lsc device: a controller by name, over whichever transport the name
 * selects: open and close, errors as one line that says what to do, the
 * settings, a program's own event loop, commands, requests and
 * notifications. Beside it, each in its own header: lsc/motion.h (a move's
 * wait, where the hand is, reach, halt and hold), lsc/play.h (play and
 * record an action), lsc/env.h (the environment, a name's kind), lsc/convert.h (actions
 * between arms), lsc/text.h (messages' text, lists of servos),
 * lsc/discovery.h (the controllers present). lscctl, the Python bindings
 * and lscd are front ends of this layer.
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
 *   "lx:PATH"         a bus of serial bus servos on the serial port PATH (lsc/bus.h)
 *   "lx:sim"          a virtual bus of servos 1..6 in the process (lsc/lxbus.h),
 *   "lx:sim:IDS"      or of the servos IDS ("3,9", "1-4"), on the real clock
 *                     (a servo that does not answer costs the timeout, as on
 *                     a port); kind LSC_DEVICE_LX (a serial port called "sim"
 *                     in the current directory: "lx:./sim")
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

#include "lsc/client.h" /* lsc/core.h's servos; notifications, the trace */

/* Declared in their own headers: an arm profile (lsc/arm.h), the connection
 * to lscd (lsc/lscd.h). */
struct lsc_arm;
struct lsc_lscd;

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_DEVICE_TIMEOUT_DEFAULT 1000u /* ms a request waits for its reply */
#define LSC_DEVICE_FOREVER UINT32_MAX    /* a wait without limit */
#define LSC_DEVICE_NAME_MAX 272u         /* room for a name: a path, or hid:SERIAL */
#define LSC_DEVICE_QUEUE 64u             /* notifications kept until read */
#define LSC_DEVICE_HID_MOVE_MAX 19u      /* servos in one move over HID (a 64-byte report) */

typedef struct lsc_device lsc_device;

/* How to open a device: an opaque object (settings to come are new
 * setters). lsc_device_config_new gives one with the defaults (NULL: out of
 * memory); free it with lsc_device_config_free (NULL is fine) when no open
 * needs it any more: lsc_device_open keeps no pointer to it. */
typedef struct lsc_device_config lsc_device_config;
LSC_API lsc_device_config *lsc_device_config_new(void);
LSC_API void lsc_device_config_free(lsc_device_config *cfg);
#define LSC_DEVICE_BAUD_MAX 4000000u     /* lsc_device_config_set_baud */
#define LSC_DEVICE_TIMEOUT_MAX 86400000u /* ms (a day): lsc_device_config_set_timeout_ms */
/* Serial ports' baud rate, 1..LSC_DEVICE_BAUD_MAX (default 9600,
 * LSC_SERIAL_BAUD_DEFAULT; a bus of servos, lx:PATH: 115200; a rate the port
 * does not take is the open's LSC_EINVAL). Each request's reply timeout, 1..LSC_DEVICE_TIMEOUT_MAX ms
 * (default LSC_DEVICE_TIMEOUT_DEFAULT). HID: another controller's USB ids to
 * accept besides the known ones (lsc/hid.h, lsc_hid_open_path_extra) when a
 * HID name is opened and when NULL looks for the one controller present;
 * vid 0: any vendor's pid; 0:0 (the default): none. Each returns 0, or
 * LSC_EINVAL (cfg NULL, a value out of range) with cfg unchanged. */
LSC_API int lsc_device_config_set_baud(lsc_device_config *cfg, uint32_t baud);
LSC_API int lsc_device_config_set_timeout_ms(lsc_device_config *cfg, uint32_t timeout_ms);
LSC_API int lsc_device_config_set_hid_id(lsc_device_config *cfg, uint16_t vid, uint16_t pid);

/* What a name selected. */
typedef enum lsc_device_kind {
    LSC_DEVICE_SERIAL = 0,
    LSC_DEVICE_HID = 1,
    LSC_DEVICE_SIM = 2,
    LSC_DEVICE_LSCD = 3, /* a controller that lscd owns, through its socket (lsc/lscd.h) */
    LSC_DEVICE_LX = 4    /* a bus of serial bus servos, "lx:PATH" (lsc/bus.h) */
} lsc_device_kind;

/* ---- Opening and closing ---------------------------------------------------- */

/* Opens the controller `name` (see the top) with cfg (NULL: defaults). On
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
LSC_API int lsc_device_open(const char *name, const lsc_device_config *cfg,
                            lsc_device **out);

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
LSC_API int lsc_device_set_arm(lsc_device *d, const struct lsc_arm *arm);
/* The device's profile, or NULL. */
LSC_API const struct lsc_arm *lsc_device_arm(const lsc_device *d);

/* The connection to lscd of a device that goes through lscd (kind
 * LSC_DEVICE_LSCD: "lscd:NAME", or a port lscd holds), for what only lscd
 * does: its status, a lease (lsc/lscd.h). NULL for other devices and a NULL
 * d. Owned by d: valid until lsc_device_close; not to be closed. */
LSC_API struct lsc_lscd *lsc_device_lscd(lsc_device *d);

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
 * The loop: take what is queued (lsc_device_notification with timeout 0),
 * poll() the descriptor until it is readable or lsc_device_next_event_ms
 * has passed, then lsc_device_poll(d, 0) (without a descriptor: the time
 * that passed, at most next); docs/library.md ("Waiting on a controller in
 * your own event loop") shows it whole. Requests may be made between
 * rounds: what arrives meanwhile is queued, and next is then 0. */
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

/* ---- Notifications and groups ------------------------------------------------- */

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

#ifdef __cplusplus
}
#endif

#endif /* LSC_DEVICE_H */

