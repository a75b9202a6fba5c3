/* Escaping text for one-line messages (escape.h). Portable C99. */
#include "escape.h"

#include <stdint.h>
#include <string.h>

/* The length of the valid UTF-8 sequence of two or more bytes at s (lead
 * byte s[0] >= 0xc2), or 0 when it is not one (or is a C1 control). */
static size_t utf8_len(const unsigned char *s)
{
    unsigned char c = s[0];
    unsigned char lo = 0x80u, hi = 0xbfu; /* the range of the second byte */
    size_t n;
    if (c >= 0xc2u && c <= 0xdfu) {
        n = 2;
        if (c == 0xc2u) {
            lo = 0xa0u; /* U+0080..U+009F are the C1 controls */
        }
    } else if (c >= 0xe0u && c <= 0xefu) {
        n = 3;
        lo = c == 0xe0u ? 0xa0u : 0x80u; /* no overlong forms */
        hi = c == 0xedu ? 0x9fu : 0xbfu; /* no surrogates */
    } else if (c >= 0xf0u && c <= 0xf4u) {
        n = 4;
        lo = c == 0xf0u ? 0x90u : 0x80u;
        hi = c == 0xf4u ? 0x8fu : 0xbfu; /* at most U+10FFFF */
    } else {
        return 0;
    }
    if (s[1] < lo || s[1] > hi) {
        return 0;
    }
    for (size_t i = 2; i < n; i++) {
        if (s[i] < 0x80u || s[i] > 0xbfu) { /* a NUL ends the check here too */
            return 0;
        }
    }
    return n;
}

size_t lsc_escape_text(char *out, size_t cap, const char *s)
{
    static const char hex[] = "0123456789abcdef";
    const unsigned char *p = (const unsigned char *)(s != NULL ? s : "(null)");
    size_t len = 0;
    if (out == NULL || cap == 0) {
        return 0;
    }
    while (*p != 0) {
        unsigned char c = *p;
        size_t n = 1;
        char esc[4];
        const char *from = (const char *)p;
        if (c == '\\') {
            esc[0] = '\\';
            esc[1] = '\\';
            from = esc;
            n = 2;
        } else if (c >= 0x80u) {
            n = utf8_len(p);
        }
        if (n == 0 || c < 0x20u || c == 0x7fu) {
            esc[0] = '\\';
            esc[1] = 'x';
            esc[2] = hex[c >> 4];
            esc[3] = hex[c & 0x0fu];
            from = esc;
            n = 4;
        }
        if (n >= cap - len) {
            break; /* it does not fit whole with the NUL */
        }
        for (size_t i = 0; i < n; i++) {
            out[len++] = from[i];
        }
        p += from == esc ? 1u : n;
    }
    out[len] = '\0';
    return len;
}

size_t lsc_escape_text_n(char *out, size_t cap, const char *s, size_t n)
{
    static const char hex[] = "0123456789ABCDEF";
    size_t len = 0;
    if (cap == 0) {
        return 0;
    }
    for (size_t i = 0; i < n && s[i] != '\0'; i++) {
        unsigned char c = (unsigned char)s[i];
        char one[4] = {'\\', '\\', 0, 0};
        size_t w = 2;
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            one[0] = (char)c;
            w = 1;
        } else if (c != '\\') {
            one[1] = 'x';
            one[2] = hex[c >> 4];
            one[3] = hex[c & 0x0fu];
            w = 4;
        }
        if (len + w >= cap) {
            break;
        }
        memcpy(out + len, one, w);
        len += w;
    }
    out[len] = '\0';
    return len;
}
