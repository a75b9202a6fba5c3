/* Fuzz harness for the core: the parser (byte at a time, and its bulk path
 * compared with it) and every typed decoder and encoder (include/lsc/core.h).
 * Each input is used twice:
 *
 * 1. As bytes from the wire, fed to a parser with the largest buffer and to
 *    one with a small buffer (its size taken from the input). Checked: the
 *    parser never writes outside its buffer (canaries on both sides); every
 *    byte fed is accounted for (discarded + in returned frames + pending);
 *    each returned frame is well formed and lsc_encode_frame rebuilds exactly
 *    its bytes; every typed decoder that accepts it gives values whose
 *    encoder rebuilds exactly the frame (encode(decode(frame)) == frame), and
 *    a too-small output array gives LSC_ENOSPC without writing. A second
 *    parser fed the same bytes through lsc_parser_feed_buf, in chunks of
 *    sizes taken from the input, gives the same results at the same bytes
 *    and ends in the same state.
 * 2. As a description of one message (kind, buffer size, fields). Checked:
 *    each encoder returns what an independent model of its rules predicts
 *    (length, LSC_EINVAL or LSC_ENOSPC) and writes nothing on error; an
 *    encoded frame, after noise without 0x55, parses back to one frame whose
 *    decoder returns the same fields (decode(encode(x)) == x).
 */
#include <stdbool.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/core.h"

#define GUARD 16u

static uint16_t next16(fuzz_cursor *c)
{
    uint8_t lo = fuzz_next(c);
    return (uint16_t)(lo | (fuzz_next(c) << 8));
}

static bool ids_distinct(const uint8_t *ids, size_t stride, size_t n)
{
    bool seen[256] = {false};
    for (size_t i = 0; i < n; i++) {
        if (seen[ids[i * stride]]) {
            return false;
        }
        seen[ids[i * stride]] = true;
    }
    return true;
}

/* ---- Part 1: any bytes through the parser and the decoders ------------------ */

/* Checks that the decoder of a list message refuses an array one item too
 * small with LSC_ENOSPC and leaves it untouched. */
static void check_enospc(int (*decode)(const lsc_frame *, uint8_t *, size_t), const lsc_frame *f,
                         int n)
{
    uint8_t ids[LSC_UNLOAD_MAX + 1];
    memset(ids, FUZZ_CANARY, sizeof ids);
    FUZZ_CHECK(decode(f, ids, (size_t)n - 1u) == LSC_ENOSPC);
    FUZZ_CHECK(fuzz_all_canary(ids, sizeof ids));
}

/* Every typed decoder on frame f whose wire bytes are wire[0..len): a decoder
 * that accepts must give values that encode back to exactly those bytes. */
static void check_decoders(const lsc_frame *f, const uint8_t *wire, size_t len)
{
    uint8_t out[LSC_FRAME_MAX];
    lsc_servo servos[LSC_READ_MAX + 1];
    uint8_t ids[LSC_UNLOAD_MAX + 1];
    uint16_t u16 = 0;
    uint8_t u8 = 0;
    int accepted = 0;
    int n;

    n = lsc_decode_servo_move(f, &u16, servos, LSC_MOVE_MAX);
    if (n >= 0) {
        accepted++;
        FUZZ_CHECK(n >= 1 && (size_t)n <= LSC_MOVE_MAX);
        FUZZ_CHECK(lsc_encode_servo_move(out, sizeof out, u16, servos, (size_t)n) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
        lsc_servo few[LSC_MOVE_MAX];
        memset(few, FUZZ_CANARY, sizeof few);
        uint16_t t = 0x5A5A;
        FUZZ_CHECK(lsc_decode_servo_move(f, &t, few, (size_t)n - 1u) == LSC_ENOSPC);
        FUZZ_CHECK(t == 0x5A5A && fuzz_all_canary((const uint8_t *)few, sizeof few));
    }
    if (lsc_decode_group_run(f, &u8, &u16) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_group_run(out, sizeof out, u8, u16) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    if (lsc_decode_group_stop(f) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_group_stop(out, sizeof out) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    if (lsc_decode_group_complete(f, &u8, &u16) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_group_complete(out, sizeof out, u8, u16) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    if (lsc_decode_group_speed(f, &u8, &u16) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_group_speed(out, sizeof out, u8, u16) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    if (lsc_decode_battery_request(f) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_battery_request(out, sizeof out) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    if (lsc_decode_battery_reply(f, &u16) == 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_battery_reply(out, sizeof out, u16) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    n = lsc_decode_unload(f, ids, LSC_UNLOAD_MAX);
    if (n >= 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_unload(out, sizeof out, ids, (size_t)n) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
        check_enospc(lsc_decode_unload, f, n);
    }
    n = lsc_decode_pos_request(f, ids, LSC_READ_MAX);
    if (n >= 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_pos_request(out, sizeof out, ids, (size_t)n) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
        check_enospc(lsc_decode_pos_request, f, n);
    }
    n = lsc_decode_pos_reply(f, servos, LSC_READ_MAX);
    if (n >= 0) {
        accepted++;
        FUZZ_CHECK(lsc_encode_pos_reply(out, sizeof out, servos, (size_t)n) == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
    }
    /* No frame is two messages: the request and reply of commands 15 and 21
     * differ in length for every count. */
    FUZZ_CHECK(accepted <= 1);
}

/* A frame the parser returned: its bytes, their re-encoding, a fresh parser. */
static void check_frame(const lsc_parser *p, const lsc_frame *f, const uint8_t *buf)
{
    size_t len = p->len;
    FUZZ_CHECK(p->complete && len >= LSC_FRAME_MIN && len <= p->cap);
    FUZZ_CHECK(buf[0] == LSC_HEADER_BYTE && buf[1] == LSC_HEADER_BYTE);
    FUZZ_CHECK(buf[2] != LSC_HEADER_BYTE && buf[2] == len - 2u && buf[3] == f->cmd);
    FUZZ_CHECK(f->nparams == len - 4u && f->params == &buf[4]);

    uint8_t again[LSC_FRAME_MAX];
    FUZZ_CHECK(lsc_encode_frame(again, sizeof again, f->cmd, f->params, f->nparams) == (int)len);
    FUZZ_CHECK(memcmp(again, buf, len) == 0);

    /* The same bytes alone, into a fresh parser: one frame, on the last byte. */
    uint8_t pbuf[LSC_FRAME_MAX];
    lsc_parser q;
    lsc_frame g;
    FUZZ_CHECK(lsc_parser_init(&q, pbuf, sizeof pbuf) == 0);
    for (size_t i = 0; i < len; i++) {
        FUZZ_CHECK(lsc_parser_feed(&q, again[i], &g) == (i + 1 == len ? 1 : 0));
    }
    FUZZ_CHECK(g.cmd == f->cmd && g.nparams == f->nparams);
    FUZZ_CHECK(memcmp(g.params, f->params, f->nparams) == 0);

    check_decoders(f, again, len);
}

/* Feeds data to a parser with a cap-byte buffer fenced by canaries, byte at
 * a time, and in lockstep to a second one through the bulk path, in chunks
 * whose sizes come from the data: both must give the same results at the
 * same bytes, the same frames, and end in the same state. */
static void run_stream(const uint8_t *data, size_t size, size_t cap)
{
    uint8_t mem[GUARD + LSC_FRAME_MAX + GUARD], mem2[GUARD + LSC_FRAME_MAX + GUARD];
    uint8_t *buf = &mem[GUARD], *buf2 = &mem2[GUARD];
    memset(mem, FUZZ_CANARY, sizeof mem);
    memset(mem2, FUZZ_CANARY, sizeof mem2);
    lsc_parser p, q;
    FUZZ_CHECK(lsc_parser_init(&p, buf, cap) == 0);
    FUZZ_CHECK(lsc_parser_init(&q, buf2, cap) == 0);

    uint64_t in_frames = 0;
    uint32_t frames = 0, errors = 0;
    size_t bulk_at = 0, bulk_last = 0; /* next byte for q; the last its call consumed */
    int bulk_rc = 0;
    lsc_frame fb = {0, 0, NULL};
    for (size_t i = 0; i < size; i++) {
        if (i == bulk_at) {
            size_t chunk = 1u + (size_t)data[i] * 7u % (size - i);
            size_t k = lsc_parser_feed_buf(&q, &data[i], chunk, &fb, &bulk_rc);
            FUZZ_CHECK(k >= 1 && k <= chunk && (bulk_rc != 0 || k == chunk));
            bulk_at = i + k;
            bulk_last = bulk_at - 1;
        }
        lsc_frame f;
        int r = lsc_parser_feed(&p, data[i], &f);
        FUZZ_CHECK(r == (i == bulk_last ? bulk_rc : 0));
        FUZZ_CHECK(r == 1 || r == 0 || r == LSC_ESYNC || r == LSC_EFRAME || r == LSC_ETOOBIG);
        FUZZ_CHECK(p.len <= cap && p.len <= LSC_FRAME_MAX);
        if (r == 1) {
            frames++;
            in_frames += p.len;
            check_frame(&p, &f, buf);
            FUZZ_CHECK(fb.cmd == f.cmd && fb.nparams == f.nparams);
            FUZZ_CHECK(memcmp(fb.params, f.params, f.nparams) == 0);
        } else {
            FUZZ_CHECK(!p.complete);
            if (r == LSC_EFRAME || r == LSC_ETOOBIG) {
                errors++;
            }
        }
        if (r == LSC_ETOOBIG) {
            FUZZ_CHECK(cap < LSC_FRAME_MAX);
        }
        /* Every byte fed is discarded, in a returned frame, or pending. */
        FUZZ_CHECK(p.frames == frames && p.errors >= errors);
        FUZZ_CHECK((uint64_t)p.discarded + in_frames + (p.complete ? 0 : p.len) == i + 1);
    }
    /* A byte written outside the buffer stays there: checking once is enough. */
    FUZZ_CHECK(fuzz_all_canary(mem, GUARD) && fuzz_all_canary(buf + cap, GUARD + LSC_FRAME_MAX - cap));
    FUZZ_CHECK(fuzz_all_canary(mem2, GUARD) &&
               fuzz_all_canary(buf2 + cap, GUARD + LSC_FRAME_MAX - cap));
    FUZZ_CHECK(q.len == p.len && q.complete == p.complete && q.frames == p.frames &&
               q.discarded == p.discarded && q.errors == p.errors);
    FUZZ_CHECK(memcmp(buf, buf2, p.len) == 0);
    uint32_t discarded = p.discarded;
    size_t pending = p.complete ? 0 : p.len;
    lsc_parser_reset(&p);
    FUZZ_CHECK(p.len == 0 && !p.complete && p.discarded == discarded + pending);
    FUZZ_CHECK(p.frames == frames);
}

/* ---- Part 2: one message described by the input, encoded and decoded -------- */

enum kind {
    K_FRAME, K_MOVE, K_RUN, K_STOP, K_COMPLETE, K_SPEED,
    K_BAT_REQ, K_BAT_REPLY, K_UNLOAD, K_POS_REQ, K_POS_REPLY, K_KINDS
};

/* Feeds wire[0..len) after noise without 0x55 taken from c; returns the
 * frame the parser completes on the last byte (and checks there is only that). */
static lsc_frame parse_back(fuzz_cursor *c, lsc_parser *p, const uint8_t *wire, size_t len)
{
    lsc_frame f = {0, 0, NULL};
    for (uint8_t noise = fuzz_next(c) % 8u; noise > 0; noise--) {
        uint8_t b = fuzz_next(c);
        FUZZ_CHECK(lsc_parser_feed(p, b == LSC_HEADER_BYTE ? 0 : b, &f) == LSC_ESYNC);
    }
    for (size_t i = 0; i < len; i++) {
        FUZZ_CHECK(lsc_parser_feed(p, wire[i], &f) == (i + 1 == len ? 1 : 0));
    }
    return f;
}

static void run_message(fuzz_cursor *c)
{
    uint8_t kind = (uint8_t)(fuzz_next(c) % K_KINDS);
    size_t cap = next16(c) % (LSC_FRAME_MAX + 3u);
    uint8_t cmd = fuzz_next(c), a = fuzz_next(c);
    uint16_t v = next16(c);
    size_t n = fuzz_next(c);
    lsc_servo servos[256];
    uint8_t ids[256];
    for (size_t i = 0; i < n; i++) {
        ids[i] = fuzz_next(c);
        servos[i].id = ids[i];
        servos[i].position = next16(c);
    }

    uint8_t mem[GUARD + LSC_FRAME_MAX + 3u + GUARD];
    uint8_t *buf = &mem[GUARD];
    memset(mem, FUZZ_CANARY, sizeof mem);

    /* What the encoder must do: valid arguments and the frame's length. */
    bool valid = true;
    size_t want = 0;
    int r = 0;
    switch (kind) {
    case K_FRAME:
        n = n > LSC_PARAMS_MAX + 2u ? LSC_PARAMS_MAX + 2u : n;
        valid = n <= LSC_PARAMS_MAX && n + 2u != LSC_HEADER_BYTE;
        want = n + 4u;
        r = lsc_encode_frame(buf, cap, cmd, ids, n);
        break;
    case K_MOVE:
        n %= LSC_MOVE_MAX + 3u;
        valid = n >= 1 && n <= LSC_MOVE_MAX && ids_distinct(ids, 1, n);
        want = 3u * n + 7u;
        r = lsc_encode_servo_move(buf, cap, v, servos, n);
        break;
    case K_RUN: want = 7; r = lsc_encode_group_run(buf, cap, a, v); break;
    case K_STOP: want = 4; r = lsc_encode_group_stop(buf, cap); break;
    case K_COMPLETE: want = 7; r = lsc_encode_group_complete(buf, cap, a, v); break;
    case K_SPEED: want = 7; r = lsc_encode_group_speed(buf, cap, a, v); break;
    case K_BAT_REQ: want = 4; r = lsc_encode_battery_request(buf, cap); break;
    case K_BAT_REPLY: want = 6; r = lsc_encode_battery_reply(buf, cap, v); break;
    case K_UNLOAD:
        valid = n >= 1 && n <= LSC_UNLOAD_MAX && n != 82 && ids_distinct(ids, 1, n);
        want = n + 5u;
        r = lsc_encode_unload(buf, cap, ids, n);
        break;
    case K_POS_REQ:
        n %= LSC_READ_MAX + 3u;
        valid = n >= 1 && n <= LSC_READ_MAX && n != 82 && ids_distinct(ids, 1, n);
        want = n + 5u;
        r = lsc_encode_pos_request(buf, cap, ids, n);
        break;
    default:
        n %= LSC_READ_MAX + 3u;
        valid = n >= 1 && n <= LSC_READ_MAX && ids_distinct(ids, 1, n);
        want = 3u * n + 5u;
        r = lsc_encode_pos_reply(buf, cap, servos, n);
        break;
    }
    int expect = !valid ? LSC_EINVAL : cap < want ? LSC_ENOSPC : (int)want;
    FUZZ_CHECK(r == expect);
    FUZZ_CHECK(fuzz_all_canary(mem, GUARD) && fuzz_all_canary(buf + (r > 0 ? (size_t)r : 0),
                                                    sizeof mem - GUARD - (r > 0 ? (size_t)r : 0)));
    if (r < 0) {
        return;
    }

    uint8_t pbuf[LSC_FRAME_MAX];
    lsc_parser p;
    FUZZ_CHECK(lsc_parser_init(&p, pbuf, sizeof pbuf) == 0);
    size_t len = (size_t)r;
    if (kind == K_FRAME) {
        /* Arbitrary parameters may contradict a known command: the parser
         * then refuses the frame (and may find another one inside its
         * parameters). When it discards nothing, it must return exactly
         * this frame, on its last byte. */
        lsc_frame f = {0, 0, NULL};
        int got = 0;
        for (size_t i = 0; i < len; i++) {
            got = lsc_parser_feed(&p, buf[i], &f);
        }
        if (p.discarded == 0) {
            FUZZ_CHECK(got == 1 && p.frames == 1);
            FUZZ_CHECK(f.cmd == cmd && f.nparams == n && memcmp(f.params, ids, n) == 0);
        }
        return;
    }
    lsc_frame f = parse_back(c, &p, buf, len);
    lsc_servo sv[LSC_READ_MAX + 1];
    uint8_t id2[LSC_UNLOAD_MAX + 1];
    uint16_t v2 = 0;
    uint8_t a2 = 0;
    switch (kind) {
    case K_MOVE:
        FUZZ_CHECK(lsc_decode_servo_move(&f, &v2, sv, LSC_MOVE_MAX) == (int)n && v2 == v);
        for (size_t i = 0; i < n; i++) {
            FUZZ_CHECK(sv[i].id == servos[i].id && sv[i].position == servos[i].position);
        }
        break;
    case K_RUN: FUZZ_CHECK(lsc_decode_group_run(&f, &a2, &v2) == 0 && a2 == a && v2 == v); break;
    case K_STOP: FUZZ_CHECK(lsc_decode_group_stop(&f) == 0); break;
    case K_COMPLETE:
        FUZZ_CHECK(lsc_decode_group_complete(&f, &a2, &v2) == 0 && a2 == a && v2 == v);
        break;
    case K_SPEED: FUZZ_CHECK(lsc_decode_group_speed(&f, &a2, &v2) == 0 && a2 == a && v2 == v); break;
    case K_BAT_REQ: FUZZ_CHECK(lsc_decode_battery_request(&f) == 0); break;
    case K_BAT_REPLY: FUZZ_CHECK(lsc_decode_battery_reply(&f, &v2) == 0 && v2 == v); break;
    case K_UNLOAD:
        FUZZ_CHECK(lsc_decode_unload(&f, id2, LSC_UNLOAD_MAX) == (int)n);
        FUZZ_CHECK(memcmp(id2, ids, n) == 0);
        break;
    case K_POS_REQ:
        FUZZ_CHECK(lsc_decode_pos_request(&f, id2, LSC_READ_MAX) == (int)n);
        FUZZ_CHECK(memcmp(id2, ids, n) == 0);
        break;
    default:
        FUZZ_CHECK(lsc_decode_pos_reply(&f, sv, LSC_READ_MAX) == (int)n);
        for (size_t i = 0; i < n; i++) {
            FUZZ_CHECK(sv[i].id == servos[i].id && sv[i].position == servos[i].position);
        }
        break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    run_stream(data, size, LSC_FRAME_MAX);
    /* A small buffer: from 4 bytes (the smallest frame) up to 67. */
    size_t small = LSC_FRAME_MIN + (size > 0 ? data[size - 1] % 64u : 0);
    run_stream(data, size, small);
    fuzz_cursor c = {data, size, 0};
    run_message(&c);
    return 0;
}
