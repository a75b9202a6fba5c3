/* Helpers shared by the core's tests: a seeded PRNG, random valid frames,
 * and feeding a parser. Test code only (links to cmocka). */
#ifndef LSC_TEST_CORE_UTIL_H
#define LSC_TEST_CORE_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"

/* xorshift64*: small, fast, and the same sequence on every platform. */
typedef struct test_rng {
    uint64_t state;
} test_rng;

void rng_seed(test_rng *r, uint64_t seed);
uint32_t rng_next(test_rng *r);
/* Uniform enough in 0..n-1 (n >= 1). */
uint32_t rng_below(test_rng *r, uint32_t n);

/* The kinds of frame random_frame makes: every message of both directions,
 * and commands the core does not know. */
enum frame_kind {
    KIND_MOVE,
    KIND_GROUP_RUN,
    KIND_GROUP_STOP,
    KIND_GROUP_COMPLETE,
    KIND_GROUP_SPEED,
    KIND_BATTERY_REQUEST,
    KIND_BATTERY_REPLY,
    KIND_UNLOAD,
    KIND_POS_REQUEST,
    KIND_POS_REPLY,
    KIND_UNKNOWN,
    KIND_COUNT
};

/* True if cmd is one of the protocol's commands. */
int cmd_known(uint8_t cmd);

/* Writes to out a random frame of that kind that the parser must accept (ids
 * may repeat), of at most max bytes (max >= 4; a kind that cannot fit in max
 * gives a LEN 2 frame of an unknown command). Written from the protocol
 * table, without the core's encoders. Returns its length in bytes. */
size_t random_frame_of(test_rng *r, int kind, uint8_t *out, size_t max);
/* The same, of a random kind. */
size_t random_frame(test_rng *r, uint8_t *out, size_t max);

/* Writes the bytes of the frame f (header, LEN, command, parameters) to out
 * (room for LSC_FRAME_MAX bytes); returns their count. */
size_t frame_bytes(const lsc_frame *f, uint8_t *out);

/* Feeds n bytes, asserting that every feed but the last returns 0 and the
 * last returns 1 with the frame in *f, whose bytes must equal the input. */
void parse_exactly(lsc_parser *p, const uint8_t *bytes, size_t n, lsc_frame *f);

#endif
