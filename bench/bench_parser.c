/* Benchmark (not a test): the parser's cost on this host.
 *
 * Builds a stream of a few MB of what a host receives: replies (battery,
 * positions of 1..6 servos), notifications (action group run, stop,
 * complete) and 5% noise bytes (random values, 0x55 included), feeds it to
 * the parser byte by byte with lsc_parser_feed (feed_bytes) and through the
 * bulk path lsc_parser_feed_buf (feed_bulk), checks that both give the same
 * frames, and prints ns/byte and bytes/s of each (the best of several passes).
 * Usage: bench_parser [MEGABYTES [PASSES [long]]] (default 4 and 5);
 * with "long", the stream is frames of the longest LEN (255) instead: the
 * cost of parameter bytes, the parser's fast path.
 * scripts/bench.sh runs it, and again under callgrind for instructions/byte
 * (of lsc_parser_feed and lsc_parser_feed_buf alone, and of the loops
 * feed_bytes and feed_bulk around them), beside the receive path of the
 * vendor's Arduino library on the same stream (vendor_receive, rewritten in
 * bench_vendor.c: it reads the stream itself, as feed_bytes does). */
#define _POSIX_C_SOURCE 199309L

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lsc/core.h"

#include "bench_vendor.h"

static uint32_t rng_state = 12345u;

static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* Appends one random message at out (a reply or a notification); returns its length. */
static size_t random_message(uint8_t *out, size_t room)
{
    lsc_servo servos[6];
    size_t n = 1 + rnd() % 6;
    for (size_t i = 0; i < n; i++) {
        servos[i].id = (uint8_t)(i + 1);
        servos[i].position = (uint16_t)(500 + rnd() % 2000);
    }
    uint16_t v = (uint16_t)rnd();
    int len;
    switch (rnd() % 5) {
    case 0: len = lsc_encode_battery_reply(out, room, v); break;
    case 1: len = lsc_encode_pos_reply(out, room, servos, n); break;
    case 2: len = lsc_encode_group_run(out, room, (uint8_t)v, v); break;
    case 3: len = lsc_encode_group_stop(out, room); break;
    default: len = lsc_encode_group_complete(out, room, (uint8_t)v, v); break;
    }
    return len > 0 ? (size_t)len : 0;
}

static volatile uint32_t sink; /* uses each frame, so that nothing is optimised away */

/* The byte loop: every byte through lsc_parser_feed; returns the sum of
 * the frames' commands (so that nothing is optimised away). Not inlined, so
 * that callgrind can count its instructions (--toggle-collect=feed_bytes). */
__attribute__((noinline)) static uint32_t feed_bytes(lsc_parser *p, const uint8_t *s, size_t n)
{
    lsc_frame f;
    uint32_t sum = 0;
    for (size_t i = 0; i < n; i++) {
        if (lsc_parser_feed(p, s[i], &f) == 1) {
            sum += f.cmd;
        }
    }
    return sum;
}

/* The bulk path: the bytes through lsc_parser_feed_buf, one call per frame
 * (or per discarded stretch); the same result as feed_bytes. */
__attribute__((noinline)) static uint32_t feed_bulk(lsc_parser *p, const uint8_t *s, size_t n)
{
    lsc_frame f;
    uint32_t sum = 0;
    while (n > 0) {
        int r;
        size_t k = lsc_parser_feed_buf(p, s, n, &f, &r);
        s += k;
        n -= k;
        if (r == 1) {
            sum += f.cmd;
        }
    }
    return sum;
}

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
    size_t size = mb << 20, len = 0, noise = 0;
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
        } else if (noise * 19u < len - noise) {
            /* 5% of the bytes: a noise byte at a random place between frames */
            if (rnd() % 2 == 0) {
                stream[len++] = (uint8_t)rnd();
                noise++;
            }
            len += random_message(&stream[len], size - len);
        } else {
            len += random_message(&stream[len], size - len);
        }
    }

    double best = 0, best_bulk = 0, best_vendor = 0;
    vendor_state v;
    lsc_parser p;
    for (long pass = 0; pass < passes; pass++) {
        uint8_t buf[LSC_FRAME_MAX];
        lsc_parser_init(&p, buf, sizeof buf);
        double t0 = now_ns();
        uint32_t sum = feed_bytes(&p, stream, len);
        double t = now_ns() - t0;
        uint32_t frames = p.frames;
        lsc_parser_init(&p, buf, sizeof buf);
        t0 = now_ns();
        uint32_t bulk_sum = feed_bulk(&p, stream, len);
        double t_bulk = now_ns() - t0;
        if (bulk_sum != sum || p.frames != frames) {
            fprintf(stderr, "the bulk path disagrees with the byte path\n");
            free(stream);
            return 1;
        }
        sink = sum;
        memset(&v, 0, sizeof v);
        vendor_stream vs;
        vendor_stream_init(&vs, stream, len);
        t0 = now_ns();
        vendor_receive(&v, &vs);
        double t_vendor = now_ns() - t0;
        best_vendor = pass == 0 || t_vendor < best_vendor ? t_vendor : best_vendor;
        best = pass == 0 || t < best ? t : best;
        best_bulk = pass == 0 || t_bulk < best_bulk ? t_bulk : best_bulk;
    }
    printf("parser: %zu bytes of %s (%zu of them noise; %u frames, %u bytes discarded), "
           "best of %ld passes\n",
           len, longest ? "frames of LEN 255" : "replies and notifications", noise,
           (unsigned)p.frames, (unsigned)p.discarded, passes);
    printf("parser: %.2f ns/byte, %.1f MB/s (%.0f bytes/s) byte at a time (lsc_parser_feed)\n",
           best / (double)len, (double)len / best * 1e3, (double)len / best * 1e9);
    printf("parser: %.2f ns/byte, %.1f MB/s (%.0f bytes/s) through the bulk path "
           "(lsc_parser_feed_buf)\n",
           best_bulk / (double)len, (double)len / best_bulk * 1e3, (double)len / best_bulk * 1e9);
    printf("parser: %.2f ns/byte, %.1f MB/s (%.0f bytes/s) the vendor's receive path "
           "(vendor_receive: %u frames taken, lengths unchecked)\n",
           best_vendor / (double)len, (double)len / best_vendor * 1e3,
           (double)len / best_vendor * 1e9, (unsigned)v.frames);
    free(stream);
    return 0;
}
