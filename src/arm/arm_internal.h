/* Inside src/arm (arm profiles, include/lsc/arm.h): what its files share.
 *
 *   arm.c         the runtime API: joints by name or id, JOINT:VALUE targets,
 *                 limits, degrees, the chain, the stand-in
 *   arm_file.c    profiles on disk: a file read whole, a name looked up
 *   arm_parse.c   the format (docs/arm-profile.md): text into an lsc_arm,
 *                 every error with its FILE:LINE:COLUMN
 *   arm_text.c    what they all read and write: messages, numbers, values
 *
 * The names here start with lsc_armi_: internal, never exported (they are not
 * LSC_API, and the shared library hides what is not). calibrate.c stands on
 * the public API only. */
#ifndef LSC_ARM_INTERNAL_H
#define LSC_ARM_INTERNAL_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/arm.h"

#define DIGITS_MAX 6u  /* of a value's whole part: keeps every value far from overflow */
#define SHOWN_MAX 40u  /* bytes of an argument or a field a message repeats */
#define SHOWN_CAP (4u * SHOWN_MAX + 1u) /* ... escaped: \xNN each at most */
#define ID_TEXT_MAX 15u /* characters of a servo id in a profile or a target */

/* ---- the profile in memory --------------------------------------------------- */

typedef struct arm_joint {
    char name[LSC_ARM_NAME_MAX + 1u];
    lsc_joint joint;
    bool has_end[2];  /* open=, closed= given (a gripper's ends: lsc_arm_end) */
    uint16_t end[2];  /* ... their positions */
} arm_joint;

#define LINKS 4u /* height, upper, fore, tool */

/* The geometry lines: chain: JOINT... and links: KEY=LENGTH... */
typedef struct arm_chain {
    size_t chain_line, links_line; /* where they were (0: not given) */
    size_t n;                      /* joints in the chain: 5 or 6 (with the gripper) */
    size_t joint[LSC_ARM_CHAIN_MAX];
    long length[LINKS]; /* hundredths of a mm */
} arm_chain;

struct lsc_arm {
    size_t n;
    arm_joint joints[LSC_ARM_JOINTS_MAX];
    arm_chain chain;
};

/* ---- messages (arm_text.c) ----------------------------------------------------- */

#ifdef __GNUC__
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

/* A why being written: s[cap] (cap 0: nothing is written), len used. */
typedef struct lsc_armi_msg {
    char *s;
    size_t cap;
    size_t len;
} lsc_armi_msg;

/* An empty why in why[whylen] (why may be NULL: nothing is written). */
lsc_armi_msg lsc_armi_msg_start(char *why, size_t whylen);
/* Appends s[0..n) escaped (a file's name: never raw control characters). */
void lsc_armi_msg_text(lsc_armi_msg *m, const char *s, size_t n);
/* Appends the string s escaped. */
void lsc_armi_msg_str(lsc_armi_msg *m, const char *s);
/* Appends fmt formatted, as it is. */
void lsc_armi_msg_vf(lsc_armi_msg *m, const char *fmt, va_list ap);
/* Writes fmt formatted as why; returns code. */
int lsc_armi_fail(int code, char *why, size_t whylen, const char *fmt, ...) PRINTF_LIKE(4, 5);
/* before, then the file's name escaped, then fmt; returns code. */
int lsc_armi_file_fail(int code, char *why, size_t whylen, const char *before, const char *file,
                       const char *fmt, ...) PRINTF_LIKE(6, 7);
/* At most SHOWN_MAX bytes of s[0..n) escaped into out[SHOWN_CAP]; returns out. */
const char *lsc_armi_shown(char *out, const char *s, size_t n);
/* "out of memory": returns LSC_ENOSPC. */
int lsc_armi_oom(char *why, size_t whylen);

/* ---- numbers and values (arm_text.c) -------------------------------------------- */

bool lsc_armi_is_digit(char c);
/* s (NUL-terminated) as a decimal or 0x-hex number in 0..max (max >= 15): no
 * sign, no spaces, no suffix. what names it in the reason ("id"). */
int lsc_armi_parse_uint(const char *s, unsigned long max, const char *what, unsigned long *out,
                        char *why, size_t whylen);
/* s[0..n) as a servo id, 0..255 (lsc_armi_parse_uint's rules and reasons; at
 * most ID_TEXT_MAX characters). */
int lsc_armi_span_id(const char *s, size_t n, unsigned long *id, char *why, size_t whylen);
/* s[0..n) as a servo id (at most 7 characters, the first a digit), or -1. */
long lsc_armi_as_id(const char *s, size_t n);

/* A value as written: a position (whole number) or an angle (deg). */
typedef struct lsc_armi_value {
    bool deg;
    long v; /* position, or centidegrees; |v| < 10^8 */
} lsc_armi_value;

/* s[0..n): [+-]DIGITS[.D[D]]deg, [+-]DIGITS or [+-]0xHEX (a position, as
 * numbers are everywhere else: decimal or 0x-hex). Returns NULL, or why not. */
const char *lsc_armi_parse_value(const char *s, size_t n, lsc_armi_value *out);
/* num / den rounded down (den > 0). */
long lsc_armi_floor_div(long num, long den);
/* cdeg as degrees with two decimals ("-15.50") into out[cap] (cap > 0). */
void lsc_armi_degrees(char *out, size_t cap, int32_t cdeg);
/* The positions the limits of j allow, lo..hi (lsc_joint_allows_pos, exactly,
 * without trying each): false when there is none. j is valid. */
bool lsc_armi_positions(const lsc_joint *j, long *lo, long *hi);

#endif
