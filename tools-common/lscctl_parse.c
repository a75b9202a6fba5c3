#include "lscctl_parse.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "lsc/device.h"
#include "lsc/text.h"

static int hexval(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

/* At most n bytes of s (up to its NUL) for a message, cut to fit cap: the
 * library's escapes (lsc_escape_text, lsc/device.h). */
static const char *shown(char *out, size_t cap, const char *s, size_t n)
{
    (void)lsc_escape_text(out, cap, s, n);
    return out;
}

#define SHOWN_MAX 40u /* input bytes a message repeats */
#define SHOWN_CAP (4u * SHOWN_MAX + 1u)

int lscctl_parse_uint(const char *s, unsigned long max, const char *what, unsigned long *out,
                      char *why, size_t whylen)
{
    return lscctl_parse_range(s, 0, max, what, out, why, whylen);
}

int lscctl_parse_range(const char *s, unsigned long min, unsigned long max, const char *what,
                       unsigned long *out, char *why, size_t whylen)
{
    unsigned long base = 10, v = 0;
    const char *p = s;
    char text[SHOWN_CAP];
    shown(text, sizeof text, s, SHOWN_MAX);
    if (*p == '-') {
        snprintf(why, whylen, "%s '%s' is negative: use %lu..%lu", what, text, min, max);
        return -1;
    }
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        base = 16;
        p += 2;
    }
    if (*p == '\0') {
        snprintf(why, whylen, "%s '%s' is not a number: write it in decimal or 0x-hex", what,
                 text);
        return -1;
    }
    for (; *p != '\0'; p++) {
        int d = hexval(*p);
        if (d < 0 || (unsigned long)d >= base) {
            snprintf(why, whylen, "%s '%s' is not a number: write it in decimal or 0x-hex",
                     what, text);
            return -1;
        }
        /* v * base + d > max, checked without overflowing (max may be ULONG_MAX) */
        if (v > (max - (unsigned long)d) / base || (unsigned long)d > max) {
            snprintf(why, whylen, "%s %s is out of range: use %lu..%lu", what, text, min, max);
            return -1;
        }
        v = v * base + (unsigned long)d;
    }
    if (v < min) {
        snprintf(why, whylen, "%s %s is out of range: use %lu..%lu", what, text, min, max);
        return -1;
    }
    *out = v;
    return 0;
}

int lscctl_parse_hex(const char *s, uint8_t *buf, size_t cap, size_t *n, char *why,
                     size_t whylen)
{
    const char *p = s;
    while (*p != '\0') {
        if (strchr(" \t\r\n,:", *p) != NULL) {
            p++;
            continue;
        }
        const char *group = p;
        size_t digits = 0;
        bool prefixed = p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
        if (prefixed) {
            p += 2;
        }
        while (hexval(p[digits]) >= 0) {
            digits++;
        }
        char c = p[digits];
        if ((c != '\0' && strchr(" \t\r\n,:", c) == NULL) || digits == 0 ||
            (prefixed && digits > 2) || (!prefixed && digits % 2 != 0)) {
            size_t len = 0;
            char text[SHOWN_CAP];
            while (group[len] != '\0' && strchr(" \t\r\n,:", group[len]) == NULL &&
                   len < SHOWN_MAX) {
                len++;
            }
            snprintf(why, whylen,
                     "'%s' is not hex bytes: write pairs of hex digits like 55 55 02 07",
                     shown(text, sizeof text, group, len));
            return -1;
        }
        for (size_t i = 0; i < digits; i += 2) {
            int hi = hexval(p[i]), lo;
            if (digits == 1) {
                lo = hi;
                hi = 0;
            } else {
                lo = hexval(p[i + 1]);
            }
            if (*n >= cap) {
                snprintf(why, whylen, "too much hex input (more than %zu bytes)", cap);
                return -1;
            }
            buf[(*n)++] = (uint8_t)(hi * 16 + lo);
        }
        p += digits;
    }
    return 0;
}

int lscctl_parse_decimal(const char *s, double min, double max, const char *what, double *out,
                         char *why, size_t whylen)
{
    const char *p = s;
    double v = 0, scale = 1;
    size_t digits = 0;
    char text[SHOWN_CAP];
    bool neg = false;
    shown(text, sizeof text, s, SHOWN_MAX);
    if (*p == '-' || *p == '+') {
        neg = *p++ == '-';
    }
    for (; *p >= '0' && *p <= '9' && digits < 9; p++, digits++) {
        v = v * 10 + (*p - '0');
    }
    if (*p == '.' && digits > 0) {
        size_t frac = 0;
        for (p++; *p >= '0' && *p <= '9' && frac < 6; p++, frac++) {
            scale /= 10;
            v += (*p - '0') * scale;
        }
        if (frac == 0) {
            digits = 0; /* "5." */
        }
    }
    if (digits == 0 || *p != '\0') {
        snprintf(why, whylen, "%s '%s' is not a number: write it in decimal (-15, 2.5)", what,
                 text);
        return -1;
    }
    v = neg ? -v : v;
    if (v < min || v > max) {
        snprintf(why, whylen, "%s %s is out of range: use %g..%g", what, text, min, max);
        return -1;
    }
    *out = v;
    return 0;
}
