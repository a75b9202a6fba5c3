/* The parser: the three properties of docs/contributing.md over seeded random cases, and
 * a unit test for each of its rules. Every random case prints its seed when it
 * fails; rerun with the same seed to reproduce it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "core_util.h"
#include "lsc/core.h"

#define STREAM_MAX 8192u

/* A stream of frames and where each begins. */
typedef struct stream {
    uint8_t bytes[STREAM_MAX];
    size_t len;
    size_t starts[STREAM_MAX / 4 + 1];
    size_t nframes;
} stream;

/* Appends random valid frames (each at most max bytes) until about `want` bytes. */
static void random_stream(test_rng *r, stream *s, size_t want, size_t max)
{
    s->len = 0;
    s->nframes = 0;
    while (s->len < want && s->len + LSC_FRAME_MAX <= STREAM_MAX) {
        s->starts[s->nframes++] = s->len;
        s->len += random_frame(r, &s->bytes[s->len], max);
    }
    s->starts[s->nframes] = s->len;
}

/* Feeds bytes[0..n) to p through the byte-at-a-time path (bulk false: one
 * lsc_parser_feed per byte) or the bulk path (bulk true: lsc_parser_feed_buf
 * on what is left, again after each result), and calls fn for every nonzero
 * result with the index of the byte that gave it. Returns nonzero if the
 * bulk path broke its contract (consumed nothing, or more than it was given,
 * or stopped early with a zero result). */
typedef int (*on_result)(void *ctx, size_t at, int rc, const lsc_frame *f);
static int feed_all(bool bulk, lsc_parser *p, const uint8_t *bytes, size_t n, on_result fn,
                    void *ctx)
{
    lsc_frame f; /* a fresh one per call: nothing may depend on the caller keeping it */
    memset(&f, 0, sizeof f);
    int bad = 0;
    for (size_t i = 0; i < n;) {
        int rc;
        if (bulk) {
            size_t k = lsc_parser_feed_buf(p, &bytes[i], n - i, &f, &rc);
            bad |= k == 0 || k > n - i || (rc == 0 && k != n - i);
            i += k;
        } else {
            rc = lsc_parser_feed(p, bytes[i++], &f);
        }
        if (rc != 0) {
            bad |= fn(ctx, i - 1, rc, &f);
        }
    }
    return bad;
}

/* Checks each frame the parser returns against the stream's next one; at
 * is relative to the stream's byte `from`. */
typedef struct checking {
    const struct stream *s;
    size_t from;
    size_t next;
} checking;

static int check_next_frame(void *ctx, size_t at, int rc, const lsc_frame *f)
{
    checking *c = ctx;
    const stream *s = c->s;
    at += c->from;
    if (rc != 1 || c->next >= s->nframes || s->starts[c->next + 1] != at + 1) {
        return 1;
    }
    uint8_t got[LSC_FRAME_MAX];
    size_t n = frame_bytes(f, got);
    if (n != at + 1 - s->starts[c->next] || memcmp(got, &s->bytes[s->starts[c->next]], n) != 0) {
        return 1;
    }
    c->next++;
    return 0;
}

/* Feeds bytes[from..to) and checks each frame returned against the stream's
 * next one (*next); every other result must be 0. Returns nonzero on a
 * mismatch (the caller prints its seed). */
static int feed_checking(bool bulk, lsc_parser *p, const stream *s, size_t from, size_t to,
                         size_t *next)
{
    checking c = {s, from, *next};
    int bad = feed_all(bulk, p, &s->bytes[from], to - from, check_next_frame, &c);
    *next = c.next;
    return bad;
}

/* (a) Any sequence of valid frames decodes to exactly that sequence, whatever
 * the parser's buffer size (each frame fits it). */
static void test_property_a_valid_frames_decode_exactly(void **state)
{
    (void)state;
    static stream s;
    for (uint64_t seed = 1; seed <= 6000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        size_t cap = rng_below(&r, 2) ? LSC_FRAME_MAX : 4 + rng_below(&r, 300);
        uint8_t buf[300];
        lsc_parser p;
        assert_int_equal(lsc_parser_init(&p, buf, cap), 0);
        random_stream(&r, &s, 1 + rng_below(&r, 2000), cap);
        size_t next = 0;
        bool bulk = seed % 2 == 0; /* odd seeds byte at a time, even ones in bulk */
        int bad = feed_checking(bulk, &p, &s, 0, s.len, &next);
        if (bad || next != s.nframes || p.frames != s.nframes || p.discarded != 0 ||
            p.errors != 0) {
            fail_msg("property (a) fails with seed %llu (cap %zu, %s)", (unsigned long long)seed,
                     cap, bulk ? "bulk" : "byte at a time");
        }
    }
}

/* (a) A short stream cut into three chunks at every pair of cut points. */
static void test_property_a_every_chunking(void **state)
{
    (void)state;
    static stream s;
    for (uint64_t seed = 1; seed <= 40; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        s.len = 0;
        s.nframes = 0;
        while (s.len < 24) { /* short frames only: every pair of cuts stays cheap */
            s.starts[s.nframes++] = s.len;
            s.len += random_frame(&r, &s.bytes[s.len], 4 + rng_below(&r, 12));
        }
        s.starts[s.nframes] = s.len;
        for (size_t c1 = 0; c1 <= s.len; c1++) {
            for (size_t c2 = c1; c2 <= s.len; c2++) {
                for (int bulk = 0; bulk < 2; bulk++) {
                    uint8_t buf[LSC_FRAME_MAX];
                    lsc_parser p;
                    lsc_parser_init(&p, buf, sizeof buf);
                    size_t next = 0;
                    int bad = feed_checking(bulk, &p, &s, 0, c1, &next);
                    bad |= feed_checking(bulk, &p, &s, c1, c2, &next);
                    bad |= feed_checking(bulk, &p, &s, c2, s.len, &next);
                    if (bad || next != s.nframes) {
                        fail_msg("chunking fails with seed %llu, cuts at %zu and %zu (%s)",
                                 (unsigned long long)seed, c1, c2,
                                 bulk ? "bulk" : "byte at a time");
                    }
                }
            }
        }
    }
}

/* What a feed gave: the ESYNC results, each for the byte at its own index
 * (noise first), then frames (the last one kept), anything else counted. */
typedef struct results {
    size_t esync;
    size_t frames;
    size_t other;
    size_t last_at;
    uint8_t last[LSC_FRAME_MAX];
    size_t last_n;
} results;

static int collect(void *ctx, size_t at, int rc, const lsc_frame *f)
{
    results *res = ctx;
    if (rc == LSC_ESYNC && res->frames == 0 && at == res->esync) {
        res->esync++;
    } else if (rc == 1) {
        res->frames++;
        res->last_at = at;
        res->last_n = frame_bytes(f, res->last);
    } else {
        res->other++;
    }
    return 0;
}

/* Feeds in[0..n) and checks that it gave `esync` ESYNC results for its first
 * bytes, then exactly one frame, on the last byte, equal to frame[0..nf). */
static int gives_noise_then_frame(bool bulk, lsc_parser *p, const uint8_t *in, size_t n,
                                  size_t esync, const uint8_t *frame, size_t nf)
{
    results res;
    memset(&res, 0, sizeof res);
    int bad = feed_all(bulk, p, in, n, collect, &res);
    return bad || res.esync != esync || res.frames != 1 || res.other != 0 ||
           res.last_at != n - 1 || res.last_n != nf || memcmp(res.last, frame, nf) != 0;
}

/* (b) Garbage without a 0x55 byte, then a valid frame: the frame comes out,
 * every garbage byte is reported and counted as discarded. */
static void test_property_b_garbage_then_frame(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 10000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, buf, sizeof buf);
        size_t ngarbage = rng_below(&r, 4) ? rng_below(&r, 8) : rng_below(&r, 600);
        uint8_t in[600 + LSC_FRAME_MAX];
        for (size_t i = 0; i < ngarbage; i++) {
            uint8_t b;
            do {
                b = (uint8_t)rng_next(&r);
            } while (b == 0x55);
            in[i] = b;
        }
        size_t n = random_frame(&r, &in[ngarbage], LSC_FRAME_MAX);
        bool bulk = seed % 2 == 0;
        int bad = gives_noise_then_frame(bulk, &p, in, ngarbage + n, ngarbage, &in[ngarbage], n);
        bad |= p.frames != 1 || p.discarded != ngarbage || p.errors != 0;
        if (bad) {
            fail_msg("property (b) fails with seed %llu (%s)", (unsigned long long)seed,
                     bulk ? "bulk" : "byte at a time");
        }
    }
}

/* Random bytes rich in 0x55, small values and pieces of frames: anything the
 * parser may have to swallow. */
static size_t random_noise(test_rng *r, uint8_t *out, size_t max)
{
    size_t n = 0;
    size_t want = rng_below(r, (uint32_t)max);
    while (n < want) {
        uint32_t what = rng_below(r, 8);
        if (what == 0 && n + LSC_FRAME_MAX <= max) { /* a piece of a valid frame */
            uint8_t frame[LSC_FRAME_MAX];
            size_t len = random_frame(r, frame, sizeof frame);
            size_t from = rng_below(r, (uint32_t)len);
            size_t to = from + rng_below(r, (uint32_t)(len - from)) + 1;
            memcpy(&out[n], &frame[from], to - from);
            n += to - from;
        } else if (what < 4) {
            out[n++] = 0x55;
        } else if (what < 6) {
            out[n++] = (uint8_t)rng_below(r, 24);
        } else {
            out[n++] = (uint8_t)rng_next(r);
        }
    }
    return n;
}

/* Fails unless rc is one of the parser's results for input it may swallow. */
static int any_result(void *ctx, size_t at, int rc, const lsc_frame *f)
{
    (void)ctx;
    (void)at;
    (void)f;
    return rc < LSC_ETOOBIG || rc > 1;
}

/* (c) After lsc_parser_reset any valid frame is decoded, whatever came before. */
static void test_property_c_reset_then_frame(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 10000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, buf, sizeof buf);
        uint8_t noise[1024];
        size_t nnoise = random_noise(&r, noise, rng_below(&r, 2) ? 16 : sizeof noise);
        bool bulk = seed % 2 == 0;
        if (feed_all(bulk, &p, noise, nnoise, any_result, NULL) != 0) {
            fail_msg("property (c): a wrong result with seed %llu", (unsigned long long)seed);
        }
        uint32_t frames = p.frames;
        uint32_t discarded = p.discarded + (uint32_t)(p.complete ? 0 : p.len);
        lsc_parser_reset(&p);
        uint8_t frame[LSC_FRAME_MAX];
        size_t n = random_frame(&r, frame, sizeof frame);
        int bad = gives_noise_then_frame(bulk, &p, frame, n, 0, frame, n);
        bad |= p.frames != frames + 1 || p.discarded != discarded;
        if (bad) {
            fail_msg("property (c) fails with seed %llu (%s)", (unsigned long long)seed,
                     bulk ? "bulk" : "byte at a time");
        }
    }
}

/* The bulk path is the byte-at-a-time path: on any input (0x55-rich noise,
 * pieces of frames, malformed and oversized ones), fed in chunks of random
 * sizes, the same results at the same bytes, the same frames, the same
 * counters and the same parser state. */
typedef struct trace {
    size_t n;
    size_t at[1100];
    int rc[1100];
    uint32_t sum[1100]; /* of the frame's bytes, position-weighted */
} trace;

static int record(void *ctx, size_t at, int rc, const lsc_frame *f)
{
    trace *t = ctx;
    uint32_t sum = 0;
    if (rc == 1) {
        uint8_t bytes[LSC_FRAME_MAX];
        size_t n = frame_bytes(f, bytes);
        for (size_t i = 0; i < n; i++) {
            sum = sum * 31u + bytes[i];
        }
    }
    t->at[t->n] = at;
    t->rc[t->n] = rc;
    t->sum[t->n] = sum;
    t->n++;
    return 0;
}

/* Nonzero if two feeds of the same bytes gave different results, frames,
 * counters, state or buffered bytes. */
static int differ(const trace *t1, const lsc_parser *p1, const trace *t2, const lsc_parser *p2)
{
    return t1->n != t2->n || memcmp(t1->at, t2->at, t1->n * sizeof t1->at[0]) != 0 ||
           memcmp(t1->rc, t2->rc, t1->n * sizeof t1->rc[0]) != 0 ||
           memcmp(t1->sum, t2->sum, t1->n * sizeof t1->sum[0]) != 0 || p1->len != p2->len ||
           p1->complete != p2->complete || p1->frames != p2->frames ||
           p1->discarded != p2->discarded || p1->errors != p2->errors ||
           memcmp(p1->buf, p2->buf, p1->len) != 0;
}

static void test_bulk_equals_byte_at_a_time(void **state)
{
    (void)state;
    static trace byte, bulk;
    for (uint64_t seed = 1; seed <= 4000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        size_t cap = rng_below(&r, 2) ? LSC_FRAME_MAX : 4 + rng_below(&r, 60);
        uint8_t in[1024];
        size_t n = random_noise(&r, in, sizeof in);
        uint8_t buf1[LSC_FRAME_MAX], buf2[LSC_FRAME_MAX];
        lsc_parser p1, p2;
        lsc_parser_init(&p1, buf1, cap);
        lsc_parser_init(&p2, buf2, cap);
        byte.n = 0;
        bulk.n = 0;
        int bad = feed_all(false, &p1, in, n, record, &byte);
        /* the bulk path in random chunks, the parser's state carried across */
        for (size_t i = 0; i < n;) {
            size_t chunk = 1 + rng_below(&r, (uint32_t)(n - i));
            trace part;
            part.n = 0;
            bad |= feed_all(true, &p2, &in[i], chunk, record, &part);
            for (size_t k = 0; k < part.n; k++) {
                bulk.at[bulk.n] = i + part.at[k];
                bulk.rc[bulk.n] = part.rc[k];
                bulk.sum[bulk.n] = part.sum[k];
                bulk.n++;
            }
            i += chunk;
        }
        bad |= differ(&byte, &p1, &bulk, &p2);
        if (bad) {
            fail_msg("bulk and byte at a time differ with seed %llu", (unsigned long long)seed);
        }
    }
}

/* The length rules of the known commands: LEN = a*N + b for count N. */
static int frame_valid(const lsc_frame *f)
{
    size_t len = (size_t)f->nparams + 2;
    size_t n = f->nparams > 0 ? f->params[0] : 0;
    switch (f->cmd) {
    case 3: return n >= 1 && len == 3 * n + 5;
    case 6:
    case 8:
    case 11: return len == 5;
    case 7: return len == 2;
    case 15: return len == 2 || len == 4;
    case 20: return n >= 1 && len == n + 3;
    case 21: return n >= 1 && (len == n + 3 || len == 3 * n + 3);
    default: return len != 0x55;
    }
}

/* Whatever bytes come in, every frame out obeys the rules, the return codes
 * are the documented ones, and the counters add up: each byte fed is part of
 * a returned frame, discarded, or still buffered. */
static void test_any_input_gives_only_valid_frames(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 3000; seed++) {
        test_rng r;
        rng_seed(&r, seed);
        size_t cap = rng_below(&r, 2) ? LSC_FRAME_MAX : 4 + rng_below(&r, 60);
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, buf, cap);
        uint8_t noise[1024];
        size_t n = random_noise(&r, noise, sizeof noise);
        size_t framed = 0;
        uint32_t errors = 0;
        int bad = 0;
        for (size_t i = 0; i < n; i++) {
            lsc_frame f;
            int rc = lsc_parser_feed(&p, noise[i], &f);
            if (rc == 1) {
                bad |= !frame_valid(&f) || (size_t)f.nparams + 4 > cap;
                framed += (size_t)f.nparams + 4;
            } else {
                bad |= rc != 0 && rc != LSC_ESYNC && rc != LSC_EFRAME && rc != LSC_ETOOBIG;
                errors += rc == LSC_EFRAME || rc == LSC_ETOOBIG;
            }
        }
        size_t held = p.complete ? 0 : p.len;
        bad |= framed + p.discarded + held != n || p.errors < errors || held > 4 + 253;
        if (bad) {
            fail_msg("random input fails with seed %llu", (unsigned long long)seed);
        }
    }
}

/* ---- The rules, one by one ---- */

/* Feeds bytes and checks each return code. */
static void feed_expect(lsc_parser *p, const uint8_t *bytes, const int *rcs, size_t n,
                        lsc_frame *f)
{
    for (size_t i = 0; i < n; i++) {
        int rc = lsc_parser_feed(p, bytes[i], f);
        if (rc != rcs[i]) {
            fail_msg("byte %zu (0x%02X): returned %d, expected %d", i, bytes[i], rc, rcs[i]);
        }
    }
}

#define FEED(p, f, ...)                                                                  \
    do {                                                                                 \
        const uint8_t b_[] = {__VA_ARGS__};                                              \
        assert_int_equal(sizeof expect_ / sizeof expect_[0], sizeof b_);                 \
        feed_expect(p, b_, expect_, sizeof b_, f);                                       \
    } while (0)

static void check_counters(const lsc_parser *p, uint32_t frames, uint32_t discarded,
                           uint32_t errors)
{
    assert_int_equal(p->frames, frames);
    assert_int_equal(p->discarded, discarded);
    assert_int_equal(p->errors, errors);
}

static lsc_parser fresh(uint8_t *buf, size_t cap)
{
    lsc_parser p;
    assert_int_equal(lsc_parser_init(&p, buf, cap), 0);
    return p;
}

static void test_len_0x55_is_one_more_header_byte(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p = fresh(buf, sizeof buf);
    lsc_frame f;
    {
        const int expect_[] = {0, 0, LSC_ESYNC, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x55, 0x02, 0x07);
    }
    assert_int_equal(f.cmd, 7);
    assert_int_equal(f.nparams, 0);
    {
        const int expect_[] = {0, 0, LSC_ESYNC, LSC_ESYNC, LSC_ESYNC, 0, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x55, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    }
    assert_int_equal(f.cmd, 15);
    check_counters(&p, 2, 4, 0);
}

static void test_rescan_finds_frame_begun_inside_malformed_one(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p = fresh(buf, sizeof buf);
    lsc_frame f;
    /* a move whose count (0x55) contradicts LEN 8: that count byte began a stop frame */
    {
        const int expect_[] = {0, 0, 0, 0, LSC_EFRAME, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x08, 0x03, 0x55, 0x55, 0x02, 0x07);
    }
    assert_int_equal(f.cmd, 7);
    check_counters(&p, 1, 4, 1);
    /* the same inside a position read whose count fits neither shape */
    {
        const int expect_[] = {0, 0, 0, 0, LSC_EFRAME, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x06, 0x15, 0x55, 0x55, 0x02, 0x0F);
    }
    assert_int_equal(f.cmd, 15);
    check_counters(&p, 2, 8, 2);
}

static void test_len_below_2_is_malformed(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p = fresh(buf, sizeof buf);
    lsc_frame f;
    {
        const int expect_[] = {0, 0, LSC_EFRAME, 0, 0, LSC_EFRAME, 0, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x00, 0x55, 0x55, 0x01, 0x55, 0x55, 0x02, 0x07);
    }
    assert_int_equal(p.errors, 2);
    /* the rescan drops the first header byte, then the second one as noise */
    assert_int_equal(p.discarded, 6);
    assert_int_equal(p.frames, 1);
}

/* LEN that contradicts a known command is malformed; the lengths it allows are not. */
static void test_len_against_command(void **state)
{
    (void)state;
    static const struct {
        uint8_t len, cmd;
        int ok;
    } cases[] = {
        {7, 3, 0},   {8, 3, 1},   {0xFF, 3, 1}, {2, 3, 0},  {4, 6, 0},  {5, 6, 1},
        {6, 6, 0},   {2, 7, 1},   {3, 7, 0},    {5, 8, 1},  {2, 8, 0},  {5, 11, 1},
        {0xFF, 11, 0}, {2, 15, 1}, {3, 15, 0},  {4, 15, 1}, {5, 15, 0}, {3, 20, 0},
        {4, 20, 1},  {0xFF, 20, 1}, {3, 21, 0}, {4, 21, 1}, {2, 21, 0}, {2, 0, 1},
        {0xFF, 0x55, 1}, {3, 0xFF, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p = fresh(buf, sizeof buf);
        lsc_frame f;
        int rc = 0;
        const uint8_t bytes[] = {0x55, 0x55, cases[i].len, cases[i].cmd};
        for (size_t k = 0; k < sizeof bytes; k++) {
            rc = lsc_parser_feed(&p, bytes[k], &f);
        }
        int want = cases[i].ok ? (cases[i].len == 2 ? 1 : 0) : LSC_EFRAME;
        if (rc != want || p.errors != (uint32_t)!cases[i].ok) {
            fail_msg("LEN %u command %u: returned %d, expected %d", cases[i].len, cases[i].cmd,
                     rc, want);
        }
    }
}

/* The count byte of 3, 20 and 21 must agree with LEN (21: either shape). */
static void test_count_against_len(void **state)
{
    (void)state;
    static const struct {
        uint8_t len, cmd, count;
        int ok;
    } cases[] = {
        {8, 3, 1, 1},    {8, 3, 0, 0},    {8, 3, 2, 0},  {11, 3, 2, 1}, {11, 3, 1, 0},
        {0xFE, 3, 83, 1}, {0xFE, 3, 84, 0}, {4, 20, 1, 1}, {4, 20, 0, 0}, {4, 20, 2, 0},
        {0xFF, 20, 252, 1}, {0xFF, 20, 251, 0}, {9, 21, 6, 1},  /* request of 6 ids */
        {0x15, 21, 6, 1}, /* reply of 6 servos */
        {9, 21, 2, 1},    /* reply of 2 servos: also LEN 9 */
        {9, 21, 3, 0},    {4, 21, 1, 1},   {6, 21, 1, 1}, {6, 21, 3, 1}, {6, 21, 0, 0},
        {6, 21, 2, 0},    {0xFF, 21, 84, 1}, {0xFF, 21, 252, 1}, {0xFF, 21, 85, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p = fresh(buf, sizeof buf);
        lsc_frame f;
        int rc = 0;
        const uint8_t bytes[] = {0x55, 0x55, cases[i].len, cases[i].cmd, cases[i].count};
        for (size_t k = 0; k < sizeof bytes; k++) {
            rc = lsc_parser_feed(&p, bytes[k], &f);
        }
        int want = cases[i].ok ? 0 : LSC_EFRAME;
        if (rc != want || p.errors != (uint32_t)!cases[i].ok) {
            fail_msg("LEN %u command %u count %u: returned %d, expected %d", cases[i].len,
                     cases[i].cmd, cases[i].count, rc, want);
        }
        if (cases[i].ok) { /* the rest of the frame completes it */
            for (size_t k = 5; k < (size_t)cases[i].len + 2u; k++) {
                rc = lsc_parser_feed(&p, 0x55, &f);
            }
            assert_int_equal(rc, 1);
            assert_int_equal(f.nparams, cases[i].len - 2);
        }
    }
}

/* Unknown commands take any LEN up to what the buffer holds; longer is LSC_ETOOBIG. */
static void test_unknown_commands_up_to_capacity(void **state)
{
    (void)state;
    for (size_t cap = 4; cap <= 300; cap++) {
        uint8_t buf[300];
        lsc_parser p = fresh(buf, cap);
        size_t fits = cap < LSC_FRAME_MAX ? cap : LSC_FRAME_MAX;
        uint8_t frame[LSC_FRAME_MAX] = {0x55, 0x55, (uint8_t)(fits - 2), 0x63};
        if (fits - 2 == 0x55 || fits - 1 == 0x55) {
            continue; /* not a LEN */
        }
        for (size_t i = 4; i < fits; i++) {
            frame[i] = (uint8_t)(i * 7);
        }
        lsc_frame f;
        parse_exactly(&p, frame, fits, &f);
        if (cap < LSC_FRAME_MAX) {
            frame[2] = (uint8_t)(fits - 1); /* one byte too long */
            const int expect_[] = {0, 0, LSC_ETOOBIG};
            feed_expect(&p, frame, expect_, 3, &f);
            assert_int_equal(p.errors, 1);
            assert_int_equal(p.discarded, 3); /* rescanned: the header bytes and LEN */
            assert_int_equal(p.len, 0);
        }
    }
}

/* A known frame longer than a small buffer is LSC_ETOOBIG; its body is then
 * noise, and the frame after it is found. */
static void test_too_big_for_small_buffer(void **state)
{
    (void)state;
    uint8_t buf[10];
    lsc_parser p = fresh(buf, sizeof buf);
    lsc_frame f;
    {
        const int expect_[] = {0, 0, LSC_ETOOBIG, LSC_ESYNC, LSC_ESYNC, LSC_ESYNC,
                               LSC_ESYNC, LSC_ESYNC, LSC_ESYNC, LSC_ESYNC, LSC_ESYNC,
                               LSC_ESYNC, LSC_ESYNC, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x0B, 0x03, 0x02, 0x20, 0x03, 0x02, 0xB0, 0x04, 0x09, 0xFC,
             0x08, 0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xD0, 0x07);
    }
    assert_int_equal(f.cmd, 3);
    check_counters(&p, 1, 13, 1);
}

static void test_counters_and_return_codes(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p = fresh(buf, sizeof buf);
    assert_int_equal(p.frames + p.discarded + p.errors, 0);
    lsc_frame f;
    {
        const int expect_[] = {LSC_ESYNC, LSC_ESYNC, 0, 0, 0, LSC_EFRAME, 0, 0, 0, 1};
        FEED(&p, &f, 0x00, 0xAA, 0x55, 0x55, 0x03, 0x07, 0x55, 0x55, 0x02, 0x07);
    }
    assert_int_equal(p.frames, 1);
    assert_int_equal(p.errors, 1);
    assert_int_equal(p.discarded, 2 + 4);
    assert_true(p.complete);
    /* the frame stays readable until the next feed; the next byte starts anew */
    assert_ptr_equal(f.params, &buf[4]);
    {
        const int expect_[] = {0, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x02, 0x0F);
    }
    assert_int_equal(f.cmd, 15);
    assert_int_equal(p.frames, 2);
    assert_int_equal(p.discarded, 6);
}

static void test_reset(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p = fresh(buf, sizeof buf);
    lsc_frame f;
    {
        const int expect_[] = {0, 0, 0, 0, 0};
        FEED(&p, &f, 0x55, 0x55, 0x08, 0x03, 0x01);
    }
    lsc_parser_reset(&p);
    assert_int_equal(p.discarded, 5);
    assert_int_equal(p.len, 0);
    {
        const int expect_[] = {0, 0, 0, 1};
        FEED(&p, &f, 0x55, 0x55, 0x02, 0x07);
    }
    lsc_parser_reset(&p); /* after a complete frame nothing is discarded */
    assert_int_equal(p.discarded, 5);
    assert_int_equal(p.frames, 1);
    assert_false(p.complete);
    lsc_parser_reset(&p);
    assert_int_equal(p.discarded, 5);
    lsc_parser_reset(NULL); /* harmless */
}

static void test_null_and_small_buffers(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p;
    lsc_frame f;
    assert_int_equal(lsc_parser_init(NULL, buf, sizeof buf), LSC_EINVAL);
    assert_int_equal(lsc_parser_init(&p, NULL, sizeof buf), LSC_EINVAL);
    assert_int_equal(lsc_parser_feed(&p, 0x55, &f), LSC_EINVAL);
    assert_int_equal(lsc_parser_init(&p, buf, LSC_FRAME_MIN - 1), LSC_EINVAL);
    assert_int_equal(lsc_parser_feed(&p, 0x55, &f), LSC_EINVAL);
    assert_int_equal(p.frames + p.discarded + p.errors, 0);
    lsc_parser_reset(&p);
    assert_int_equal(lsc_parser_feed(&p, 0x55, &f), LSC_EINVAL);

    /* the smallest buffer holds LEN 2 frames only */
    assert_int_equal(lsc_parser_init(&p, buf, LSC_FRAME_MIN), 0);
    {
        const int expect_[] = {0, 0, 0, 1, 0, 0, LSC_ETOOBIG};
        FEED(&p, &f, 0x55, 0x55, 0x02, 0x07, 0x55, 0x55, 0x03);
    }
    assert_int_equal(lsc_parser_feed(NULL, 0x55, &f), LSC_EINVAL);
    assert_int_equal(lsc_parser_feed(&p, 0x55, NULL), LSC_EINVAL);
    assert_int_equal(p.frames, 1);
    assert_int_equal(p.errors, 1);
}

/* Feeds in[0..n) whole to the bulk path and byte by byte to another parser
 * (both of capacity cap), fails if they differ; returns the bulk path's
 * results in *t. */
static void bulk_as_bytes(const uint8_t *in, size_t n, size_t cap, trace *t)
{
    static trace byte;
    uint8_t buf1[LSC_FRAME_MAX], buf2[LSC_FRAME_MAX];
    lsc_parser p1, p2;
    assert_int_equal(lsc_parser_init(&p1, buf1, cap), 0);
    assert_int_equal(lsc_parser_init(&p2, buf2, cap), 0);
    byte.n = 0;
    t->n = 0;
    assert_int_equal(feed_all(false, &p1, in, n, record, &byte), 0);
    assert_int_equal(feed_all(true, &p2, in, n, record, t), 0);
    assert_int_equal(differ(&byte, &p1, t, &p2), 0);
}

/* The cases the bulk path decides at once, with the whole frame in its input
 * (a noise byte; a whole frame checked in one go against its command and
 * copied by size): each as byte at a time. */
static void test_bulk_whole_frames(void **state)
{
    (void)state;
    static trace t;
    /* a list whose count is 0, LEN one item short of the smallest
     * (LEN - lo wraps to -w, as w * (0 - 1) does): malformed at the command */
    const uint8_t move0[] = {0x55, 0x55, 0x05, 0x03, 0x00, 0x00, 0x00};
    bulk_as_bytes(move0, sizeof move0, LSC_FRAME_MAX, &t);
    assert_true(t.n >= 1 && t.at[0] == 3 && t.rc[0] == LSC_EFRAME);
    const uint8_t read0[] = {0x55, 0x55, 0x02, 0x15, 0x55, 0x55, 0x03, 0x15, 0x00, 0x55};
    bulk_as_bytes(read0, sizeof read0, LSC_FRAME_MAX, &t);
    assert_true(t.n >= 2 && t.rc[0] == LSC_EFRAME && t.rc[1] == LSC_EFRAME);
    /* both shapes of a position reply and of the battery, a count that
     * contradicts LEN, noise after a frame, a frame at the very end */
    const uint8_t mixed[] = {0x55, 0x55, 0x06, 0x15, 0x01, 0x01, 0xF4, 0x01, /* N=1, 3N+3 */
                             0x55, 0x55, 0x04, 0x15, 0x01, 0x07,             /* N=1, N+3 */
                             0x55, 0x55, 0x04, 0x15, 0x02, 0x07,             /* N=2: bad */
                             0x00, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D,       /* battery */
                             0x55, 0x55, 0x02, 0x0F, 0x13, 0x55, 0x55, 0x05, 0x06, 0x01,
                             0x02, 0x00};
    bulk_as_bytes(mixed, sizeof mixed, LSC_FRAME_MAX, &t);
    const size_t at[] = {7, 13, 18, 19, 20, 26, 30, 31, 38};
    const int rc[] = {1, 1, LSC_EFRAME, LSC_ESYNC, LSC_ESYNC, 1, 1, LSC_ESYNC, 1};
    assert_int_equal(t.n, 9);
    for (size_t i = 0; i < 9; i++) {
        assert_int_equal(t.at[i], at[i]);
        assert_int_equal(t.rc[i], rc[i]);
    }
    /* frames of every copy size (4..8, 9..16, 17..257 bytes), in a buffer
     * just big enough and one byte too small */
    static uint8_t in[2 * LSC_FRAME_MAX];
    uint8_t params[LSC_PARAMS_MAX];
    for (size_t i = 0; i < sizeof params; i++) {
        params[i] = (uint8_t)(i * 7u + 1u);
    }
    const size_t sizes[] = {4, 5, 8, 9, 16, 17, 18, 100, LSC_FRAME_MAX};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        size_t size = sizes[k];
        if (size == LSC_HEADER_BYTE + 2u) {
            continue; /* a LEN of 0x55 cannot be sent */
        }
        int n = lsc_encode_frame(in, sizeof in, 0x22, params, size - 4);
        assert_int_equal(n, (int)size);
        int m = lsc_encode_frame(&in[n], sizeof in - (size_t)n, 0x22, params, size - 4);
        assert_int_equal(m, (int)size);
        bulk_as_bytes(in, 2 * size, size, &t);
        assert_true(t.n == 2 && t.at[0] == size - 1 && t.rc[0] == 1 && t.rc[1] == 1);
        if (size > LSC_FRAME_MIN) {
            bulk_as_bytes(in, 2 * size, size - 1, &t);
            assert_true(t.n >= 1 && t.at[0] == 2 && t.rc[0] == LSC_ETOOBIG);
        }
    }
}

/* lsc_parser_feed_buf's contract: where it stops, what it consumes, and its
 * arguments. */
static void test_bulk_contract(void **state)
{
    (void)state;
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser p;
    lsc_frame f;
    int rc = 99;
    lsc_parser_init(&p, buf, sizeof buf);
    /* noise, a frame, half of the next: one result per call */
    const uint8_t in[] = {0x01, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D, 0x55, 0x55, 0x02};
    assert_int_equal(lsc_parser_feed_buf(&p, in, sizeof in, &f, &rc), 1);
    assert_int_equal(rc, LSC_ESYNC);
    assert_int_equal(lsc_parser_feed_buf(&p, &in[1], sizeof in - 1, &f, &rc), 6);
    assert_int_equal(rc, 1);
    assert_int_equal(f.cmd, 0x0F);
    assert_int_equal(f.nparams, 2);
    assert_int_equal(f.params[0], 0x4C);
    assert_int_equal(lsc_parser_feed_buf(&p, &in[7], sizeof in - 7, &f, &rc), 3);
    assert_int_equal(rc, 0);
    assert_int_equal(p.len, 3);
    /* nothing to feed: nothing happens */
    rc = 99;
    assert_int_equal(lsc_parser_feed_buf(&p, NULL, 0, &f, &rc), 0);
    assert_int_equal(rc, 0);
    assert_int_equal(lsc_parser_feed_buf(&p, in, 0, &f, &rc), 0);
    assert_int_equal(p.len, 3);
    lsc_parser q;
    uint8_t qbuf[LSC_FRAME_MIN];
    lsc_parser_init(&q, qbuf, sizeof qbuf); /* between frames too */
    rc = 99;
    assert_int_equal(lsc_parser_feed_buf(&q, in, 0, &f, &rc), 0);
    assert_int_equal(rc, 0);
    assert_int_equal(q.len + q.discarded, 0);
    /* the rest of that frame: 07 ends it */
    const uint8_t stop = 0x07;
    assert_int_equal(lsc_parser_feed_buf(&p, &stop, 1, &f, &rc), 1);
    assert_int_equal(rc, 1);
    assert_int_equal(f.cmd, 0x07);
    assert_int_equal(p.frames, 2);
    assert_int_equal(p.discarded, 1);

    /* a malformed frame stops the feed at the byte that shows it */
    const uint8_t bad[] = {0x55, 0x55, 0x03, 0x07, 0x55};
    assert_int_equal(lsc_parser_feed_buf(&p, bad, sizeof bad, &f, &rc), 4);
    assert_int_equal(rc, LSC_EFRAME);

    /* what lsc_parser_feed refuses: one byte at a time, nothing changes */
    lsc_parser_init(&p, buf, sizeof buf);
    assert_int_equal(lsc_parser_feed_buf(NULL, in, sizeof in, &f, &rc), 1);
    assert_int_equal(rc, LSC_EINVAL);
    rc = 0;
    assert_int_equal(lsc_parser_feed_buf(&p, in, sizeof in, NULL, &rc), 1);
    assert_int_equal(rc, LSC_EINVAL);
    /* no input, or nowhere to say what happened: everything, unread */
    rc = 0;
    assert_int_equal(lsc_parser_feed_buf(&p, NULL, 3, &f, &rc), 3);
    assert_int_equal(rc, LSC_EINVAL);
    assert_int_equal(lsc_parser_feed_buf(&p, in, sizeof in, &f, NULL), sizeof in);
    assert_int_equal(lsc_parser_feed_buf(NULL, NULL, 0, NULL, NULL), 0);
    assert_int_equal(p.len + p.frames + p.discarded + p.errors, 0);

    /* an uninitialised parser refuses byte by byte, as lsc_parser_feed does */
    lsc_parser_init(&p, buf, LSC_FRAME_MIN - 1);
    rc = 0;
    assert_int_equal(lsc_parser_feed_buf(&p, in, sizeof in, &f, &rc), 1);
    assert_int_equal(rc, LSC_EINVAL);
    assert_int_equal(p.len + p.frames + p.discarded + p.errors, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_property_a_valid_frames_decode_exactly),
        cmocka_unit_test(test_property_a_every_chunking),
        cmocka_unit_test(test_property_b_garbage_then_frame),
        cmocka_unit_test(test_property_c_reset_then_frame),
        cmocka_unit_test(test_bulk_equals_byte_at_a_time),
        cmocka_unit_test(test_bulk_contract),
        cmocka_unit_test(test_bulk_whole_frames),
        cmocka_unit_test(test_any_input_gives_only_valid_frames),
        cmocka_unit_test(test_len_0x55_is_one_more_header_byte),
        cmocka_unit_test(test_rescan_finds_frame_begun_inside_malformed_one),
        cmocka_unit_test(test_len_below_2_is_malformed),
        cmocka_unit_test(test_len_against_command),
        cmocka_unit_test(test_count_against_len),
        cmocka_unit_test(test_unknown_commands_up_to_capacity),
        cmocka_unit_test(test_too_big_for_small_buffer),
        cmocka_unit_test(test_counters_and_return_codes),
        cmocka_unit_test(test_reset),
        cmocka_unit_test(test_null_and_small_buffers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
