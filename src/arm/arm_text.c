/* Arm profiles: what the parser and the runtime API both read and write
 * (src/arm/arm_internal.h): messages with the outside's text escaped, servo
 * ids, numbers, values (a position or an angle), the positions a joint's
 * limits allow. Host only: compiles to nothing elsewhere (the Arduino IDE
 * builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "arm_internal.h"
#include "../util/escape.h"

/* ---- messages ------------------------------------------------------------- */

lsc_armi_msg lsc_armi_msg_start(char *why, size_t whylen)
{
    lsc_armi_msg m = {why, why != NULL ? whylen : 0u, 0u};
    if (m.cap > 0) {
        m.s[0] = '\0';
    }
    return m;
}

/* Appends s[0..n) escaped (a file's name: never raw control characters). */
void lsc_armi_msg_text(lsc_armi_msg *m, const char *s, size_t n)
{
    if (m->cap > 0) {
        m->len += lsc_escape_text(m->s + m->len, m->cap - m->len, s, n);
    }
}

/* Appends the string s escaped. */
void lsc_armi_msg_str(lsc_armi_msg *m, const char *s)
{
    lsc_armi_msg_text(m, s, strlen(s));
}

void lsc_armi_msg_vf(lsc_armi_msg *m, const char *fmt, va_list ap)
{
    if (m->cap > 0) {
        (void)vsnprintf(m->s + m->len, m->cap - m->len, fmt, ap);
        m->len += strlen(m->s + m->len);
    }
}

int lsc_armi_fail(int code, char *why, size_t whylen, const char *fmt, ...)
{
    lsc_armi_msg m = lsc_armi_msg_start(why, whylen);
    va_list ap;
    va_start(ap, fmt);
    lsc_armi_msg_vf(&m, fmt, ap);
    va_end(ap);
    return code;
}

/* before, then the file's name escaped, then fmt */
int lsc_armi_file_fail(int code, char *why, size_t whylen, const char *before, const char *file,
                       const char *fmt, ...)
{
    lsc_armi_msg m = lsc_armi_msg_start(why, whylen);
    va_list ap;
    lsc_armi_msg_text(&m, before, strlen(before));
    lsc_armi_msg_text(&m, file, strlen(file));
    va_start(ap, fmt);
    lsc_armi_msg_vf(&m, fmt, ap);
    va_end(ap);
    return code;
}

/* At most SHOWN_MAX bytes of s[0..n) escaped into out[SHOWN_CAP]. */
const char *lsc_armi_shown(char *out, const char *s, size_t n)
{
    (void)lsc_escape_text(out, SHOWN_CAP, s, n < SHOWN_MAX ? n : SHOWN_MAX);
    return out;
}

int lsc_armi_oom(char *why, size_t whylen)
{
    return lsc_armi_fail(LSC_ENOSPC, why, whylen, "out of memory");
}

/* ---- numbers -------------------------------------------------------------- */

bool lsc_armi_is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int hexval(char c)
{
    if (lsc_armi_is_digit(c)) {
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

/* s (NUL-terminated) as a decimal or 0x-hex number in 0..max (max >= 15): no
 * sign, no spaces, no suffix. what names it in the reason ("id"). */
int lsc_armi_parse_uint(const char *s, unsigned long max, const char *what, unsigned long *out,
                        char *why, size_t whylen)
{
    unsigned long base = 10, v = 0;
    const char *p = s;
    char text[SHOWN_CAP];
    (void)lsc_armi_shown(text, s, strlen(s));
    if (*p == '-') {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "%s '%s' is negative: use 0..%lu", what,
                             text, max);
    }
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        base = 16;
        p += 2;
    }
    if (*p == '\0') {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "%s '%s' is not a number: write it in decimal or 0x-hex", what, text);
    }
    for (; *p != '\0'; p++) {
        int d = hexval(*p);
        if (d < 0 || (unsigned long)d >= base) {
            return lsc_armi_fail(LSC_EINVAL, why, whylen,
                                 "%s '%s' is not a number: write it in decimal or 0x-hex", what,
                                 text);
        }
        if (v > (max - (unsigned long)d) / base) { /* v * base + d > max */
            return lsc_armi_fail(LSC_EINVAL, why, whylen, "%s %s is out of range: use 0..%lu", what,
                                 text, max);
        }
        v = v * base + (unsigned long)d;
    }
    *out = v;
    return LSC_OK;
}

/* s[0..n) as a servo id, 0..255 (lsc_armi_parse_uint's rules and reasons; at most
 * ID_TEXT_MAX characters). */
int lsc_armi_span_id(const char *s, size_t n, unsigned long *id, char *why, size_t whylen)
{
    char text[ID_TEXT_MAX + 1u];
    if (n > ID_TEXT_MAX) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "id: use 0..255");
    }
    memcpy(text, s, n);
    text[n] = '\0';
    return lsc_armi_parse_uint(text, 255, "id", id, why, whylen);
}

/* s[0..n) as a servo id (at most 7 characters, the first a digit), or -1. */
long lsc_armi_as_id(const char *s, size_t n)
{
    unsigned long id = 0;
    if (n == 0 || n >= 8u || !lsc_armi_is_digit(s[0])) {
        return -1;
    }
    return lsc_armi_span_id(s, n, &id, NULL, 0) == LSC_OK ? (long)id : -1;
}

/* s[0..n): [+-]DIGITS[.D[D]]deg, [+-]DIGITS or [+-]0xHEX (a position, as
 * numbers are everywhere else: decimal or 0x-hex). Returns NULL, or why not. */
const char *lsc_armi_parse_value(const char *s, size_t n, lsc_armi_value *out)
{
    size_t i = 0, digits = 0, frac = 0;
    long whole = 0, cents = 0;
    bool neg = false;
    if (i < n && (s[i] == '+' || s[i] == '-')) {
        neg = s[i++] == '-';
    }
    if (n - i >= 2u && s[i] == '0' && (s[i + 1] == 'x' || s[i + 1] == 'X')) {
        for (i += 2; i < n && hexval(s[i]) >= 0; i++, digits++) {
            if (digits == DIGITS_MAX) {
                return "too many digits";
            }
            whole = whole * 16 + (long)hexval(s[i]);
        }
        if (digits == 0 || i != n) {
            return n >= 3u && memcmp(s + n - 3u, "deg", 3) == 0
                       ? "an angle is written in decimal (30deg, -15.5deg)"
                       : "not a number (0x needs hex digits: 0x2BC)";
        }
        out->deg = false;
        out->v = neg ? -whole : whole;
        return NULL;
    }
    for (; i < n && lsc_armi_is_digit(s[i]); i++, digits++) {
        if (digits == DIGITS_MAX) {
            return "too many digits";
        }
        whole = whole * 10 + (long)(s[i] - '0');
    }
    if (digits == 0) {
        return "not a number (a position such as 700, or an angle such as -15.5deg)";
    }
    if (i < n && s[i] == '.') {
        for (i++; i < n && lsc_armi_is_digit(s[i]); i++, frac++) {
            if (frac == 2) {
                return "an angle has at most two decimals (0.01 degree)";
            }
            cents += (long)(s[i] - '0') * (frac == 0 ? 10L : 1L);
        }
        if (frac == 0) {
            return "a decimal point needs a digit after it";
        }
    }
    out->deg = n - i == 3 && memcmp(s + i, "deg", 3) == 0;
    if (!out->deg && i != n) {
        return "unknown unit: write a position (700) or degrees (30deg, -15.5deg)";
    }
    if (!out->deg && frac > 0) {
        return "a position is a whole number: for an angle add deg (15.5deg)";
    }
    out->v = out->deg ? whole * 100 + cents : whole;
    if (neg) {
        out->v = -out->v;
    }
    return NULL;
}

long lsc_armi_floor_div(long num, long den) /* den > 0 */
{
    return num >= 0 ? num / den : -((-num + den - 1) / den);
}

/* cdeg as degrees with two decimals ("-15.50") into out[cap] (cap > 0). */
void lsc_armi_degrees(char *out, size_t cap, int32_t cdeg)
{
    long a = cdeg < 0 ? -(long)cdeg : (long)cdeg;
    (void)snprintf(out, cap, "%s%ld.%02ld", cdeg < 0 ? "-" : "", a / 100, a % 100);
}

/* The positions the limits of j allow, lo..hi (lsc_joint_allows_pos, exactly,
 * without trying each): false when there is none. j is valid. */
bool lsc_armi_positions(const lsc_joint *j, long *lo, long *hi)
{
    long range = (long)j->pos_max - (long)j->pos_min;
    /* allowed: min * range <= (pos - zero) * dir * span <= max * range */
    long a = -lsc_armi_floor_div(-(long)j->min_cdeg * range, (long)j->span_cdeg);
    long b = lsc_armi_floor_div((long)j->max_cdeg * range, (long)j->span_cdeg);
    long p0 = j->direction > 0 ? (long)j->zero + a : (long)j->zero - b;
    long p1 = j->direction > 0 ? (long)j->zero + b : (long)j->zero - a;
    *lo = p0 > (long)j->pos_min ? p0 : (long)j->pos_min;
    *hi = p1 < (long)j->pos_max ? p1 : (long)j->pos_max;
    return *lo <= *hi;
}

#endif
