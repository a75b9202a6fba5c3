/* The byte-at-a-time frame parser (rules in lsc/core.h and docs/parser.md).
 *
 * buf[0..len) always holds a valid prefix of a frame, and each byte is checked
 * against its position as it arrives. Only positions 0..4 (header, LEN,
 * command, count) can reject a byte; later ones are stored unchecked.
 *
 * The rescan after a rejection needs no loop. Say the byte b at position k is
 * rejected, buf[0..k) being valid. A frame that began inside buf[1..k] and
 * survives up to b must start with 0x55 0x55, or be b = 0x55 alone. Starting at
 * 1 needs buf[1] = buf[2] = 0x55: that is k = 2 and b = 0x55 (a LEN of 0x55,
 * one more header byte). Starting at 2 needs LEN = 0x55, which was rejected
 * before; at 3, a command 0x55, which is unknown and never rejected. So the
 * rescan keeps 55 55 if k = 2 and b = 0x55, else just 55 if b = 0x55, else
 * nothing; and since buf[0] (and for k = 2 buf[1]) already holds 0x55, keeping
 * means only setting len. */
#include "lsc/core.h"

#include "internal.h"

#include <string.h>

/* The lengths a known command allows, indexed by command - 3 (the lowest
 * known one): lo << 4 | w, plus ALT when a second shape (lo + 2, 3*w) exists
 * (the replies of 15 and 21). A shape is a frame of LEN lo with one item of w
 * bytes, and w more bytes per extra item: LEN - lo = w*(N - 1) for the count
 * byte N. w = 0: LEN = lo. */
#define ALT 0x04u
#define SHAPE(lo, w) ((lo) << 4 | (w))
#define AT(cmd) [(cmd) - LSC_CMD_SERVO_MOVE]
static const uint8_t shapes[LSC_CMD_POS_READ + 1 - LSC_CMD_SERVO_MOVE] LSC_ROM = {
    AT(LSC_CMD_SERVO_MOVE) = SHAPE(8, 3),     /* 3*N + 5 */
    AT(LSC_CMD_GROUP_RUN) = SHAPE(5, 0),      AT(LSC_CMD_GROUP_STOP) = SHAPE(2, 0),
    AT(LSC_CMD_GROUP_COMPLETE) = SHAPE(5, 0), AT(LSC_CMD_GROUP_SPEED) = SHAPE(5, 0),
    AT(LSC_CMD_BATTERY) = SHAPE(2, 0) | ALT,  /* 2, or 4 */
    AT(LSC_CMD_UNLOAD) = SHAPE(4, 1),         /* N + 3 */
    AT(LSC_CMD_POS_READ) = SHAPE(4, 1) | ALT, /* N + 3, or 3*N + 3 */
};

#if LSC_FAST
/* 0 if byte b may follow the valid prefix buf[0..pos) (pos <= 4: no rule
 * rejects a later byte), else why not. (The compact path has its own
 * reject, below: the same rules in less code.) */
LSC_REJECT static int reject(const uint8_t *buf, lsc_small pos, lsc_small b, size_t cap)
{
    if (pos < 2) {
        return b == LSC_HEADER_BYTE ? 0 : LSC_ESYNC;
    }
    if (pos == 2) {
        if (b == LSC_HEADER_BYTE) {
            return LSC_ESYNC; /* one more header byte */
        }
        if (b < LSC_LEN_MIN) {
            return LSC_EFRAME;
        }
        return b > cap - 2u ? LSC_ETOOBIG : 0; /* cap >= LSC_FRAME_MIN */
    }
    lsc_small cmd = (lsc_small)((pos == 3 ? b : buf[3]) - LSC_CMD_SERVO_MOVE);
    if (cmd >= sizeof shapes) {
        return 0; /* unknown commands: any LEN */
    }
    lsc_small e = lsc_rom_u8(&shapes[cmd]);
    if (e == 0) {
        return 0; /* nor the unknown ones between 3 and 21 */
    }
    lsc_small lo = e >> 4, w = e & 3u;
    const lsc_small n = buf[2], m = (lsc_small)(b - 1u);
    for (;;) {
        /* a list's command: LEN >= lo; else LEN = lo + w*(N - 1): for a
         * fixed LEN (w = 0) at the command and again (always true) at the
         * next byte; for a list's count N. At the command, LEN - lo <= 251
         * when LEN >= lo and wraps past 256*w when not (w = 0: LEN = lo):
         * no branch. A count of 0 never fits: on AVR m = 255 makes
         * lo + w*m at least 259; elsewhere m is the largest unsigned and
         * lo + w*m is lo - w, wrapped or less than the lo that LEN passed
         * at the command. */
        const bool fits = pos == 3 ? (unsigned)(n - lo) <= (unsigned)w << 8 : n == lo + w * m;
        if (fits) {
            return 0;
        }
        if (!(e & ALT)) {
            return LSC_EFRAME;
        }
        e = 0;
        lo = (lsc_small)(lo + 2u);
        w = (lsc_small)(w * 3u);
    }
}

#endif

int lsc_parser_init(lsc_parser *p, uint8_t *buf, size_t cap)
{
    if (p == NULL) {
        return LSC_EINVAL;
    }
    p->buf = buf;
    p->cap = 0; /* unusable until the checks below pass */
    p->len = 0;
    p->complete = false;
    p->frames = 0;
    p->discarded = 0;
    p->errors = 0;
    if (buf == NULL || cap < LSC_FRAME_MIN) {
        return LSC_EINVAL;
    }
    p->cap = cap;
    return 0;
}

/* The frame of len bytes in p's buffer buf is complete: returns it in out (1). */
static inline int finish(lsc_parser *p, const uint8_t *buf, size_t len, lsc_frame *out)
{
    p->len = len;
    p->complete = true;
    p->frames++;
    out->params = &buf[4];
    out->nparams = (uint8_t)(len - 4u);
    out->cmd = buf[3];
    return 1;
}

#if LSC_FAST
/* lsc_parser_feed but its fast path (p and out valid): a byte at positions
 * 0..4 of a frame, or the byte after a complete frame (then position 0).
 * One case per position, each checking only that position's rule; a
 * rejected byte ends in one place, which counts what it discards. Also
 * called by feed_run for a byte it rejected (p->len set, not complete). */
LSC_SLOW static int feed_slow(lsc_parser *p, uint8_t byte, lsc_frame *out)
{
    uint8_t *buf = p->buf;
    size_t len = p->len;
    size_t keep = 0;
    int why = LSC_ESYNC;
    if (p->complete) {
        p->complete = false;
        len = 0;
    }
    switch (len) {
    case 0:
        if (p->cap == 0) {
            return LSC_EINVAL; /* never initialised */
        }
        if (byte != LSC_HEADER_BYTE) {
            goto rejected;
        }
        break;
    case 1:
        if (byte != LSC_HEADER_BYTE) {
            goto rejected;
        }
        break;
    case 2:
        if (byte == LSC_HEADER_BYTE) {
            keep = 2; /* one more header byte */
            goto rejected;
        }
        why = byte < LSC_LEN_MIN ? LSC_EFRAME : byte + 2u > p->cap ? LSC_ETOOBIG : 0;
        if (why != 0) {
            goto rejected;
        }
        break;
    case 3:
        if (reject(buf, 3, byte, 0) != 0) {
            why = LSC_EFRAME; /* a command 0x55 is unknown: never rejected */
            goto rejected;
        }
        break;
    default: /* 4 */
        if (reject(buf, 4, byte, 0) != 0) {
            why = LSC_EFRAME;
            keep = byte == LSC_HEADER_BYTE; /* a count of 0x55 may begin a frame */
            goto rejected;
        }
        break;
    }
    buf[len++] = byte;
    p->len = len;
    if (len < 4 || len != buf[2] + 2u) {
        return 0;
    }
    return finish(p, buf, len, out);
rejected:
    p->discarded += (uint32_t)(len + 1u - keep);
    p->errors += why != LSC_ESYNC;
    p->len = keep;
    return why;
}
#else
/* The compact path's rules (those of the fast path's reject, in less
 * code): 0 if the byte at buf[pos] (pos <= 4: no rule rejects a later byte)
 * may follow the valid prefix buf[0..pos), else why not. A list's command
 * needs LEN >= lo. Any other command, and a count N, need LEN - lo = t for
 * t = w*(N - 1) (at the command w = 0: t = 0), or 3*t + 2: the second
 * shape, (lo + 2, 3*w). Where t can be more than 2 (a list's count), LEN
 * passed LEN >= lo at the command, so LEN - lo is exact; where it cannot,
 * a LEN below lo makes LEN - lo wrap to 250 or more. t is exact too (16
 * bits on AVR hold 3*(3*255) + 2), and a count of 0 makes it 255*w (on
 * AVR; -w, wrapped, elsewhere), never LEN - lo. The codes as int_fast8_t:
 * one register on AVR, where an int takes two for each code and compare
 * (VendorParityRead: 30 B). */
LSC_REJECT static int_fast8_t reject(const uint8_t *buf, lsc_small pos, size_t cap)
{
    const lsc_small b = buf[pos];
    if (pos < 2) {
        return b == LSC_HEADER_BYTE ? 0 : LSC_ESYNC;
    }
    const lsc_small n = buf[2];
    if (pos == 2) {
        if (n == LSC_HEADER_BYTE) {
            return LSC_ESYNC; /* one more header byte */
        }
        if (n < LSC_LEN_MIN) {
            return LSC_EFRAME;
        }
        return n > cap - 2u ? LSC_ETOOBIG : 0; /* cap >= LSC_FRAME_MIN */
    }
    const lsc_small cmd = (lsc_small)(buf[3] - LSC_CMD_SERVO_MOVE);
    if (cmd >= sizeof shapes) {
        return 0; /* unknown commands: any LEN */
    }
    lsc_small e = lsc_rom_u8(&shapes[cmd]);
    if (e == 0) {
        return 0; /* nor the unknown ones between 3 and 21 */
    }
    const lsc_small lo = e >> 4, w = e & 3u;
    if (w != 0 && pos == 3) {
        return n >= lo ? 0 : LSC_EFRAME;
    }
    const lsc_small d = (lsc_small)(n - lo);
    unsigned t = (unsigned)w * (lsc_small)(b - 1u);
    for (;;) {
        if (d == t) {
            return 0;
        }
        if (!(e & ALT)) {
            return LSC_EFRAME;
        }
        e = 0;
        t = 3u * t + 2u;
    }
}

/* STEP(name, T) defines name: one byte into p (p and out valid, p
 * initialised), lsc_parser_feed's result, the frame's length held in a T
 * (which must hold p->cap). The byte goes to buf[len] before the rules
 * are checked (len < cap: below 3, cap >= 4; from 3 on, LEN is held and
 * len < LEN + 2 <= cap), so that reject reads it, LEN and the command from
 * the buffer alike; a byte rejected stays there, past the bytes kept. */
#define STEP(name, T)                                                                   \
    static inline int name(lsc_parser *p, uint8_t byte, lsc_frame *out)                 \
    {                                                                                   \
        uint8_t *buf = p->buf;                                                          \
        T len = (T)(p->len & ((size_t)p->complete - 1u)); /* 0 after a frame */         \
        p->complete = false;                                                            \
        buf[len] = byte;                                                                \
        const lsc_small pos = (lsc_small)len; /* when len <= 4 */                       \
        int why = len > 4 ? 0 : reject(buf, pos, p->cap);                               \
        if (why != 0) {                                                                 \
            /* a rejected 0x55 is a LEN (len 2: keep 55 55) or a count (4: keep 55) */  \
            lsc_small keep = byte == LSC_HEADER_BYTE ? (lsc_small)(3u - pos / 2u) : 0u; \
            p->discarded += (uint32_t)(len + 1u - keep);                                \
            p->errors += (uint32_t)(why - LSC_ESYNC) >> 31; /* below LSC_ESYNC */       \
            p->len = keep;                                                              \
            return why;                                                                 \
        }                                                                               \
        len++;                                                                          \
        p->len = len;                                                                   \
        /* the end: len - 2 = LEN (len <= LEN + 2 <= 257: a byte holds len - 2) */      \
        if (len < 4 || (lsc_small)(len - 2u) != buf[2]) {                               \
            return 0;                                                                   \
        }                                                                               \
        return finish(p, buf, len, out);                                                \
    }

#if defined(__AVR__) && defined(__GNUC__)
/* Where the capacity is a constant under 256 (a sketch's parser, its feed
 * inlined into the sketch), the length fits a byte, one register on AVR:
 * 8-bit arithmetic for it (examples/arduino/VendorParityRead 4 to 12 B
 * less, as the code around it is laid out). */
STEP(step_u8, uint8_t)
STEP(step_any, size_t)
static int step(lsc_parser *p, uint8_t byte, lsc_frame *out)
{
    if (__builtin_constant_p(p->cap) && p->cap < 256) {
        return step_u8(p, byte, out);
    }
    return step_any(p, byte, out);
}
#else
STEP(step, size_t)
#endif

static int feed_slow(lsc_parser *p, uint8_t byte, lsc_frame *out)
{
    return p->cap == 0 ? LSC_EINVAL : step(p, byte, out);
}
#endif

int lsc_parser_feed(lsc_parser *p, uint8_t byte, lsc_frame *out)
{
    if (p == NULL || out == NULL) {
        return LSC_EINVAL;
    }
#if LSC_FAST
    /* Fast path: a parameter byte, which no rule can reject (len > 4; never
     * after a complete frame, whose len is LEN + 2), the frame's last one
     * included. */
    size_t len = p->len;
    if (len > 4) {
        uint8_t *buf = p->buf;
        size_t end = buf[2]; /* the last byte's position, less one */
        if (len <= end) {
            buf[len] = byte;
            p->len = len + 1u;
            return 0;
        }
        if (len == end + 1u) {
            buf[len] = byte;
            return finish(p, buf, len + 1u, out);
        }
    }
#endif
    return feed_slow(p, byte, out);
}

#if LSC_FAST
/* The bulk path for speed (p, out, result valid; n > 0; p initialised): the
 * transitions of step, with the state in locals and one case per position
 * of the header (reject, inlined, then checks only that position's rule).
 * A rejected byte goes to step itself, which rejects it again and does the
 * bookkeeping. Parameter bytes are copied in one run. Out of line, so that
 * lsc_parser_feed_buf's path for a whole frame needs no stack frame. */
LSC_SLOW static size_t feed_run(lsc_parser *p, const uint8_t *data, size_t n, lsc_frame *out,
                                int *result)
{
    uint8_t *buf = p->buf;
    const size_t cap = p->cap;
    size_t len = p->complete ? 0 : p->len;
    const uint8_t *at = data, *end = data + n;
    p->complete = false;
    do {
        uint8_t b = *at;
        int why;
        switch (len) {
        case 0: why = reject(buf, 0, b, cap); break;
        case 1: why = reject(buf, 1, b, cap); break;
        case 2: why = reject(buf, 2, b, cap); break;
        case 3: why = reject(buf, 3, b, cap); break;
        case 4: why = reject(buf, 4, b, cap); break;
        default: {
            /* parameter bytes, up to the frame's last */
            size_t k = buf[2] + 2u - len, left = (size_t)(end - at);
            k = k < left ? k : left;
            for (const uint8_t *stop = at + k; at != stop;) {
                buf[len++] = *at++;
            }
            why = 1; /* stored already */
        }
        }
        if (why < 0) {
            p->len = len;
            *result = feed_slow(p, b, out);
            return (size_t)(at + 1 - data);
        }
        if (why == 0) {
            buf[len++] = b;
            at++;
        }
        if (len >= 4 && len == buf[2] + 2u) {
            *result = finish(p, buf, len, out);
            return (size_t)(at - data);
        }
    } while (at != end);
    p->len = len;
    *result = 0;
    return n;
}
#endif

#if LSC_FAST
/* True if a whole frame of LEN len, command cmd and (len > 2) count byte n
 * passes every check of reject at positions 3 and 4: for a shape (lo, w),
 * LEN - lo = w*(n - 1). n - 1 is taken mod 256, so that a count of 0 can
 * never match (w*255 is more than LEN - lo can be, unwrapped or wrapped); a
 * shape that fits at position 4 fits at position 3 too. */
static inline bool shape_fits(unsigned cmd, unsigned len, unsigned n)
{
    unsigned c = cmd - LSC_CMD_SERVO_MOVE;
    unsigned e = c < sizeof shapes ? lsc_rom_u8(&shapes[c]) : 0u;
    unsigned lo = e >> 4, w = e & 3u, m = (n - 1u) & 0xFFu;
    return e == 0 || len - lo == w * m || ((e & ALT) != 0 && len - lo - 2u == 3u * w * m);
}

/* lsc_parser_feed_buf but its two fast paths. */
LSC_SLOW static size_t feed_buf_slow(lsc_parser *p, const uint8_t *data, size_t n,
                                     lsc_frame *out, int *result)
{
    if (result == NULL || (data == NULL && n > 0)) {
        if (result != NULL) {
            *result = LSC_EINVAL;
        }
        return n; /* nothing to read, or nowhere to say what happened */
    }
    if (n > 0 && p != NULL && out != NULL && p->cap > 0) {
        return feed_run(p, data, n, out, result);
    }
    /* one byte with LSC_EINVAL, or n = 0 */
    *result = n > 0 ? lsc_parser_feed(p, data[0], out) : 0;
    return n > 0;
}

/* lsc_parser_feed_buf's result for the whole frame of total bytes at data
 * (its header and LEN checked; p initialised): its command and count checked
 * in full, then copied (one call of memcpy), or feed_run. */
LSC_SLOW static size_t feed_frame_checked(lsc_parser *p, const uint8_t *data, size_t n,
                                          lsc_frame *out, int *result)
{
    size_t total = data[2] + 2u;
    if (shape_fits(data[3], data[2], total > 4 ? data[4] : 0)) {
        memcpy(p->buf, data, total);
        *result = finish(p, p->buf, total, out);
        return total;
    }
    return feed_run(p, data, n, out, result);
}

/* For a whole frame of up to 16 bytes whose command has one fixed LEN (the
 * battery: its reply's), that LEN; 0xFF when the frame's count or its other
 * shape must be checked (feed_frame_checked); 0: an unknown command, any LEN. */
static const uint8_t fixed_len[sizeof shapes] LSC_ROM = {
    AT(LSC_CMD_SERVO_MOVE) = 0xFF,   AT(LSC_CMD_GROUP_RUN) = 5,   AT(LSC_CMD_GROUP_STOP) = 2,
    AT(LSC_CMD_GROUP_COMPLETE) = 5, AT(LSC_CMD_GROUP_SPEED) = 5, AT(LSC_CMD_BATTERY) = 4,
    AT(LSC_CMD_UNLOAD) = 0xFF,       AT(LSC_CMD_POS_READ) = 0xFF,
};

/* lsc_parser_feed_buf between frames, data[0] a header byte (p, data, out,
 * result valid; n > 0; p initialised): a whole valid frame at the start of
 * the input is checked and copied at once, anything else goes to feed_run.
 * A frame of up to 16 bytes whose command has one LEN is decided here, with
 * no call (so no stack frame); the others in feed_frame_checked. */
LSC_STEP static size_t feed_frame(lsc_parser *p, const uint8_t *data, size_t n, lsc_frame *out,
                                  int *result)
{
    if (n < 4) {
        return feed_run(p, data, n, out, result);
    }
    size_t total = data[2] + 2u;
    /* LEN is used as total alone from here: the empty asm hides where total
     * came from, so that the compiler keeps no copy of LEN in another
     * register (which costs it a stack frame) */
    __asm__("" : "+r"(total));
    if (total > n || total > p->cap || total < LSC_LEN_MIN + 2u ||
        total == LSC_HEADER_BYTE + 2u || data[1] != LSC_HEADER_BYTE) {
        return feed_run(p, data, n, out, result);
    }
    unsigned c = data[3] - LSC_CMD_SERVO_MOVE;
    unsigned want = c < sizeof fixed_len ? lsc_rom_u8(&fixed_len[c]) : 0u;
    if ((want != 0 && want + 2u != total) || total > 16) {
        return feed_frame_checked(p, data, n, out, result);
    }
    /* up to 16 bytes as two overlapping words: no call, no loop */
    uint8_t *buf = p->buf;
    if (total <= 8) {
        memcpy(buf, data, 4);
        memcpy(&buf[total - 4], &data[total - 4], 4);
    } else {
        memcpy(buf, data, 8);
        memcpy(&buf[total - 8], &data[total - 8], 8);
    }
    *result = finish(p, buf, total, out);
    return total;
}

size_t lsc_parser_feed_buf(lsc_parser *p, const uint8_t *data, size_t n, lsc_frame *out,
                           int *result)
{
    /* Between frames (the usual state when the input is a chunk of whole
     * frames with noise between them), a noise byte is decided here, and a
     * whole frame in feed_frame; both with the state in few registers. */
    if (p != NULL && (p->complete || (p->len == 0 && p->cap > 0)) && n > 0 && data != NULL &&
        out != NULL && result != NULL) { /* (complete: initialised) */
        if (data[0] != LSC_HEADER_BYTE) {
            p->complete = false;
            p->len = 0;
            p->discarded++;
            *result = LSC_ESYNC;
            return 1;
        }
        return feed_frame(p, data, n, out, result);
    }
    return feed_buf_slow(p, data, n, out, result);
}
#else
size_t lsc_parser_feed_buf(lsc_parser *p, const uint8_t *data, size_t n, lsc_frame *out,
                           int *result)
{
    /* byte by byte (the same results); nothing to read, or nowhere to say
     * what happened: n, unread */
    int r = LSC_EINVAL;
    size_t i = n;
    if (result != NULL) {
        if (data != NULL || n == 0) {
            r = 0;
            for (i = 0; i < n && r == 0;) {
                r = lsc_parser_feed(p, data[i++], out);
            }
        }
        *result = r;
    }
    return i;
}
#endif

void lsc_parser_reset(lsc_parser *p)
{
    if (p != NULL) {
        if (!p->complete) {
            p->discarded += (uint32_t)p->len;
        }
        p->len = 0;
        p->complete = false;
    }
}
