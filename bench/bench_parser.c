/* Benchmark (not a test): the parser's cost on this host.
 *
 * Builds a stream of a few MB of mixed frames (every message of both
 * directions, an unknown command, and a noise byte every hundred frames or
 * so), feeds it to the
 * parser byte by byte, and prints ns/byte and bytes/s (the best of several
 * passes). Usage: bench_parser [MEGABYTES [PASSES [long]]] (default 4 and 5);
 * with "long", the stream is frames of the longest LEN (255) instead: the
 * cost of parameter bytes, the parser's fast path.
 * scripts/bench.sh runs it, and again under callgrind for instructions/byte. */
#define _POSIX_C_SOURCE 199309L

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lsc/core.h"

static uint32_t rng_state = 12345u;

static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* Appends one random message (or a noise byte) at out; returns its length. */
static size_t random_message(uint8_t *out, size_t room)
{
    lsc_servo servos[LSC_READ_MAX];
    uint8_t ids[32];
    size_t n = 1 + rnd() % 6;
    for (size_t i = 0; i < n; i++) {
        ids[i] = (uint8_t)(i + 1);
        servos[i].id = (uint8_t)(i + 1);
        servos[i].position = (uint16_t)(500 + rnd() % 2000);
    }
    uint16_t v = (uint16_t)rnd();
    int len;
    switch (rnd() % 13) {
    case 0: len = lsc_encode_servo_move(out, room, v, servos, n); break;
    case 1: len = lsc_encode_group_run(out, room, (uint8_t)v, v); break;
    case 2: len = lsc_encode_group_stop(out, room); break;
    case 3: len = lsc_encode_group_complete(out, room, (uint8_t)v, v); break;
    case 4: len = lsc_encode_group_speed(out, room, (uint8_t)v, v); break;
    case 5: len = lsc_encode_battery_request(out, room); break;
    case 6: len = lsc_encode_battery_reply(out, room, v); break;
    case 7: len = lsc_encode_unload(out, room, ids, n); break;
    case 8: len = lsc_encode_pos_request(out, room, ids, n); break;
    case 9:
    case 10: len = lsc_encode_pos_reply(out, room, servos, n); break;
    case 11: len = lsc_encode_frame(out, room, 0x22, ids, n); break; /* an xArm command */
    default:
        if (rnd() % 8 != 0) { /* a noise byte for about 1 frame in 100 */
            return 0;
        }
        out[0] = (uint8_t)rnd();
        return room > 0 ? 1 : 0;
    }
    return len > 0 ? (size_t)len : 0;
}

static volatile uint32_t sink; /* uses each frame, so that nothing is optimised away */

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    size_t mb = argc > 1 ? (size_t)strtoul(argv[1], NULL, 10) : 4;
    long passes = argc > 2 ? strtol(argv[2], NULL, 10) : 5;
    int longest = argc > 3 && strcmp(argv[3], "long") == 0;
    if (mb == 0 || mb > 1024 || passes < 1 || passes > 1000 || (argc > 3 && !longest)) {
        fprintf(stderr, "usage: %s [MEGABYTES (1..1024) [PASSES (1..1000) [long]]]\n", argv[0]);
        return 2;
    }
    size_t size = mb << 20, len = 0;
    uint8_t *stream = malloc(size);
    if (stream == NULL) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    while (len + LSC_FRAME_MAX <= size) {
        if (longest) {
            uint8_t params[LSC_PARAMS_MAX];
            for (size_t i = 0; i < sizeof params; i++) {
                params[i] = (uint8_t)rnd();
            }
            len += (size_t)lsc_encode_frame(&stream[len], size - len, 0x22, params, sizeof params);
        } else {
            len += random_message(&stream[len], size - len);
        }
    }

    double best = 0;
    uint32_t frames = 0, discarded = 0;
    for (long pass = 0; pass < passes; pass++) {
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser p;
        lsc_parser_init(&p, buf, sizeof buf);
        lsc_frame f;
        uint32_t sum = 0;
        double t0 = now_ns();
        for (size_t i = 0; i < len; i++) {
            if (lsc_parser_feed(&p, stream[i], &f) == 1) {
                sum += f.cmd;
            }
        }
        double t = now_ns() - t0;
        if (pass == 0 || t < best) {
            best = t;
        }
        sink = sum;
        frames = p.frames;
        discarded = p.discarded;
    }
    printf("parser: %zu bytes of %s (%u frames, %u bytes discarded), best of %ld passes\n", len,
           longest ? "frames of LEN 255" : "mixed frames", (unsigned)frames, (unsigned)discarded,
           passes);
    printf("parser: %.2f ns/byte, %.1f MB/s (%.0f bytes/s)\n", best / (double)len,
           (double)len / best * 1e3, (double)len / best * 1e9);
    free(stream);
    return 0;
}
