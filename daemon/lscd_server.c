/* lscd: the server loop. It owns the clients: reads and decodes what they
 * send (lscd_wire), queues their frames in arrival order, hands the device
 * thread one job at a time (lscd_dev.c), keeps the lease, answers control
 * requests, and writes to every client without ever blocking: what a client
 * does not read in time waits in its bounded queue, and what does not fit is
 * dropped, counted and told (docs/lscd-protocol.md, lscd.8). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "lsc/device.h" /* lsc_escape_text */
#include "lsc/text.h"
#include "lsc/lscd.h"
#include "lscd.h"

#ifndef POLLRDHUP
#define POLLRDHUP 0 /* (Linux's: elsewhere a half-close is seen at the end of the input) */
#endif

#define IN_CHUNK 4096u
#define ROUND_INPUTS 16u /* requests taken from one client per turn of the loop */
#define STATUS_CLIENTS_MAX 32u /* client lines in a status (the rest are counted) */

typedef struct client client;

typedef enum item_kind { IT_FRAME = 0, IT_LEASE, IT_RELEASE, IT_HALT } item_kind;

/* Something a client asked for that waits its turn. */
typedef struct item {
    struct item *next, *prev;
    client *c; /* NULL: its client is gone (a frame without reply still goes) */
    item_kind kind;
    uint64_t deadline; /* dropped if not begun by then */
    uint32_t lease_ms; /* IT_LEASE: the lease's; IT_HALT: the halt's timeout */
    lscd_job job;
} item;

struct client {
    client *next;
    int fd;
    uint64_t id;
    long pid, uid;
    lscd_wire wire;
    uint8_t in[IN_CHUNK];
    size_t in_len, in_off;
    bool eof;  /* it sent all it will (its lease has ended) */
    bool shut; /* it shut its sending side: no lease for it any more */
    bool dead; /* gone: removed at the end of the loop */
    bool subscribed, ack, refuse;
    uint32_t timeout_ms;
    unsigned queued; /* its items waiting or running */
    uint64_t last_deadline;
    uint64_t walk; /* the scheduling pass in which one of its items had to wait */
    unsigned taken;          /* requests taken from it in this turn of the loop */
    uint64_t blocked_since;  /* when output began to wait in out (0: none waits) */
    uint8_t *out;
    size_t out_len, out_cap;
    uint32_t dropped;
    bool drop_notice;
    uint32_t frames;
};

typedef struct server {
    const lscd_config *cfg;
    lscd_dev *dv;
    int listen_fd, sigfd;
    bool accept_paused;
    bool more_input; /* a client has input it may still take: do not sleep */
    client *clients;
    unsigned nclients, nsubscribers;
    uint64_t next_id;
    item *qhead, *qtail;
    unsigned qlen;
    bool busy; /* a job is with the device thread */
    uint64_t walk;
    client *holder;
    uint64_t lease_until;
    bool present;
    bool stop;
    int exit_code;
    uint64_t started;
    /* counters */
    uint32_t n_frames, n_done, n_timeouts, n_failed, n_expired, n_refused, n_notifications,
        n_dropped, n_losses, n_clients_total, n_full;
    uint64_t gone_malformed, gone_discarded; /* the parser counters of clients that left */
} server;

void lscd_log(const char *fmt, ...)
{
    char line[1024], shown[4 * sizeof line];
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    /* one line, whatever the paths, names and messages in it hold: every byte
     * outside printable ASCII escaped by the library's one rule */
    (void)lsc_escape_text(shown, sizeof shown, line, strlen(line));
    (void)fprintf(stderr, LSCD_PROG ": %s\n", shown);
}

uint64_t lscd_now_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
}

/* ---- Writing to a client ------------------------------------------------------------ */

/* Sends what waits for c, as much as its socket takes now. */
static void flush_out(server *s, client *c);

static bool out_store(server *s, client *c, const uint8_t *p, size_t n)
{
    if (n > s->cfg->client_queue - c->out_len) {
        return false;
    }
    if (c->out_len + n > c->out_cap) {
        size_t cap = c->out_cap != 0u ? c->out_cap : 1024u;
        while (cap < c->out_len + n) {
            cap *= 2u;
        }
        if (cap > s->cfg->client_queue) {
            cap = s->cfg->client_queue;
        }
        uint8_t *q = realloc(c->out, cap);
        if (q == NULL) {
            return false;
        }
        c->out = q;
        c->out_cap = cap;
    }
    memcpy(c->out + c->out_len, p, n);
    if (c->out_len == 0u) {
        c->blocked_since = lscd_now_ms();
    }
    c->out_len += n;
    return true;
}

/* The DROPPED event, once there is room for it after drops. */
static bool put_notice(server *s, client *c)
{
    uint8_t args[4], frame[16];
    lsc_lscd_put_u32(args, c->dropped);
    int len = lscd_encode_ctl(frame, sizeof frame, LSC_LSCD_EV_DROPPED, args, sizeof args);
    if (len > 0 && out_store(s, c, frame, (size_t)len)) {
        c->drop_notice = false;
        return true;
    }
    return false;
}

/* Queues a whole frame for c, or drops it (counted, and told when there is
 * room again). */
static void put(server *s, client *c, const uint8_t *p, size_t n)
{
    if (c->dead) {
        return;
    }
    if (c->drop_notice && !put_notice(s, c)) {
        c->dropped++;
        s->n_dropped++;
        return;
    }
    if (c->out_len == 0u) {
        ssize_t w = send(c->fd, p, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w == (ssize_t)n) {
            return;
        }
        if (w < 0 && !lscd_would_block(errno)) {
            c->dead = true;
            return;
        }
        if (w > 0) {
            p += w;
            n -= (size_t)w;
        }
    }
    if (!out_store(s, c, p, n)) {
        c->dropped++;
        c->drop_notice = true;
        s->n_dropped++;
    }
}

static void flush_out(server *s, client *c)
{
    while (c->out_len > 0u && !c->dead) {
        ssize_t w = send(c->fd, c->out, c->out_len, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w < 0) {
            if (!lscd_would_block(errno)) {
                c->dead = true;
            }
            break;
        }
        memmove(c->out, c->out + w, c->out_len - (size_t)w);
        c->out_len -= (size_t)w;
        if (w > 0 && c->out_len > 0u) {
            c->blocked_since = lscd_now_ms(); /* it reads, if slower than lscd writes */
        }
    }
    if (c->out_len == 0u) {
        c->blocked_since = 0;
    }
    if (c->drop_notice && !c->dead) {
        (void)put_notice(s, c);
    }
}

static void put_ctl(server *s, client *c, uint8_t ev, const uint8_t *args, size_t n)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lscd_encode_ctl(frame, sizeof frame, ev, args, n);
    if (len > 0) {
        put(s, c, frame, (size_t)len);
    }
}

static void put_text(server *s, client *c, uint8_t ev, const uint8_t *prefix, size_t np,
                     const char *text)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lscd_encode_ctl_text(frame, sizeof frame, ev, prefix, np, text);
    if (len > 0) {
        put(s, c, frame, (size_t)len);
    }
}

static void verdict(server *s, client *c, uint8_t cmd, int rc)
{
    if (c != NULL && c->ack) {
        uint8_t args[2] = {cmd, (uint8_t)(int8_t)rc};
        put_ctl(s, c, LSC_LSCD_EV_VERDICT, args, sizeof args);
    }
}

static void lease_event(server *s, client *c, uint8_t state, uint32_t ms)
{
    uint8_t args[5];
    args[0] = state;
    lsc_lscd_put_u32(args + 1, ms);
    put_ctl(s, c, LSC_LSCD_EV_LEASE, args, sizeof args);
}

/* ---- The queue ----------------------------------------------------------------------- */

static void q_append(server *s, item *it)
{
    it->next = NULL;
    it->prev = s->qtail;
    if (s->qtail != NULL) {
        s->qtail->next = it;
    } else {
        s->qhead = it;
    }
    s->qtail = it;
    s->qlen++;
}

static void q_remove(server *s, item *it)
{
    if (it->prev != NULL) {
        it->prev->next = it->next;
    } else {
        s->qhead = it->next;
    }
    if (it->next != NULL) {
        it->next->prev = it->prev;
    } else {
        s->qtail = it->prev;
    }
    s->qlen--;
    if (it->c != NULL) {
        it->c->queued--;
    }
    free(it);
}

static item *new_item(server *s, client *c, item_kind kind, uint64_t deadline)
{
    item *it = calloc(1, sizeof *it);
    if (it == NULL) {
        return NULL;
    }
    it->c = c;
    it->kind = kind;
    it->deadline = deadline;
    c->queued++;
    q_append(s, it);
    return it;
}

static client *find_client(server *s, uint64_t id)
{
    for (client *c = s->clients; c != NULL; c = c->next) {
        if (c->id == id) {
            return c;
        }
    }
    return NULL;
}

static void end_lease(server *s, uint8_t state)
{
    client *c = s->holder;
    s->holder = NULL;
    if (c == NULL) {
        return;
    }
    if (state != 0u) {
        lease_event(s, c, state, 0);
    }
    if (s->cfg->verbose) {
        lscd_log("client %llu (pid %ld): lease ended (%s)", (unsigned long long)c->id, c->pid,
                 state == LSC_LSCD_LEASE_EXPIRED    ? "its time ran out"
                 : state == LSC_LSCD_LEASE_RELEASED ? "released"
                 : state == LSC_LSCD_LEASE_HALTED   ? "a halt"
                                                    : "the client left or stopped sending");
    }
}

static void release(server *s, client *c)
{
    if (c != NULL && s->holder == c) {
        end_lease(s, LSC_LSCD_LEASE_RELEASED);
    } else if (c != NULL) {
        lease_event(s, c, LSC_LSCD_LEASE_NONE, 0);
    }
}

/* Whether c can still use a lease: it has not shut its sending side, and
 * what lscd sends it has not waited unread longer than LSCD_LEASE_BLOCKED_MS. */
static bool can_lease(const client *c, uint64_t now)
{
    return !c->shut && !c->eof &&
           (c->blocked_since == 0u || now - c->blocked_since < LSCD_LEASE_BLOCKED_MS);
}

/* An item that could not begin before its deadline. */
static void expire(server *s, item *it, bool leased)
{
    client *c = it->c;
    if (it->kind == IT_FRAME) {
        s->n_expired++;
        verdict(s, c, it->job.cmd, leased ? LSC_EBUSY : LSC_ETIMEOUT);
    } else if (it->kind == IT_LEASE && c != NULL) {
        lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
    } else {
        release(s, c);
    }
    q_remove(s, it);
}

/* A halt is done (rc, lscd's message text): every client is told. */
static void halted(server *s, int rc, const char *text)
{
    uint8_t result = (uint8_t)(int8_t)rc;
    lscd_log("halt done: %s", rc == 0 ? "every servo holds where it was" : text);
    for (client *c = s->clients; c != NULL; c = c->next) {
        put_text(s, c, LSC_LSCD_EV_HALTED, &result, 1, text);
    }
}

/* OP_HALT from c: the lease ends (its holder is told), every frame waiting
 * for the controller is dropped (LSC_EBUSY), and the halt goes first, ahead
 * of what comes after it, whoever holds a lease (docs/lscd-protocol.md). */
static void halt_request(server *s, client *c)
{
    lscd_log("client %llu (pid %ld): halt", (unsigned long long)c->id, c->pid);
    end_lease(s, LSC_LSCD_LEASE_HALTED);
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next;
        if (it->kind == IT_FRAME) {
            s->n_refused++;
            verdict(s, it->c, it->job.cmd, LSC_EBUSY);
            q_remove(s, it);
        }
    }
    item *it = new_item(s, c, IT_HALT, UINT64_MAX);
    if (it == NULL) {
        halted(s, LSC_ENOSPC, "out of memory");
        return;
    }
    it->lease_ms = c->timeout_ms;
    it->job.kind = LSCD_JOB_HALT;
    it->job.cmd = (uint8_t)LSC_LSCD_CMD;
    /* to the front: before the leases and releases still waiting */
    if (it != s->qhead) {
        it->prev->next = NULL;
        s->qtail = it->prev;
        it->prev = NULL;
        it->next = s->qhead;
        s->qhead->prev = it;
        s->qhead = it;
    }
}

/* One pass over the queue in arrival order: drops what is due, refuses what
 * must be refused, grants leases, and starts the first frame that may go
 * (one at a time: a frame that must wait holds back every later lease
 * grant). A client's items keep their order: once one of them must wait,
 * its later ones wait too. Returns true if the lease changed (another pass
 * may start what it held back). */
static bool walk_once(server *s, uint64_t now)
{
    bool frame_waits = s->busy;
    s->walk++;
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next;
        client *c = it->c;
        if (c != NULL && c->walk == s->walk) {
            continue;
        }
        bool leased = s->holder != NULL && s->holder != c && it->kind != IT_RELEASE &&
                      it->kind != IT_HALT; /* (a halt outranks a lease) */
        if (now >= it->deadline) {
            expire(s, it, leased);
            continue;
        }
        if (leased) {
            if (c != NULL && c->refuse && it->kind == IT_FRAME) {
                s->n_refused++;
                verdict(s, c, it->job.cmd, LSC_EBUSY);
                q_remove(s, it);
            } else if (c != NULL) {
                c->walk = s->walk;
            }
            continue;
        }
        switch (it->kind) {
        case IT_RELEASE: {
            bool had = s->holder == c;
            release(s, c);
            q_remove(s, it);
            if (had) {
                return true;
            }
            break;
        }
        case IT_LEASE:
            if (!can_lease(c, now)) {
                lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
                q_remove(s, it);
                break;
            }
            if (frame_waits) {
                c->walk = s->walk;
                break;
            }
            s->holder = c;
            s->lease_until = now + it->lease_ms;
            lease_event(s, c, LSC_LSCD_LEASE_GRANTED, it->lease_ms);
            if (s->cfg->verbose) {
                lscd_log("client %llu (pid %ld): lease for %lu ms", (unsigned long long)c->id,
                         c->pid, (unsigned long)it->lease_ms);
            }
            q_remove(s, it);
            return true;
        case IT_HALT:
            if (!s->present) {
                halted(s, LSC_ENODEV, "the controller is gone");
                q_remove(s, it);
                break;
            }
            if (frame_waits) { /* the job under way ends first */
                break;
            }
            lscd_dev_submit(s->dv, c != NULL ? c->id : 0u, &it->job, it->lease_ms);
            s->busy = true;
            frame_waits = true;
            if (c != NULL) {
                c->queued++; /* (q_remove takes it back: it counts until DONE) */
            }
            q_remove(s, it);
            break;
        default: /* IT_FRAME */
            if (!s->present) {
                s->n_failed++;
                verdict(s, c, it->job.cmd, LSC_ENODEV);
                q_remove(s, it);
                break;
            }
            if (frame_waits) {
                if (c != NULL) {
                    c->walk = s->walk;
                }
                break;
            }
            uint64_t left = it->deadline - now;
            lscd_dev_submit(s->dv, c != NULL ? c->id : 0u, &it->job,
                            left > UINT32_MAX ? UINT32_MAX : (uint32_t)left);
            s->busy = true;
            frame_waits = true;
            if (c != NULL) {
                c->queued++; /* (q_remove takes it back: it counts until DONE) */
                c->walk = s->walk;
            }
            q_remove(s, it);
            break;
        }
    }
    return false;
}

static void schedule(server *s)
{
    uint64_t now = lscd_now_ms();
    if (s->holder != NULL && now >= s->lease_until) {
        end_lease(s, LSC_LSCD_LEASE_EXPIRED);
    } else if (s->holder != NULL && !can_lease(s->holder, now)) {
        if (s->cfg->verbose) {
            lscd_log("client %llu (pid %ld) has not read for %u ms", (unsigned long long)s->holder->id,
                     s->holder->pid, LSCD_LEASE_BLOCKED_MS);
        }
        end_lease(s, LSC_LSCD_LEASE_EXPIRED);
    }
    while (walk_once(s, now)) {
    }
}

/* ms until the next deadline (a queued item's, the lease's), or -1. */
static int next_timer(const server *s)
{
    uint64_t due = UINT64_MAX;
    for (const item *it = s->qhead; it != NULL; it = it->next) {
        if (it->deadline < due) {
            due = it->deadline;
        }
    }
    if (s->holder != NULL && s->lease_until < due) {
        due = s->lease_until;
    }
    if (s->holder != NULL && s->holder->blocked_since != 0u &&
        s->holder->blocked_since + LSCD_LEASE_BLOCKED_MS < due) {
        due = s->holder->blocked_since + LSCD_LEASE_BLOCKED_MS;
    }
    if (s->more_input) {
        return 0;
    }
    if (due == UINT64_MAX) {
        return -1;
    }
    uint64_t now = lscd_now_ms();
    if (due <= now) {
        return 0;
    }
    return due - now > (uint64_t)INT_MAX ? INT_MAX : (int)(due - now);
}

/* ---- Status ---------------------------------------------------------------------------- */

static void status_item(server *s, client *c, const char *key, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void status_item(server *s, client *c, const char *key, const char *fmt, ...)
{
    char text[LSCD_ARGS_MAX + 1u];
    int n = snprintf(text, sizeof text, "%s=", key);
    if (n > 0 && (size_t)n < sizeof text) {
        va_list ap;
        va_start(ap, fmt);
        (void)vsnprintf(text + n, sizeof text - (size_t)n, fmt, ap);
        va_end(ap);
    }
    put_text(s, c, LSC_LSCD_EV_STATUS, NULL, 0, text);
}

static const char *kind_name(lsc_device_kind k)
{
    switch (k) {
    case LSC_DEVICE_HID:
        return "hid";
    case LSC_DEVICE_SIM:
        return "sim";
    default:
        return "serial";
    }
}

static void send_status(server *s, client *asker)
{
    char name[LSC_DEVICE_NAME_MAX], error[512];
    lsc_device_kind kind;
    uint32_t stray, overrun;
    lscd_dev *dv = s->dv;
    (void)pthread_mutex_lock(&dv->lock);
    memcpy(name, dv->name, sizeof name);
    memcpy(error, dv->error, sizeof error);
    kind = dv->kind;
    stray = dv->stray;
    overrun = dv->overrun;
    (void)pthread_mutex_unlock(&dv->lock);
    uint64_t now = lscd_now_ms();
    status_item(s, asker, "version", "%s", LSCD_VERSION);
    status_item(s, asker, "protocol", "%u", (unsigned)LSC_LSCD_PROTOCOL);
    status_item(s, asker, "port", "%s", s->cfg->port);
    status_item(s, asker, "device", "%s", name);
    status_item(s, asker, "kind", "%s", kind_name(kind));
    status_item(s, asker, "controller", "%s", s->present ? "present" : "gone");
    if (!s->present) {
        status_item(s, asker, "error", "%s", error);
    }
    status_item(s, asker, "socket", "%s%s", s->cfg->socket_path,
                s->cfg->activated ? " (systemd)" : "");
    status_item(s, asker, "uptime_ms", "%llu", (unsigned long long)(now - s->started));
    status_item(s, asker, "clients", "%u", s->nclients);
    status_item(s, asker, "subscribers", "%u", s->nsubscribers);
    if (s->holder != NULL) {
        status_item(s, asker, "lease", "client %llu (pid %ld), %llu ms left",
                    (unsigned long long)s->holder->id, s->holder->pid,
                    (unsigned long long)(s->lease_until > now ? s->lease_until - now : 0u));
    } else {
        status_item(s, asker, "lease", "none");
    }
    status_item(s, asker, "queue", "%u", s->qlen + (s->busy ? 1u : 0u));
    status_item(s, asker, "frames", "%lu", (unsigned long)s->n_frames);
    status_item(s, asker, "done", "%lu", (unsigned long)s->n_done);
    status_item(s, asker, "timeouts", "%lu", (unsigned long)s->n_timeouts);
    status_item(s, asker, "failed", "%lu", (unsigned long)s->n_failed);
    status_item(s, asker, "expired", "%lu", (unsigned long)s->n_expired);
    status_item(s, asker, "refused", "%lu", (unsigned long)s->n_refused);
    status_item(s, asker, "notifications", "%lu", (unsigned long)s->n_notifications);
    status_item(s, asker, "dropped", "%lu", (unsigned long)s->n_dropped);
    status_item(s, asker, "stray", "%lu", (unsigned long)stray);
    status_item(s, asker, "overrun", "%lu", (unsigned long)overrun);
    status_item(s, asker, "losses", "%lu", (unsigned long)s->n_losses);
    status_item(s, asker, "connections", "%lu", (unsigned long)s->n_clients_total);
    status_item(s, asker, "max_clients", "%lu", (unsigned long)s->cfg->max_clients);
    status_item(s, asker, "full", "%lu", (unsigned long)s->n_full);
    uint64_t malformed = s->gone_malformed, discarded = s->gone_discarded;
    for (const client *c = s->clients; c != NULL; c = c->next) {
        malformed += c->wire.parser.errors;
        discarded += c->wire.parser.discarded;
    }
    status_item(s, asker, "malformed", "%llu", (unsigned long long)malformed);
    status_item(s, asker, "discarded", "%llu", (unsigned long long)discarded);
    unsigned listed = 0;
    for (client *c = s->clients; c != NULL; c = c->next) {
        if (listed++ == STATUS_CLIENTS_MAX) {
            status_item(s, asker, "client", "... and %u more", s->nclients - STATUS_CLIENTS_MAX);
            break;
        }
        status_item(s, asker, "client",
                    "%llu pid=%ld uid=%ld%s%s%s%s%s frames=%lu queue=%u dropped=%lu%s",
                    (unsigned long long)c->id, c->pid, c->uid, c->subscribed ? " subscribed" : "",
                    c->ack ? " ack" : "", c->refuse ? " refuse" : "", c->shut ? " shut" : "",
                    c->out_len > 0u ? " unread" : "", (unsigned long)c->frames,
                    c->queued, (unsigned long)c->dropped, c == asker ? " (this one)" : "");
    }
    put_ctl(s, asker, LSC_LSCD_EV_STATUS_END, NULL, 0);
}

/* ---- What clients send ------------------------------------------------------------------ */

static void on_control(server *s, client *c, const lscd_in *in)
{
    uint8_t args[4];
    uint64_t now = lscd_now_ms();
    switch (in->op) {
    case LSC_LSCD_OP_SUBSCRIBE:
        if (c->subscribed != (in->a != 0u)) {
            c->subscribed = in->a != 0u;
            s->nsubscribers = c->subscribed ? s->nsubscribers + 1u : s->nsubscribers - 1u;
        }
        break;
    case LSC_LSCD_OP_MODE:
        c->ack = (in->a & LSC_LSCD_MODE_ACK) != 0u;
        c->refuse = (in->a & LSC_LSCD_MODE_REFUSE) != 0u;
        break;
    case LSC_LSCD_OP_TIMEOUT:
        c->timeout_ms = in->a == 0u ? s->cfg->timeout_ms
                        : in->a > LSCD_TIMEOUT_MAX ? LSCD_TIMEOUT_MAX
                                                   : in->a;
        break;
    case LSC_LSCD_OP_LEASE: {
        uint32_t ms = in->a == 0u || in->a > s->cfg->lease_max_ms ? s->cfg->lease_max_ms : in->a;
        if ((in->b == 0u && s->holder != NULL && s->holder != c) || !can_lease(c, now)) {
            lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
            break;
        }
        uint32_t wait = in->b > c->timeout_ms ? in->b : c->timeout_ms;
        item *it = new_item(s, c, IT_LEASE, now + wait);
        if (it != NULL) {
            it->lease_ms = ms;
        }
        break;
    }
    case LSC_LSCD_OP_RELEASE:
        (void)new_item(s, c, IT_RELEASE, UINT64_MAX);
        break;
    case LSC_LSCD_OP_STATUS:
        send_status(s, c);
        break;
    case LSC_LSCD_OP_HALT:
        halt_request(s, c);
        break;
    default: /* PING */
        lsc_lscd_put_u32(args, in->a);
        put_ctl(s, c, LSC_LSCD_EV_PONG, args, sizeof args);
        break;
    }
}

static void on_frame(server *s, client *c, const lscd_in *in)
{
    uint64_t deadline = lscd_now_ms() + c->timeout_ms;
    if (deadline < c->last_deadline) {
        deadline = c->last_deadline; /* its frames keep their order */
    }
    c->last_deadline = deadline;
    c->frames++;
    s->n_frames++;
    item *it = new_item(s, c, IT_FRAME, deadline);
    if (it != NULL) {
        it->job = in->job;
    } else {
        verdict(s, c, in->job.cmd, LSC_ENOSPC);
    }
}

/* Whether lscd takes more of what c sent now: not while what it was sent
 * waits unread (backpressure: a client that does not read cannot make lscd
 * work for it), nor beyond its share of this turn of the loop. */
static bool may_take(server *s, client *c)
{
    if (c->dead || c->out_len > 0u || c->queued >= LSCD_CLIENT_ITEMS) {
        return false;
    }
    if (c->taken >= ROUND_INPUTS) {
        s->more_input = true; /* its next turn comes at once */
        return false;
    }
    return true;
}

/* Decodes what c has sent, while it may queue more. */
static void take_input(server *s, client *c)
{
    while (c->in_off < c->in_len && may_take(s, c)) {
        lscd_in in;
        c->in_off += lscd_wire_feed(&c->wire, c->in + c->in_off, c->in_len - c->in_off, &in);
        if (in.kind != LSCD_IN_NONE) {
            c->taken++;
        }
        if (in.kind == LSCD_IN_FRAME) {
            on_frame(s, c, &in);
        } else if (in.kind == LSCD_IN_CONTROL) {
            on_control(s, c, &in);
        } else if (in.kind == LSCD_IN_BAD_CONTROL) {
            uint8_t op = in.op;
            put_text(s, c, LSC_LSCD_EV_ERROR, &op, 1, in.why);
        }
    }
    if (c->in_off == c->in_len) {
        c->in_off = c->in_len = 0;
    }
}

/* c shut its sending side (seen before lscd read all it sent, or at the end
 * of its input): its lease ends and it gets no other. */
static void on_shut(server *s, client *c)
{
    c->shut = true;
    if (s->holder == c) {
        end_lease(s, 0);
    }
}

static void read_client(server *s, client *c)
{
    if (c->in_len > 0u) {
        return; /* what it sent before is not all taken yet */
    }
    ssize_t got = recv(c->fd, c->in, sizeof c->in, MSG_DONTWAIT);
    if (got > 0) {
        c->in_len = (size_t)got;
        c->in_off = 0;
        take_input(s, c);
        return;
    }
    if (got < 0 && lscd_would_block(errno)) {
        return;
    }
    if (got < 0) {
        c->dead = true; /* (ECONNRESET: it closed with unread data, or crashed) */
        return;
    }
    /* end of its input: what it queued still goes; its lease ends now */
    c->eof = true;
    on_shut(s, c);
}

/* ---- Clients coming and going --------------------------------------------------------------- */

static void remove_client(server *s, client *c)
{
    if (s->holder == c) {
        end_lease(s, 0);
    }
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next;
        if (it->c != c) {
            continue;
        }
        if (it->kind == IT_FRAME && it->job.kind == LSCD_JOB_SEND) {
            it->c = NULL; /* sent by a client that is gone: it still goes */
            c->queued--;
        } else {
            q_remove(s, it);
        }
    }
    for (client **at = &s->clients; *at != NULL; at = &(*at)->next) {
        if (*at == c) {
            *at = c->next;
            break;
        }
    }
    s->nclients--;
    s->gone_malformed += c->wire.parser.errors;
    s->gone_discarded += c->wire.parser.discarded;
    if (c->subscribed) {
        s->nsubscribers--;
    }
    if (s->cfg->verbose) {
        lscd_log("client %llu (pid %ld) left", (unsigned long long)c->id, c->pid);
    }
    (void)close(c->fd);
    free(c->out);
    free(c);
    s->accept_paused = false;
    lscd_dev_set_clients(s->dv, s->nclients);
}

static void peer_of(client *c)
{
    c->pid = -1;
    c->uid = -1;
#ifdef SO_PEERCRED
    struct ucred cred;
    socklen_t len = sizeof cred;
    if (getsockopt(c->fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0) {
        c->pid = (long)cred.pid;
        c->uid = (long)cred.uid;
    }
#endif
}

/* One client too many (or no memory for it): it is told why, instead of a
 * HELLO, and disconnected. */
static void refuse_client(server *s, int fd, bool no_memory)
{
    char text[LSCD_ARGS_MAX];
    uint8_t frame[LSC_FRAME_MAX], op = 0;
    if (no_memory) {
        (void)snprintf(text, sizeof text, "lscd is out of memory: try again later");
    } else {
        (void)snprintf(text, sizeof text,
                       "lscd serves at most %lu clients at once and has %u: try again later, "
                       "or raise its limit (lscd --max-clients)",
                       (unsigned long)s->cfg->max_clients, s->nclients);
    }
    int len = lscd_encode_ctl_text(frame, sizeof frame, LSC_LSCD_EV_ERROR, &op, 1, text);
    if (len > 0) {
        (void)send(fd, frame, (size_t)len, MSG_NOSIGNAL | MSG_DONTWAIT);
    }
    (void)close(fd);
    if (s->n_full++ == 0u || s->cfg->verbose) {
        lscd_log("a client was refused: %s", text);
    }
}

static void accept_clients(server *s)
{
    for (unsigned i = 0; i < 64u; i++) {
        int fd = accept(s->listen_fd, NULL, NULL);
        if (fd < 0) {
            if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
                lscd_log("cannot take more clients: %s", strerror(errno));
                s->accept_paused = true;
            }
            return;
        }
        (void)fcntl(fd, F_SETFD, FD_CLOEXEC);
        (void)fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
        client *c = s->nclients < s->cfg->max_clients ? calloc(1, sizeof *c) : NULL;
        if (c == NULL) {
            refuse_client(s, fd, s->nclients < s->cfg->max_clients);
            continue;
        }
        c->fd = fd;
        c->id = ++s->next_id;
        c->subscribed = true;
        c->timeout_ms = s->cfg->timeout_ms;
        lscd_wire_init(&c->wire);
        peer_of(c);
        c->next = s->clients;
        s->clients = c;
        s->nclients++;
        s->nsubscribers++;
        s->n_clients_total++;
        uint8_t hello[2] = {LSC_LSCD_PROTOCOL, s->present ? 1u : 0u};
        put_ctl(s, c, LSC_LSCD_EV_HELLO, hello, sizeof hello);
        if (s->cfg->verbose) {
            lscd_log("client %llu (pid %ld, uid %ld) connected", (unsigned long long)c->id, c->pid,
                     c->uid);
        }
        lscd_dev_set_clients(s->dv, s->nclients);
    }
}

/* ---- What the device thread tells ------------------------------------------------------- */

static void controller_event(server *s, bool present, const char *text)
{
    uint8_t state = present ? 1u : 0u;
    for (client *c = s->clients; c != NULL; c = c->next) {
        put_text(s, c, LSC_LSCD_EV_CONTROLLER, &state, 1, text);
    }
}

static void on_device(server *s)
{
    lscd_ev *e = lscd_dev_take(s->dv);
    while (e != NULL) {
        lscd_ev *next = e->next;
        client *c;
        switch (e->kind) {
        case LSCD_EV_BROADCAST:
            s->n_notifications++;
            for (c = s->clients; c != NULL; c = c->next) {
                if (c->subscribed) {
                    put(s, c, e->data, e->len);
                }
            }
            break;
        case LSCD_EV_TO:
            c = find_client(s, e->client);
            if (c != NULL) {
                put(s, c, e->data, e->len);
            }
            break;
        case LSCD_EV_DONE:
            s->busy = false;
            if (e->cmd == LSC_LSCD_CMD) { /* a halt */
                c = find_client(s, e->client);
                if (c != NULL) {
                    c->queued--;
                }
                halted(s, e->rc, (const char *)e->data);
                break;
            }
            if (e->rc == 0) {
                s->n_done++;
            } else if (e->rc == LSC_ETIMEOUT) {
                s->n_timeouts++;
            } else {
                s->n_failed++;
            }
            c = find_client(s, e->client);
            if (c != NULL) {
                c->queued--;
                verdict(s, c, e->cmd, e->rc);
            }
            break;
        case LSCD_EV_GONE:
        case LSCD_EV_FATAL:
            s->present = false;
            s->n_losses++;
            lscd_log("controller lost: %s", (const char *)e->data);
            controller_event(s, false, (const char *)e->data);
            if (e->kind == LSCD_EV_FATAL) {
                lscd_log("exiting (--exit-on-loss)");
                s->stop = true;
                s->exit_code = LSCD_EXIT_FAIL;
            } else {
                lscd_log("opening %s again every %lu ms until it is back", s->cfg->port,
                         (unsigned long)s->cfg->retry_ms);
            }
            break;
        default: /* BACK */
            s->present = true;
            lscd_log("controller back: %s", (const char *)e->data);
            controller_event(s, true, (const char *)e->data);
            break;
        }
        free(e);
        e = next;
    }
}

/* ---- The loop ------------------------------------------------------------------------------ */

int lscd_serve(const lscd_config *cfg, lscd_dev *dv, int listen_fd, int sigfd)
{
    server srv;
    server *s = &srv;
    struct pollfd *pfd = NULL;
    size_t pfd_cap = 0;
    memset(s, 0, sizeof *s);
    s->cfg = cfg;
    s->dv = dv;
    s->listen_fd = listen_fd;
    s->sigfd = sigfd;
    s->present = true;
    s->started = lscd_now_ms();
    while (!s->stop) {
        size_t need = 3u + s->nclients;
        if (need > pfd_cap) {
            struct pollfd *p = realloc(pfd, need * sizeof *p);
            if (p == NULL) {
                lscd_log("out of memory");
                s->exit_code = LSCD_EXIT_FAIL;
                break;
            }
            pfd = p;
            pfd_cap = need;
        }
        pfd[0] = (struct pollfd){sigfd, POLLIN, 0};
        pfd[1] = (struct pollfd){dv->notify[0], POLLIN, 0};
        pfd[2] = (struct pollfd){s->accept_paused ? -1 : listen_fd, POLLIN, 0};
        size_t n = 3;
        for (client *c = s->clients; c != NULL; c = c->next) {
            short ev = 0;
            if (!c->eof && c->in_len == 0u && c->out_len == 0u) {
                ev |= POLLIN;
            }
            if (!c->shut) {
                ev |= POLLRDHUP; /* a half-close ends its lease even while lscd does not read */
            }
            if (c->out_len > 0u) {
                ev |= POLLOUT;
            }
            pfd[n++] = (struct pollfd){c->fd, ev, 0};
        }
        int r = poll(pfd, (nfds_t)n, next_timer(s));
        s->more_input = false;
        for (client *c = s->clients; c != NULL; c = c->next) {
            c->taken = 0;
        }
        if (r < 0 && errno != EINTR) {
            lscd_log("poll: %s", strerror(errno));
            s->exit_code = LSCD_EXIT_FAIL;
            break;
        }
        if (r > 0 && pfd[0].revents != 0) {
            s->stop = true;
            s->exit_code = LSCD_EXIT_OK;
        }
        if (r > 0 && pfd[1].revents != 0) {
            on_device(s);
        }
        /* clients, in the order of the poll set (it was built from the list) */
        n = 3;
        for (client *c = s->clients; c != NULL && r > 0; c = c->next) {
            short rev = pfd[n++].revents;
            if ((rev & POLLRDHUP) != 0 && !c->shut) {
                on_shut(s, c);
            }
            if ((rev & POLLOUT) != 0) {
                flush_out(s, c);
            }
            if ((rev & POLLIN) != 0) {
                read_client(s, c);
            }
            if ((rev & (POLLHUP | POLLERR | POLLNVAL)) != 0 && (rev & POLLIN) == 0) {
                c->dead = true; /* closed both ways: nobody reads what it asked for */
            }
        }
        if (r > 0 && pfd[2].revents != 0) {
            accept_clients(s);
        }
        schedule(s);
        /* what waits in clients' buffers, now that their queues may have room */
        for (client *c = s->clients, *next; c != NULL; c = next) {
            next = c->next;
            take_input(s, c);
            if (c->eof && c->queued == 0u && c->out_len == 0u && c->in_len == 0u) {
                c->dead = true;
            }
            if (c->dead) {
                remove_client(s, c);
            }
        }
        schedule(s);
    }
    for (client *c = s->clients, *next; c != NULL; c = next) {
        next = c->next;
        flush_out(s, c);
        remove_client(s, c);
    }
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next; /* (only frames of clients that left remain) */
        free(it);
    }
    free(pfd);
    return s->exit_code;
}
