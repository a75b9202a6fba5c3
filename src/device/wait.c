/* lsc device: waiting (for a notification, for a
 * group's end, for time to pass), settling a move, and the virtual
 * controller's waits that can never end (contract in lsc/device.h). Host
 * only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>

#include "device_internal.h"

#define SETTLE_POLL_MS 20u /* between position reads while servos settle */

uint32_t lsc_device_dropped_notifications(const lsc_device *d)
{
    return d == NULL ? 0u : d->dropped;
}

bool lsc_device_group_started(const lsc_device *d)
{
    return d != NULL && d->started;
}


/* Decides, for each notification taken, whether the wait is over. */
typedef bool (*take_fn)(lsc_device *d, const device_note *note, void *user);

/* Takes queued notifications through fn until it says the wait is over
 * (0), reading more for up to timeout_ms; LSC_ETIMEOUT (the message: "what
 * within N ms"), or the link's error. */
static int wait_for(lsc_device *d, uint32_t timeout_ms, take_fn fn, void *user, const char *what)
{
    uint32_t start = d->io.now_ms(d->io.ctx);
    bool polled = false;
    for (;;) {
        device_note note;
        while (lsc_dev_take(d, &note)) {
            if (fn(d, &note, user)) {
                return 0;
            }
        }
        uint32_t spent = d->io.now_ms(d->io.ctx) - start;
        if (polled && timeout_ms != LSC_DEVICE_FOREVER && spent >= timeout_ms) {
            return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_WAIT_TIMEOUT,
                                "%s within %lu ms", what, (unsigned long)timeout_ms);
        }
        uint32_t t = timeout_ms == LSC_DEVICE_FOREVER ? DEVICE_WAIT_CHUNK_MS
                     : spent < timeout_ms             ? timeout_ms - spent
                                                      : 0u;
        /* (when the entry knows nothing else can come, e.g. nothing is
         * scheduled on "sim", only what came already is read) */
        bool idle = d->t->quiet != NULL && d->t->quiet(d);
        int r = lsc_client_poll(&d->client, idle ? 0u : t);
        polled = true;
        if (r < 0) {
            return lsc_dev_link_fail(d, r);
        }
        if (r == 0 && t > 0 && d->t->hopeless != NULL && (r = d->t->hopeless(d, timeout_ms)) != 0) {
            return r;
        }
    }
}

static bool any_note(lsc_device *d, const device_note *note, void *user)
{
    (void)d;
    *(lsc_notification *)user = note->n;
    return true;
}

int lsc_device_notification(lsc_device *d, uint32_t timeout_ms, lsc_notification *out)
{
    lsc_notification n;
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = wait_for(d, timeout_ms, any_note, &n, "nothing arrived");
    if (r == 0 && out != NULL) {
        *out = n;
    }
    return r;
}

/* Whether seq comes at or after from (sequence numbers wrap). */
static bool since(uint32_t seq, uint32_t from)
{
    return seq - from < 0x80000000u;
}

/* Lets timeout_ms pass on d's clock, reading (notifications are queued).
 * Returns 0 or the link's error (after its line). */
static int pass(lsc_device *d, uint32_t timeout_ms)
{
    uint32_t start = d->io.now_ms(d->io.ctx), spent = 0;
    /* bounded, as the client's waits are, against a clock that stands still */
    uint64_t polls = LSC_CLIENT_WAIT_READS_MIN + (uint64_t)LSC_CLIENT_READS_PER_MS * timeout_ms;
    do {
        int r = lsc_client_poll(&d->client, timeout_ms - spent);
        if (r < 0) {
            return lsc_dev_link_fail(d, r);
        }
        spent = d->io.now_ms(d->io.ctx) - start;
    } while (spent < timeout_ms && --polls > 0);
    return 0;
}

int lsc_dev_pass(lsc_device *d, uint32_t timeout_ms)
{
    return pass(d, timeout_ms);
}

/* lsc_device_wait_group's decision: the end of any group (ALL), or of
 * d->wait_group after its start. Starting a group while another runs makes
 * the controller send 7 (the old one stopped) before 6 (ours started): ends
 * before our 6 are not ours. */
static bool group_end(lsc_device *d, const device_note *note, void *user)
{
    const lsc_notification *n = &note->n;
    lsc_notification *out = user;
    bool end;
    if (!d->waiting) {
        end = n->cmd == LSC_CMD_GROUP_STOP || n->cmd == LSC_CMD_GROUP_COMPLETE;
    } else if (!since(note->seq, d->wait_seq)) {
        return false; /* before the run, or before the wait began */
    } else if (!d->started) {
        d->started = n->cmd == LSC_CMD_GROUP_RUN && n->group == d->wait_group;
        return false;
    } else {
        end = n->cmd == LSC_CMD_GROUP_STOP ||
              (n->cmd == LSC_CMD_GROUP_COMPLETE && n->group == d->wait_group);
    }
    if (end) {
        *out = *n;
        d->waiting = false;
    }
    return end;
}

/* The bytes of a run (6) and of the start it brings back: 7 each. */
#define RUN_AND_START_BYTES 14u

uint32_t lsc_device_start_ms(const lsc_device *d)
{
    if (d == NULL) {
        return LSC_DEVICE_TIMEOUT_DEFAULT;
    }
    /* 10 bits a byte (8N1), rounded up to a whole ms; the reply's margin is
     * the device's timeout, at most the default one (a longer timeout for slow
     * replies does not make the wait for a start that never comes longer) */
    uint32_t wire = (RUN_AND_START_BYTES * 10u * 1000u + d->baud - 1u) / d->baud;
    return wire + (d->timeout_ms < LSC_DEVICE_TIMEOUT_DEFAULT ? d->timeout_ms
                                                              : LSC_DEVICE_TIMEOUT_DEFAULT);
}

/* group_end until the start of d->wait_group has been seen (before its
 * start, group_end never ends the wait). */
static bool group_start(lsc_device *d, const device_note *note, void *user)
{
    (void)group_end(d, note, user);
    return d->started;
}

/* After lsc_device_run of d->wait_group: waits for its start within what is
 * left of lsc_device_start_ms since the run, when that ends before timeout_ms.
 * 0 (started, or the wait's own timeout comes first), LSC_ETIMEOUT with the
 * cause LSC_DEVICE_CAUSE_NEVER_STARTED, or the wait's other errors. */
static int await_start(lsc_device *d, uint32_t timeout_ms, lsc_notification *n)
{
    if (!d->start_due || d->started) {
        return 0;
    }
    uint32_t since_run = d->io.now_ms(d->io.ctx) - d->run_at;
    uint32_t window = lsc_device_start_ms(d);
    uint32_t left = since_run < window ? window - since_run : 0u;
    if (left >= timeout_ms) {
        return 0; /* the wait ends first: it says so itself */
    }
    int r = wait_for(d, left, group_start, n, "no start");
    if (r == LSC_ETIMEOUT && d->cause == LSC_DEVICE_CAUSE_WAIT_TIMEOUT) {
        return lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NEVER_STARTED,
                            "group %u never started: the controller on %s did not report its "
                            "start within %lu ms of the run, as a board does at once for a "
                            "group it has; it has no group %u (or the run did not reach it): "
                            "run one it has (the vendor's software writes them)",
                            d->wait_group, d->shown, (unsigned long)window, d->wait_group);
    }
    return r;
}

/* After a stop (7) that ended a wait for d->wait_group: whether the
 * controller starts that group at once (its 6 is queued, or arrives within
 * the entry's restart_grace_ms: the wait's end comes that much later). A run that
 * arrives while a group runs makes the controller send 7 then 6, so a 7 and
 * at once our group's 6 means the start taken for ours was an earlier run's
 * of the same group whose notice came late (a command just before ours,
 * from another program): this 6 is ours, taken, and the wait goes on.
 * Anything else stays queued. */
static int restarts_at_once(lsc_device *d, bool *restarts)
{
    int r = pass(d, d->t->restart_grace_ms);
    *restarts = r == 0 && d->count > 0 && d->queue[d->head].n.cmd == LSC_CMD_GROUP_RUN &&
                d->queue[d->head].n.group == d->wait_group;
    if (*restarts) {
        device_note ours;
        (void)lsc_dev_take(d, &ours);
        d->waiting = true;
        d->started = true;
    }
    return r;
}

int lsc_device_wait_group(lsc_device *d, uint8_t group, uint32_t timeout_ms,
                          lsc_notification *out)
{
    lsc_notification n = {0, 0, 0}; /* (set by the wait that returns 0) */
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
    if (group == LSC_GROUP_ALL) {
        d->waiting = false;
    } else if (!d->waiting || d->wait_group != group) {
        /* no run of it on d to wait for: its start from now on */
        d->waiting = true;
        d->wait_group = group;
        d->wait_seq = d->seq;
        d->started = false;
        d->start_due = false;
    }
    bool again; /* (each round of the wait has the whole timeout) */
    do {
        again = false;
        r = group == LSC_GROUP_ALL ? 0 : await_start(d, timeout_ms, &n);
        if (r == 0) {
            r = wait_for(d, timeout_ms, group_end, &n, "no action group ended");
        }
        if (r == 0 && group != LSC_GROUP_ALL && n.cmd == LSC_CMD_GROUP_STOP) {
            r = restarts_at_once(d, &again);
        }
    } while (again);
    if (r == 0 && out != NULL) {
        *out = n;
    }
    return r;
}

int lsc_device_poll(lsc_device *d, uint32_t timeout_ms)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    uint32_t before = d->seq;
    int r = timeout_ms == 0 ? lsc_dev_read_ready(d) : pass(d, timeout_ms);
    if (r != 0) {
        return r;
    }
    uint32_t queued = d->seq - before;
    return queued > (uint32_t)LSC_DEVICE_QUEUE ? (int)LSC_DEVICE_QUEUE : (int)queued;
}

/* One servo's watch while servos settle: where its reads have stayed
 * (within LSC_SETTLE_STILL) since when. */
typedef struct settle_watch {
    uint16_t still_at;
    uint32_t still_since;
} settle_watch;

/* Whether servo i is still moving towards its target: outside the
 * tolerance, and not stopped short (its reads have moved within the last
 * LSC_SETTLE_STILL_MS). Updates its watch with the read got. */
static bool still_moving(settle_watch *w, const lsc_servo *got, const lsc_servo *target,
                         uint16_t tolerance, uint32_t now, bool first)
{
    int dist = (int)got->position - (int)w->still_at;
    if (first || dist > (int)LSC_SETTLE_STILL || dist < -(int)LSC_SETTLE_STILL) {
        w->still_at = got->position;
        w->still_since = now;
    }
    int off = (int)got->position - (int)target->position;
    if (off <= (int)tolerance && off >= -(int)tolerance) {
        return false;
    }
    return now - w->still_since < LSC_SETTLE_STILL_MS;
}

/* The servos of targets[0..n) outside the tolerance in got into *out; and
 * the message that names them. Returns err. */
static int stopped_short(lsc_device *d, int err, const lsc_servo *targets, const lsc_servo *got,
                         size_t n, uint16_t tolerance, lsc_settle_result *out)
{
    size_t len = 0;
    out->nstopped = 0;
    d->message[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        int off = (int)targets[i].position - (int)got[i].position;
        if (off <= (int)tolerance && off >= -(int)tolerance) {
            continue;
        }
        lsc_settle_stop *s = &out->stopped[out->nstopped++];
        s->id = got[i].id;
        s->position = got[i].position;
        s->target = targets[i].position;
        if (len < sizeof d->message) {
            len += (size_t)snprintf(d->message + len, sizeof d->message - len,
                                    "%sservo %u stopped at %u, %d short of its target %u",
                                    len == 0 ? "" : "; ", s->id, s->position,
                                    off < 0 ? -off : off, s->target);
        }
    }
    d->cause = err < 0 ? LSC_DEVICE_CAUSE_STOPPED_SHORT : LSC_DEVICE_CAUSE_NONE;
    return err;
}

/* lsc_device_settle_ex after its size check, into the whole *out. */
static int settle(lsc_device *d, const lsc_servo *targets, size_t n, uint16_t time_ms,
                  uint16_t tolerance, unsigned flags, lsc_settle_result *out)
{
    uint8_t ids[LSC_READ_MAX];
    lsc_servo got[LSC_READ_MAX];
    settle_watch watch[LSC_READ_MAX];
    int r;
    if (targets == NULL || n == 0 || n > LSC_READ_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "settling %lu servos: one position read takes 1..%u",
                            targets == NULL ? 0ul : (unsigned long)n, LSC_READ_MAX);
    }
    if ((flags & ~LSC_SETTLE_STRICT) != 0u) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "settling: unknown flags 0x%x", flags);
    }
    /* the move's time (notifications that arrive meanwhile are queued) */
    r = pass(d, time_ms);
    if (r != 0) {
        return r;
    }
    for (size_t i = 0; i < n; i++) {
        ids[i] = targets[i].id;
        watch[i].still_at = 0; /* (the first read sets it) */
        watch[i].still_since = 0;
    }
    uint32_t start = d->io.now_ms(d->io.ctx);
    for (bool first = true;; first = false) {
        r = lsc_dev_read_positions(d, ids, n, got);
        if (r == LSC_ETIMEOUT) { /* LSC boards' PWM servos may not report */
            (void)lsc_dev_fail(d, LSC_SETTLE_NO_READS, LSC_DEVICE_CAUSE_NONE,
                               "the controller on %s does not answer position reads: the "
                               "move's time has passed",
                               d->shown);
            return LSC_SETTLE_NO_READS;
        }
        if (r < 0) {
            return r;
        }
        uint32_t now = d->io.now_ms(d->io.ctx);
        size_t moving = n, off = n;
        for (size_t i = 0; i < n; i++) {
            int dist = (int)got[i].position - (int)targets[i].position;
            off = off == n && (dist > (int)tolerance || dist < -(int)tolerance) ? i : off;
            bool m = still_moving(&watch[i], &got[i], &targets[i], tolerance, now, first);
            moving = moving == n && m ? i : moving;
        }
        if (off == n) {
            return 0;
        }
        if (moving == n) {
            return stopped_short(d, (flags & LSC_SETTLE_STRICT) != 0u ? LSC_ETIMEOUT
                                                                      : LSC_SETTLE_STOPPED,
                                 targets, got, n, tolerance, out);
        }
        uint32_t spent = now - start;
        if (spent >= d->timeout_ms) {
            return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_NOT_SETTLED,
                                "servo %u is at %u, not within %u of its target %u, %lu ms "
                                "after the move's time; raise the timeout or the tolerance",
                                got[moving].id, got[moving].position, tolerance,
                                targets[moving].position, (unsigned long)d->timeout_ms);
        }
        r = pass(d, d->timeout_ms - spent < SETTLE_POLL_MS ? d->timeout_ms - spent
                                                           : SETTLE_POLL_MS);
        if (r != 0) {
            return r;
        }
    }
}

int lsc_device_settle_ex(lsc_device *d, const lsc_servo *targets, size_t n, uint16_t time_ms,
                         uint16_t tolerance, unsigned flags, lsc_settle_result *out)
{
    lsc_settle_result all = {0};
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = lsc_dev_sized(d, out, LSC_SIZED_MIN(lsc_settle_result, nstopped),
                          "lsc_settle_result");
    if (r != 0) {
        return r;
    }
    all.size = sizeof all;
    r = settle(d, targets, n, time_ms, tolerance, flags, &all);
    lsc_sized_give(out, &all, sizeof all);
    return r;
}

int lsc_device_settle(lsc_device *d, const lsc_servo *targets, size_t n, uint16_t time_ms,
                      uint16_t tolerance)
{
    return lsc_device_settle_ex(d, targets, n, time_ms, tolerance, LSC_SETTLE_STRICT, NULL);
}

#endif
