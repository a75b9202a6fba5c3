/* lscd: the device thread. It alone calls the device layer (but for
 * lsc_device_interrupt, which the server calls to end a job under way): it
 * runs the server's jobs one at a time, reads what the controller sends
 * between them (waiting on the device's descriptor and its next deadline,
 * lsc_device_fileno and lsc_device_next_event_ms, so an idle daemon costs no
 * CPU), sorts every received frame (the device's frame hook gives each: a
 * job's reply, a notification, an answer to a command lscd does not know, a
 * stray), notices a lost controller and opens it again (lsc_device_reopen:
 * the same handle). The device's trace is not lscd's: it stays for people. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lscd.h"
#include "lsc/motion.h"
#include "lsc/env.h"
#include "lsc/lscd.h"

#define FRAMES_MAX 65536u /* bytes of received frames kept during one call */

/* Whether the port named is lscd's own socket ("lscd:..."): then a device of
 * kind LSC_DEVICE_LSCD is what was asked for, else another lscd holds the
 * port (and lscd does not serve lscd). */
static bool asked_for_lscd(const lscd_config *cfg)
{
    lsc_device_kind asked = LSC_DEVICE_SERIAL;
    (void)lsc_device_kind_of_name(cfg->port, &asked);
    return asked == LSC_DEVICE_LSCD;
}

int lscd_open_device(const lscd_config *cfg, lsc_device **d)
{
    lsc_device_config *opt = lsc_device_config_new();
    if (opt == NULL) {
        *d = NULL;
        return LSC_ENOSPC;
    }
    /* (within the setters' ranges: main parses them so; baud 0: the default) */
    if (cfg->baud != 0u) {
        (void)lsc_device_config_set_baud(opt, cfg->baud);
    }
    (void)lsc_device_config_set_timeout_ms(opt, cfg->timeout_ms);
    /* $LSC_HID_ID: another HID controller's ids, as for lscctl (main
     * refused a malformed one before anything was opened) */
    (void)lsc_device_config_from_env(opt, NULL, 0);
    int r = lsc_device_open(cfg->port, opt, d);
    lsc_device_config_free(opt);
    if (r == 0 && lsc_device_kind_of(*d) == LSC_DEVICE_LSCD && !asked_for_lscd(cfg)) {
        return LSC_EBUSY; /* held by another lscd: not lscd on lscd */
    }
    return r;
}

const char *lscd_open_error(const lsc_device *d)
{
    const char *e = lsc_device_error(d);
    return e[0] != '\0' ? e : "port busy: another lscd holds it and serves it already";
}

/* ---- Telling the server ---------------------------------------------------------- */

static void signal_fd(int fd)
{
    const char c = 1;
    while (write(fd, &c, 1) < 0 && errno == EINTR) {
    }
}

static void drain_fd(int fd)
{
    char buf[64];
    while (read(fd, buf, sizeof buf) > 0) {
    }
}

static void post(lscd_dev *dv, lscd_ev_kind kind, uint64_t client, uint8_t cmd, int rc,
                 const void *data, size_t len)
{
    lscd_ev *e = malloc(sizeof *e + len + 1u);
    if (e == NULL) {
        (void)pthread_mutex_lock(&dv->lock);
        dv->overrun++;
        (void)pthread_mutex_unlock(&dv->lock);
        return;
    }
    e->next = NULL;
    e->kind = kind;
    e->client = client;
    e->cmd = cmd;
    e->rc = rc;
    e->len = len;
    if (len > 0u) {
        memcpy(e->data, data, len);
    }
    e->data[len] = 0;
    (void)pthread_mutex_lock(&dv->lock);
    if (dv->tail != NULL) {
        dv->tail->next = e;
    } else {
        dv->head = e;
    }
    dv->tail = e;
    (void)pthread_mutex_unlock(&dv->lock);
    signal_fd(dv->notify[1]);
}

static void post_text(lscd_dev *dv, lscd_ev_kind kind, const char *text)
{
    post(dv, kind, 0, 0, 0, text, strlen(text));
}

/* ---- What the controller sent ------------------------------------------------------ */

/* The device's frame hook: every frame received, kept until the call that
 * read it returns (sort_received). */
static void on_frame(void *user, const uint8_t *frame, size_t n)
{
    lscd_dev *dv = user;
    if (dv->frames_len + n + 2u > dv->frames_cap) {
        size_t cap = dv->frames_cap != 0u ? dv->frames_cap * 2u : 1024u;
        while (cap < dv->frames_len + n + 2u) {
            cap *= 2u;
        }
        uint8_t *p = cap <= FRAMES_MAX ? realloc(dv->frames, cap) : NULL;
        if (p == NULL) {
            (void)pthread_mutex_lock(&dv->lock);
            dv->overrun++;
            (void)pthread_mutex_unlock(&dv->lock);
            return;
        }
        dv->frames = p;
        dv->frames_cap = cap;
    }
    dv->frames[dv->frames_len] = (uint8_t)(n >> 8);
    dv->frames[dv->frames_len + 1u] = (uint8_t)(n & 0xFFu);
    memcpy(dv->frames + dv->frames_len + 2u, frame, n);
    dv->frames_len += n + 2u;
}

static void count_stray(lscd_dev *dv)
{
    (void)pthread_mutex_lock(&dv->lock);
    dv->stray++;
    (void)pthread_mutex_unlock(&dv->lock);
}

/* Sorts the frames received during the last call, in the order they came:
 * the reply (reply[0..rlen), for client) where it was, notifications to
 * everyone, answers to commands lscd does not know to the client that sent
 * the last of those, the rest counted as strays. A reply that the hook did
 * not see goes last. */
static void sort_received(lscd_dev *dv, uint64_t client, const uint8_t *reply, size_t rlen)
{
    bool replied = false;
    size_t at = 0;
    while (at + 2u <= dv->frames_len) {
        size_t n = ((size_t)dv->frames[at] << 8) | dv->frames[at + 1u];
        const uint8_t *f = dv->frames + at + 2u;
        at += n + 2u;
        if (!replied && rlen > 0u && n == rlen && memcmp(f, reply, n) == 0) {
            post(dv, LSCD_EV_TO, client, f[3], 0, f, n);
            replied = true;
        } else if (lscd_is_notification(f[3])) {
            post(dv, LSCD_EV_BROADCAST, 0, f[3], 0, f, n);
        } else if (!lscd_cmd_known(f[3]) && f[3] != LSC_LSCD_CMD && dv->raw_client != 0u) {
            post(dv, LSCD_EV_TO, dv->raw_client, f[3], 0, f, n);
        } else {
            count_stray(dv);
        }
    }
    dv->frames_len = 0;
    if (rlen > 0u && !replied) {
        post(dv, LSCD_EV_TO, client, reply[3], 0, reply, rlen);
    }
}

/* The link's counters, for the status (after each exchange). */
static void keep_counters(lscd_dev *dv)
{
    lsc_device_counters c;
    c.size = sizeof c;
    (void)lsc_device_get_counters(dv->d, &c); /* (d and the size are valid) */
    (void)pthread_mutex_lock(&dv->lock);
    dv->link = c;
    (void)pthread_mutex_unlock(&dv->lock);
}

/* ---- Losing the controller and getting it back ------------------------------------ */

static void set_state(lscd_dev *dv, bool present, const char *error)
{
    (void)pthread_mutex_lock(&dv->lock);
    dv->present = present;
    if (present) {
        (void)snprintf(dv->name, sizeof dv->name, "%s", lsc_device_name(dv->d));
        dv->kind = lsc_device_kind_of(dv->d);
        dv->error[0] = '\0';
    } else {
        (void)snprintf(dv->error, sizeof dv->error, "%s", error);
    }
    (void)pthread_mutex_unlock(&dv->lock);
}

static void lost(lscd_dev *dv, const char *why)
{
    char msg[512];
    const char *err = lsc_device_error(dv->d);
    if (why != NULL || err[0] == '\0') {
        (void)snprintf(msg, sizeof msg, "%s: %s", lsc_device_name(dv->d),
                       why != NULL ? why : "the controller went away");
    } else {
        (void)snprintf(msg, sizeof msg, "%s", err);
    }
    lsc_device_close_port(dv->d); /* the port is free (the same name when it is back) */
    dv->gone = true; /* (the handle stays: lsc_device_reopen opens it again) */
    dv->next_retry = lscd_now_ms() + dv->cfg->retry_ms;
    set_state(dv, false, msg);
    post_text(dv, dv->cfg->exit_on_loss ? LSCD_EV_FATAL : LSCD_EV_GONE, msg);
}

static bool is_loss(int rc)
{
    return rc == LSC_ENODEV || rc == LSC_EIO;
}

/* Opens the lost controller again, into the same handle (its frame hook
 * stays). A port that another lscd took meanwhile is no controller of
 * lscd's: it stays lost (the next reopen lets go of that lscd). */
static void reopen(lscd_dev *dv)
{
    int r = lsc_device_reopen(dv->d);
    if (r == 0 && lsc_device_kind_of(dv->d) == LSC_DEVICE_LSCD && !dv->lscd_asked) {
        r = LSC_EBUSY;
    }
    if (r != 0) {
        (void)pthread_mutex_lock(&dv->lock);
        (void)snprintf(dv->error, sizeof dv->error, "%s", lscd_open_error(dv->d));
        (void)pthread_mutex_unlock(&dv->lock);
        return;
    }
    dv->gone = false;
    set_state(dv, true, NULL);
    post_text(dv, LSCD_EV_BACK, lsc_device_name(dv->d));
}

/* ---- Reading between jobs, and the jobs -------------------------------------------- */

/* Reads what the controller sent (hup: its descriptor hung up); the frame
 * hook has every frame (the device queues no notifications while it is
 * set). */
static void idle_read(lscd_dev *dv, bool hup)
{
    int r = lsc_device_poll(dv->d, 0); /* what has arrived ("sim": by now) */
    sort_received(dv, 0, NULL, 0);
    keep_counters(dv);
    if (r < 0 && is_loss(r)) {
        lost(dv, NULL);
    } else if (hup) {
        lost(dv, r < 0 ? NULL : "the port hung up");
    }
}

/* A client's frame, as it came (its command and parameters, encoded again). */
static int send_frame(lsc_device *d, const lscd_job *job)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_encode_frame(frame, sizeof frame, job->cmd, job->params, job->nparams);
    /* (the parser gave it: it always encodes again) */
    return len < 0 ? len : lsc_device_send_frame(d, frame, (size_t)len);
}

/* A job that lscd_dev_interrupt cut short (r LSC_EINTR) ends as the frames
 * a halt drops: LSC_EBUSY. One that ended before its wait took the
 * interrupt leaves it pending, and the next wait (the halt's read) would
 * take it: a wait of 1 ms takes it now (LSC_EINTR at once, nothing read);
 * after a loss, once the port is closed (its message is the loss's). */
static int after_interrupt(lscd_dev *dv, int r)
{
    if (r == LSC_EINTR) {
        return LSC_EBUSY;
    }
    if (!is_loss(r)) {
        (void)lsc_device_poll(dv->d, 1);
    }
    return r;
}

static void run_job(lscd_dev *dv, const lscd_job *job, uint64_t client, uint32_t timeout_ms)
{
    char halt_why[512] = "";
    uint8_t reply[LSC_FRAME_MAX];
    int rlen = 0;
    int r;
    lsc_device_set_timeout(dv->d, timeout_ms);
    (void)pthread_mutex_lock(&dv->lock);
    dv->running = job->kind != LSCD_JOB_HALT; /* (a halt is never cut short) */
    dv->interrupted = false;
    (void)pthread_mutex_unlock(&dv->lock);
    char why[512] = ""; /* a failure's line, for its client (VERDICT) */
    switch (job->kind) {
    case LSCD_JOB_BATTERY: {
        uint16_t mv = 0;
        r = lsc_device_battery(dv->d, &mv);
        if (r == 0) {
            rlen = lsc_encode_battery_reply(reply, sizeof reply, mv);
        }
        break;
    }
    case LSCD_JOB_READ: {
        lsc_servo got[LSC_READ_MAX];
        r = lsc_device_read(dv->d, job->ids, job->nids, got);
        if (r >= 0) {
            rlen = lsc_encode_pos_reply(reply, sizeof reply, got, job->nids);
            r = 0;
        }
        break;
    }
    case LSCD_JOB_OFFSETS: {
        lsc_servo_offset got[LSC_READ_MAX];
        r = lsc_device_read_offsets(dv->d, job->ids, job->nids, got);
        if (r >= 0) {
            rlen = lsc_encode_offset_reply(reply, sizeof reply, got, job->nids);
            r = 0;
        }
        break;
    }
    case LSCD_JOB_HALT:
        r = lsc_device_halt(dv->d); /* (its message goes with DONE) */
        (void)snprintf(halt_why, sizeof halt_why, "%s", lsc_device_error(dv->d));
        break;
    default:
        if (!lscd_cmd_known(job->cmd)) {
            dv->raw_client = client; /* answers to it, if any, are this client's */
        }
        r = send_frame(dv->d, job);
        break;
    }
    if (r < 0 && job->kind != LSCD_JOB_HALT) {
        (void)snprintf(why, sizeof why, "%s", lsc_device_error(dv->d));
    }
    (void)pthread_mutex_lock(&dv->lock);
    bool cut = dv->interrupted;
    dv->running = false;
    (void)pthread_mutex_unlock(&dv->lock);
    if (cut) {
        r = after_interrupt(dv, r);
        if (r == LSC_EBUSY) { /* a halt ended it: the client says so */
            why[0] = '\0';
        }
    }
    if (!is_loss(r)) {
        (void)lsc_device_poll(dv->d, 0); /* what came with it, sorted with the reply */
    }
    if (rlen < 0) { /* (a reply decoded from the controller always encodes again) */
        rlen = 0;
        r = LSC_EREPLY;
    }
    sort_received(dv, client, reply, (size_t)rlen);
    keep_counters(dv);
    if (job->kind == LSCD_JOB_HALT) {
        post(dv, LSCD_EV_DONE, client, job->cmd, r, halt_why, strlen(halt_why));
    } else {
        post(dv, LSCD_EV_DONE, client, job->cmd, r, why, strlen(why));
    }
    if (is_loss(r)) {
        lost(dv, NULL);
        if (cut) {
            (void)lsc_device_poll(dv->d, 1); /* (closed: it only takes an interrupt) */
        }
    }
}

/* How long the device thread may sleep: until the device's next event
 * (lsc_device_next_event_ms; -1: none, only its descriptor or a job can
 * bring one). */
static int idle_timeout(const lscd_dev *dv)
{
    uint32_t next = lsc_device_next_event_ms(dv->d);
    return next == LSC_DEVICE_FOREVER ? -1 : next > (uint32_t)INT_MAX ? INT_MAX : (int)next;
}

static void *dev_main(void *arg)
{
    lscd_dev *dv = arg;
    lscd_job job;
    for (;;) {
        (void)pthread_mutex_lock(&dv->lock);
        bool quit = dv->quit, has_job = dv->job_pending;
        uint64_t client = dv->job_client;
        uint32_t timeout_ms = dv->job_timeout_ms;
        if (has_job) {
            job = dv->job;
            dv->job_pending = false; /* taken: the server hands the next after DONE */
        }
        (void)pthread_mutex_unlock(&dv->lock);
        if (quit) {
            break;
        }
        uint64_t now = lscd_now_ms();
        if (has_job) {
            if (!dv->gone) {
                run_job(dv, &job, client, timeout_ms);
            } else {
                post(dv, LSCD_EV_DONE, client, job.cmd, LSC_ENODEV, NULL, 0);
            }
            continue;
        }
        struct pollfd p[2] = {{dv->wake[0], POLLIN, 0}, {-1, POLLIN, 0}};
        int timeout = -1;
        if (dv->gone) {
            uint64_t wait = dv->next_retry > now ? dv->next_retry - now : 0u;
            timeout = wait > (uint64_t)INT_MAX ? INT_MAX : (int)wait;
        } else {
            p[1].fd = lsc_device_fileno(dv->d); /* poll() passes over -1 */
            timeout = idle_timeout(dv);
        }
        int r = poll(p, 2, timeout);
        if (r < 0 && errno != EINTR) {
            lscd_log("device thread: poll: %s", strerror(errno));
        }
        if (r > 0 && (p[0].revents & POLLIN) != 0) {
            drain_fd(dv->wake[0]);
        }
        now = lscd_now_ms();
        if (dv->gone) {
            if (now >= dv->next_retry) {
                dv->next_retry = now + dv->cfg->retry_ms;
                reopen(dv);
            }
        } else if (r > 0 && p[1].revents != 0) {
            idle_read(dv, (p[1].revents & (POLLHUP | POLLERR | POLLNVAL)) != 0);
        } else if (r == 0) { /* its time came */
            idle_read(dv, false);
        }
    }
    return NULL;
}

/* ---- The server's side --------------------------------------------------------------- */

static int make_pipe(int p[2])
{
    if (pipe(p) != 0) {
        return -1;
    }
    for (int i = 0; i < 2; i++) {
        (void)fcntl(p[i], F_SETFD, FD_CLOEXEC);
        (void)fcntl(p[i], F_SETFL, fcntl(p[i], F_GETFL) | O_NONBLOCK);
    }
    return 0;
}

int lscd_dev_start(lscd_dev *dv, const lscd_config *cfg, lsc_device *d)
{
    memset(dv, 0, sizeof *dv);
    dv->cfg = cfg;
    dv->d = d;
    dv->wake[0] = dv->wake[1] = dv->notify[0] = dv->notify[1] = -1;
    if (pthread_mutex_init(&dv->lock, NULL) != 0) {
        return -1;
    }
    if (make_pipe(dv->wake) != 0 || make_pipe(dv->notify) != 0) {
        return -1;
    }
    lsc_device_set_frame_hook(d, on_frame, dv);
    dv->lscd_asked = asked_for_lscd(cfg);
    dv->present = true;
    (void)snprintf(dv->name, sizeof dv->name, "%s", lsc_device_name(d));
    dv->kind = lsc_device_kind_of(d);
    /* the thread takes no signals: they go to the server (its pipe) */
    sigset_t all, old;
    (void)sigfillset(&all);
    (void)pthread_sigmask(SIG_SETMASK, &all, &old);
    int r = pthread_create(&dv->thread, NULL, dev_main, dv);
    (void)pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (r != 0) {
        errno = r;
        return -1;
    }
    return 0;
}

void lscd_dev_submit(lscd_dev *dv, uint64_t client, const lscd_job *job, uint32_t timeout_ms)
{
    (void)pthread_mutex_lock(&dv->lock);
    dv->job = *job;
    dv->job_client = client;
    dv->job_timeout_ms = timeout_ms;
    dv->job_pending = true;
    (void)pthread_mutex_unlock(&dv->lock);
    signal_fd(dv->wake[1]);
}

lscd_ev *lscd_dev_take(lscd_dev *dv)
{
    drain_fd(dv->notify[0]);
    (void)pthread_mutex_lock(&dv->lock);
    lscd_ev *e = dv->head;
    dv->head = dv->tail = NULL;
    (void)pthread_mutex_unlock(&dv->lock);
    return e;
}

void lscd_dev_interrupt(lscd_dev *dv)
{
    (void)pthread_mutex_lock(&dv->lock);
    if (dv->running) { /* (under the lock: the job cannot end unseen meanwhile) */
        lsc_device_interrupt(dv->d);
        dv->interrupted = true;
    }
    (void)pthread_mutex_unlock(&dv->lock);
}

void lscd_dev_stop(lscd_dev *dv)
{
    (void)pthread_mutex_lock(&dv->lock);
    dv->quit = true;
    (void)pthread_mutex_unlock(&dv->lock);
    lscd_dev_interrupt(dv); /* a job under way ends now, not at its timeout */
    signal_fd(dv->wake[1]);
    (void)pthread_join(dv->thread, NULL);
    lsc_device_close(dv->d);
    dv->d = NULL;
    lscd_ev *e = lscd_dev_take(dv);
    while (e != NULL) {
        lscd_ev *next = e->next;
        free(e);
        e = next;
    }
    free(dv->frames);
    dv->frames = NULL;
    for (int i = 0; i < 2; i++) {
        (void)close(dv->wake[i]);
        (void)close(dv->notify[i]);
    }
    (void)pthread_mutex_destroy(&dv->lock);
}
