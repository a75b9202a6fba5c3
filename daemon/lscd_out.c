/* lscd: writing to a client without ever blocking: what it does not read
 * in time waits in its bounded queue, and what does not fit is dropped,
 * counted and told (the DROPPED event); the events lscd sends. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>

#include "lscd_server.h"

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
void lscd_put(server *s, client *c, const uint8_t *p, size_t n)
{
    if (c == NULL || c->dead) { /* (NULL: nobody to tell) */
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

void lscd_flush_out(server *s, client *c)
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

void lscd_put_ctl(server *s, client *c, uint8_t ev, const uint8_t *args, size_t n)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lscd_encode_ctl(frame, sizeof frame, ev, args, n);
    if (len > 0) {
        lscd_put(s, c, frame, (size_t)len);
    }
}

void lscd_put_text(server *s, client *c, uint8_t ev, const uint8_t *prefix, size_t np,
                     const char *text)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lscd_encode_ctl_text(frame, sizeof frame, ev, prefix, np, text);
    if (len > 0) {
        lscd_put(s, c, frame, (size_t)len);
    }
}

void lscd_verdict(server *s, client *c, uint8_t cmd, int rc)
{
    lscd_verdict_why(s, c, cmd, rc, NULL);
}

void lscd_verdict_why(server *s, client *c, uint8_t cmd, int rc, const char *why)
{
    if (c != NULL && c->ack) {
        uint8_t args[2] = {cmd, (uint8_t)(int8_t)rc};
        if (rc != 0 && why != NULL && why[0] != '\0') {
            lscd_put_text(s, c, LSC_LSCD_EV_VERDICT, args, sizeof args, why);
        } else {
            lscd_put_ctl(s, c, LSC_LSCD_EV_VERDICT, args, sizeof args);
        }
    }
}

void lscd_lease_event(server *s, client *c, uint8_t state, uint32_t ms)
{
    uint8_t args[5];
    args[0] = state;
    lsc_lscd_put_u32(args + 1, ms);
    lscd_put_ctl(s, c, LSC_LSCD_EV_LEASE, args, sizeof args);
}
