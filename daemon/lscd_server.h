/* lscd: what the server loop's parts share (private to the daemon): a
 * client, what it asked for that waits its turn, the server's state, and the
 * calls between the parts. One thread: the server's (the device thread has
 * lscd_dev.c and lscd.h). */
#ifndef LSCD_SERVER_H
#define LSCD_SERVER_H

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

/* ---- Writing to a client (lscd_out.c) ---- */

/* Queues a whole frame for c, or drops it (counted, and told when there is
 * room again). c NULL or gone: nothing. */
void lscd_put(server *s, client *c, const uint8_t *p, size_t n);
/* Sends what waits for c, as much as its socket takes now. */
void lscd_flush_out(server *s, client *c);
/* An event (lsc/lscd.h's LSC_LSCD_EV_*) with args, or with a prefix and text. */
void lscd_put_ctl(server *s, client *c, uint8_t ev, const uint8_t *args, size_t n);
void lscd_put_text(server *s, client *c, uint8_t ev, const uint8_t *prefix, size_t np,
                   const char *text);
/* The VERDICT of a frame of c's (only in ACK mode; c may be NULL). */
void lscd_verdict(server *s, client *c, uint8_t cmd, int rc);
/* ... with why it failed (the device's line; "" or NULL: none). */
void lscd_verdict_why(server *s, client *c, uint8_t cmd, int rc, const char *why);
/* A LEASE event: state (LSC_LSCD_LEASE_*) and ms. */
void lscd_lease_event(server *s, client *c, uint8_t state, uint32_t ms);

/* ---- The queue and the schedule (lscd_queue.c) ---- */

/* Takes it out of the queue and frees it (its client's count goes down). */
void lscd_q_remove(server *s, item *it);
/* A new item of c's at the end of the queue (NULL: out of memory). */
item *lscd_new_item(server *s, client *c, item_kind kind, uint64_t deadline);
/* Ends a lease whose time ran out or whose holder stopped reading, then
 * starts what may start. */
void lscd_schedule(server *s);
/* ms until the next deadline (a queued item's, the lease's), or -1. */
int lscd_next_timer(const server *s);

/* ---- The lease and the halt (lscd_lease.c) ---- */

/* Ends the lease, its holder told with state (0: not told). */
void lscd_end_lease(server *s, uint8_t state);
/* c's release: its lease ends, or it is told it had none. */
void lscd_release(server *s, client *c);
/* Whether c can still use a lease: it has not shut its sending side, and
 * what lscd sends it has not waited unread longer than LSCD_LEASE_BLOCKED_MS. */
static inline bool lscd_can_lease(const client *c, uint64_t now)
{
    return !c->shut && !c->eof &&
           (c->blocked_since == 0u || now - c->blocked_since < LSCD_LEASE_BLOCKED_MS);
}
/* A halt is done (rc, lscd's message text): every client is told. */
void lscd_halted(server *s, int rc, const char *text);
/* OP_HALT from c. */
void lscd_halt_request(server *s, client *c);

/* ---- Status and control (lscd_status.c, lscd_control.c) ---- */

/* The status items, then STATUS_END, to asker. */
void lscd_send_status(server *s, client *asker);
/* A control request of c's. */
void lscd_on_control(server *s, client *c, const lscd_in *in);

/* ---- The clients (lscd_clients.c) ---- */

/* The client with that id, or NULL (it left). */
client *lscd_find_client(server *s, uint64_t id);
/* Decodes what c has sent, while it may queue more. */
void lscd_take_input(server *s, client *c);
/* c shut its sending side: its lease ends and it gets no other. */
void lscd_on_shut(server *s, client *c);
/* Reads what c sent (its socket polled readable). */
void lscd_read_client(server *s, client *c);
/* Removes c: its lease ends, its items go (frames without reply still go),
 * its socket closes. */
void lscd_remove_client(server *s, client *c);
/* Accepts who is waiting on the listening socket. */
void lscd_accept_clients(server *s);

#endif
