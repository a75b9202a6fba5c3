/* The bus-servo parser (include/lsc/lx.h): frames in any chunks, noise, bad
 * checksums (never believed: counted, discarded, and the frame that began
 * inside them found), malformed headers, the host's echo, reset. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/lx.h"
#include "lx_vectors.h"

/* Feeds n bytes; returns how many frames came out (copied to frames[] as
 * whole wire frames, each LSC_LX_FRAME_MAX apart) and checks no byte gave an
 * error unless errors_ok. */
static size_t feed_all(lsc_lx_parser *p, const uint8_t *bytes, size_t n, uint8_t *frames,
                       size_t cap, bool errors_ok)
{
    size_t got = 0;
    for (size_t i = 0; i < n; i++) {
        lsc_lx_frame f;
        int r = lsc_lx_parser_feed(p, bytes[i], &f);
        if (r == 1) {
            assert_true(got < cap);
            uint8_t out[LSC_LX_FRAME_MAX];
            int len = lsc_lx_encode_frame(out, sizeof out, f.id, f.cmd, f.params, f.nparams);
            assert_true(len > 0);
            memcpy(&frames[got * LSC_LX_FRAME_MAX], out, (size_t)len);
            got++;
        } else if (!errors_ok) {
            assert_int_equal(r, 0);
        }
    }
    return got;
}

/* Every vector, one after the other, then fed again in one stream: each is
 * found, nothing is discarded. */
static void test_stream_of_vectors(void **state)
{
    (void)state;
    uint8_t stream[LX_NVECTORS * LSC_LX_FRAME_MAX];
    uint8_t frames[LX_NVECTORS * LSC_LX_FRAME_MAX];
    size_t n = 0;
    for (size_t k = 0; k < LX_NVECTORS; k++) {
        memcpy(&stream[n], lx_vectors[k].bytes, lx_vectors[k].n);
        n += lx_vectors[k].n;
    }
    lsc_lx_parser p;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(feed_all(&p, stream, n, frames, LX_NVECTORS, false), LX_NVECTORS);
    for (size_t k = 0; k < LX_NVECTORS; k++) {
        assert_memory_equal(&frames[k * LSC_LX_FRAME_MAX], lx_vectors[k].bytes,
                            lx_vectors[k].n);
    }
    assert_int_equal(p.frames, LX_NVECTORS);
    assert_int_equal(p.discarded, 0);
    assert_int_equal(p.errors, 0);
}

/* Noise without 0x55 before a frame: each byte LSC_ESYNC, then the frame. */
static void test_noise_then_frame(void **state)
{
    (void)state;
    lsc_lx_parser p;
    lsc_lx_frame f;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    for (unsigned b = 0; b < 256; b++) {
        if (b != 0x55) {
            assert_int_equal(lsc_lx_parser_feed(&p, (uint8_t)b, &f), LSC_ESYNC);
        }
    }
    assert_int_equal(p.discarded, 255);
    assert_int_equal(p.errors, 0);
    uint8_t frames[LSC_LX_FRAME_MAX];
    assert_int_equal(feed_all(&p, lx_vectors[0].bytes, lx_vectors[0].n, frames, 1, false), 1);
}

/* A single flipped bit anywhere in a frame never yields a frame (the
 * checksum, the header or the shapes catch it), and the next good frame is
 * found: a position reply with a flipped bit is never believed. */
static void test_flipped_bits_never_believed(void **state)
{
    (void)state;
    for (size_t k = 0; k < LX_NVECTORS; k++) {
        const lx_vector *v = &lx_vectors[k];
        for (size_t at = 0; at < v->n; at++) {
            for (unsigned bit = 0; bit < 8; bit++) {
                uint8_t bad[LSC_LX_FRAME_MAX];
                uint8_t frames[2 * LSC_LX_FRAME_MAX];
                memcpy(bad, v->bytes, v->n);
                bad[at] = (uint8_t)(bad[at] ^ (1u << bit));
                lsc_lx_parser p;
                assert_int_equal(lsc_lx_parser_init(&p), 0);
                assert_int_equal(feed_all(&p, bad, v->n, frames, 2, true), 0);
                /* the line then carries a good frame */
                assert_int_equal(feed_all(&p, lx_vectors[16].bytes, lx_vectors[16].n, frames, 2,
                                          true),
                                 1);
                assert_memory_equal(frames, lx_vectors[16].bytes, lx_vectors[16].n);
            }
        }
    }
}

/* A bad checksum: LSC_EFRAME at the last byte, counted in bad_checksums and
 * errors, its bytes discarded. */
static void test_bad_checksum_counted(void **state)
{
    (void)state;
    const lx_vector *v = &lx_vectors[16]; /* a position reply, -20 */
    uint8_t bad[LSC_LX_FRAME_MAX];
    memcpy(bad, v->bytes, v->n);
    bad[v->n - 1u] ^= 0x01u;
    lsc_lx_parser p;
    lsc_lx_frame f;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    for (size_t i = 0; i + 1u < v->n; i++) {
        assert_int_equal(lsc_lx_parser_feed(&p, bad[i], &f), 0);
    }
    assert_int_equal(lsc_lx_parser_feed(&p, bad[v->n - 1u], &f), LSC_EFRAME);
    assert_int_equal(p.bad_checksums, 1);
    assert_int_equal(p.errors, 1);
    assert_int_equal(p.discarded, v->n);
    assert_int_equal(p.frames, 0);
    assert_int_equal(p.len, 0);
}

/* A frame that began inside a candidate whose checksum failed is still
 * found: 55 55 07 07 07 (a MOVE_TIME_WAIT_WRITE to 7) swallows the real
 * frame's first bytes, fails, and the rescan keeps them. */
static void test_frame_inside_bad_candidate(void **state)
{
    (void)state;
    const lx_vector *v = &lx_vectors[30]; /* id_read request 55 55 01 03 0E ED */
    uint8_t stream[32];
    size_t n = 0;
    static const uint8_t head[] = {0x55, 0x55, 0x07, 0x07, 0x07};
    memcpy(stream, head, sizeof head);
    n += sizeof head;
    memcpy(&stream[n], v->bytes, v->n);
    n += v->n;
    lsc_lx_parser p;
    uint8_t frames[2 * LSC_LX_FRAME_MAX];
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(feed_all(&p, stream, n, frames, 2, true), 1);
    assert_memory_equal(frames, v->bytes, v->n);
    assert_int_equal(p.bad_checksums, 1);
    assert_int_equal(p.discarded, sizeof head);
}

/* Malformed at each header position: LSC_EFRAME (id 255, LEN outside 3..7,
 * an unknown command, a LEN the command does not have) or LSC_ESYNC (not a
 * header byte). */
static void test_malformed_headers(void **state)
{
    (void)state;
    static const struct {
        uint8_t bytes[5];
        uint8_t n;
        int why;
    } t[] = {
        {{0x55, 0x00}, 2, LSC_ESYNC},
        {{0x55, 0x55, 0xFF}, 3, LSC_EFRAME},
        {{0x55, 0x55, 0x01, 0x02}, 4, LSC_EFRAME},
        {{0x55, 0x55, 0x01, 0x08}, 4, LSC_EFRAME},
        {{0x55, 0x55, 0x01, 0x03, 0x09}, 5, LSC_EFRAME}, /* 9: no command */
        {{0x55, 0x55, 0x01, 0x04, 0x01}, 5, LSC_EFRAME}, /* 1 is LEN 7 */
        {{0x55, 0x55, 0x01, 0x06, 0x1C}, 5, LSC_EFRAME}, /* 28 is 3 or 5 */
        {{0x55, 0x55, 0x01, 0x07, 0x0B}, 5, LSC_EFRAME}, /* 11 is 3 */
        {{0x55, 0x55, 0x01, 0x03, 0x00}, 5, LSC_EFRAME},
    };
    for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
        lsc_lx_parser p;
        lsc_lx_frame f;
        assert_int_equal(lsc_lx_parser_init(&p), 0);
        for (size_t i = 0; i + 1u < t[k].n; i++) {
            assert_int_equal(lsc_lx_parser_feed(&p, t[k].bytes[i], &f), 0);
        }
        assert_int_equal(lsc_lx_parser_feed(&p, t[k].bytes[t[k].n - 1u], &f), t[k].why);
        assert_int_equal(p.errors, t[k].why == LSC_EFRAME ? 1u : 0u);
        /* and the next frame is found */
        uint8_t frames[LSC_LX_FRAME_MAX];
        assert_int_equal(feed_all(&p, lx_vectors[5].bytes, lx_vectors[5].n, frames, 1, false),
                         1);
    }
}

/* Id 0x55 (85) is an id like any other; a 0x55 of noise before a frame is
 * discarded and the frame found. */
static void test_id_0x55(void **state)
{
    (void)state;
    uint8_t fr[LSC_LX_FRAME_MAX], frames[2 * LSC_LX_FRAME_MAX], stream[16];
    assert_int_equal(lsc_lx_encode_request(fr, sizeof fr, 0x55, LSC_LX_POS_READ), 6);
    lsc_lx_parser p;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(feed_all(&p, fr, 6, frames, 2, false), 1);
    assert_memory_equal(frames, fr, 6);
    /* 55 then 55 55 03 04 ... (a frame to id 3): 55 55 55 03 reads as id 0x55
     * LEN 3 until the command 0x04 refuses it */
    assert_int_equal(lsc_lx_encode_load(fr, sizeof fr, 3, LSC_LX_LOAD_WRITE, true), 7);
    stream[0] = 0x55;
    memcpy(&stream[1], fr, 7);
    assert_int_equal(feed_all(&p, stream, 8, frames, 2, true), 1);
    assert_memory_equal(frames, fr, 7);
    /* 55 55 55 55 then a frame */
    static const uint8_t four[4] = {0x55, 0x55, 0x55, 0x55};
    assert_int_equal(feed_all(&p, four, 4, frames, 2, true), 0);
    assert_int_equal(feed_all(&p, fr, 7, frames, 2, true), 1);
    assert_memory_equal(frames, fr, 7);
}

/* The host's echo: expected, it is dropped and the reply returned. */
static void test_echo_dropped(void **state)
{
    (void)state;
    uint8_t req[LSC_LX_FRAME_MAX], rep[LSC_LX_FRAME_MAX], frames[2 * LSC_LX_FRAME_MAX];
    int nreq = lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ);
    int nrep = lsc_lx_encode_position(rep, sizeof rep, 1, 500);
    lsc_lx_parser p;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)nreq), 0);
    assert_int_equal(feed_all(&p, req, (size_t)nreq, frames, 2, false), 0);
    assert_int_equal(p.echoes, 1);
    assert_int_equal(p.frames, 0);
    assert_int_equal(feed_all(&p, rep, (size_t)nrep, frames, 2, false), 1);
    assert_memory_equal(frames, rep, (size_t)nrep);
    /* the expectation ended: the same bytes later are a frame */
    assert_int_equal(feed_all(&p, req, (size_t)nreq, frames, 2, false), 1);
    assert_int_equal(p.echoes, 1);
}

/* On a line without an echo the reply comes first: returned, and the
 * expectation ends, so the request's bytes later are not dropped. */
static void test_no_echo_line(void **state)
{
    (void)state;
    uint8_t req[LSC_LX_FRAME_MAX], rep[LSC_LX_FRAME_MAX], frames[2 * LSC_LX_FRAME_MAX];
    int nreq = lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ);
    int nrep = lsc_lx_encode_position(rep, sizeof rep, 1, 500);
    lsc_lx_parser p;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)nreq), 0);
    assert_int_equal(feed_all(&p, rep, (size_t)nrep, frames, 2, false), 1);
    assert_int_equal(feed_all(&p, req, (size_t)nreq, frames, 2, false), 1);
    assert_int_equal(p.echoes, 0);
    /* a broken echo is no echo: a bad checksum, then the reply */
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)nreq), 0);
    uint8_t bad[LSC_LX_FRAME_MAX];
    memcpy(bad, req, (size_t)nreq);
    bad[4] ^= 0x40u; /* 0x1C -> 0x5C: no command */
    assert_int_equal(feed_all(&p, bad, (size_t)nreq, frames, 2, true), 0);
    assert_int_equal(feed_all(&p, rep, (size_t)nrep, frames, 2, false), 1);
    assert_int_equal(p.echoes, 0);
    /* an echo of the same length but other bytes is a frame */
    uint8_t other[LSC_LX_FRAME_MAX];
    int nother = lsc_lx_encode_request(other, sizeof other, 2, LSC_LX_POS_READ);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)nreq), 0);
    assert_int_equal(feed_all(&p, other, (size_t)nother, frames, 2, false), 1);
}

static void test_expect_echo_refuses(void **state)
{
    (void)state;
    uint8_t req[LSC_LX_FRAME_MAX];
    int n = lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ);
    lsc_lx_parser p;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(lsc_lx_parser_expect_echo(NULL, req, (size_t)n), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, NULL, (size_t)n), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, 5), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, 11), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, 7), LSC_EINVAL); /* LEN says 6 */
    req[5] ^= 1u;
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)n), LSC_EINVAL);
    assert_int_equal(p.echo_len, 0);
}

static void test_reset_and_null(void **state)
{
    (void)state;
    lsc_lx_parser p;
    lsc_lx_frame f;
    assert_int_equal(lsc_lx_parser_init(NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(lsc_lx_parser_feed(NULL, 0x55, &f), LSC_EINVAL);
    assert_int_equal(lsc_lx_parser_feed(&p, 0x55, NULL), LSC_EINVAL);
    lsc_lx_parser_reset(NULL);
    /* a partial frame: its bytes discarded */
    assert_int_equal(lsc_lx_parser_feed(&p, 0x55, &f), 0);
    assert_int_equal(lsc_lx_parser_feed(&p, 0x55, &f), 0);
    assert_int_equal(lsc_lx_parser_feed(&p, 0x01, &f), 0);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, lx_vectors[5].bytes, lx_vectors[5].n), 0);
    lsc_lx_parser_reset(&p);
    assert_int_equal(p.discarded, 3);
    assert_int_equal(p.len, 0);
    assert_int_equal(p.echo_len, 0); /* the echo expectation ends too */
    /* after a whole frame nothing is discarded */
    uint8_t frames[LSC_LX_FRAME_MAX];
    assert_int_equal(feed_all(&p, lx_vectors[5].bytes, lx_vectors[5].n, frames, 1, false), 1);
    lsc_lx_parser_reset(&p);
    assert_int_equal(p.discarded, 3);
    /* a reset in the middle of a frame: the frame is lost, the next one found */
    assert_int_equal(feed_all(&p, lx_vectors[0].bytes, 5, frames, 1, false), 0);
    lsc_lx_parser_reset(&p);
    assert_int_equal(feed_all(&p, lx_vectors[0].bytes, lx_vectors[0].n, frames, 1, false), 1);
}

/* xorshift, for the property below */
static uint32_t rnd(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (uint32_t)(*s >> 32);
}

/* Any sequence of valid frames with noise (no 0x55) between them decodes to
 * exactly those frames. */
static void test_random_streams(void **state)
{
    (void)state;
    uint64_t seed = 0x9E3779B97F4A7C15u;
    for (int round = 0; round < 2000; round++) {
        uint8_t stream[8 * (LSC_LX_FRAME_MAX + 3)], want[8 * LSC_LX_FRAME_MAX];
        uint8_t frames[8 * LSC_LX_FRAME_MAX];
        size_t n = 0, nf = 1 + rnd(&seed) % 8;
        for (size_t k = 0; k < nf; k++) {
            for (uint32_t noise = rnd(&seed) % 4; noise > 0; noise--) {
                uint8_t b = (uint8_t)rnd(&seed);
                stream[n++] = b == 0x55 ? 0x54 : b;
            }
            const lx_vector *v = &lx_vectors[rnd(&seed) % LX_NVECTORS];
            uint8_t params[LSC_LX_PARAMS_MAX];
            for (size_t i = 0; i < LSC_LX_PARAMS_MAX; i++) {
                params[i] = (uint8_t)rnd(&seed);
            }
            /* random values, random id: the raw encoder checks shapes only */
            uint8_t id = (uint8_t)(rnd(&seed) % 254);
            int len = lsc_lx_encode_frame(&stream[n], LSC_LX_FRAME_MAX, id, v->cmd, params,
                                          v->n - 6u);
            assert_int_equal(len, v->n);
            memcpy(&want[k * LSC_LX_FRAME_MAX], &stream[n], (size_t)len);
            n += (size_t)len;
        }
        lsc_lx_parser p;
        assert_int_equal(lsc_lx_parser_init(&p), 0);
        assert_int_equal(feed_all(&p, stream, n, frames, 8, true), nf);
        for (size_t k = 0; k < nf; k++) {
            size_t len = frames[k * LSC_LX_FRAME_MAX + 3] + 3u;
            assert_memory_equal(&frames[k * LSC_LX_FRAME_MAX], &want[k * LSC_LX_FRAME_MAX], len);
        }
        assert_int_equal(p.errors, 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stream_of_vectors),
        cmocka_unit_test(test_noise_then_frame),
        cmocka_unit_test(test_flipped_bits_never_believed),
        cmocka_unit_test(test_bad_checksum_counted),
        cmocka_unit_test(test_frame_inside_bad_candidate),
        cmocka_unit_test(test_malformed_headers),
        cmocka_unit_test(test_id_0x55),
        cmocka_unit_test(test_echo_dropped),
        cmocka_unit_test(test_no_echo_line),
        cmocka_unit_test(test_expect_echo_refuses),
        cmocka_unit_test(test_reset_and_null),
        cmocka_unit_test(test_random_streams),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
