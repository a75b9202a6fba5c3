/* lsc device: talking through the client: the guarded write, the trace, the
 * commands without a reply and the requests with the HID first-request retry
 * (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <pthread.h>
#include <signal.h>
#include <stdio.h>

#include "device_internal.h"

/* xArm command 27 writes a setting to every servo on the bus at once. */
#define CMD_WRITE_ALL 27u

/* Every frame through the client: the command of the last one sent, and of
 * the last received one that is no notification, are kept for the timeout
 * message; then the caller's trace, if any. */
static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    lsc_device *d = user;
    if (dir == LSC_TRACE_RX &&
        (frame[3] < LSC_CMD_GROUP_RUN || frame[3] > LSC_CMD_GROUP_COMPLETE)) {
        d->rx_other = frame[3];
    }
    if (dir == LSC_TRACE_TX) {
        d->asked = frame[3];
    }
    lsc_dev_frame_seen(d, dir, frame, n);
    if (d->trace != NULL) {
        d->trace(d->trace_user, dir, frame, n);
    }
}

int lsc_dev_write_frame(lsc_device *d, const uint8_t *frame, size_t n)
{
    trace(d, LSC_TRACE_TX, frame, n);
    int r = d->io.write(d->io.ctx, frame, n); /* n, or an error (lsc/io.h) */
    return r == (int)n ? 0 : lsc_dev_link_fail(d, r);
}

/* True if sig is pending, was not blocked before the write (old) and will
 * end the process when unblocked (its default action). */
static bool ends_process(const sigset_t *pending, const sigset_t *old, int sig)
{
    struct sigaction sa;
    (void)sigaction(sig, NULL, &sa); /* only reads: cannot fail for a valid sig */
    return sigismember(pending, sig) == 1 && sigismember(old, sig) == 0 &&
           sa.sa_handler == SIG_DFL;
}

/* The client's write: the port's, with SIGINT, SIGTERM and SIGHUP blocked in
 * the calling thread (pthread_sigmask) until the frame is out or the write
 * gave up (bounded by the port's write timeout), so that Ctrl-C or kill never
 * leaves part of a frame on the line for the controller to glue to the next
 * one. A signal that came meanwhile then takes effect as usual; if it will
 * end the process and the write failed, the last-word callback reports the
 * failure first. */
static int guarded_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_device *d = ctx;
    sigset_t stop, old, pending;
    (void)sigemptyset(&stop);
    (void)sigaddset(&stop, SIGINT);
    (void)sigaddset(&stop, SIGTERM);
    (void)sigaddset(&stop, SIGHUP);
    /* (pthread_sigmask fails only for an invalid `how`, sigpending only for
     * a bad pointer) */
    (void)pthread_sigmask(SIG_BLOCK, &stop, &old);
    /* n is a whole frame (4 bytes at least); the port's write returns n or a
     * negative error (lsc/io.h) */
    int r = d->port.write(d->port.ctx, data, n);
    d->tx_failed = r != (int)n;
    if (d->tx_failed) {
        d->tx_cmd = data[3];
        d->tx_len = n;
    }
    if (d->tx_failed && d->last_word != NULL) {
        (void)sigpending(&pending);
        if (ends_process(&pending, &old, SIGINT) || ends_process(&pending, &old, SIGTERM) ||
            ends_process(&pending, &old, SIGHUP)) {
            (void)lsc_dev_link_fail(d, r);
            d->last_word(d->last_word_user, d);
        }
    }
    (void)pthread_sigmask(SIG_SETMASK, &old, NULL);
    return r;
}

void lsc_device_interrupt(lsc_device *d)
{
    if (d != NULL) { /* one lock-free store: safe in a signal handler */
        __atomic_store_n(&d->interrupted, 1, __ATOMIC_SEQ_CST);
    }
}

/* Whether lsc_device_interrupt was called since the last time this said so. */
static bool interrupted(lsc_device *d)
{
    return __atomic_exchange_n(&d->interrupted, 0, __ATOMIC_SEQ_CST) != 0;
}

/* The client's read: the port's. One that waits (timeout_ms > 0) waits in
 * slices of at most DEVICE_INTERRUPT_SLICE_MS, so that lsc_device_interrupt
 * ends it within a slice (LSC_EINTR); a read that only takes what is there
 * (0) never does. Bounded by slices as well as by time, against a clock that
 * stands still. */
static int port_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_device *d = ctx;
    uint32_t start = d->port.now_ms(d->port.ctx), spent = 0;
    uint32_t slices = timeout_ms / DEVICE_INTERRUPT_SLICE_MS + 2u;
    int r;
    do {
        if (timeout_ms > 0 && interrupted(d)) {
            return LSC_EINTR; /* (d->got: unchanged, no bytes came) */
        }
        uint32_t left = timeout_ms - spent;
        r = d->port.read(d->port.ctx, buf, cap,
                         left < DEVICE_INTERRUPT_SLICE_MS ? left : DEVICE_INTERRUPT_SLICE_MS);
        spent = d->port.now_ms(d->port.ctx) - start;
    } while (r == 0 && spent < timeout_ms && --slices > 0);
    d->got = r > 0;
    return r;
}

static uint32_t port_now(void *ctx)
{
    lsc_device *d = ctx;
    return d->port.now_ms(d->port.ctx);
}

void lsc_dev_io_init(lsc_device *d)
{
    d->io.ctx = d;
    d->io.write = guarded_write;
    d->io.read = port_read;
    d->io.now_ms = port_now;
    (void)lsc_client_init(&d->client, &d->io);
    lsc_client_set_trace(&d->client, trace, d);
    lsc_client_set_notify(&d->client, lsc_dev_queue, d);
}

/* A send-only client call's result r for a frame of command cmd. */
static int sent(lsc_device *d, int r, uint8_t cmd)
{
    if (r == 0) {
        return 0;
    }
    if (r == LSC_EINVAL && !d->tx_failed && d->message[0] != '\0') {
        return r; /* the entry's own line (it checked the arguments) */
    }
    if (r == LSC_EINVAL && !d->tx_failed) {
        return lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NONE,
                            "%s (command %u): the arguments do not make a valid frame; nothing "
                            "was sent",
                            lsc_device_cmd_name(cmd), cmd);
    }
    return lsc_dev_link_fail(d, r);
}

int lsc_dev_bound(lsc_device *d, size_t n, const char *what, const char *advice)
{
    return d->t->bound != NULL ? d->t->bound(d, n, what, advice) : 0;
}

/* The line for a command the kind has none of (`what`: "action groups"). */
static int none(lsc_device *d, const char *what)
{
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "%s is %s, which has no %s; nothing was sent", d->shown, d->t->name,
                        what);
}

/* ---- The board's commands over the client (lsc_dev_board_ops) ------------------------ */

int lsc_dev_board_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    return lsc_client_move(&d->client, time_ms, servos, n);
}

int lsc_dev_board_unload(lsc_device *d, const uint8_t *ids, size_t n)
{
    return lsc_client_unload(&d->client, ids, n);
}

int lsc_dev_board_adjust_offset(lsc_device *d, uint8_t id, int8_t offset)
{
    return lsc_client_adjust_offset(&d->client, id, offset);
}

int lsc_dev_board_run(lsc_device *d, uint8_t group, uint16_t times)
{
    return lsc_client_run_group(&d->client, group, times);
}

int lsc_dev_board_stop(lsc_device *d)
{
    return lsc_client_stop_group(&d->client);
}

int lsc_dev_board_speed(lsc_device *d, uint8_t group, uint16_t percent)
{
    return lsc_client_set_group_speed(&d->client, group, percent);
}

int lsc_dev_board_battery(lsc_device *d, uint16_t *millivolts)
{
    return lsc_client_get_battery(&d->client, millivolts, d->timeout_ms);
}

int lsc_dev_board_read_positions(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out)
{
    return lsc_client_read_positions(&d->client, ids, n, out, d->timeout_ms);
}

int lsc_dev_board_read_offsets(lsc_device *d, const uint8_t *ids, size_t n,
                               lsc_servo_offset *out)
{
    return lsc_client_read_offsets(&d->client, ids, n, out, d->timeout_ms);
}

const lsc_dev_ops lsc_dev_board_ops = LSC_DEV_BOARD_OPS(NULL); /* the shared halt (halt.c) */

/* ---- Commands ---------------------------------------------------------------------- */

int lsc_device_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
    if (servos == NULL || n == 0 || n > LSC_MOVE_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "a move of %lu servos: one move takes 1..%u; nothing was sent",
                            servos == NULL ? 0ul : (unsigned long)n, LSC_MOVE_MAX);
    }
    if (d->t->ops->move == NULL) {
        return none(d, "moves of several servos");
    }
    r = lsc_dev_bound(d, n, "a move", "; split it");
    if (r != 0) {
        return r;
    }
    size_t rep = lsc_ids_first_repeat(&servos[0].id, sizeof servos[0], n);
    if (rep < n) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "servo %u is given twice in one move; nothing was sent",
                            servos[rep].id);
    }
    r = lsc_dev_arm_check(d, servos, n);
    if (r != 0) {
        return r;
    }
    r = sent(d, d->t->ops->move(d, time_ms, servos, n), LSC_CMD_SERVO_MOVE);
    if (r == 0) {
        lsc_dev_remember(d, servos, n);
    }
    return r;
}

int lsc_device_run(lsc_device *d, uint8_t group, uint16_t times)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (d->t->ops->run == NULL) {
        return none(d, "action groups");
    }
    /* what has arrived by now is queued first: none of it is this run's start */
    int r = lsc_client_poll(&d->client, 0);
    if (r < 0) {
        return lsc_dev_link_fail(d, r);
    }
    d->ran = true;
    d->run_group = group;
    d->run_forever = times == 0;
    d->waiting = true;
    d->wait_group = group;
    d->wait_seq = d->seq;
    d->started = false;
    d->start_due = true;
    d->run_at = d->io.now_ms(d->io.ctx);
    return sent(d, d->t->ops->run(d, group, times), LSC_CMD_GROUP_RUN);
}

int lsc_device_stop(lsc_device *d)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    return d->t->ops->stop == NULL ? none(d, "action groups")
                                   : sent(d, d->t->ops->stop(d), LSC_CMD_GROUP_STOP);
}

int lsc_device_speed(lsc_device *d, uint8_t group, uint16_t percent)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    return d->t->ops->speed == NULL
               ? none(d, "action groups")
               : sent(d, d->t->ops->speed(d, group, percent), LSC_CMD_GROUP_SPEED);
}

int lsc_device_unload(lsc_device *d, const uint8_t *ids, size_t n)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    return d->t->ops->unload == NULL ? none(d, "unload")
                                     : sent(d, d->t->ops->unload(d, ids, n), LSC_CMD_UNLOAD);
}

int lsc_device_adjust_offset(lsc_device *d, uint8_t id, int8_t offset)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    return d->t->ops->adjust_offset == NULL
               ? none(d, "servo offsets")
               : sent(d, d->t->ops->adjust_offset(d, id, offset), LSC_CMD_OFFSET_ADJUST);
}

int lsc_device_send(lsc_device *d, uint8_t cmd, const uint8_t *params, size_t n, bool force)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (!force && (cmd == LSC_CMD_GROUP_COMPLETE || cmd == CMD_WRITE_ALL)) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            cmd == LSC_CMD_GROUP_COMPLETE
                                ? "command 8 erases the action groups on xArm firmware: it is "
                                  "sent only when forced; nothing was sent"
                                : "command 27 writes a setting (such as the servo id) to every "
                                  "servo on the bus at once on xArm firmware: it is sent only "
                                  "when forced; nothing was sent");
    }
    if (cmd != LSC_CMD_GROUP_COMPLETE) {
        return sent(d, lsc_client_send_raw(&d->client, cmd, params, n), cmd);
    }
    /* 8, forced: the client refuses command 8 by design, so this one frame
     * goes out directly (traced the same way) */
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_encode_frame(frame, sizeof frame, cmd, params, n);
    if (len < 0) {
        return sent(d, len, cmd);
    }
    return lsc_dev_write_frame(d, frame, (size_t)len);
}

/* ---- Requests ---------------------------------------------------------------- */

/* Some kinds may leave the first request after the open unanswered (HID:
 * docs/hid.md): that one is sent again, the entry's first_retries times,
 * when it timed out. Returns whether r allows another try. */
static bool retry(lsc_device *d, int r, unsigned tried)
{
    if (r != LSC_ETIMEOUT) {
        d->answered = true;
    }
    return r == LSC_ETIMEOUT && !d->answered && tried < d->t->first_retries;
}

/* A request's arguments, for ask and its callers. */
typedef struct request {
    const uint8_t *ids;
    size_t n;
    void *out;
    uint8_t cmd, reply_cmd; /* raw */
    size_t cap;
} request;

typedef int (*ask_fn)(lsc_device *d, const request *q);

static int ask_battery(lsc_device *d, const request *q)
{
    return d->t->ops->battery(d, q->out);
}

static int ask_positions(lsc_device *d, const request *q)
{
    return d->t->ops->read_positions(d, q->ids, q->n, q->out);
}

static int ask_offsets(lsc_device *d, const request *q)
{
    return d->t->ops->read_offsets(d, q->ids, q->n, q->out);
}

static int ask_raw(lsc_device *d, const request *q)
{
    return lsc_client_request_raw(&d->client, q->cmd, q->ids, q->n, q->reply_cmd, q->out, q->cap,
                                  d->timeout_ms);
}

/* A request and its reply (fn, the device's timeout), sent again as retry
 * says; the counts at the start of each try are kept for the timeout
 * message. Returns fn's result. */
static int ask(lsc_device *d, ask_fn fn, const request *q)
{
    int r;
    unsigned tried = 0;
    do {
        lsc_client_get_counts(&d->client, &d->before);
        d->tx_failed = false;
        r = fn(d, q);
        d->n_timeouts += r == LSC_ETIMEOUT ? 1u : 0u;
    } while (retry(d, r, tried++));
    return r;
}

/* ask, then the error's line if it failed. */
static int asked(lsc_device *d, ask_fn fn, const request *q, uint8_t cmd)
{
    int r = ask(d, fn, q);
    if (r == LSC_EINVAL && !d->tx_failed) {
        return sent(d, r, cmd);
    }
    return r >= 0 ? r : lsc_dev_link_fail(d, r);
}

int lsc_dev_read_positions(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out)
{
    if (d->t->ops->read_positions == NULL) {
        return none(d, "position reads");
    }
    request q = {ids, n, out, 0, 0, 0};
    int r = asked(d, ask_positions, &q, LSC_CMD_POS_READ);
    if (r > 0) {
        lsc_dev_remember(d, out, (size_t)r);
    }
    return r;
}

int lsc_device_battery(lsc_device *d, uint16_t *millivolts)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (d->t->ops->battery == NULL && d->t->no_battery != NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE, "%s: %s; nothing was sent",
                            d->shown, d->t->no_battery);
    }
    if (d->t->ops->battery == NULL) {
        return none(d, "battery");
    }
    request q = {NULL, 0, millivolts, 0, 0, 0};
    return asked(d, ask_battery, &q, LSC_CMD_BATTERY);
}

int lsc_device_read(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    return lsc_dev_read_positions(d, ids, n, out);
}

int lsc_device_read_offsets(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo_offset *out)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (d->t->ops->read_offsets == NULL) {
        return none(d, "servo offsets");
    }
    request q = {ids, n, out, 0, 0, 0};
    int r = ask(d, ask_offsets, &q);
    if (r == LSC_ETIMEOUT) {
        return lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NO_REPLY,
                            "no reply from the controller on %s within %lu ms: servo offsets "
                            "(command 23) are the xArm firmware's, LSC-6/16/32 boards may not "
                            "answer; else check the port, the power and the timeout",
                            d->shown, (unsigned long)d->timeout_ms);
    }
    if (r == LSC_EINVAL && !d->tx_failed) {
        return sent(d, r, LSC_CMD_OFFSET_READ);
    }
    return r >= 0 ? r : lsc_dev_link_fail(d, r);
}

int lsc_device_request(lsc_device *d, uint8_t cmd, const uint8_t *params, size_t n,
                       uint8_t reply_cmd, uint8_t *reply, size_t cap)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
    if (cmd == CMD_WRITE_ALL || cmd == LSC_CMD_GROUP_COMPLETE) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "command %u is no request: lsc_device_send sends it when forced; "
                            "nothing was sent",
                            cmd);
    }
    request q = {params, n, reply, cmd, reply_cmd, cap};
    r = ask(d, ask_raw, &q);
    if (r == LSC_ENOSPC) {
        return lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NONE,
                            "the reply from the controller on %s (command %u) is longer than "
                            "the %lu bytes given for it",
                            d->shown, reply_cmd, (unsigned long)cap);
    }
    if (r == LSC_EINVAL && !d->tx_failed) {
        return sent(d, r, cmd);
    }
    return r >= 0 ? r : lsc_dev_link_fail(d, r);
}

#endif
