/* Text from outside (a file's name, an argument, bytes of a file) made safe to
 * repeat in a one-line message. Public as declared in lsc/device.h (front
 * ends escape what they repeat by the same rules); declared here for the
 * layers below the device layer (arm profiles, files), which do not include
 * lsc/device.h (src/device takes it from there). Portable C99, no allocation. */
#ifndef LSC_UTIL_ESCAPE_H
#define LSC_UTIL_ESCAPE_H

#include <stddef.h>

#include "lsc/core.h" /* LSC_API */

/* Writes s[0..n) (up to a NUL byte, if one comes first) into out[cap]:
 * printable ASCII as it is, a backslash as \\, any other byte (control
 * characters, DEL, bytes >= 0x80) as \xNN with upper-case hex digits. Cut to
 * fit, never in the middle of an escape; out is NUL-terminated when cap > 0.
 * s may be NULL when n is 0. Returns the length written (without the NUL). */
LSC_API size_t lsc_escape_text(char *out, size_t cap, const char *s, size_t n);

#endif
