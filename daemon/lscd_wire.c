/* lscd: what a client's bytes ask for (lscd_wire.h). */
#include "lscd_wire.h"

#include <string.h>

void lscd_wire_init(lscd_wire *w)
{
    (void)lsc_parser_init(&w->parser, w->buf, sizeof w->buf);
}

/* The exact argument length of each client op (-1: no such op). */
static int args_of(uint8_t op)
{
    switch (op) {
    case LSC_LSCD_OP_SUBSCRIBE:
    case LSC_LSCD_OP_MODE:
        return 1;
    case LSC_LSCD_OP_TIMEOUT:
    case LSC_LSCD_OP_PING:
        return 4;
    case LSC_LSCD_OP_LEASE:
        return 8;
    case LSC_LSCD_OP_RELEASE:
    case LSC_LSCD_OP_STATUS:
    case LSC_LSCD_OP_HALT:
        return 0;
    default:
        return -1;
    }
}

void lscd_wire_control(const lsc_frame *f, lscd_in *out)
{
    out->kind = LSCD_IN_BAD_CONTROL;
    out->op = 0;
    out->a = 0;
    out->b = 0;
    out->why = NULL;
    if (f->nparams == 0u) {
        out->why = "a control frame needs an op byte";
        return;
    }
    out->op = f->params[0];
    const uint8_t *a = f->params + 1;
    int want = args_of(out->op);
    if (want < 0) {
        out->why = "unknown op";
        return;
    }
    if ((size_t)f->nparams - 1u != (size_t)want) {
        out->why = "wrong length for this op";
        return;
    }
    switch (out->op) {
    case LSC_LSCD_OP_SUBSCRIBE:
        if (a[0] > 1u) {
            out->why = "SUBSCRIBE takes 0 or 1";
            return;
        }
        out->a = a[0];
        break;
    case LSC_LSCD_OP_MODE:
        if ((a[0] & (uint8_t)~(LSC_LSCD_MODE_ACK | LSC_LSCD_MODE_REFUSE)) != 0u) {
            out->why = "unknown MODE flags";
            return;
        }
        out->a = a[0];
        break;
    case LSC_LSCD_OP_TIMEOUT:
    case LSC_LSCD_OP_PING:
        out->a = lsc_lscd_get_u32(a);
        break;
    case LSC_LSCD_OP_LEASE:
        out->a = lsc_lscd_get_u32(a);
        out->b = lsc_lscd_get_u32(a + 4);
        break;
    default: /* RELEASE, STATUS: no arguments */
        break;
    }
    out->kind = LSCD_IN_CONTROL;
}

size_t lscd_wire_feed(lscd_wire *w, const uint8_t *data, size_t n, lscd_in *out)
{
    size_t used = 0;
    out->kind = LSCD_IN_NONE;
    while (used < n) {
        lsc_frame f;
        int r = 0;
        used += lsc_parser_feed_buf(&w->parser, data + used, n - used, &f, &r);
        if (r != 1) {
            continue; /* noise or a malformed frame: counted by the parser */
        }
        if (f.cmd == LSC_LSCD_CMD) {
            lscd_wire_control(&f, out);
            return used;
        }
        out->kind = LSCD_IN_FRAME;
        out->job.cmd = f.cmd;
        out->job.nparams = f.nparams;
        if (f.nparams > 0u) {
            memcpy(out->job.params, f.params, f.nparams);
        }
        out->job.kind = lscd_classify(&f, out->job.ids, &out->job.nids);
        return used;
    }
    return used;
}

/* ---- The daemon's side of the wire (docs/lscd-protocol.md) --------------------- */

int lscd_encode_ctl_text(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *prefix,
                         size_t prefix_n, const char *text)
{
    uint8_t args[LSCD_ARGS_MAX];
    size_t len = text != NULL ? strlen(text) : 0u;
    if (prefix_n > sizeof args || (prefix_n > 0u && prefix == NULL)) {
        return LSC_EINVAL;
    }
    if (len > sizeof args - prefix_n) {
        len = sizeof args - prefix_n;
    }
    if (prefix_n + len == 82u) { /* LEN would be 0x55: one byte less */
        len--;
    }
    for (size_t i = 0; i < prefix_n; i++) {
        args[i] = prefix[i];
    }
    for (size_t i = 0; i < len; i++) {
        args[prefix_n + i] = (uint8_t)text[i];
    }
    return lsc_lscd_encode_ctl(buf, cap, op, args, prefix_n + len);
}

lscd_job_kind lscd_classify(const lsc_frame *f, uint8_t *ids, size_t *nids)
{
    int n;
    *nids = 0u;
    switch (f->cmd) {
    case LSC_CMD_BATTERY:
        return lsc_decode_battery_request(f) == 0 ? LSCD_JOB_BATTERY : LSCD_JOB_SEND;
    case LSC_CMD_POS_READ:
        n = lsc_decode_pos_request(f, ids, LSC_READ_MAX);
        if (n > 0) {
            *nids = (size_t)n;
            return LSCD_JOB_READ;
        }
        return LSCD_JOB_SEND;
    case LSC_CMD_OFFSET_READ:
        n = lsc_decode_offset_request(f, ids, LSC_READ_MAX);
        if (n > 0) {
            *nids = (size_t)n;
            return LSCD_JOB_OFFSETS;
        }
        return LSCD_JOB_SEND;
    default:
        return LSCD_JOB_SEND;
    }
}

bool lscd_cmd_known(uint8_t cmd)
{
    switch (cmd) {
    case LSC_CMD_SERVO_MOVE:
    case LSC_CMD_GROUP_RUN:
    case LSC_CMD_GROUP_STOP:
    case LSC_CMD_GROUP_COMPLETE:
    case LSC_CMD_GROUP_SPEED:
    case LSC_CMD_BATTERY:
    case LSC_CMD_UNLOAD:
    case LSC_CMD_POS_READ:
    case LSC_CMD_OFFSET_READ:
    case LSC_CMD_OFFSET_ADJUST:
        return true;
    default:
        return false;
    }
}

