/* lscd: a client's control requests (subscribe, mode, timeout, lease,
 * release, status, halt, ping: docs/lscd-protocol.md). */
#include "lscd_server.h"

void lscd_on_control(server *s, client *c, const lscd_in *in)
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
        if ((in->b == 0u && s->holder != NULL && s->holder != c) || !lscd_can_lease(c, now)) {
            lscd_lease_event(s, c, LSC_LSCD_LEASE_BUSY, 0);
            break;
        }
        uint32_t wait = in->b > c->timeout_ms ? in->b : c->timeout_ms;
        item *it = lscd_new_item(s, c, IT_LEASE, now + wait);
        if (it != NULL) {
            it->lease_ms = ms;
        }
        break;
    }
    case LSC_LSCD_OP_RELEASE:
        (void)lscd_new_item(s, c, IT_RELEASE, UINT64_MAX);
        break;
    case LSC_LSCD_OP_STATUS:
        lscd_send_status(s, c);
        break;
    case LSC_LSCD_OP_HALT:
        lscd_halt_request(s, c);
        break;
    default: /* PING */
        lsc_lscd_put_u32(args, in->a);
        lscd_put_ctl(s, c, LSC_LSCD_EV_PONG, args, sizeof args);
        break;
    }
}
