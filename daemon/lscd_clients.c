/* lscd: the clients: reading and decoding what they send (lscd_wire), with
 * backpressure and a share per turn of the loop; their frames into the
 * queue; clients coming (accepted, or refused beyond --max-clients) and
 * going. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include "lscd_server.h"

client *lscd_find_client(server *s, uint64_t id)
{
    for (client *c = s->clients; c != NULL; c = c->next) {
        if (c->id == id) {
            return c;
        }
    }
    return NULL;
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
    item *it = lscd_new_item(s, c, IT_FRAME, deadline);
    if (it != NULL) {
        it->job = in->job;
    } else {
        lscd_verdict(s, c, in->job.cmd, LSC_ENOSPC);
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
void lscd_take_input(server *s, client *c)
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
            lscd_on_control(s, c, &in);
        } else if (in.kind == LSCD_IN_BAD_CONTROL) {
            uint8_t op = in.op;
            lscd_put_text(s, c, LSC_LSCD_EV_ERROR, &op, 1, in.why);
        }
    }
    if (c->in_off == c->in_len) {
        c->in_off = c->in_len = 0;
    }
}

/* c shut its sending side (seen before lscd read all it sent, or at the end
 * of its input): its lease ends and it gets no other. */
void lscd_on_shut(server *s, client *c)
{
    c->shut = true;
    if (s->holder == c) {
        lscd_end_lease(s, 0);
    }
}

void lscd_read_client(server *s, client *c)
{
    if (c->in_len > 0u) {
        return; /* what it sent before is not all taken yet */
    }
    ssize_t got = recv(c->fd, c->in, sizeof c->in, MSG_DONTWAIT);
    if (got > 0) {
        c->in_len = (size_t)got;
        c->in_off = 0;
        lscd_take_input(s, c);
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
    lscd_on_shut(s, c);
}

void lscd_remove_client(server *s, client *c)
{
    if (s->holder == c) {
        lscd_end_lease(s, 0);
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
            lscd_q_remove(s, it);
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

void lscd_accept_clients(server *s)
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
        lscd_put_ctl(s, c, LSC_LSCD_EV_HELLO, hello, sizeof hello);
        if (s->cfg->verbose) {
            lscd_log("client %llu (pid %ld, uid %ld) connected", (unsigned long long)c->id, c->pid,
                     c->uid);
        }
    }
}
