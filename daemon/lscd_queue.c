/* lscd: the queue of what clients asked for, in arrival order, and the
 * schedule: what is due is dropped, what a lease holds back waits, the first
 * frame that may go goes to the device thread (one at a time). */
#include <limits.h>
#include <stdlib.h>

#include "lscd_server.h"

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

void lscd_q_remove(server *s, item *it)
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

item *lscd_new_item(server *s, client *c, item_kind kind, uint64_t deadline)
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

/* An item that could not begin before its deadline. */
static void expire(server *s, item *it, bool leased)
{
    client *c = it->c;
    if (it->kind == IT_FRAME) {
        s->n_expired++;
        lscd_verdict(s, c, it->job.cmd, leased ? LSC_EBUSY : LSC_ETIMEOUT);
    } else if (it->kind == IT_LEASE && c != NULL) {
        lscd_lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
    } else {
        lscd_release(s, c);
    }
    lscd_q_remove(s, it);
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
                lscd_verdict(s, c, it->job.cmd, LSC_EBUSY);
                lscd_q_remove(s, it);
            } else if (c != NULL) {
                c->walk = s->walk;
            }
            continue;
        }
        switch (it->kind) {
        case IT_RELEASE: {
            bool had = s->holder == c;
            lscd_release(s, c);
            lscd_q_remove(s, it);
            if (had) {
                return true;
            }
            break;
        }
        case IT_LEASE: /* (c is never NULL: a client's leases leave with it) */
            if (c == NULL || !lscd_can_lease(c, now)) {
                lscd_lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
                lscd_q_remove(s, it);
                break;
            }
            if (frame_waits) {
                c->walk = s->walk;
                break;
            }
            s->holder = c;
            s->lease_until = now + it->lease_ms;
            lscd_lease_event(s, c, LSC_LSCD_LEASE_GRANTED, it->lease_ms);
            if (s->cfg->verbose) {
                lscd_log("client %llu (pid %ld): lease for %lu ms", (unsigned long long)c->id,
                         c->pid, (unsigned long)it->lease_ms);
            }
            lscd_q_remove(s, it);
            return true;
        case IT_HALT:
            if (!s->present) {
                lscd_halted(s, LSC_ENODEV, "the controller is gone");
                lscd_q_remove(s, it);
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
            lscd_q_remove(s, it);
            break;
        default: /* IT_FRAME */
            if (!s->present) {
                s->n_failed++;
                lscd_verdict(s, c, it->job.cmd, LSC_ENODEV);
                lscd_q_remove(s, it);
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
            lscd_q_remove(s, it);
            break;
        }
    }
    return false;
}

void lscd_schedule(server *s)
{
    uint64_t now = lscd_now_ms();
    if (s->holder != NULL && now >= s->lease_until) {
        lscd_end_lease(s, LSC_LSCD_LEASE_EXPIRED);
    } else if (s->holder != NULL && !lscd_can_lease(s->holder, now)) {
        if (s->cfg->verbose) {
            lscd_log("client %llu (pid %ld) has not read for %u ms", (unsigned long long)s->holder->id,
                     s->holder->pid, LSCD_LEASE_BLOCKED_MS);
        }
        lscd_end_lease(s, LSC_LSCD_LEASE_EXPIRED);
    }
    while (walk_once(s, now)) {
    }
}

/* ms until the next deadline (a queued item's, the lease's), or -1. */
int lscd_next_timer(const server *s)
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
