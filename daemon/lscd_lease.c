/* lscd: the lease (one client's exclusive use of the controller for a
 * while) and the halt, which outranks it (docs/lscd-protocol.md). */
#include <stdlib.h>

#include "lscd_server.h"

void lscd_end_lease(server *s, uint8_t state)
{
    client *c = s->holder;
    s->holder = NULL;
    if (c == NULL) {
        return;
    }
    if (state != 0u) {
        lscd_lease_event(s, c, state, 0);
    }
    if (s->cfg->verbose) {
        lscd_log("client %llu (pid %ld): lease ended (%s)", (unsigned long long)c->id, c->pid,
                 state == LSC_LSCD_LEASE_EXPIRED    ? "its time ran out"
                 : state == LSC_LSCD_LEASE_RELEASED ? "released"
                 : state == LSC_LSCD_LEASE_HALTED   ? "a halt"
                                                    : "the client left or stopped sending");
    }
}

void lscd_release(server *s, client *c)
{
    if (c != NULL && s->holder == c) {
        lscd_end_lease(s, LSC_LSCD_LEASE_RELEASED);
    } else if (c != NULL) {
        lscd_lease_event(s, c, LSC_LSCD_LEASE_NONE, 0);
    }
}

/* A halt is done (rc, lscd's message text): every client is told. */
void lscd_halted(server *s, int rc, const char *text)
{
    uint8_t result = (uint8_t)(int8_t)rc;
    lscd_log("halt done: %s", rc == 0 ? "every servo holds where it was" : text);
    for (client *c = s->clients; c != NULL; c = c->next) {
        lscd_put_text(s, c, LSC_LSCD_EV_HALTED, &result, 1, text);
    }
}

/* OP_HALT from c: the lease ends (its holder is told), every frame waiting
 * for the controller is dropped (LSC_EBUSY), and the halt goes first, ahead
 * of what comes after it, whoever holds a lease (docs/lscd-protocol.md). */
void lscd_halt_request(server *s, client *c)
{
    lscd_log("client %llu (pid %ld): halt", (unsigned long long)c->id, c->pid);
    lscd_end_lease(s, LSC_LSCD_LEASE_HALTED);
    if (s->busy) { /* the frame under way stops waiting for its reply */
        lscd_dev_interrupt(s->dv);
    }
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next;
        if (it->kind == IT_FRAME) {
            s->n_refused++;
            lscd_verdict(s, it->c, it->job.cmd, LSC_EBUSY);
            lscd_q_remove(s, it);
        }
    }
    item *it = lscd_new_item(s, c, IT_HALT, UINT64_MAX);
    if (it == NULL) {
        lscd_halted(s, LSC_ENOSPC, "out of memory");
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
