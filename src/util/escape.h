/* Escaping text for one-line messages (internal, not installed). */
#ifndef LSC_UTIL_ESCAPE_H
#define LSC_UTIL_ESCAPE_H

#include <stddef.h>

/* Copies the NUL-terminated s into out (cap bytes, cap >= 1), always
 * NUL-terminated, so that it prints as it reads on one line: a control
 * character (bytes 0x00..0x1f and 0x7f, and the C1 controls U+0080..U+009F
 * in UTF-8), a byte that is not part of valid UTF-8, and the backslash
 * become "\xNN" ("\\" for the backslash); every other character, UTF-8
 * included, is copied. When out is too small it ends after the last
 * character (escape or UTF-8 sequence) that fits whole. s NULL is "(null)".
 * Returns the length written (without the NUL). Linear in the input; no
 * allocation, no state. */
size_t lsc_escape_text(char *out, size_t cap, const char *s);

/* Writes s[0..n) (up to a NUL byte, if one comes first) into out[cap]:
 * printable ASCII as it is, a backslash as \\, any other byte as \xNN with
 * upper-case hex digits. Cut to fit, never in the middle of an escape; out is
 * NUL-terminated when cap > 0. s may be NULL when n is 0. Returns the length
 * written (without the NUL). (The arm profile parser's.) */
size_t lsc_escape_text_n(char *out, size_t cap, const char *s, size_t n);

#endif
