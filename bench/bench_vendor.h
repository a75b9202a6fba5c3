/* The receive path of the vendor's Arduino library (LobotServoController,
 * Hiwonder's download for the LSC boards), rewritten in C for the parser's
 * bench (bench_parser.c), so that both run on the same stream on this host.
 *
 * What it does, as the vendor's handler does: while the stream holds bytes,
 * wait for 0x55 0x55, take the next byte as LEN, read LEN - 1 more bytes in
 * one readBytes, then look at the command (battery reply, group run, stop,
 * complete) and start again. No length is checked, nothing is counted, a
 * frame inside a malformed one is lost. Two departures, both in its favour:
 * the vendor's buffer is 16 bytes (a position reply of 6 servos, LEN 21,
 * overruns it): here it holds any LEN; and its Stream reads memory, not
 * HardwareSerial's ring buffer (bench_vendor.c: the same calls, each less
 * work). */
#ifndef BENCH_VENDOR_H
#define BENCH_VENDOR_H

#include <stddef.h>
#include <stdint.h>

/* The bytes the handler reads, as an Arduino Stream gives them. */
typedef struct vendor_stream vendor_stream;
struct vendor_stream {
    const uint8_t *data;
    size_t n, at;
    unsigned long clock;
    int (*available)(const vendor_stream *s);
    int (*read)(vendor_stream *s);
    uint32_t (*millis)(vendor_stream *s);
};

/* A stream of the n bytes at data. */
void vendor_stream_init(vendor_stream *s, const uint8_t *data, size_t n);

/* What the handler keeps between calls, and what it found. */
typedef struct vendor_state {
    uint8_t header; /* 0..4: where in a frame the handler is */
    uint8_t len;    /* the frame's LEN */
    uint16_t battery_mv;
    uint8_t group;
    uint16_t times;
    uint8_t running;
    uint32_t frames; /* frames looked at (not in the vendor's code: the bench's check) */
} vendor_state;

/* Reads everything s holds, as the vendor's receiveHandle does. */
void vendor_receive(vendor_state *v, vendor_stream *s);

#endif
