/* The README's example of the core ("Use the core from C"): encode a move,
 * feed received bytes to the parser (byte at a time, then through the bulk
 * path), decode a battery reply. ctest runs it
 * (so the example stays true) and so does scripts/demo.sh. Exits 1 if any
 * step does not give what the protocol says. */
#include <stdio.h>

#include "lsc/lsc.h"

static void print_bytes(const char *what, const uint8_t *bytes, size_t n)
{
    printf("%-28s", what);
    for (size_t i = 0; i < n; i++) {
        printf(" %02X", bytes[i]);
    }
    printf("\n");
}

int main(void)
{
    /* Encode a move: servo 1 to 1500 and servo 2 to 2000 over 1000 ms. */
    const lsc_servo targets[] = {{1, 1500}, {2, 2000}};
    uint8_t out[LSC_FRAME_MAX];
    int n = lsc_encode_servo_move(out, sizeof out, 1000, targets, 2);
    if (n < 0) {
        fprintf(stderr, "move: %s\n", lsc_strerror(n));
        return 1;
    }
    print_bytes("servo_move frame to send:", out, (size_t)n); /* write them to the port */

    /* Feed the bytes received, one at a time, to a parser: here line noise,
     * then the controller's answer to a battery request (7500 mV). */
    static const uint8_t received[] = {0x00, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
    print_bytes("bytes received:", received, sizeof received);
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser parser;
    lsc_parser_init(&parser, buf, sizeof buf);
    uint16_t millivolts = 0;
    for (size_t i = 0; i < sizeof received; i++) {
        lsc_frame frame;
        int r = lsc_parser_feed(&parser, received[i], &frame);
        if (r < 0) {
            printf("  byte %zu: %s\n", i, lsc_strerror(r));
        } else if (r == 1 && lsc_decode_battery_reply(&frame, &millivolts) == 0) {
            printf("  battery reply: %u mV\n", (unsigned)millivolts);
        }
    }
    printf("parser: %u frame(s), %u byte(s) discarded, %u error(s)\n", (unsigned)parser.frames,
           (unsigned)parser.discarded, (unsigned)parser.errors);

    /* The same bytes through the bulk path: one call per frame (or per
     * stretch of discarded input). */
    lsc_parser bulk;
    lsc_parser_init(&bulk, buf, sizeof buf);
    uint16_t bulk_mv = 0;
    const uint8_t *at = received;
    size_t left = sizeof received;
    while (left > 0) {
        lsc_frame frame;
        int result; /* 1: a frame; < 0: bytes discarded; 0: all consumed */
        size_t used = lsc_parser_feed_buf(&bulk, at, left, &frame, &result);
        at += used;
        left -= used;
        if (result == 1 && lsc_decode_battery_reply(&frame, &bulk_mv) == 0) {
            printf("  bulk path: battery reply: %u mV\n", (unsigned)bulk_mv);
        }
    }

    static const uint8_t move[] = {0x55, 0x55, 0x0B, 0x03, 0x02, 0xE8, 0x03,
                                   0x01, 0xDC, 0x05, 0x02, 0xD0, 0x07};
    int ok = n == (int)sizeof move && millivolts == 7500 && parser.frames == 1 &&
             parser.discarded == 1 && bulk_mv == 7500 && bulk.frames == 1 && bulk.discarded == 1;
    for (size_t i = 0; ok && i < sizeof move; i++) {
        ok = out[i] == move[i];
    }
    printf("%s\n", ok ? "ok" : "UNEXPECTED RESULT");
    return ok ? 0 : 1;
}
