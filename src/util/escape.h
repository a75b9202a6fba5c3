/* Text from outside (a file's name, an argument, bytes of a file) made safe to
 * repeat in a one-line message. Internal to the library: not exported, not
 * in include/. Portable C99, no allocation. */
#ifndef LSC_UTIL_ESCAPE_H
#define LSC_UTIL_ESCAPE_H

#include <stddef.h>

/* Writes s[0..n) (up to a NUL byte, if one comes first) into out[cap]:
 * printable ASCII as it is, a backslash as \\, any other byte (control
 * characters, DEL, bytes >= 0x80) as \xNN with upper-case hex digits. Cut to
 * fit, never in the middle of an escape; out is NUL-terminated when cap > 0.
 * s may be NULL when n is 0. Returns the length written (without the NUL). */
size_t lsc_escape_text(char *out, size_t cap, const char *s, size_t n);

#endif
