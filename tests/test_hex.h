/* Test helper: bytes written as hex text ("55 55 02 07"). */
#ifndef LSC_TEST_HEX_H
#define LSC_TEST_HEX_H

#include <ctype.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

/* Parses the hex byte pairs of hex (separated by any blanks) into out (cap
 * bytes at most); returns how many were parsed (it stops at anything else). */
static inline size_t test_hex(const char *hex, uint8_t *out, size_t cap)
{
    size_t n = 0;
    while (n < cap) {
        while (isspace((unsigned char)*hex)) {
            hex++;
        }
        if (!isxdigit((unsigned char)hex[0]) || !isxdigit((unsigned char)hex[1])) {
            break;
        }
        char pair[3] = {hex[0], hex[1], '\0'};
        out[n++] = (uint8_t)strtoul(pair, NULL, 16);
        hex += 2;
    }
    return n;
}

#endif
