/* Fuzz harness for lscd's decoding of what a client sends (daemon/lscd_wire.c)
 * and the control frames it answers with (daemon/lscd_wire.c, lsc_lscd_encode_ctl).
 *
 * Input: byte 0 chooses how the rest is cut into the chunks lscd's reads
 * would bring (its low 6 bits + 1 is the largest chunk; 0x40 set: chunk
 * sizes vary with the data); the rest is a client's byte stream.
 *
 * Checked on every input:
 *  - every call consumes 1..n bytes (never 0, never more than it was given),
 *    so a read loop always ends; every byte is consumed once;
 *  - it finds exactly the frames lsc_parser_feed finds byte by byte, in the
 *    same order (control frames and controller frames alike);
 *  - a controller frame is never lscd's own command, carries at most 253
 *    bytes, and its job is consistent with it: BATTERY is a 15 without
 *    parameters, READ/OFFSETS a 21/23 whose ids are its parameters (1..84,
 *    distinct), everything else is SEND;
 *  - a control request has a known op with exactly its arguments, within
 *    their ranges; a refused one says why;
 *  - every answer lscd would give (an ERROR with the reason, a STATUS line of
 *    any length) encodes as one whole frame that parses back to itself. */
#include <string.h>

#include "fuzz.h"
#include "lscd_wire.h"

static void check_answer(uint8_t op, const char *text)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lscd_encode_ctl_text(frame, sizeof frame, LSC_LSCD_EV_ERROR, &op, 1, text);
    FUZZ_CHECK(len >= 6 && (size_t)len <= LSC_FRAME_MAX);
    FUZZ_CHECK(frame[2] != 0x55u && frame[2] == (uint8_t)(len - 2));
    lsc_parser p;
    uint8_t buf[LSC_FRAME_MAX];
    FUZZ_CHECK(lsc_parser_init(&p, buf, sizeof buf) == 0);
    lsc_frame f;
    int r = 0;
    size_t used = lsc_parser_feed_buf(&p, frame, (size_t)len, &f, &r);
    FUZZ_CHECK(used == (size_t)len && r == 1);
    FUZZ_CHECK(f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_ERROR && f.params[1] == op);
}

/* The bytes as text (NULs replaced), cut to fit out[cap]. */
static void as_text(const uint8_t *p, size_t n, char *out, size_t cap)
{
    size_t k = 0;
    while (k < n && k + 1u < cap) {
        uint8_t b = p[k] == 0u ? (uint8_t)'x' : p[k];
        out[k] = (char)b;
        k++;
    }
    out[k] = '\0';
}

static void check_job(const lscd_job *j)
{
    FUZZ_CHECK(j->cmd != LSC_LSCD_CMD);
    switch (j->kind) {
    case LSCD_JOB_BATTERY:
        FUZZ_CHECK(j->cmd == LSC_CMD_BATTERY && j->nparams == 0u);
        break;
    case LSCD_JOB_READ:
    case LSCD_JOB_OFFSETS:
        FUZZ_CHECK(j->cmd == (j->kind == LSCD_JOB_READ ? LSC_CMD_POS_READ : LSC_CMD_OFFSET_READ));
        FUZZ_CHECK(j->nids >= 1u && j->nids <= LSC_READ_MAX && j->nids == j->params[0]);
        FUZZ_CHECK(j->nparams == j->nids + 1u);
        for (size_t i = 0; i < j->nids; i++) {
            FUZZ_CHECK(j->ids[i] == j->params[1 + i]);
            for (size_t k = 0; k < i; k++) {
                FUZZ_CHECK(j->ids[k] != j->ids[i]);
            }
        }
        break;
    default:
        FUZZ_CHECK(j->kind == LSCD_JOB_SEND && j->nids == 0u);
        break;
    }
}

static void check_control(const lscd_in *in)
{
    switch (in->op) {
    case LSC_LSCD_OP_SUBSCRIBE:
        FUZZ_CHECK(in->a <= 1u);
        break;
    case LSC_LSCD_OP_MODE:
        FUZZ_CHECK((in->a & ~(uint32_t)(LSC_LSCD_MODE_ACK | LSC_LSCD_MODE_REFUSE)) == 0u);
        break;
    case LSC_LSCD_OP_TIMEOUT:
    case LSC_LSCD_OP_LEASE:
    case LSC_LSCD_OP_RELEASE:
    case LSC_LSCD_OP_STATUS:
    case LSC_LSCD_OP_PING:
    case LSC_LSCD_OP_HALT:
        break;
    default: {
        bool known = false; /* an op the protocol does not have was accepted */
        FUZZ_CHECK(known);
        break;
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0u) {
        return 0;
    }
    /* STATUS lines of every length up to and past what a frame holds */
    char text[300];
    as_text(data + 1, size - 1u, text, sizeof text);
    check_answer(data[0], text);
    uint8_t how = data[0];
    data++;
    size--;

    /* the reference: the core parser, byte by byte */
    lsc_parser ref;
    uint8_t refbuf[LSC_FRAME_MAX];
    FUZZ_CHECK(lsc_parser_init(&ref, refbuf, sizeof refbuf) == 0);
    uint8_t want_cmd[4096];
    size_t want = 0;
    for (size_t i = 0; i < size; i++) {
        lsc_frame f;
        if (lsc_parser_feed(&ref, data[i], &f) == 1 && want < sizeof want_cmd) {
            want_cmd[want++] = f.cmd;
        }
    }

    lscd_wire w;
    lscd_wire_init(&w);
    size_t at = 0, got = 0;
    while (at < size) {
        size_t chunk = (size_t)(how & 0x3Fu) + 1u;
        if ((how & 0x40u) != 0u) {
            chunk = (size_t)(data[at] % chunk) + 1u;
        }
        if (chunk > size - at) {
            chunk = size - at;
        }
        size_t end = at + chunk;
        while (at < end) {
            lscd_in in;
            memset(&in, FUZZ_CANARY, sizeof in);
            size_t used = lscd_wire_feed(&w, data + at, end - at, &in);
            FUZZ_CHECK(used >= 1u && used <= end - at);
            at += used;
            if (in.kind == LSCD_IN_NONE) {
                FUZZ_CHECK(at == end);
                continue;
            }
            FUZZ_CHECK(got < want);
            if (in.kind == LSCD_IN_FRAME) {
                FUZZ_CHECK(in.job.cmd == want_cmd[got]);
                check_job(&in.job);
            } else if (in.kind == LSCD_IN_CONTROL) {
                FUZZ_CHECK(want_cmd[got] == LSC_LSCD_CMD);
                check_control(&in);
            } else {
                FUZZ_CHECK(in.kind == LSCD_IN_BAD_CONTROL && want_cmd[got] == LSC_LSCD_CMD);
                FUZZ_CHECK(in.why != NULL && in.why[0] != '\0');
                check_answer(in.op, in.why);
            }
            got++;
        }
    }
    FUZZ_CHECK(at == size);
    FUZZ_CHECK(got == want || want == sizeof want_cmd);
    FUZZ_CHECK(w.parser.frames == ref.frames && w.parser.discarded == ref.discarded);

    return 0;
}
