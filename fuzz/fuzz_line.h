/* A scripted line with a fake clock, for the harnesses of a client over
 * lsc_io (fuzz_client.c, fuzz_lxclient.c): each read takes one control byte
 * from the script and gets a chunk of bytes, silence, a transport's error, an
 * impossible count, or a wake-up with nothing. When the script runs out, the
 * line is silent until the timeout. */
#ifndef LSC_FUZZ_LINE_H
#define LSC_FUZZ_LINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/core.h"

typedef struct fuzz_line {
    fuzz_cursor in;  /* the script: what the other end does */
    uint32_t now;    /* fake clock, ms */
    uint32_t reads;  /* reads in the current client call (the harness zeroes it) */
    int io_error;    /* last error the transport returned (0: none) */
    bool impossible; /* the transport returned an impossible count */
    uint8_t delivered[8192];
    size_t ndelivered; /* bytes delivered so far (the first 8192 kept) */
} fuzz_line;

/* Splits an input: byte 0 = L, bytes 1..L the calls (*ops), the rest l's
 * script. The clock starts 100 ms before it wraps around, so that it wraps
 * during the calls. */
static inline void fuzz_line_split(fuzz_line *l, fuzz_cursor *ops, const uint8_t *data,
                                   size_t size)
{
    size_t nops = size > 0 ? data[0] : 0;
    nops = nops < size - (size > 0) ? nops : size - (size > 0);
    *ops = (fuzz_cursor){data + (size > 0), nops, 0};
    l->in = (fuzz_cursor){data + (size > 0) + nops, size - (size > 0) - nops, 0};
    l->now = UINT32_MAX - 100u;
}

/* One read of at most cap bytes into buf, waiting at most timeout_ms of the
 * fake clock: what lsc_io's read returns. */
static inline int fuzz_line_read(fuzz_line *l, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    FUZZ_CHECK(buf != NULL && cap >= 1);
    l->reads++;
    if (l->in.at >= l->in.size) {
        l->now += timeout_ms; /* silence until the timeout */
        return 0;
    }
    uint8_t ctl = fuzz_next(&l->in);
    if (ctl < 0xC0) { /* a chunk of 1..64 bytes, arriving after 0..2 ms */
        size_t len = (size_t)(ctl & 0x3Fu) + 1u;
        uint32_t delay = (uint32_t)(ctl >> 6);
        l->now += delay < timeout_ms ? delay : timeout_ms;
        len = len < cap ? len : cap;
        size_t got = 0;
        while (got < len && l->in.at < l->in.size) {
            uint8_t b = fuzz_next(&l->in);
            buf[got++] = b;
            if (l->ndelivered < sizeof l->delivered) {
                l->delivered[l->ndelivered] = b;
            }
            l->ndelivered++;
        }
        if (got > 0) {
            return (int)got;
        }
        l->now += timeout_ms;
        return 0;
    }
    if (ctl < 0xF0) { /* silence for up to 4 * 48 ms, then nothing */
        uint32_t ms = (uint32_t)(ctl - 0xC0u) * 4u;
        l->now += ms < timeout_ms ? ms : timeout_ms;
        return 0;
    }
    if (ctl < 0xFC) { /* a transport error, passed through by the client */
        static const int codes[] = {LSC_EIO, LSC_ENODEV, LSC_EBUSY, LSC_EACCES};
        l->io_error = codes[ctl & 3u];
        return l->io_error;
    }
    if (ctl == 0xFC) { /* more bytes than asked: the client must not trust it */
        l->impossible = true;
        return (int)cap + 1;
    }
    return 0; /* woken with nothing, no time passed */
}

/* Whether bytes[0..n) were on the line, in a row (true when too much came to
 * tell). */
static inline bool fuzz_line_delivered(const fuzz_line *l, const uint8_t *bytes, size_t n)
{
    if (l->ndelivered > sizeof l->delivered) {
        return true; /* too much input to tell */
    }
    for (size_t i = 0; i + n <= l->ndelivered; i++) {
        if (memcmp(&l->delivered[i], bytes, n) == 0) {
            return true;
        }
    }
    return false;
}

#endif
