/* The bus-servo protocol's byte-at-a-time parser (include/lsc/lx.h).
 *
 * buf[0..len) always holds a valid prefix of a frame: each byte is checked
 * against its position as it arrives (lsc_lx_reject), the last one against
 * the checksum. A byte that is refused ends the candidate; the parser then
 * keeps the longest tail of the bytes it held (the refused one included)
 * that is still a valid prefix, so a frame that began inside them is found.
 * No frame can end inside a refused candidate before its last byte (a frame
 * that began inside one ends at or after it: see docs/protocol.md), so the
 * tail is never a whole frame. A frame is at most LSC_LX_FRAME_MAX bytes:
 * the rescan costs at most that many checks of that many bytes. */
#include "lsc/lx.h"

#include "lx_internal.h"

int lsc_lx_parser_init(lsc_lx_parser *p)
{
    if (p == NULL) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < LSC_LX_FRAME_MAX; i++) {
        p->buf[i] = 0;
        p->echo[i] = 0;
    }
    p->len = 0;
    p->complete = false;
    p->echo_len = 0;
    p->frames = 0;
    p->discarded = 0;
    p->errors = 0;
    p->bad_checksums = 0;
    p->echoes = 0;
    return 0;
}

/* Whether the n bytes at a and b are the same. */
static bool same(const uint8_t *a, const uint8_t *b, size_t n)
{
    size_t i = 0;
    while (i < n && a[i] == b[i]) {
        i++;
    }
    return i == n;
}

int lsc_lx_parser_feed(lsc_lx_parser *p, uint8_t byte, lsc_lx_frame *out)
{
    if (p == NULL || out == NULL) {
        return LSC_EINVAL;
    }
    uint8_t *b = p->buf;
    size_t n = p->complete ? 0u : p->len;
    p->complete = false;
    b[n++] = byte;
    int r = 0;
    int why = lsc_lx_reject(b, n - 1u);
    if (why != 0) {
        /* the longest valid tail (the empty one at worst) */
        size_t s = 1;
        while (s < n && lsc_lx_check(&b[s], n - s) != 0) {
            s++;
        }
        for (size_t i = s; i < n; i++) {
            b[i - s] = b[i];
        }
        n -= s;
        p->discarded += (uint32_t)s;
        p->errors += why != LSC_ESYNC;
        p->bad_checksums += why == LSC_LX_BADSUM;
        r = why == LSC_LX_BADSUM ? LSC_EFRAME : why;
    }
    p->len = (uint8_t)n;
    if (n < LSC_LX_FRAME_MIN || n != b[3] + 3u) {
        return r;
    }
    /* a whole frame, its checksum right: the host's echo, or a frame */
    bool echo = p->echo_len == n && same(p->echo, b, n);
    p->echo_len = 0;
    if (echo) {
        p->echoes++;
        p->len = 0;
        return 0;
    }
    p->complete = true;
    p->frames++;
    out->id = b[2];
    out->cmd = b[4];
    out->nparams = (uint8_t)(n - 6u);
    out->reply = b[3] != lsc_lx_len(b[4], false);
    out->params = &b[5];
    return 1;
}

int lsc_lx_parser_expect_echo(lsc_lx_parser *p, const uint8_t *frame, size_t n)
{
    if (p == NULL || frame == NULL || n < LSC_LX_FRAME_MIN || n > LSC_LX_FRAME_MAX ||
        n != frame[3] + 3u || lsc_lx_check(frame, n) != 0) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        p->echo[i] = frame[i];
    }
    p->echo_len = (uint8_t)n;
    return 0;
}

void lsc_lx_parser_reset(lsc_lx_parser *p)
{
    if (p != NULL) {
        if (!p->complete) {
            p->discarded += p->len;
        }
        p->len = 0;
        p->complete = false;
        p->echo_len = 0;
    }
}
