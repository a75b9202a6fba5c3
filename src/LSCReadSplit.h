/*
 * How LSC::readPositions (LSC.cpp) splits a read of many servos into
 * mult_servo_pos_read requests. Plain C99 and C++ with no Arduino in it, so
 * that a host test (tests/embedded/test_read_split.c) checks the rule for
 * every receive-buffer size, not only the one the sketch's board has.
 */
#ifndef LSC_READ_SPLIT_H
#define LSC_READ_SPLIT_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"

/* The most servos one request may ask for when the client receives frames of
 * at most rx_max bytes (LSC_CLIENT_RX_MAX): a reply for n servos is 3n + 5
 * bytes, and no request asks for more than LSC_READ_MAX. 0 when not even one
 * servo's reply fits (rx_max < 8). LSC_READ_PER is the same as a constant
 * expression (for an array's size). */
#define LSC_READ_PER(rx_max)                                                                       \
    ((rx_max) < 5u                              ? 0u                                               \
     : ((rx_max) - 5u) / 3u < LSC_READ_MAX ? ((rx_max) - 5u) / 3u                                 \
                                              : LSC_READ_MAX)
static inline uint8_t lsc_read_per(size_t rx_max)
{
    return (uint8_t)LSC_READ_PER(rx_max);
}

/* How many of the `left` servos still to read the next request asks for:
 * at most per, and never the one count whose request the core refuses (82
 * ids make the length byte 0x55, which a receiver takes for a header byte):
 * one fewer instead, the rest going in the next request. */
static inline uint8_t lsc_read_chunk(uint8_t left, uint8_t per)
{
    uint8_t n = left < per ? left : per;
    if ((unsigned)n + 3u == LSC_HEADER_BYTE)
        n = (uint8_t)(n - 1u);
    return n;
}

#endif /* LSC_READ_SPLIT_H */
