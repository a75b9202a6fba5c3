/* The byte-at-a-time frame parser (rules in lsc/core.h and DESIGN.md).
 *
 * buf[0..len) always holds a valid prefix of a frame. A new byte is appended
 * and checked against its position; when it makes the prefix invalid, the
 * first buffered byte is dropped and the remaining ones are checked again
 * from position 0 (the rescan). Only positions 0..4 can be rejected, so a
 * rescan never looks at more than 5 bytes and never completes a frame. */
#include "lsc/core.h"

/* The lengths a known command allows: LEN = a*N + b, where N is the first
 * parameter (a = 0: LEN = b exactly). Two shapes: request and reply. */
typedef struct lsc_shape {
    uint8_t cmd, a1, b1, a2, b2;
} lsc_shape;

static const lsc_shape shapes[] = {
    {LSC_CMD_SERVO_MOVE, 3, 5, 3, 5},  {LSC_CMD_GROUP_RUN, 0, 5, 0, 5},
    {LSC_CMD_GROUP_STOP, 0, 2, 0, 2},  {LSC_CMD_GROUP_COMPLETE, 0, 5, 0, 5},
    {LSC_CMD_GROUP_SPEED, 0, 5, 0, 5}, {LSC_CMD_BATTERY, 0, 2, 0, 4},
    {LSC_CMD_UNLOAD, 1, 3, 1, 3},      {LSC_CMD_POS_READ, 1, 3, 3, 3},
};

/* 0 if buf[0..pos] is a valid frame prefix, else why it is not. */
static int check(const uint8_t *buf, size_t pos, size_t cap)
{
    unsigned len = buf[2];
    if (pos < 2) {
        return buf[pos] == LSC_HEADER_BYTE ? 0 : LSC_ESYNC;
    }
    if (pos == 2) {
        if (len == LSC_HEADER_BYTE) {
            return LSC_ESYNC; /* one more header byte: drop the oldest one */
        }
        if (len < LSC_LEN_MIN) {
            return LSC_EFRAME;
        }
        return len + 2u > cap ? LSC_ETOOBIG : 0;
    }
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        const lsc_shape *s = &shapes[i];
        if (s->cmd != buf[3] || pos > 4) {
            continue;
        }
        if (pos == 3) { /* LEN against the command: exact, or room for one item */
            bool ok = s->a1 ? len >= s->a1 + s->b1 : (len == s->b1 || len == s->b2);
            return ok ? 0 : LSC_EFRAME;
        }
        unsigned n = buf[4];
        if (s->a1 && len != s->a1 * n + s->b1 && len != s->a2 * n + s->b2) {
            return LSC_EFRAME; /* the count byte contradicts LEN */
        }
    }
    return 0;
}

int lsc_parser_init(lsc_parser *p, uint8_t *buf, size_t cap)
{
    if (p == NULL) {
        return LSC_EINVAL;
    }
    bool usable = buf != NULL && cap >= LSC_FRAME_MIN;
    p->buf = buf;
    p->cap = usable ? cap : 0;
    p->len = 0;
    p->complete = false;
    p->frames = 0;
    p->discarded = 0;
    p->errors = 0;
    return usable ? 0 : LSC_EINVAL;
}

int lsc_parser_feed(lsc_parser *p, uint8_t byte, lsc_frame *out)
{
    if (p == NULL || out == NULL || p->cap == 0) {
        return LSC_EINVAL;
    }
    size_t len = p->complete ? 0 : p->len;
    p->complete = false;
    /* Fast path: a parameter byte that neither ends the frame nor can be rejected. */
    if (len > 4 && len + 1u < p->buf[2] + 2u) {
        p->buf[len] = byte;
        p->len = len + 1u;
        return 0;
    }
    int result = 0;
    size_t end = len; /* buf[len..end) are bytes still to check */
    p->buf[end++] = byte;
    while (len < end) {
        int why = check(p->buf, len, p->cap);
        if (why == 0) {
            len++;
            continue;
        }
        p->errors += why != LSC_ESYNC;
        result = result ? result : why;
        p->discarded++;
        end--;
        for (size_t i = 0; i < end; i++) {
            p->buf[i] = p->buf[i + 1];
        }
        len = 0;
    }
    p->len = len;
    if (len > 2 && len == p->buf[2] + 2u) {
        p->complete = true;
        p->frames++;
        out->cmd = p->buf[3];
        out->nparams = (uint8_t)(len - 4u);
        out->params = &p->buf[4];
        return 1;
    }
    return result;
}

void lsc_parser_reset(lsc_parser *p)
{
    if (p != NULL) {
        p->discarded += (uint32_t)(p->complete ? 0 : p->len);
        p->len = 0;
        p->complete = false;
    }
}
