/* The programs' strict parsing (lscctl, lsc-sim, lscd) of numbers, servo ids,
 * ID:POS pairs and hex bytes.
 * Every function returns 0 on success or -1 after writing a one-line reason
 * (without the program name) into why[whylen]. */
#ifndef LSCCTL_PARSE_H
#define LSCCTL_PARSE_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"

/* A decimal or 0x-hex number in 0..max: no sign, no spaces, no suffix.
 * what names the field in the reason ("position", "id", ...). */
int lscctl_parse_uint(const char *s, unsigned long max, const char *what, unsigned long *out,
                      char *why, size_t whylen);

/* The same in min..max: a value below min is out of range, and the reason
 * states min..max (the range the caller accepts, never 0.. when 0 is not). */
int lscctl_parse_range(const char *s, unsigned long min, unsigned long max, const char *what,
                       unsigned long *out, char *why, size_t whylen);

/* A decimal number in min..max: [+-]DIGITS[.DIGITS], at most 9 digits
 * before the point and 6 after; no exponent, no spaces, no suffix. */
int lscctl_parse_decimal(const char *s, double min, double max, const char *what, double *out,
                         char *why, size_t whylen);

/* Appends the bytes written in hex in s to buf[*n..cap). Bytes are pairs of
 * hex digits (any case), optionally separated by spaces, tabs, newlines,
 * commas or colons; a group may start with 0x (then one or two digits). */
int lscctl_parse_hex(const char *s, uint8_t *buf, size_t cap, size_t *n, char *why,
                     size_t whylen);

#endif
