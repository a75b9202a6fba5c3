/* Encoders and typed decoders: every error path, canary bytes around every
 * output buffer (nothing written past its capacity, nothing at all on error),
 * decode(encode(x)) == x over random messages, and encode(decode(f)) == f for
 * every frame the parser accepts from random streams. */
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "core_util.h"
#include "lsc/core.h"

#define GUARD 16u
#define ROOM (LSC_FRAME_MAX + 8u)

/* ---- Any message, so that one loop drives every encoder and decoder ---- */

typedef struct msg {
    int kind; /* enum frame_kind, not KIND_UNKNOWN */
    uint8_t group;
    uint16_t value; /* time, times, percent or millivolts */
    size_t n;
    lsc_servo servos[LSC_MOVE_MAX + 2];
    uint8_t ids[LSC_UNLOAD_MAX + 2];
} msg;

static int encode_msg(const msg *m, uint8_t *buf, size_t cap)
{
    switch (m->kind) {
    case KIND_MOVE: return lsc_encode_servo_move(buf, cap, m->value, m->servos, m->n);
    case KIND_GROUP_RUN: return lsc_encode_group_run(buf, cap, m->group, m->value);
    case KIND_GROUP_STOP: return lsc_encode_group_stop(buf, cap);
    case KIND_GROUP_COMPLETE: return lsc_encode_group_complete(buf, cap, m->group, m->value);
    case KIND_GROUP_SPEED: return lsc_encode_group_speed(buf, cap, m->group, m->value);
    case KIND_BATTERY_REQUEST: return lsc_encode_battery_request(buf, cap);
    case KIND_BATTERY_REPLY: return lsc_encode_battery_reply(buf, cap, m->value);
    case KIND_UNLOAD: return lsc_encode_unload(buf, cap, m->ids, m->n);
    case KIND_POS_REQUEST: return lsc_encode_pos_request(buf, cap, m->ids, m->n);
    default: return lsc_encode_pos_reply(buf, cap, m->servos, m->n);
    }
}

/* Decodes f as a message of m->kind into m, with room for cap list items. */
static int decode_msg(const lsc_frame *f, msg *m, size_t cap)
{
    switch (m->kind) {
    case KIND_MOVE: return lsc_decode_servo_move(f, &m->value, m->servos, cap);
    case KIND_GROUP_RUN: return lsc_decode_group_run(f, &m->group, &m->value);
    case KIND_GROUP_STOP: return lsc_decode_group_stop(f);
    case KIND_GROUP_COMPLETE: return lsc_decode_group_complete(f, &m->group, &m->value);
    case KIND_GROUP_SPEED: return lsc_decode_group_speed(f, &m->group, &m->value);
    case KIND_BATTERY_REQUEST: return lsc_decode_battery_request(f);
    case KIND_BATTERY_REPLY: return lsc_decode_battery_reply(f, &m->value);
    case KIND_UNLOAD: return lsc_decode_unload(f, m->ids, cap);
    case KIND_POS_REQUEST: return lsc_decode_pos_request(f, m->ids, cap);
    default: return lsc_decode_pos_reply(f, m->servos, cap);
    }
}

static int has_servos(int kind)
{
    return kind == KIND_MOVE || kind == KIND_POS_REPLY;
}

static int has_ids(int kind)
{
    return kind == KIND_UNLOAD || kind == KIND_POS_REQUEST;
}

static size_t max_items(int kind)
{
    return kind == KIND_MOVE ? LSC_MOVE_MAX : kind == KIND_UNLOAD ? LSC_UNLOAD_MAX : LSC_READ_MAX;
}

/* A random valid message of that kind: distinct ids, an allowed count. */
static void random_msg(test_rng *r, int kind, msg *m)
{
    memset(m, 0, sizeof *m);
    m->kind = kind;
    m->group = (uint8_t)rng_next(r);
    m->value = (uint16_t)rng_next(r);
    if (has_servos(kind) || has_ids(kind)) {
        do {
            m->n = 1 + rng_below(r, rng_below(r, 3) ? 8 : (uint32_t)max_items(kind));
        } while (m->n == 82 && has_ids(kind));
        uint8_t perm[256];
        for (size_t i = 0; i < 256; i++) {
            perm[i] = (uint8_t)i;
        }
        for (size_t i = 0; i < m->n; i++) { /* the first n of a shuffle: distinct */
            size_t j = i + rng_below(r, (uint32_t)(256 - i));
            uint8_t t = perm[i];
            perm[i] = perm[j];
            perm[j] = t;
            if (has_ids(kind)) {
                m->ids[i] = perm[i];
            } else {
                m->servos[i].id = perm[i];
                m->servos[i].position = (uint16_t)rng_next(r);
            }
        }
    }
}

static void assert_msg_equal(const msg *a, const msg *b, size_t n)
{
    int k = a->kind;
    if (k == KIND_GROUP_RUN || k == KIND_GROUP_COMPLETE || k == KIND_GROUP_SPEED) {
        assert_int_equal(a->group, b->group);
    }
    if (k != KIND_GROUP_STOP && k != KIND_BATTERY_REQUEST && k != KIND_POS_REPLY && !has_ids(k)) {
        assert_int_equal(a->value, b->value);
    }
    for (size_t i = 0; i < n; i++) {
        if (has_servos(a->kind)) {
            assert_int_equal(a->servos[i].id, b->servos[i].id);
            assert_int_equal(a->servos[i].position, b->servos[i].position);
        } else {
            assert_int_equal(a->ids[i], b->ids[i]);
        }
    }
}

/* ---- Guarded output buffers ---- */

/* Calls encode_msg with cap bytes (buf NULL if null), twice, with two canary
 * values filling the buffer and GUARD bytes each side; checks that only the
 * frame's bytes were written. Returns the result; copies the frame to out. */
static int guarded_encode(const msg *m, size_t cap, int null, uint8_t *out)
{
    static const uint8_t canaries[2] = {0xA5, 0x5A};
    int rc = 0;
    for (size_t c = 0; c < 2; c++) {
        uint8_t g[GUARD + ROOM + GUARD];
        memset(g, canaries[c], sizeof g);
        rc = encode_msg(m, null ? NULL : &g[GUARD], cap);
        size_t written = rc > 0 ? (size_t)rc : 0;
        assert_true(written <= cap);
        for (size_t i = 0; i < sizeof g; i++) {
            if ((i < GUARD || i >= GUARD + written) && g[i] != canaries[c]) {
                fail_msg("kind %d cap %zu: byte %zd written (result %d)", m->kind, cap,
                         (ptrdiff_t)i - (ptrdiff_t)GUARD, rc);
            }
        }
        if (out != NULL && written > 0) {
            memcpy(out, &g[GUARD], written);
        }
    }
    return rc;
}

/* Expects encode_msg to fail with err and write nothing, at every capacity. */
static void expect_encode_error(const msg *m, int err)
{
    for (size_t cap = 0; cap <= ROOM; cap += cap < 12 ? 1 : 61) {
        assert_int_equal(guarded_encode(m, cap, 0, NULL), err);
    }
    assert_int_equal(guarded_encode(m, ROOM, 0, NULL), err);
}

/* Decodes with every output pre-filled with a pattern; on error nothing may change. */
static int guarded_decode(const lsc_frame *f, int kind, size_t cap, msg *out)
{
    msg before;
    memset(&before, 0xC3, sizeof before);
    before.kind = kind;
    *out = before;
    int rc = decode_msg(f, out, cap);
    if (rc < 0) {
        assert_memory_equal(out, &before, sizeof before);
    } else {
        size_t n = (size_t)rc;
        assert_true(n <= cap);
        for (size_t i = n; i < sizeof out->ids; i++) { /* nothing past the items */
            assert_int_equal(out->ids[i], before.ids[i]);
        }
        for (size_t i = n; i < sizeof out->servos / sizeof out->servos[0]; i++) {
            assert_memory_equal(&out->servos[i], &before.servos[i], sizeof out->servos[i]);
        }
    }
    return rc;
}

/* ---- Round trips ---- */

static void test_decode_encode_roundtrip_random_messages(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        msg m;
        random_msg(&r, (int)rng_below(&r, KIND_UNKNOWN), &m);
        uint8_t frame[ROOM];
        int len = guarded_encode(&m, ROOM, 0, frame);
        if (len < (int)LSC_FRAME_MIN) {
            fail_msg("encode fails (%d) with seed %llu (kind %d, %zu items)", len, (unsigned long long)seed, m.kind, m.n);
        }
        size_t n = (size_t)len;
        assert_int_equal(frame[2] + 2u, n);
        /* exactly the frame's size works; one byte less writes nothing */
        assert_int_equal(guarded_encode(&m, n, 0, NULL), len);
        assert_int_equal(guarded_encode(&m, n - 1, 0, NULL), LSC_ENOSPC);
        assert_int_equal(guarded_encode(&m, 0, 1, NULL), LSC_ENOSPC);
        assert_int_equal(guarded_encode(&m, n, 1, NULL), LSC_EINVAL);

        uint8_t pbuf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, pbuf, sizeof pbuf);
        lsc_frame f;
        parse_exactly(&p, frame, n, &f);
        msg d;
        size_t items = m.n;
        if (guarded_decode(&f, m.kind, items, &d) != (int)items) {
            fail_msg("decode fails with seed %llu", (unsigned long long)seed);
        }
        assert_msg_equal(&m, &d, items);
        if (items > 0) {
            assert_int_equal(guarded_decode(&f, m.kind, items - 1, &d), LSC_ENOSPC);
        }
    }
}

/* The kinds a known command's frame may be. */
static size_t kinds_of(uint8_t cmd, int *kinds)
{
    switch (cmd) {
    case 3: kinds[0] = KIND_MOVE; return 1;
    case 6: kinds[0] = KIND_GROUP_RUN; return 1;
    case 7: kinds[0] = KIND_GROUP_STOP; return 1;
    case 8: kinds[0] = KIND_GROUP_COMPLETE; return 1;
    case 11: kinds[0] = KIND_GROUP_SPEED; return 1;
    case 15: kinds[0] = KIND_BATTERY_REQUEST; kinds[1] = KIND_BATTERY_REPLY; return 2;
    case 20: kinds[0] = KIND_UNLOAD; return 1;
    default: kinds[0] = KIND_POS_REQUEST; kinds[1] = KIND_POS_REPLY; return 2;
    }
}

/* True if the frame's list items repeat an id. */
static int repeats_id(const lsc_frame *f, int kind)
{
    size_t head = kind == KIND_MOVE ? 3 : 1, width = has_servos(kind) ? 3 : 1;
    size_t n = ((size_t)f->nparams - head) / width;
    uint8_t seen[256] = {0};
    for (size_t i = 0; i < n; i++) {
        if (seen[f->params[head + i * width]]++) {
            return 1;
        }
    }
    return 0;
}

/* Checks encode(decode(f)) == f for one frame the parser returned. */
static void reencode(const lsc_frame *f, unsigned long long seed)
{
    uint8_t bytes[LSC_FRAME_MAX];
    size_t n = frame_bytes(f, bytes);
    uint8_t again[ROOM];
    if (!cmd_known(f->cmd)) {
        int rc = lsc_encode_frame(again, n, f->cmd, f->params, f->nparams);
        if (rc != (int)n || memcmp(again, bytes, n) != 0) {
            fail_msg("unknown command re-encodes wrongly with seed %llu", seed);
        }
        return;
    }
    int kinds[2];
    size_t nk = kinds_of(f->cmd, kinds), decoded = 0;
    for (size_t k = 0; k < nk; k++) {
        msg d;
        int rc = guarded_decode(f, kinds[k], ROOM, &d);
        if (rc < 0) {
            continue;
        }
        decoded++;
        d.n = (size_t)rc;
        if (guarded_encode(&d, n, 0, again) != (int)n || memcmp(again, bytes, n) != 0) {
            fail_msg("command %u re-encodes wrongly with seed %llu", f->cmd, seed);
        }
    }
    if (decoded == 0) { /* only a repeated id, or a position request no reply could answer */
        int list = nk == 1 ? kinds[0] : kinds[f->nparams == 1 + f->params[0] ? 0 : 1];
        int ok = (has_ids(list) || has_servos(list)) &&
                 (repeats_id(f, list) || (list == KIND_POS_REQUEST && f->params[0] > LSC_READ_MAX));
        if (!ok) {
            fail_msg("command %u (%u params) decodes as nothing with seed %llu", f->cmd,
                     f->nparams, seed);
        }
    }
    assert_true(decoded <= 1);
}

static void test_encode_decode_roundtrip_parsed_frames(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 1500; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        uint8_t stream[4096];
        size_t len = 0;
        while (len + LSC_FRAME_MAX <= sizeof stream) {
            uint32_t what = rng_below(&r, 8);
            if (what == 0) { /* noise */
                stream[len++] = rng_below(&r, 2) ? 0x55 : (uint8_t)rng_next(&r);
            } else if (what == 1) { /* a small list with a likely repeated id */
                size_t n = random_frame_of(&r, (int)rng_below(&r, KIND_UNKNOWN), &stream[len],
                                           LSC_FRAME_MAX);
                for (size_t i = 5; i < n; i++) {
                    stream[len + i] &= 3;
                }
                len += n;
            } else {
                len += random_frame(&r, &stream[len], LSC_FRAME_MAX);
            }
        }
        uint8_t pbuf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, pbuf, sizeof pbuf);
        for (size_t i = 0; i < len; i++) {
            lsc_frame f;
            if (lsc_parser_feed(&p, stream[i], &f) == 1) {
                reencode(&f, (unsigned long long)seed);
            }
        }
    }
}

/* ---- Encoder errors ---- */

static void test_encode_frame_errors(void **state)
{
    (void)state;
    uint8_t params[LSC_PARAMS_MAX + 1];
    memset(params, 0x55, sizeof params);
    uint8_t g[GUARD + ROOM + GUARD];
    for (size_t n = 0; n <= LSC_PARAMS_MAX + 1; n++) {
        int want = n > LSC_PARAMS_MAX || n == 83 ? LSC_EINVAL : (int)n + 4;
        memset(g, 0xA5, sizeof g);
        assert_int_equal(lsc_encode_frame(&g[GUARD], ROOM, 0x42, params, n), want);
        if (want > 0) {
            assert_int_equal(g[GUARD + 2], n + 2);
            assert_int_equal(g[GUARD + 3], 0x42);
            assert_int_equal(lsc_encode_frame(&g[GUARD], n + 3, 0x42, params, n), LSC_ENOSPC);
        }
        size_t written = want > 0 ? (size_t)want : 0;
        for (size_t i = 0; i < sizeof g; i++) {
            if (i < GUARD || i >= GUARD + written) {
                assert_int_equal(g[i], 0xA5);
            }
        }
    }
    assert_int_equal(lsc_encode_frame(g, sizeof g, 1, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_encode_frame(g, sizeof g, 1, NULL, 0), 4);
    assert_int_equal(lsc_encode_frame(NULL, 0, 1, params, 1), LSC_ENOSPC);
    assert_int_equal(lsc_encode_frame(NULL, 5, 1, params, 1), LSC_EINVAL);
}

/* The parameters may already be where they go (params = buf + 4). */
static void test_encode_frame_in_place(void **state)
{
    (void)state;
    uint8_t f[LSC_FRAME_MIN + 4] = {0, 0, 0, 0, 3, 1, 2, 3};
    assert_int_equal(lsc_encode_frame(f, sizeof f, LSC_CMD_POS_READ, &f[4], 4), 8);
    static const uint8_t want[] = {0x55, 0x55, 6, LSC_CMD_POS_READ, 3, 1, 2, 3};
    assert_memory_equal(f, want, sizeof want);
}

static void test_encode_list_errors(void **state)
{
    (void)state;
    static const int list_kinds[] = {KIND_MOVE, KIND_UNLOAD, KIND_POS_REQUEST, KIND_POS_REPLY};
    for (size_t k = 0; k < 4; k++) {
        msg m;
        memset(&m, 0, sizeof m);
        m.kind = list_kinds[k];
        size_t max = max_items(m.kind);
        for (size_t i = 0; i < sizeof m.ids; i++) {
            m.ids[i] = (uint8_t)i;
        }
        for (size_t i = 0; i < sizeof m.servos / sizeof m.servos[0]; i++) {
            m.servos[i].id = (uint8_t)i;
            m.servos[i].position = (uint16_t)(500 + i);
        }
        m.n = 0; /* no servo */
        expect_encode_error(&m, LSC_EINVAL);
        m.n = max + 1; /* too many */
        expect_encode_error(&m, LSC_EINVAL);
        m.n = max; /* the most: fits exactly in LEN <= 255 */
        assert_int_equal(guarded_encode(&m, ROOM, 0, NULL), m.kind == KIND_MOVE ? 3 * 83 + 7
                                                            : m.kind == KIND_UNLOAD ? 257
                                                            : m.kind == KIND_POS_REPLY ? 3 * 84 + 5
                                                                                       : 84 + 5);
        if (has_ids(m.kind)) { /* 82 ids would need LEN 0x55 */
            m.n = 82;
            expect_encode_error(&m, LSC_EINVAL);
            m.n = 81;
            assert_int_equal(guarded_encode(&m, ROOM, 0, NULL), 81 + 5);
            m.n = 83;
            assert_int_equal(guarded_encode(&m, ROOM, 0, NULL), 83 + 5);
        }
        m.n = 5; /* a repeated id, first and last, or neighbours */
        m.ids[4] = m.ids[0];
        m.servos[4].id = m.servos[0].id;
        expect_encode_error(&m, LSC_EINVAL);
        m.ids[4] = 4;
        m.servos[4].id = 4;
        m.ids[2] = 1;
        m.servos[2].id = 1;
        expect_encode_error(&m, LSC_EINVAL);
        m.ids[2] = 2;
        m.servos[2].id = 2;
        assert_int_equal(guarded_encode(&m, ROOM, 0, NULL), has_servos(m.kind) ? 15 + (m.kind == KIND_MOVE ? 7 : 5) : 10);
        /* NULL list */
        if (has_ids(m.kind)) {
            assert_int_equal(m.kind == KIND_UNLOAD ? lsc_encode_unload(m.ids, 20, NULL, 1)
                                                   : lsc_encode_pos_request(m.ids, 20, NULL, 1),
                             LSC_EINVAL);
        } else {
            uint8_t buf[20];
            assert_int_equal(m.kind == KIND_MOVE ? lsc_encode_servo_move(buf, 20, 1, NULL, 1)
                                                 : lsc_encode_pos_reply(buf, 20, NULL, 1),
                             LSC_EINVAL);
        }
    }
}

/* Every encoder, every capacity from 0 to one more than its frame: ENOSPC and
 * nothing written below the frame's size, the frame at or above it; NULL buf. */
static void test_encode_every_capacity(void **state)
{
    (void)state;
    test_rng r;
    rng_seed(&r, 7);
    for (int kind = 0; kind < KIND_UNKNOWN; kind++) {
        msg m;
        random_msg(&r, kind, &m);
        int len = guarded_encode(&m, ROOM, 0, NULL);
        assert_true(len >= (int)LSC_FRAME_MIN);
        for (size_t cap = 0; cap <= (size_t)len + 1; cap++) {
            assert_int_equal(guarded_encode(&m, cap, 0, NULL), cap < (size_t)len ? LSC_ENOSPC : len);
        }
        assert_int_equal(guarded_encode(&m, 0, 1, NULL), LSC_ENOSPC);
        assert_int_equal(guarded_encode(&m, (size_t)len, 1, NULL), LSC_EINVAL);
    }
}

/* ---- Decoder errors ---- */

static void test_decode_null_arguments(void **state)
{
    (void)state;
    static const uint8_t move[] = {1, 0xE8, 0x03, 1, 0xD0, 0x07};
    lsc_frame f = {3, sizeof move, move};
    uint16_t u16;
    uint8_t u8;
    lsc_servo s[2];
    uint8_t ids[2];
    assert_int_equal(lsc_decode_servo_move(NULL, &u16, s, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_servo_move(&f, NULL, s, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_servo_move(&f, &u16, NULL, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_servo_move(&f, &u16, NULL, 0), LSC_ENOSPC);
    assert_int_equal(lsc_decode_group_run(NULL, &u8, &u16), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_run(&f, NULL, &u16), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_run(&f, &u8, NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_complete(NULL, &u8, &u16), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_complete(&f, NULL, &u16), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_speed(&f, &u8, NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_group_stop(NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_battery_request(NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_battery_reply(NULL, &u16), LSC_EINVAL);
    assert_int_equal(lsc_decode_battery_reply(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_unload(NULL, ids, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_unload(&f, NULL, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_pos_request(NULL, ids, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_pos_request(&f, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_decode_pos_reply(NULL, s, 2), LSC_EINVAL);
    assert_int_equal(lsc_decode_pos_reply(&f, NULL, 2), LSC_EINVAL);
    /* no array and no room: a valid list does not fit */
    static const uint8_t two_ids[] = {2, 4, 5};
    lsc_frame list = {20, sizeof two_ids, two_ids};
    assert_int_equal(lsc_decode_unload(&list, NULL, 0), LSC_ENOSPC);
    list.cmd = 21;
    assert_int_equal(lsc_decode_pos_request(&list, NULL, 0), LSC_ENOSPC);
    static const uint8_t one_pos[] = {1, 4, 0xF4, 0x01};
    list = (lsc_frame){21, sizeof one_pos, one_pos};
    assert_int_equal(lsc_decode_pos_reply(&list, NULL, 0), LSC_ENOSPC);
    /* parameters NULL although the frame claims some */
    lsc_frame bad = {3, 6, NULL};
    assert_int_equal(lsc_decode_servo_move(&bad, &u16, s, 2), LSC_EINVAL);
    bad = (lsc_frame){6, 3, NULL};
    assert_int_equal(lsc_decode_group_run(&bad, &u8, &u16), LSC_EINVAL);
    bad = (lsc_frame){15, 2, NULL};
    assert_int_equal(lsc_decode_battery_reply(&bad, &u16), LSC_EINVAL);
    bad = (lsc_frame){20, 2, NULL};
    assert_int_equal(lsc_decode_unload(&bad, ids, 2), LSC_EINVAL);
    bad = (lsc_frame){21, 4, NULL};
    assert_int_equal(lsc_decode_pos_reply(&bad, s, 2), LSC_EINVAL);
    /* no parameters, none needed */
    bad = (lsc_frame){7, 0, NULL};
    assert_int_equal(lsc_decode_group_stop(&bad), 0);
    bad = (lsc_frame){15, 0, NULL};
    assert_int_equal(lsc_decode_battery_request(&bad), 0);
}

/* Every decoder rejects every other command, and every length but its own. */
static void test_decode_wrong_command_or_length(void **state)
{
    (void)state;
    test_rng r;
    rng_seed(&r, 11);
    for (int kind = 0; kind < KIND_UNKNOWN; kind++) {
        msg m;
        random_msg(&r, kind, &m);
        uint8_t frame[ROOM];
        int len = guarded_encode(&m, ROOM, 0, frame);
        lsc_frame f = {frame[3], (uint8_t)(len - 4), &frame[4]};
        msg d;
        assert_true(guarded_decode(&f, kind, ROOM, &d) >= 0);
        for (int other = 0; other < KIND_UNKNOWN; other++) {
            int rc = guarded_decode(&f, other, ROOM, &d);
            if (other != kind) {
                assert_int_equal(rc, LSC_EFRAME);
            }
        }
        for (unsigned cmd = 0; cmd < 256; cmd++) {
            if (cmd != frame[3]) {
                lsc_frame wrong = {(uint8_t)cmd, f.nparams, f.params};
                assert_int_equal(guarded_decode(&wrong, kind, ROOM, &d), LSC_EFRAME);
            }
        }
        for (unsigned np = 0; np <= LSC_PARAMS_MAX; np++) { /* the count byte stays */
            if (np != f.nparams) {
                lsc_frame wrong = {f.cmd, (uint8_t)np, f.params};
                assert_int_equal(guarded_decode(&wrong, kind, ROOM, &d), LSC_EFRAME);
            }
        }
    }
}

/* The list decoders: count against length, no item, repeated ids, small arrays. */
static void test_decode_list_errors(void **state)
{
    (void)state;
    msg d;
    /* The frames below alias the arrays this test edits between decodes, which
     * cppcheck cannot see: its redundantAssignment findings here are suppressed. */
    /* move: count 2 but room for 1 servo; count 0 with no servo */
    uint8_t move[] = {2, 0x10, 0x00, 1, 0xF4, 0x01, 2, 0xF4, 0x01};
    lsc_frame f = {3, sizeof move, move};
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), 2);
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 1, &d), LSC_ENOSPC);
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 0, &d), LSC_ENOSPC);
    move[0] = 1;
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), LSC_EFRAME);
    // cppcheck-suppress redundantAssignment
    move[0] = 3;
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), LSC_EFRAME);
    // cppcheck-suppress redundantAssignment
    move[0] = 2;
    move[6] = 1; /* repeated id */
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), LSC_EFRAME);
    uint8_t empty_move[] = {0, 0x10, 0x00};
    f = (lsc_frame){3, sizeof empty_move, empty_move};
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), LSC_EFRAME);
    f.nparams = 2;
    assert_int_equal(guarded_decode(&f, KIND_MOVE, 2, &d), LSC_EFRAME);

    /* unload and position request */
    for (int kind = KIND_UNLOAD; kind <= KIND_POS_REQUEST; kind++) {
        uint8_t ids[] = {3, 7, 8, 9};
        f = (lsc_frame){kind == KIND_UNLOAD ? 20 : 21, sizeof ids, ids};
        assert_int_equal(guarded_decode(&f, kind, 3, &d), 3);
        assert_int_equal(guarded_decode(&f, kind, 2, &d), LSC_ENOSPC);
        ids[0] = 2;
        assert_int_equal(guarded_decode(&f, kind, 3, &d), LSC_EFRAME);
        // cppcheck-suppress redundantAssignment
        ids[0] = 0;
        f.nparams = 1;
        assert_int_equal(guarded_decode(&f, kind, 3, &d), LSC_EFRAME);
        f.nparams = 0;
        assert_int_equal(guarded_decode(&f, kind, 3, &d), LSC_EFRAME);
        ids[0] = 3;
        ids[3] = 7;
        f.nparams = 4;
        assert_int_equal(guarded_decode(&f, kind, 3, &d), LSC_EFRAME);
    }
    /* a position request no reply could answer (more than LSC_READ_MAX ids) */
    uint8_t many[1 + LSC_READ_MAX + 1];
    for (size_t i = 0; i < sizeof many; i++) {
        many[i] = (uint8_t)(i - 1);
    }
    many[0] = LSC_READ_MAX;
    f = (lsc_frame){21, 1 + LSC_READ_MAX, many};
    assert_int_equal(guarded_decode(&f, KIND_POS_REQUEST, ROOM, &d), LSC_READ_MAX);
    many[0] = LSC_READ_MAX + 1;
    f.nparams = 2 + LSC_READ_MAX;
    assert_int_equal(guarded_decode(&f, KIND_POS_REQUEST, ROOM, &d), LSC_EFRAME);
    assert_int_equal(guarded_decode(&(lsc_frame){20, 2 + LSC_READ_MAX, many}, KIND_UNLOAD,
                                    ROOM, &d),
                     LSC_READ_MAX + 1);

    /* position reply */
    uint8_t reply[] = {2, 4, 0xF4, 0x01, 5, 0xF4, 0x01};
    f = (lsc_frame){21, sizeof reply, reply};
    assert_int_equal(guarded_decode(&f, KIND_POS_REPLY, 2, &d), 2);
    assert_int_equal(guarded_decode(&f, KIND_POS_REPLY, 1, &d), LSC_ENOSPC);
    reply[4] = 4;
    assert_int_equal(guarded_decode(&f, KIND_POS_REPLY, 2, &d), LSC_EFRAME);
    // cppcheck-suppress redundantAssignment
    reply[4] = 5;
    reply[0] = 1;
    assert_int_equal(guarded_decode(&f, KIND_POS_REPLY, 2, &d), LSC_EFRAME);
    // cppcheck-suppress redundantAssignment
    reply[0] = 0;
    f.nparams = 1;
    assert_int_equal(guarded_decode(&f, KIND_POS_REPLY, 2, &d), LSC_EFRAME);
}

/* ---- The ids rule ---- */

static void test_ids_first_repeat(void **state)
{
    (void)state;
    static const uint8_t ids[] = {4, 7, 9, 7, 4};
    assert_int_equal(lsc_ids_first_repeat(NULL, 1, 0), 0);
    assert_int_equal(lsc_ids_first_repeat(ids, 1, 1), 1);
    assert_int_equal(lsc_ids_first_repeat(ids, 1, 3), 3);
    assert_int_equal(lsc_ids_first_repeat(ids, 1, 5), 3); /* the first to repeat, not 4's */
    /* an id field in structures */
    const lsc_servo s[] = {{1, 500}, {2, 1}, {3, 2}, {2, 3}};
    assert_int_equal(lsc_ids_first_repeat(&s[0].id, sizeof s[0], 3), 3);
    assert_int_equal(lsc_ids_first_repeat(&s[0].id, sizeof s[0], 4), 3);
}

/* ---- The version ---- */

/* lsc_version() is the headers' version, and the macros make it. */
static void test_version(void **state)
{
    (void)state;
    char want[32];
    (void)snprintf(want, sizeof want, "%d.%d.%d", LSC_VERSION_MAJOR, LSC_VERSION_MINOR,
                   LSC_VERSION_PATCH);
    assert_string_equal(lsc_version(), want);
    assert_string_equal(lsc_version(), LSC_VERSION_STRING);
    assert_true(LSC_VERSION_NUMBER(LSC_VERSION_MAJOR, LSC_VERSION_MINOR, LSC_VERSION_PATCH) >=
                LSC_VERSION_NUMBER(0, 3, 0));
}

/* ---- Error texts ---- */

static void test_strerror_every_code(void **state)
{
    (void)state;
    const char *unknown = lsc_strerror(-1000);
    assert_non_null(unknown);
    assert_string_equal(lsc_strerror(LSC_EINTR - 1), unknown);
    assert_string_equal(lsc_strerror(INT_MIN), unknown);
    for (int code = LSC_OK; code >= LSC_EINTR; code--) {
        const char *text = lsc_strerror(code);
        assert_non_null(text);
        assert_true(strlen(text) > 0);
        assert_string_not_equal(text, unknown);
        for (int other = code - 1; other >= LSC_EINTR; other--) {
            assert_string_not_equal(text, lsc_strerror(other));
        }
    }
    /* positive values are counts: success */
    assert_string_equal(lsc_strerror(1), lsc_strerror(LSC_OK));
    assert_string_equal(lsc_strerror(INT_MAX), lsc_strerror(LSC_OK));
    assert_string_equal(lsc_strerror(LSC_OK), "success");
    assert_string_equal(lsc_strerror(LSC_EINVAL), "invalid argument");
    assert_string_equal(lsc_strerror(LSC_ENOSPC), "buffer too small");
    assert_string_equal(lsc_strerror(LSC_ESYNC), "bytes outside a frame");
    assert_string_equal(lsc_strerror(LSC_EFRAME), "malformed frame");
    assert_string_equal(lsc_strerror(LSC_ETOOBIG), "frame too long");
    assert_string_equal(lsc_strerror(LSC_ETIMEOUT), "timed out");
    assert_string_equal(lsc_strerror(LSC_EIO), "I/O error");
    assert_string_equal(lsc_strerror(LSC_EREPLY), "unexpected reply");
    assert_string_equal(lsc_strerror(LSC_EBUSY), "port busy");
    assert_string_equal(lsc_strerror(LSC_ENODEV), "no such device");
    assert_string_equal(lsc_strerror(LSC_EACCES), "permission denied");
    assert_string_equal(lsc_strerror(LSC_EINTR), "interrupted");
    assert_string_equal(unknown, "unknown error");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode_encode_roundtrip_random_messages),
        cmocka_unit_test(test_encode_decode_roundtrip_parsed_frames),
        cmocka_unit_test(test_encode_frame_errors),
        cmocka_unit_test(test_encode_frame_in_place),
        cmocka_unit_test(test_encode_list_errors),
        cmocka_unit_test(test_encode_every_capacity),
        cmocka_unit_test(test_decode_null_arguments),
        cmocka_unit_test(test_decode_wrong_command_or_length),
        cmocka_unit_test(test_decode_list_errors),
        cmocka_unit_test(test_ids_first_repeat),
        cmocka_unit_test(test_strerror_every_code),
        cmocka_unit_test(test_version),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
