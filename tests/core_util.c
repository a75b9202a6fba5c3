#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "core_util.h"

void rng_seed(test_rng *r, uint64_t seed)
{
    r->state = seed * 0x9E3779B97F4A7C15u + 1u; /* never 0 */
}

uint32_t rng_next(test_rng *r)
{
    uint64_t x = r->state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    r->state = x;
    return (uint32_t)((x * 0x2545F4914F6CDD1Du) >> 32);
}

uint32_t rng_below(test_rng *r, uint32_t n)
{
    return (uint32_t)(((uint64_t)rng_next(r) * n) >> 32);
}

int cmd_known(uint8_t cmd)
{
    static const uint8_t known[] = {3, 6, 7, 8, 11, 15, 20, 21};
    return memchr(known, cmd, sizeof known) != NULL;
}

/* A count of list items in 1..max, often small, sometimes anything. */
static uint32_t random_count(test_rng *r, uint32_t max)
{
    return 1u + rng_below(r, rng_below(r, 4) == 0 ? max : (max < 6 ? max : 6));
}

/* 55 55 LEN cmd, then n random parameter bytes; returns the frame length. */
static size_t header(test_rng *r, uint8_t *out, uint8_t cmd, size_t n)
{
    out[0] = 0x55;
    out[1] = 0x55;
    out[2] = (uint8_t)(n + 2);
    out[3] = cmd;
    for (size_t i = 0; i < n; i++) {
        out[4 + i] = (uint8_t)rng_next(r);
    }
    return n + 4;
}

/* A random frame of the kind into frame; may be longer than max. */
static size_t generate(test_rng *r, int kind, uint8_t *frame, size_t max)
{
    size_t len;
    uint32_t n;
    switch (kind) {
    case KIND_MOVE:
        n = random_count(r, LSC_MOVE_MAX);
        len = header(r, frame, 3, 3 + 3 * n);
        frame[4] = (uint8_t)n;
        break;
    case KIND_GROUP_RUN: len = header(r, frame, 6, 3); break;
    case KIND_GROUP_STOP: len = header(r, frame, 7, 0); break;
    case KIND_GROUP_COMPLETE: len = header(r, frame, 8, 3); break;
    case KIND_GROUP_SPEED: len = header(r, frame, 11, 3); break;
    case KIND_BATTERY_REQUEST: len = header(r, frame, 15, 0); break;
    case KIND_BATTERY_REPLY: len = header(r, frame, 15, 2); break;
    case KIND_UNLOAD:
    case KIND_POS_REQUEST:
        do {
            n = random_count(r, 252);
        } while (n == 82); /* LEN 0x55 */
        len = header(r, frame, kind == KIND_UNLOAD ? 20 : 21, 1 + n);
        frame[4] = (uint8_t)n;
        break;
    case KIND_POS_REPLY:
        n = random_count(r, LSC_READ_MAX);
        len = header(r, frame, 21, 1 + 3 * n);
        frame[4] = (uint8_t)n;
        break;
    default: {
        uint8_t cmd;
        do {
            cmd = (uint8_t)rng_next(r);
        } while (cmd_known(cmd));
        size_t most = (max < LSC_FRAME_MAX ? max : LSC_FRAME_MAX) - 4; /* parameters */
        do {
            n = rng_below(r, 4) == 0 ? rng_below(r, (uint32_t)most + 1) : rng_below(r, 8);
        } while (n > most || n + 2 == 0x55);
        len = header(r, frame, cmd, n);
        break;
    }
    }
    return len;
}

size_t random_frame_of(test_rng *r, int kind, uint8_t *out, size_t max)
{
    uint8_t frame[LSC_FRAME_MAX];
    size_t len = generate(r, kind, frame, max);
    if (len > max) {
        len = generate(r, KIND_UNKNOWN, frame, 4); /* too long for the caller: 4 bytes */
    }
    memcpy(out, frame, len);
    return len;
}

size_t random_frame(test_rng *r, uint8_t *out, size_t max)
{
    return random_frame_of(r, (int)rng_below(r, KIND_COUNT), out, max);
}

size_t frame_bytes(const lsc_frame *f, uint8_t *out)
{
    out[0] = 0x55;
    out[1] = 0x55;
    out[2] = (uint8_t)(f->nparams + 2);
    out[3] = f->cmd;
    memcpy(&out[4], f->params, f->nparams);
    return (size_t)f->nparams + 4;
}

void parse_exactly(lsc_parser *p, const uint8_t *bytes, size_t n, lsc_frame *f)
{
    for (size_t i = 0; i + 1 < n; i++) {
        assert_int_equal(lsc_parser_feed(p, bytes[i], f), 0);
    }
    assert_int_equal(lsc_parser_feed(p, bytes[n - 1], f), 1);
    uint8_t got[LSC_FRAME_MAX];
    assert_int_equal(frame_bytes(f, got), n);
    assert_memory_equal(got, bytes, n);
}
