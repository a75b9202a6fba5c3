/* Test helper: bytes written as hex text ("55 55 02 07"). */
#ifndef LSC_TEST_HEX_H
#define LSC_TEST_HEX_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Parses the hex byte pairs of hex (separated by any blanks) into out (cap
 * bytes at most); returns how many were parsed. */
static inline size_t test_hex(const char *hex, uint8_t *out, size_t cap)
{
    size_t n = 0;
    unsigned v;
    int len;
    while (n < cap && sscanf(hex, " %2x%n", &v, &len) == 1) {
        out[n++] = (uint8_t)v;
        hex += len;
    }
    return n;
}

#endif
