/* Fuzz harness for the client's reply handling (include/lsc/client.h) over a
 * scripted lsc_io with a fake clock.
 *
 * Input: byte 0 = L; bytes 1..L are the calls to make (and what each write
 * returns); the rest is what the "controller" does each time the client
 * reads: a chunk of bytes, silence, an error, an impossible count, or a
 * wake-up with nothing. When the script runs out, the line is silent.
 *
 * Checked on every input:
 *  - every write is one whole frame (55 55 LEN CMD ..., LEN = n - 2), the
 *    same bytes the trace callback announced just before;
 *  - no call reads for longer than its timeout (plus the last chunk's delay)
 *    or makes more reads than the script can explain (no hang);
 *  - results are in the documented set; an error from the transport comes
 *    back unchanged; an impossible count gives LSC_EIO;
 *  - outputs are written only on success (canaries), and a successful reply
 *    was really on the line (its bytes are in what the script delivered);
 *  - every notification is a 6, 7 or 8; the client's counter matches the
 *    callback's count; every traced received frame is well formed.
 */
#include <stdbool.h>
#include <string.h>

#include "fuzz.h"
#include "fuzz_line.h"
#include "lsc/client.h"


typedef struct script {
    fuzz_cursor ops;          /* the calls, and the writes' results */
    fuzz_line line;           /* the controller's side, and its clock */
    uint8_t traced[LSC_FRAME_MAX];
    size_t ntraced;      /* the last TX frame the trace callback announced */
    uint32_t notes;      /* notifications the callback received */
} script;

static bool is_frame(const uint8_t *f, size_t n)
{
    return n >= LSC_FRAME_MIN && n <= LSC_FRAME_MAX && f[0] == LSC_HEADER_BYTE &&
           f[1] == LSC_HEADER_BYTE && f[2] == n - 2u;
}

static int io_write(void *ctx, const uint8_t *data, size_t n)
{
    script *s = ctx;
    FUZZ_CHECK(data != NULL && is_frame(data, n));
    FUZZ_CHECK(n == s->ntraced && memcmp(data, s->traced, n) == 0);
    FUZZ_CHECK(data[3] != LSC_CMD_GROUP_COMPLETE); /* erases groups on an xArm */
    uint8_t w = fuzz_next(&s->ops);
    switch (w) {
    case 0xFF: s->line.impossible = true; return (int)n + 1;
    case 0xFE: s->line.impossible = true; return (int)n - 1; /* a short write passed off as done */
    case 0xFD: s->line.io_error = LSC_EIO; return LSC_EIO;
    case 0xFC: s->line.io_error = LSC_ENODEV; return LSC_ENODEV;
    default: return (int)n;
    }
}

static int io_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    script *s = ctx;
    /* more reads than the script: a hang */
    FUZZ_CHECK(s->line.reads < s->line.in.size + 64u);
    return fuzz_line_read(&s->line, buf, cap, timeout_ms);
}

static uint32_t io_now(void *ctx)
{
    return ((script *)ctx)->line.now;
}

static void on_notify(void *user, const lsc_notification *n)
{
    script *s = user;
    FUZZ_CHECK(n->cmd == LSC_CMD_GROUP_RUN || n->cmd == LSC_CMD_GROUP_STOP ||
               n->cmd == LSC_CMD_GROUP_COMPLETE);
    FUZZ_CHECK(n->cmd != LSC_CMD_GROUP_STOP || (n->group == 0 && n->times == 0));
    s->notes++;
}

static void on_trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    script *s = user;
    FUZZ_CHECK(is_frame(frame, n));
    if (dir == LSC_TRACE_TX) {
        memcpy(s->traced, frame, n);
        s->ntraced = n;
    } else {
        FUZZ_CHECK(dir == LSC_TRACE_RX);
    }
}

/* A failed call's result: one the contract allows for a call that reads. */
static void check_error(const script *s, int r, bool reads)
{
    if (r == s->line.io_error) {
        return;
    }
    if (r == LSC_EIO && s->line.impossible) {
        return;
    }
    FUZZ_CHECK(reads && (r == LSC_ETIMEOUT || r == LSC_EREPLY));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static script s; /* 8 KiB: off the stack */
    memset(&s, 0, sizeof s);
    fuzz_line_split(&s.line, &s.ops, data, size);

    lsc_client c;
    lsc_io io = {&s, io_write, io_read, io_now};
    FUZZ_CHECK(lsc_client_init(&c, &io) == 0);
    lsc_client_set_notify(&c, on_notify, &s);
    lsc_client_set_trace(&c, on_trace, &s);

    while (s.ops.at < s.ops.size) {
        uint8_t op = fuzz_next(&s.ops) % 8u;
        uint32_t timeout = (uint32_t)fuzz_next(&s.ops) * 4u;
        uint32_t start = s.line.now;
        uint32_t before = s.notes;
        s.line.reads = 0;
        s.line.io_error = 0;
        s.line.impossible = false;
        int r;
        switch (op) {
        case 0: {
            uint16_t mv = 0xA5A5;
            r = lsc_client_get_battery(&c, &mv, timeout);
            if (r == 0) {
                uint8_t reply[6] = {0x55, 0x55, 0x04, 0x0F, (uint8_t)mv, (uint8_t)(mv >> 8)};
                FUZZ_CHECK(fuzz_line_delivered(&s.line, reply, sizeof reply));
            } else {
                FUZZ_CHECK(mv == 0xA5A5);
                check_error(&s, r, true);
            }
            break;
        }
        case 1: {
            uint8_t ids[LSC_READ_MAX + 2];
            lsc_servo out[LSC_READ_MAX + 2];
            size_t n = fuzz_next(&s.ops) % (LSC_READ_MAX + 2u);
            for (size_t i = 0; i < n; i++) {
                ids[i] = fuzz_next(&s.ops);
            }
            memset(out, FUZZ_CANARY, sizeof out);
            r = lsc_client_read_positions(&c, ids, n, out, timeout);
            if (r >= 0) {
                FUZZ_CHECK((size_t)r == n);
                for (size_t i = 0; i < n; i++) {
                    FUZZ_CHECK(out[i].id == ids[i]);
                }
                FUZZ_CHECK(fuzz_all_canary(&out[n], sizeof out - n * sizeof out[0]));
            } else {
                FUZZ_CHECK(fuzz_all_canary(out, sizeof out));
                if (r != LSC_EINVAL) {
                    check_error(&s, r, true);
                }
            }
            break;
        }
        case 2:
            r = lsc_client_poll(&c, timeout);
            if (r >= 0) {
                FUZZ_CHECK((uint32_t)r == s.notes - before);
            } else {
                check_error(&s, r, false);
            }
            break;
        case 3: {
            lsc_notification n;
            memset(&n, FUZZ_CANARY, sizeof n);
            r = lsc_client_wait_group(&c, timeout, &n);
            if (r == 0) {
                FUZZ_CHECK(n.cmd == LSC_CMD_GROUP_STOP || n.cmd == LSC_CMD_GROUP_COMPLETE);
                FUZZ_CHECK(s.notes > before);
            } else {
                FUZZ_CHECK(r == LSC_ETIMEOUT || r == s.line.io_error || (r == LSC_EIO && s.line.impossible));
            }
            break;
        }
        case 4: {
            uint8_t cmd = fuzz_next(&s.ops), reply_cmd = fuzz_next(&s.ops);
            size_t n = fuzz_next(&s.ops) % 8u, cap = fuzz_next(&s.ops) % 64u;
            uint8_t params[8], reply[64];
            for (size_t i = 0; i < n; i++) {
                params[i] = fuzz_next(&s.ops);
            }
            memset(reply, FUZZ_CANARY, sizeof reply);
            r = lsc_client_request_raw(&c, cmd, params, n, reply_cmd, reply, cap, timeout);
            if (r >= 0) {
                FUZZ_CHECK((size_t)r <= cap && fuzz_all_canary(&reply[r], sizeof reply - (size_t)r));
                FUZZ_CHECK(reply_cmd < 6 || reply_cmd > 8);
            } else {
                FUZZ_CHECK(fuzz_all_canary(reply, sizeof reply));
                if (r != LSC_EINVAL && r != LSC_ENOSPC) {
                    check_error(&s, r, true);
                }
                FUZZ_CHECK(r != LSC_EINVAL || cmd == LSC_CMD_GROUP_COMPLETE ||
                           (reply_cmd >= 6 && reply_cmd <= 8));
            }
            break;
        }
        case 5: {
            uint8_t cmd = fuzz_next(&s.ops);
            size_t n = fuzz_next(&s.ops) % 8u;
            uint8_t params[8];
            for (size_t i = 0; i < n; i++) {
                params[i] = fuzz_next(&s.ops);
            }
            r = lsc_client_send_raw(&c, cmd, params, n);
            if (r < 0 && r != LSC_EINVAL) {
                check_error(&s, r, false);
            }
            FUZZ_CHECK(r != LSC_EINVAL || cmd == LSC_CMD_GROUP_COMPLETE);
            FUZZ_CHECK(s.line.reads == 0);
            break;
        }
        case 6: {
            lsc_servo sv[4];
            size_t n = fuzz_next(&s.ops) % 5u;
            for (size_t i = 0; i < n; i++) {
                sv[i].id = fuzz_next(&s.ops);
                sv[i].position = (uint16_t)(fuzz_next(&s.ops) * 10u);
            }
            r = lsc_client_move(&c, (uint16_t)(timeout * 4u), sv, n);
            if (r < 0 && r != LSC_EINVAL) {
                check_error(&s, r, false);
            }
            FUZZ_CHECK(s.line.reads == 0);
            break;
        }
        default:
            lsc_client_set_gap(&c, timeout);
            r = 0;
            break;
        }
        /* No call waits past its timeout (a chunk may arrive up to 2 ms late). */
        FUZZ_CHECK(s.line.now - start <= timeout + 2u);
        FUZZ_CHECK(c.notifications == s.notes);
        (void)r;
    }
    return 0;
}
