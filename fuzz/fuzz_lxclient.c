/* Fuzz harness for the bus client's reply handling (include/lsc/lxclient.h)
 * over a scripted lsc_io with a fake clock.
 *
 * Input: byte 0 = L; bytes 1..L are the calls to make (each: which, a
 * timeout, an id, what each write returns); the rest is what the bus does
 * each time the client reads: a chunk of bytes, silence, an error, an
 * impossible count, or a wake-up with nothing. When the script runs out, the
 * line is silent.
 *
 * Checked on every input:
 *  - every write is one whole good frame of the bus-servo protocol (a fresh
 *    parser returns it at its last byte), never ID_WRITE to the broadcast;
 *  - no call makes more reads than the script can explain (no hang);
 *  - results are in the documented set; a transport's error comes back
 *    unchanged, an impossible count gives LSC_EIO;
 *  - outputs are written only on success, and a position taken was really
 *    on the line (its reply's bytes are in what the script delivered);
 *  - a scan's findings hold only ids it asked.
 */
#include <stdbool.h>
#include <string.h>

#include "fuzz.h"
#include "fuzz_line.h"
#include "lsc/lxclient.h"

typedef struct script {
    fuzz_cursor ops;
    fuzz_line line;
} script;

static int io_write(void *ctx, const uint8_t *data, size_t n)
{
    script *s = ctx;
    lsc_lx_parser p;
    lsc_lx_frame f;
    FUZZ_CHECK(data != NULL && n >= LSC_LX_FRAME_MIN && n <= LSC_LX_FRAME_MAX);
    FUZZ_CHECK(lsc_lx_parser_init(&p) == 0);
    for (size_t i = 0; i < n; i++) {
        FUZZ_CHECK(lsc_lx_parser_feed(&p, data[i], &f) == (i + 1 == n ? 1 : 0));
    }
    FUZZ_CHECK(!(data[4] == LSC_LX_ID_WRITE && data[2] == LSC_LX_BROADCAST));
    uint8_t w = fuzz_next(&s->ops);
    switch (w) {
    case 0xFF: s->line.impossible = true; return (int)n + 1;
    case 0xFE: s->line.impossible = true; return (int)n - 1;
    case 0xFD: s->line.io_error = LSC_EIO; return LSC_EIO;
    default: return (int)n;
    }
}

static int io_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    return fuzz_line_read(&((script *)ctx)->line, buf, cap, timeout_ms);
}

static uint32_t io_now(void *ctx)
{
    return ((script *)ctx)->line.now;
}

static void check_error(const script *s, int r)
{
    if (r == s->line.io_error || (r == LSC_EIO && s->line.impossible)) {
        return;
    }
    FUZZ_CHECK(r == LSC_ETIMEOUT || r == LSC_EREPLY || r == LSC_EINVAL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static script s; /* 8 KiB: off the stack */
    memset(&s, 0, sizeof s);
    fuzz_line_split(&s.line, &s.ops, data, size);

    lsc_lxclient c;
    lsc_io io = {&s, io_write, io_read, io_now};
    FUZZ_CHECK(lsc_lxclient_init(&c, &io) == 0);

    while (s.ops.at < s.ops.size) {
        uint8_t op = fuzz_next(&s.ops) % 6u;
        lsc_lxclient_set_timeout(&c, (uint32_t)fuzz_next(&s.ops) * 2u);
        uint8_t id = fuzz_next(&s.ops);
        size_t line_before = s.line.in.at;
        s.line.reads = 0;
        s.line.io_error = 0;
        s.line.impossible = false;
        int r;
        switch (op) {
        case 0: {
            int16_t pos = (int16_t)0x5A5A;
            r = lsc_lxclient_read_position(&c, id, &pos);
            if (r == 0) {
                uint8_t f[LSC_LX_FRAME_MAX];
                int n = lsc_lx_encode_position(f, sizeof f, id, pos);
                FUZZ_CHECK(n > 0 && fuzz_line_delivered(&s.line, f, (size_t)n));
            } else {
                FUZZ_CHECK(pos == (int16_t)0x5A5A);
                check_error(&s, r);
            }
            break;
        }
        case 1: {
            uint16_t lo = 0xA5A5, hi = 0xA5A5;
            r = lsc_lxclient_read_limits(&c, id, &lo, &hi);
            if (r == 0) {
                FUZZ_CHECK(lo < hi && hi <= LSC_LX_POSITION_MAX);
            } else {
                FUZZ_CHECK(lo == 0xA5A5 && hi == 0xA5A5);
                check_error(&s, r);
            }
            break;
        }
        case 2: {
            lsc_lx_whois who;
            r = lsc_lxclient_whois(&c, &who);
            if (r == 0) {
                FUZZ_CHECK(who.answers == 1 && !who.garbled && who.id <= LSC_LX_ID_MAX);
            } else {
                check_error(&s, r);
            }
            break;
        }
        case 3: {
            lsc_lx_scan scan;
            uint8_t ids[2] = {(uint8_t)(id % 254u), (uint8_t)((id + 1u) % 254u)};
            r = lsc_lxclient_scan(&c, ids, 2, 1u + id % 16u, &scan);
            if (r >= 0) {
                FUZZ_CHECK(r == scan.count && scan.asked == 2);
                for (unsigned i = 0; i <= LSC_LX_ID_MAX; i++) {
                    bool asked = i == ids[0] || i == ids[1];
                    FUZZ_CHECK(asked || !lsc_lx_scan_found(&scan, (uint8_t)i));
                }
            } else {
                check_error(&s, r);
            }
            break;
        }
        case 4: {
            lsc_lx_info info;
            memset(&info, FUZZ_CANARY, sizeof info);
            r = lsc_lxclient_info(&c, id, &info);
            if (r == 0) {
                FUZZ_CHECK(info.id == id && info.limit_min < info.limit_max);
            } else {
                FUZZ_CHECK(fuzz_all_canary(&info, sizeof info));
                check_error(&s, r);
            }
            break;
        }
        default: {
            lsc_lx_refusal why = LSC_LX_DONE;
            r = lsc_lxclient_change_id(&c, id, (uint8_t)(id + 1u), &why);
            if (r != 0) {
                check_error(&s, r);
                FUZZ_CHECK(r != LSC_EINVAL || why != LSC_LX_DONE);
            }
            FUZZ_CHECK(lsc_lx_refusal_str(why) != NULL);
            break;
        }
        }
        /* each request: a drain and a wait, each ended by silence or a
         * script byte; 16 requests at most (info: 12) */
        FUZZ_CHECK(s.line.reads <= (s.line.in.at - line_before) + (size_t)16u * 8u);
    }
    return 0;
}
