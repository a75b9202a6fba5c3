/* Arm profiles and JOINT:VALUE arguments (include/lsc/arm.h, the format in
 * docs/arm-profile.md). The conversions and the limit checks are
 * lsc/units.h's; what is checked is always the position that would be sent.
 * Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c
 * under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _POSIX_C_SOURCE 200809L /* O_CLOEXEC */

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lsc/arm.h"
#include "../util/escape.h"

#define TOKENS_MAX 10u /* NAME ID KIND and at most five key=value, plus extras to report */
#define DIGITS_MAX 6u  /* of a value's whole part: keeps every value far from overflow */
#define SHOWN_MAX 40u  /* bytes of an argument or a field a message repeats */
#define SHOWN_CAP (4u * SHOWN_MAX + 1u) /* ... escaped: \xNN each at most */
#define ID_TEXT_MAX 15u /* characters of a servo id in a profile or a target */

typedef struct arm_joint {
    char name[LSC_ARM_NAME_MAX + 1u];
    lsc_joint joint;
    bool has_end[2];  /* open=, closed= given (a gripper's ends: lsc_arm_end) */
    uint16_t end[2];  /* ... their positions */
} arm_joint;

#define LINKS 4u /* height, upper, fore, tool */
#define LENGTH_MAX 1000000L /* hundredths of a mm: 10 m */

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

/* ---- messages ------------------------------------------------------------- */

#ifdef __GNUC__
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

/* A why being written: s[cap] (cap 0: nothing is written), len used. */
typedef struct msg {
    char *s;
    size_t cap;
    size_t len;
} msg;

static msg msg_start(char *why, size_t whylen)
{
    msg m = {why, why != NULL ? whylen : 0u, 0u};
    if (m.cap > 0) {
        m.s[0] = '\0';
    }
    return m;
}

/* Appends s[0..n) escaped (a file's name: never raw control characters). */
static void msg_text(msg *m, const char *s, size_t n)
{
    if (m->cap > 0) {
        m->len += lsc_escape_text(m->s + m->len, m->cap - m->len, s, n);
    }
}

/* Appends the string s escaped. */
static void msg_str(msg *m, const char *s)
{
    msg_text(m, s, strlen(s));
}

static void msg_vf(msg *m, const char *fmt, va_list ap)
{
    if (m->cap > 0) {
        (void)vsnprintf(m->s + m->len, m->cap - m->len, fmt, ap);
        m->len += strlen(m->s + m->len);
    }
}

static int failf(int code, char *why, size_t whylen, const char *fmt, ...) PRINTF_LIKE(4, 5);

static int failf(int code, char *why, size_t whylen, const char *fmt, ...)
{
    msg m = msg_start(why, whylen);
    va_list ap;
    va_start(ap, fmt);
    msg_vf(&m, fmt, ap);
    va_end(ap);
    return code;
}

/* before, then the file's name escaped, then fmt */
static int file_fail(int code, char *why, size_t whylen, const char *before, const char *file,
                     const char *fmt, ...) PRINTF_LIKE(6, 7);

static int file_fail(int code, char *why, size_t whylen, const char *before, const char *file,
                     const char *fmt, ...)
{
    msg m = msg_start(why, whylen);
    va_list ap;
    msg_text(&m, before, strlen(before));
    msg_text(&m, file, strlen(file));
    va_start(ap, fmt);
    msg_vf(&m, fmt, ap);
    va_end(ap);
    return code;
}

/* At most SHOWN_MAX bytes of s[0..n) escaped into out[SHOWN_CAP]. */
static const char *shown(char *out, const char *s, size_t n)
{
    (void)lsc_escape_text(out, SHOWN_CAP, s, n < SHOWN_MAX ? n : SHOWN_MAX);
    return out;
}

static int oom(char *why, size_t whylen)
{
    return failf(LSC_ENOSPC, why, whylen, "out of memory");
}

/* ---- numbers -------------------------------------------------------------- */

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int hexval(char c)
{
    if (is_digit(c)) {
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
static int parse_uint(const char *s, unsigned long max, const char *what, unsigned long *out,
                      char *why, size_t whylen)
{
    unsigned long base = 10, v = 0;
    const char *p = s;
    char text[SHOWN_CAP];
    (void)shown(text, s, strlen(s));
    if (*p == '-') {
        return failf(LSC_EINVAL, why, whylen, "%s '%s' is negative: use 0..%lu", what, text, max);
    }
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        base = 16;
        p += 2;
    }
    if (*p == '\0') {
        return failf(LSC_EINVAL, why, whylen,
                     "%s '%s' is not a number: write it in decimal or 0x-hex", what, text);
    }
    for (; *p != '\0'; p++) {
        int d = hexval(*p);
        if (d < 0 || (unsigned long)d >= base) {
            return failf(LSC_EINVAL, why, whylen,
                         "%s '%s' is not a number: write it in decimal or 0x-hex", what, text);
        }
        if (v > (max - (unsigned long)d) / base) { /* v * base + d > max */
            return failf(LSC_EINVAL, why, whylen, "%s %s is out of range: use 0..%lu", what,
                         text, max);
        }
        v = v * base + (unsigned long)d;
    }
    *out = v;
    return LSC_OK;
}

/* s[0..n) as a servo id, 0..255 (parse_uint's rules and reasons; at most
 * ID_TEXT_MAX characters). */
static int span_id(const char *s, size_t n, unsigned long *id, char *why, size_t whylen)
{
    char text[ID_TEXT_MAX + 1u];
    if (n > ID_TEXT_MAX) {
        return failf(LSC_EINVAL, why, whylen, "id: use 0..255");
    }
    memcpy(text, s, n);
    text[n] = '\0';
    return parse_uint(text, 255, "id", id, why, whylen);
}

/* s[0..n) as a servo id (at most 7 characters, the first a digit), or -1. */
static long as_id(const char *s, size_t n)
{
    unsigned long id = 0;
    if (n == 0 || n >= 8u || !is_digit(s[0])) {
        return -1;
    }
    return span_id(s, n, &id, NULL, 0) == LSC_OK ? (long)id : -1;
}

/* A value as written: a position (whole number) or an angle (deg). */
typedef struct value {
    bool deg;
    long v; /* position, or centidegrees; |v| < 10^8 */
} value;

/* s[0..n): [+-]DIGITS[.D[D]]deg, [+-]DIGITS or [+-]0xHEX (a position, as
 * numbers are everywhere else: decimal or 0x-hex). Returns NULL, or why not. */
static const char *parse_value(const char *s, size_t n, value *out)
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
    for (; i < n && is_digit(s[i]); i++, digits++) {
        if (digits == DIGITS_MAX) {
            return "too many digits";
        }
        whole = whole * 10 + (long)(s[i] - '0');
    }
    if (digits == 0) {
        return "not a number (a position such as 700, or an angle such as -15.5deg)";
    }
    if (i < n && s[i] == '.') {
        for (i++; i < n && is_digit(s[i]); i++, frac++) {
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

static long floor_div(long num, long den) /* den > 0 */
{
    return num >= 0 ? num / den : -((-num + den - 1) / den);
}

/* cdeg as degrees with two decimals ("-15.50") into out[cap] (cap > 0). */
static void degrees(char *out, size_t cap, int32_t cdeg)
{
    long a = cdeg < 0 ? -(long)cdeg : (long)cdeg;
    (void)snprintf(out, cap, "%s%ld.%02ld", cdeg < 0 ? "-" : "", a / 100, a % 100);
}

/* The positions the limits of j allow, lo..hi (lsc_joint_allows_pos, exactly,
 * without trying each): false when there is none. j is valid. */
static bool positions(const lsc_joint *j, long *lo, long *hi)
{
    long range = (long)j->pos_max - (long)j->pos_min;
    /* allowed: min * range <= (pos - zero) * dir * span <= max * range */
    long a = -floor_div(-(long)j->min_cdeg * range, (long)j->span_cdeg);
    long b = floor_div((long)j->max_cdeg * range, (long)j->span_cdeg);
    long p0 = j->direction > 0 ? (long)j->zero + a : (long)j->zero - b;
    long p1 = j->direction > 0 ? (long)j->zero + b : (long)j->zero - a;
    *lo = p0 > (long)j->pos_min ? p0 : (long)j->pos_min;
    *hi = p1 < (long)j->pos_max ? p1 : (long)j->pos_max;
    return *lo <= *hi;
}

/* ---- the profile ---------------------------------------------------------- */

typedef struct token {
    const char *s;
    size_t n;
    size_t col; /* 1-based */
} token;

typedef struct where {
    const char *file;
    size_t line;
    char *why;
    size_t whylen;
} where;

static int at(const where *w, size_t col, const char *fmt, ...) PRINTF_LIKE(3, 4);

/* "FILE:LINE:COLUMN: reason" */
static int at(const where *w, size_t col, const char *fmt, ...)
{
    msg m = msg_start(w->why, w->whylen);
    char pos[48];
    va_list ap;
    (void)snprintf(pos, sizeof pos, ":%zu:%zu: ", w->line, col);
    msg_text(&m, w->file, strlen(w->file));
    msg_text(&m, pos, strlen(pos));
    va_start(ap, fmt);
    msg_vf(&m, fmt, ap);
    va_end(ap);
    return LSC_EINVAL;
}

/* The angle of position p through j, rounded down (*lo) and up (*hi): limits
 * lo..hi keep p in. p is within j's range. */
static void pos_angles(const lsc_joint *j, long p, int32_t *lo, int32_t *hi)
{
    long num = (p - (long)j->zero) * j->direction * j->span_cdeg;
    long range = (long)j->pos_max - (long)j->pos_min;
    *lo = (int32_t)floor_div(num, range);
    *hi = (int32_t)-floor_div(-num, range);
}

/* The angle of an end of the limits: degrees as written (lo = hi), or a
 * position's angle rounded outwards (pos_angles). */
static int limit_end(const where *w, const token *t, const char *s, size_t n,
                     const lsc_joint *j, int32_t *lo, int32_t *hi)
{
    value v;
    const char *bad = parse_value(s, n, &v);
    if (bad != NULL) {
        return at(w, t->col, "limits: %s", bad);
    }
    if (v.deg) {
        if (v.v < -LSC_UNITS_CDEG_MAX || v.v > LSC_UNITS_CDEG_MAX) {
            return at(w, t->col, "limits: an angle is within -360deg..360deg");
        }
        *lo = *hi = (int32_t)v.v;
        return LSC_OK;
    }
    if (v.v < j->pos_min || v.v > j->pos_max) {
        return at(w, t->col, "limits: position %ld is outside the servo's range %u..%u", v.v,
                  j->pos_min, j->pos_max);
    }
    pos_angles(j, v.v, lo, hi);
    return LSC_OK;
}

/* The first ".." in s[0..n), or NULL. */
static const char *find_dots(const char *s, size_t n)
{
    for (size_t i = 0; i + 1 < n; i++) {
        if (s[i] == '.' && s[i + 1] == '.') {
            return s + i;
        }
    }
    return NULL;
}

/* kind: pwm, bus, or MIN..MAX/SPANdeg */
static int parse_kind(const where *w, const token *t, lsc_joint *j, uint8_t id)
{
    if (t->n == 3 && memcmp(t->s, "pwm", 3) == 0) {
        return lsc_joint_init(j, id, LSC_JOINT_PWM);
    }
    if (t->n == 3 && memcmp(t->s, "bus", 3) == 0) {
        return lsc_joint_init(j, id, LSC_JOINT_BUS);
    }
    const char *dots = find_dots(t->s, t->n), *slash = memchr(t->s, '/', t->n);
    value lo, hi, span;
    if (dots == NULL || slash == NULL || slash < dots ||
        parse_value(t->s, (size_t)(dots - t->s), &lo) != NULL ||
        parse_value(dots + 2, (size_t)(slash - dots - 2), &hi) != NULL ||
        parse_value(slash + 1, t->n - (size_t)(slash + 1 - t->s), &span) != NULL || lo.deg ||
        hi.deg || !span.deg) {
        return at(w, t->col, "kind: use pwm (500..2500 over 180 degrees), bus (0..1000 over "
                             "240 degrees) or MIN..MAX/SPANdeg (0..4095/360deg)");
    }
    /* lsc_joint_init_range refuses a span outside 0.01deg..360deg */
    if (lo.v < 0 || lo.v >= hi.v || hi.v > LSC_UNITS_POS_MAX ||
        lsc_joint_init_range(j, id, (uint16_t)lo.v, (uint16_t)hi.v, (int32_t)span.v) != 0) {
        return at(w, t->col, "kind: positions are 0 <= MIN < MAX <= %d and the span is "
                             "0.01deg..360deg",
                  LSC_UNITS_POS_MAX);
    }
    return LSC_OK;
}

static int parse_dir(const where *w, const token *t, lsc_joint *j)
{
    const char *v = t->s + 4;
    size_t n = t->n - 4;
    if ((n == 2 && memcmp(v, "+1", 2) == 0) || (n == 1 && v[0] == '1')) {
        j->direction = 1;
    } else if (n == 2 && memcmp(v, "-1", 2) == 0) {
        j->direction = -1;
    } else {
        return at(w, t->col + 4, "dir: use +1 or -1");
    }
    return LSC_OK;
}

static int parse_offset(const where *w, const token *t, lsc_joint *j)
{
    value v;
    const char *bad = parse_value(t->s + 7, t->n - 7, &v);
    if (bad != NULL) {
        return at(w, t->col + 7, "offset: %s", bad);
    }
    lsc_joint servo = *j; /* the offset is the servo's: before any direction */
    servo.direction = 1;
    uint16_t zero = 0;
    long z = (long)j->zero + v.v;
    if (v.deg ? lsc_joint_to_pos(&servo, (int32_t)v.v, &zero) != 0
              : (z < j->pos_min || z > j->pos_max)) {
        return at(w, t->col + 7,
                  "offset: the joint's zero would be outside the servo's range %u..%u",
                  j->pos_min, j->pos_max);
    }
    j->zero = v.deg ? zero : (uint16_t)z;
    return LSC_OK;
}

/* limits=LOW..HIGH; without it the whole range (each end rounded outwards, so
 * that every position of the servo is in). A joint must keep a position. */
static int parse_limits(const where *w, const token *t, lsc_joint *j)
{
    int32_t a = 0, a_hi = 0, b = 0, b_hi = 0;
    char lo[LSC_ARM_DEGREES_MAX], hi[LSC_ARM_DEGREES_MAX];
    long plo, phi;
    if (t == NULL) {
        pos_angles(j, j->pos_min, &a, &a_hi);
        pos_angles(j, j->pos_max, &b, &b_hi);
    } else {
        const char *s = t->s + 7, *dots = find_dots(s, t->n - 7);
        size_t n = t->n - 7;
        if (dots == NULL) {
            return at(w, t->col + 7, "limits: write LOW..HIGH (-90deg..90deg, 100..900)");
        }
        if (limit_end(w, t, s, (size_t)(dots - s), j, &a, &a_hi) != 0 ||
            limit_end(w, t, dots + 2, n - (size_t)(dots + 2 - s), j, &b, &b_hi) != 0) {
            return LSC_EINVAL;
        }
    }
    j->min_cdeg = a < b ? a : b;
    j->max_cdeg = a < b ? b_hi : a_hi;
    if (t != NULL && !positions(j, &plo, &phi)) { /* the whole range keeps them all */
        degrees(lo, sizeof lo, j->min_cdeg);
        degrees(hi, sizeof hi, j->max_cdeg);
        return at(w, t->col + 7,
                  "limits: %sdeg..%sdeg hold no position of the servo: widen them", lo, hi);
    }
    return LSC_OK;
}

/* open=VALUE or closed=VALUE (a gripper's ends): a position or an angle of
 * the joint, inside its limits. */
static int parse_end(const where *w, const token *t, size_t klen, arm_joint *aj, size_t end)
{
    const lsc_joint *j = &aj->joint;
    const char *key = end == LSC_ARM_OPEN ? "open" : "closed";
    char text[SHOWN_CAP];
    value v;
    uint16_t pos = 0;
    const char *bad = parse_value(t->s + klen + 1, t->n - klen - 1, &v);
    if (bad != NULL) {
        return at(w, t->col + klen + 1, "%s: %s", key, bad);
    }
    if (v.deg ? (v.v < -LSC_UNITS_CDEG_MAX || v.v > LSC_UNITS_CDEG_MAX ||
                 lsc_joint_to_pos(j, (int32_t)v.v, &pos) != 0)
              : (v.v < j->pos_min || v.v > j->pos_max)) {
        return at(w, t->col + klen + 1, "%s: %s is outside the servo's range %u..%u", key,
                  shown(text, t->s + klen + 1, t->n - klen - 1), j->pos_min, j->pos_max);
    }
    pos = v.deg ? pos : (uint16_t)v.v;
    if (!lsc_joint_allows_pos(j, pos)) {
        return at(w, t->col + klen + 1, "%s: position %u is outside the joint's limits", key,
                  pos);
    }
    aj->has_end[end] = true;
    aj->end[end] = pos;
    return LSC_OK;
}

#define SETTINGS 5u /* dir, offset, limits, open, closed */

/* The key=value settings of a joint, applied in the order dir, offset,
 * limits, then the gripper's ends. */
static int parse_settings(const where *w, const token *tok, size_t ntok, arm_joint *aj)
{
    static const char *const keys[SETTINGS] = {"dir", "offset", "limits", "open", "closed"};
    const token *set[SETTINGS] = {NULL, NULL, NULL, NULL, NULL};
    char text[SHOWN_CAP];
    lsc_joint *j = &aj->joint;
    for (size_t i = 3; i < ntok; i++) {
        const char *eq = memchr(tok[i].s, '=', tok[i].n);
        size_t k = 0, klen = eq != NULL ? (size_t)(eq - tok[i].s) : tok[i].n;
        while (k < SETTINGS &&
               !(strlen(keys[k]) == klen && memcmp(tok[i].s, keys[k], klen) == 0)) {
            k++;
        }
        if (eq == NULL || k == SETTINGS) {
            return at(w, tok[i].col, "'%s': settings are dir=+1|-1, offset=VALUE, "
                                     "limits=LOW..HIGH, open=VALUE and closed=VALUE",
                      shown(text, tok[i].s, tok[i].n));
        }
        if (set[k] != NULL) {
            return at(w, tok[i].col, "%s is given twice", keys[k]);
        }
        set[k] = &tok[i];
    }
    if ((set[0] != NULL && parse_dir(w, set[0], j) != 0) ||
        (set[1] != NULL && parse_offset(w, set[1], j) != 0) ||
        parse_limits(w, set[2], j) != 0 ||
        (set[3] != NULL && parse_end(w, set[3], 4, aj, LSC_ARM_OPEN) != 0) ||
        (set[4] != NULL && parse_end(w, set[4], 6, aj, LSC_ARM_CLOSED) != 0)) {
        return LSC_EINVAL;
    }
    return LSC_OK;
}

static bool is_name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || is_digit(c) || c == '_' ||
           c == '-';
}

/* One joint line: tok[0..ntok) (ntok >= 1). */
static int parse_joint(lsc_arm *arm, const where *w, const token *tok, size_t ntok)
{
    char why[160];
    unsigned long id = 0;
    if (ntok < 3) {
        return at(w, tok[ntok - 1].col + tok[ntok - 1].n,
                  "a joint is NAME ID KIND [dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]");
    }
    if (ntok > 3 + SETTINGS) {
        return at(w, tok[3 + SETTINGS].col, "too many fields: a joint has at most five settings");
    }
    if (tok[0].n > LSC_ARM_NAME_MAX || !((tok[0].s[0] >= 'a' && tok[0].s[0] <= 'z') ||
                                         (tok[0].s[0] >= 'A' && tok[0].s[0] <= 'Z'))) {
        return at(w, tok[0].col, "a joint's name starts with a letter and has at most %u "
                                 "characters",
                  LSC_ARM_NAME_MAX);
    }
    for (size_t i = 0; i < tok[0].n; i++) {
        if (!is_name_char(tok[0].s[i])) {
            return at(w, tok[0].col + i, "a joint's name has letters, digits, _ and - only");
        }
    }
    if (span_id(tok[1].s, tok[1].n, &id, why, sizeof why) != 0) {
        return at(w, tok[1].col, "%s", why);
    }
    if (arm->n == LSC_ARM_JOINTS_MAX) {
        return at(w, tok[0].col, "too many joints: at most %u", LSC_ARM_JOINTS_MAX);
    }
    for (size_t i = 0; i < arm->n; i++) {
        if (strlen(arm->joints[i].name) == tok[0].n &&
            memcmp(arm->joints[i].name, tok[0].s, tok[0].n) == 0) {
            return at(w, tok[0].col, "joint %s is named twice", arm->joints[i].name);
        }
        if (arm->joints[i].joint.id == id) {
            return at(w, tok[1].col, "servo %lu is joint %s already", id, arm->joints[i].name);
        }
    }
    arm_joint *aj = &arm->joints[arm->n];
    memset(aj, 0, sizeof *aj);
    if (parse_kind(w, &tok[2], &aj->joint, (uint8_t)id) != 0 ||
        parse_settings(w, tok, ntok, aj) != 0) {
        return LSC_EINVAL;
    }
    memcpy(aj->name, tok[0].s, tok[0].n);
    aj->name[tok[0].n] = '\0';
    arm->n++;
    return LSC_OK;
}

/* ---- the geometry lines ---------------------------------------------------- */

static bool token_is(const token *t, const char *s)
{
    return t->n == strlen(s) && memcmp(t->s, s, t->n) == 0;
}

/* chain: BASE SHOULDER ELBOW WRIST ROLL [GRIPPER], joints of lines above */
static int parse_chain(lsc_arm *arm, const where *w, const token *tok, size_t ntok)
{
    char text[SHOWN_CAP];
    arm_chain *c = &arm->chain;
    if (c->chain_line != 0) {
        return at(w, tok[0].col, "chain: is given twice");
    }
    if (ntok < 1u + LSC_KIN_JOINTS || ntok > 1u + LSC_ARM_CHAIN_MAX) {
        return at(w, tok[0].col, "chain: names the joints base, shoulder, elbow, wrist "
                                 "(pitch), wrist roll and, if you like, the gripper, in that "
                                 "order");
    }
    for (size_t i = 1; i < ntok; i++) {
        size_t k = 0;
        while (k < arm->n && !token_is(&tok[i], arm->joints[k].name)) {
            k++;
        }
        if (k == arm->n) {
            return at(w, tok[i].col, "chain: '%s' is no joint of a line above",
                      shown(text, tok[i].s, tok[i].n));
        }
        for (size_t m = 0; m + 1 < i; m++) {
            if (c->joint[m] == k) {
                return at(w, tok[i].col, "chain: joint %s is named twice", arm->joints[k].name);
            }
        }
        c->joint[i - 1] = k;
    }
    c->n = ntok - 1;
    c->chain_line = w->line;
    return LSC_OK;
}

/* s[0..n): DIGITS[.D[D]]mm, in hundredths of a mm (0..LENGTH_MAX). NULL, or why not. */
static const char *parse_mm(const char *s, size_t n, long *out)
{
    size_t i = 0, frac = 0;
    long v = 0;
    for (; i < n && is_digit(s[i]); i++) {
        if (v > LENGTH_MAX) {
            return "at most 10000mm";
        }
        v = v * 10 + (long)(s[i] - '0');
    }
    if (i == 0) {
        return "write a length in mm (98.8mm)";
    }
    v *= 100;
    if (i < n && s[i] == '.') {
        for (i++; i < n && is_digit(s[i]); i++, frac++) {
            if (frac == 2) {
                return "a length has at most two decimals (0.01mm)";
            }
            v += (long)(s[i] - '0') * (frac == 0 ? 10L : 1L);
        }
        if (frac == 0) {
            return "a decimal point needs a digit after it";
        }
    }
    if (!(n - i == 2 && memcmp(s + i, "mm", 2) == 0)) {
        return "write a length in mm (98.8mm)";
    }
    if (v > LENGTH_MAX) {
        return "at most 10000mm";
    }
    *out = v;
    return NULL;
}

/* links: height=LENGTH upper=LENGTH fore=LENGTH tool=LENGTH, any order */
static int parse_links(lsc_arm *arm, const where *w, const token *tok, size_t ntok)
{
    static const char *const keys[LINKS] = {"height", "upper", "fore", "tool"};
    char text[SHOWN_CAP];
    arm_chain *c = &arm->chain;
    bool seen[LINKS] = {false, false, false, false};
    if (c->links_line != 0) {
        return at(w, tok[0].col, "links: is given twice");
    }
    for (size_t i = 1; i < ntok; i++) {
        const char *eq = memchr(tok[i].s, '=', tok[i].n);
        size_t k = 0, klen = eq != NULL ? (size_t)(eq - tok[i].s) : tok[i].n;
        while (k < LINKS && !(strlen(keys[k]) == klen && memcmp(tok[i].s, keys[k], klen) == 0)) {
            k++;
        }
        if (eq == NULL || k == LINKS) {
            return at(w, tok[i].col, "links: '%s': use height=, upper=, fore= and tool= (mm)",
                      shown(text, tok[i].s, tok[i].n));
        }
        if (seen[k]) {
            return at(w, tok[i].col, "links: %s is given twice", keys[k]);
        }
        const char *bad = parse_mm(eq + 1, tok[i].n - klen - 1u, &c->length[k]);
        if (bad == NULL && (k == 1 || k == 2) && c->length[k] == 0) {
            bad = "the arm's links are longer than 0mm";
        }
        if (bad != NULL) {
            return at(w, tok[i].col + klen + 1u, "links: %s: %s", keys[k], bad);
        }
        seen[k] = true;
    }
    for (size_t k = 0; k < LINKS; k++) {
        if (!seen[k]) {
            return at(w, tok[ntok - 1].col + tok[ntok - 1].n,
                      "links: gives height=, upper=, fore= and tool= (%s is missing)", keys[k]);
        }
    }
    c->links_line = w->line;
    return LSC_OK;
}

/* Both geometry lines, or neither. */
static int chain_complete(const lsc_arm *arm, where *w)
{
    const arm_chain *c = &arm->chain;
    if ((c->chain_line != 0) == (c->links_line != 0)) {
        return LSC_OK;
    }
    w->line = c->chain_line != 0 ? c->chain_line : c->links_line;
    return at(w, 1, c->chain_line != 0 ? "chain: needs a links: line too (docs/arm-profile.md)"
                                       : "links: needs a chain: line too (docs/arm-profile.md)");
}

/* The lines of text[0..len) into arm (empty). */
static int parse_lines(lsc_arm *arm, const char *text, size_t len, where *w)
{
    size_t pos = 0;
    while (pos < len) {
        token tok[TOKENS_MAX];
        size_t ntok = 0, start = pos;
        bool comment = false;
        w->line++;
        for (; pos < len && text[pos] != '\n'; pos++) {
            char c = text[pos];
            size_t col = pos - start + 1u;
            if (c == '\t' || (c == '\r' && (pos + 1 == len || text[pos + 1] == '\n'))) {
                continue;
            }
            if ((unsigned char)c < 0x20 || (unsigned char)c == 0x7f) {
                return at(w, col, "unexpected byte 0x%02X", (unsigned)(unsigned char)c);
            }
            if (c == '#') {
                comment = true;
            } else if (comment || c == ' ') {
                continue;
            } else if (pos > start && text[pos - 1] != ' ' && text[pos - 1] != '\t') {
                tok[ntok - 1].n++; /* inside a token */
            } else if (ntok == TOKENS_MAX) {
                return at(w, col, "too many fields: a joint has at most five settings");
            } else {
                tok[ntok++] = (token){text + pos, 1, col};
            }
        }
        if (ntok > 0 && (token_is(&tok[0], "chain:")   ? parse_chain(arm, w, tok, ntok)
                         : token_is(&tok[0], "links:") ? parse_links(arm, w, tok, ntok)
                                                        : parse_joint(arm, w, tok, ntok)) != 0) {
            return LSC_EINVAL;
        }
        pos++; /* the newline */
    }
    if (arm->n == 0) {
        return file_fail(LSC_EINVAL, w->why, w->whylen, "", w->file,
                         ": no joints: a profile names at least one (see docs/arm-profile.md)");
    }
    return chain_complete(arm, w);
}

int lsc_arm_parse(const char *text, size_t len, const char *file, lsc_arm **out, char *why,
                  size_t whylen)
{
    static const char bom[] = "\xEF\xBB\xBF";
    where w = {file != NULL ? file : "profile", 0, why, whylen};
    if (out != NULL) {
        *out = NULL;
    }
    if (out == NULL || (text == NULL && len > 0)) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_parse: no text or no out");
    }
    if (len >= 3 && memcmp(text, bom, 3) == 0) { /* a UTF-8 byte-order mark */
        text += 3;
        len -= 3;
    }
    lsc_arm *arm = malloc(sizeof *arm);
    if (arm == NULL) {
        return oom(why, whylen);
    }
    memset(arm, 0, sizeof *arm);
    int r = parse_lines(arm, text, len, &w);
    if (r != LSC_OK) {
        free(arm);
        return r;
    }
    *out = arm;
    return LSC_OK;
}

static const char *kind_of(mode_t mode)
{
    return S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO" : "a device";
}

int lsc_arm_load(const char *path, lsc_arm **out, char *why, size_t whylen)
{
    static const char cannot[] = "cannot read the arm profile ";
    struct stat st;
    if (out != NULL) {
        *out = NULL;
    }
    if (path == NULL || out == NULL) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_load: no path or no out");
    }
    /* O_NONBLOCK: opening a FIFO must not wait for a writer */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        return file_fail(LSC_EIO, why, whylen, cannot, path, ": %s", strerror(errno));
    }
    memset(&st, 0, sizeof st);
    (void)fstat(fd, &st); /* cannot fail on an open fd; if it did: mode 0, refused */
    if (!S_ISREG(st.st_mode)) {
        (void)close(fd);
        return file_fail(LSC_EINVAL, why, whylen, cannot, path,
                         ": it is %s (an arm profile is a regular file)", kind_of(st.st_mode));
    }
    char *text = malloc(LSC_ARM_FILE_MAX + 1u);
    size_t n = 0;
    int err = 0;
    while (text != NULL && n <= LSC_ARM_FILE_MAX) {
        ssize_t r = read(fd, text + n, LSC_ARM_FILE_MAX + 1u - n);
        if (r > 0) {
            n += (size_t)r;
        } else if (r == 0) {
            break;
        } else if (errno != EINTR) {
            err = errno;
            break;
        }
    }
    (void)close(fd);
    int r;
    if (text == NULL) {
        r = oom(why, whylen);
    } else if (err != 0) {
        r = file_fail(LSC_EIO, why, whylen, cannot, path, ": %s", strerror(err));
    } else if (n > LSC_ARM_FILE_MAX) {
        r = file_fail(LSC_EINVAL, why, whylen, "", path,
                      ": longer than %u bytes: not an arm profile", LSC_ARM_FILE_MAX);
    } else {
        r = lsc_arm_parse(text, n, path, out, why, whylen);
    }
    free(text);
    return r;
}

/* ---- profiles by name ------------------------------------------------------- */

/* The installed profiles (PREFIX/share/lsc/arms: CMake defines it from the
 * install prefix; this is its default prefix's). */
#ifndef LSC_ARMS_INSTALL_DIR
#define LSC_ARMS_INSTALL_DIR "/usr/local/share/lsc/arms"
#endif
#define PATH_CAP 4096u /* bytes of a profile's path looked for, with the NUL */
#define LOOKS 2u       /* places a name is looked for */

/* A variable's value when it is set and not empty, else NULL. */
static const char *env_value(const char *name)
{
    const char *v = getenv(name);
    return v != NULL && *v != '\0' ? v : NULL;
}

/* Whether name is a file's path rather than a profile's name: a '/' in it, or
 * the ending ".conf". */
static bool is_path(const char *name)
{
    static const char conf[] = ".conf";
    size_t n = strlen(name);
    return strchr(name, '/') != NULL ||
           (n >= sizeof conf - 1u && strcmp(name + n - (sizeof conf - 1u), conf) == 0);
}

/* DIR SUB/NAME.conf into out[PATH_CAP]: false when it does not fit. */
static bool join(char *out, const char *dir, const char *sub, const char *name)
{
    int n = snprintf(out, PATH_CAP, "%s%s/%s.conf", dir, sub, name);
    return (size_t)n < PATH_CAP; /* (negative: an error, as large) */
}

int lsc_arm_path(const char *name, char *out, size_t cap, char *why, size_t whylen)
{
    char path[LOOKS][PATH_CAP];
    size_t n = 0;
    bool fits = true;
    if (name == NULL || out == NULL || cap == 0) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_path: no name or no room");
    }
    if (*name == '\0') {
        return failf(LSC_EINVAL, why, whylen,
                     "no arm profile given: a profile's name (xarm) or a file's path");
    }
    if (is_path(name)) {
        fits = strlen(name) < PATH_CAP;
        (void)snprintf(path[n++], PATH_CAP, "%s", name);
    } else {
        /* $XDG_CONFIG_HOME (an absolute path, else unset: the XDG rule), else ~/.config */
        const char *config = env_value("XDG_CONFIG_HOME");
        const char *home = env_value("HOME");
        if (config != NULL && config[0] == '/') {
            fits = join(path[n++], config, "/lsc/arms", name);
        } else if (home != NULL) {
            fits = join(path[n++], home, "/.config/lsc/arms", name);
        }
        const char *installed = env_value("LSC_ARMS_DIR");
        fits = fits &&
               join(path[n++], installed != NULL ? installed : LSC_ARMS_INSTALL_DIR, "", name);
    }
    if (!fits) {
        return failf(LSC_EINVAL, why, whylen,
                     "the arm profile's name is too long (%zu bytes): a name such as xarm, or "
                     "a file's path",
                     strlen(name));
    }
    for (size_t i = 0; i < n; i++) {
        struct stat st;
        /* there (or there but not for us: lsc_arm_load says why), or a path as given */
        if (is_path(name) || stat(path[i], &st) == 0 || (errno != ENOENT && errno != ENOTDIR)) {
            if (strlen(path[i]) >= cap) {
                return failf(LSC_EINVAL, why, whylen, "lsc_arm_path: no room for the path");
            }
            memcpy(out, path[i], strlen(path[i]) + 1u);
            return LSC_OK;
        }
    }
    msg m = msg_start(why, whylen);
    msg_str(&m, "no arm profile named ");
    msg_str(&m, name);
    msg_str(&m, ": looked for ");
    for (size_t i = 0; i < n; i++) {
        msg_str(&m, i > 0 ? ", " : "");
        msg_str(&m, path[i]);
    }
    msg_str(&m, " (a file in this directory: ./");
    msg_str(&m, name);
    msg_str(&m, ")");
    return LSC_EIO;
}

int lsc_arm_open(const char *name, lsc_arm **out, char *why, size_t whylen)
{
    char path[PATH_CAP];
    if (out != NULL) {
        *out = NULL;
    }
    if (name == NULL || out == NULL) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_open: no name or no out");
    }
    int r = lsc_arm_path(name, path, sizeof path, why, whylen);
    return r != 0 ? r : lsc_arm_load(path, out, why, whylen);
}

void lsc_arm_free(lsc_arm *arm)
{
    free(arm);
}

lsc_arm *lsc_arm_copy(const lsc_arm *arm)
{
    lsc_arm *copy = arm != NULL ? malloc(sizeof *copy) : NULL;
    if (copy != NULL) {
        memcpy(copy, arm, sizeof *copy);
    }
    return copy;
}

size_t lsc_arm_count(const lsc_arm *arm)
{
    return arm != NULL ? arm->n : 0;
}

const char *lsc_arm_name(const lsc_arm *arm, size_t i)
{
    return i < lsc_arm_count(arm) ? arm->joints[i].name : NULL;
}

const lsc_joint *lsc_arm_joint(const lsc_arm *arm, size_t i)
{
    return i < lsc_arm_count(arm) ? &arm->joints[i].joint : NULL;
}

int lsc_arm_stand_in(const lsc_arm *arm, lsc_sim *sim)
{
    if (arm == NULL || sim == NULL) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < arm->n; i++) {
        const lsc_joint *j = &arm->joints[i].joint;
        (void)lsc_sim_set_servo(sim, j->id, j->zero, j->pos_min, j->pos_max);
    }
    return 0;
}

/* The joint on servo id, or NULL (arm may be NULL). */
static const arm_joint *joint_on(const lsc_arm *arm, uint8_t id)
{
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        if (arm->joints[i].joint.id == id) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

/* The joint named s[0..n), else the joint on the servo id s[0..n) spells,
 * else NULL (arm may be NULL). */
static const arm_joint *joint_named(const lsc_arm *arm, const char *s, size_t n)
{
    long id = as_id(s, n);
    if (id >= 0) {
        return joint_on(arm, (uint8_t)id);
    }
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        if (strlen(arm->joints[i].name) == n && memcmp(arm->joints[i].name, s, n) == 0) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

/* aj's index in arm (aj one of its joints), or -1 for NULL */
static int index_of(const lsc_arm *arm, const arm_joint *aj)
{
    return aj != NULL ? (int)(aj - arm->joints) : -1;
}

int lsc_arm_end(const lsc_arm *arm, size_t i, lsc_arm_end_kind end, uint16_t *pos)
{
    if (arm == NULL || i >= arm->n || (end != LSC_ARM_OPEN && end != LSC_ARM_CLOSED) ||
        !arm->joints[i].has_end[end]) {
        return LSC_EINVAL;
    }
    if (pos != NULL) {
        *pos = arm->joints[i].end[end];
    }
    return LSC_OK;
}

int lsc_arm_by_id(const lsc_arm *arm, uint8_t id)
{
    return index_of(arm, joint_on(arm, id));
}

int lsc_arm_find(const lsc_arm *arm, const char *name)
{
    return name != NULL ? index_of(arm, joint_named(arm, name, strlen(name))) : -1;
}

/* "WHAT is outside the limits of joint base (servo 6): -90.00deg..90.00deg,
 * positions 125..875" */
static int refuse(const arm_joint *aj, const char *what, char *why, size_t whylen)
{
    const lsc_joint *j = &aj->joint;
    char lo[LSC_ARM_DEGREES_MAX], hi[LSC_ARM_DEGREES_MAX];
    long plo, phi;
    degrees(lo, sizeof lo, j->min_cdeg);
    degrees(hi, sizeof hi, j->max_cdeg);
    (void)positions(j, &plo, &phi); /* a profile's joints always keep one */
    return failf(LSC_EINVAL, why, whylen,
                 "%s is outside the limits of joint %s (servo %u): %sdeg..%sdeg, "
                 "positions %ld..%ld",
                 what, aj->name, j->id, lo, hi, plo, phi);
}

/* "ID:POSITION" (either decimal or 0x-hex): without a profile. */
static int parse_servo(const char *s, lsc_servo *out, char *why, size_t whylen)
{
    const char *colon = strchr(s, ':');
    char idtext[32], text[SHOWN_CAP];
    unsigned long id = 0, pos = 0;
    size_t idlen = colon != NULL ? (size_t)(colon - s) : 0;
    if (colon == NULL || idlen >= sizeof idtext) {
        return failf(LSC_EINVAL, why, whylen, "'%s' is not ID:POS (for example 1:1500)",
                     shown(text, s, strlen(s)));
    }
    memcpy(idtext, s, idlen);
    idtext[idlen] = '\0';
    if (parse_uint(idtext, 255, "id", &id, why, whylen) != 0 ||
        parse_uint(colon + 1, 65535, "position", &pos, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    out->id = (uint8_t)id;
    out->position = (uint16_t)pos;
    return LSC_OK;
}

static bool is_letter(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

lsc_arm_need lsc_arm_needs_profile(const char *arg)
{
    size_t len = arg != NULL ? strlen(arg) : 0u;
    if (len == 0u) {
        return LSC_ARM_NEEDS_NONE;
    }
    if (is_letter(arg[0])) {
        return LSC_ARM_NEEDS_JOINT;
    }
    return strchr(arg, ':') != NULL && len >= 3 && memcmp(arg + len - 3, "deg", 3) == 0
               ? LSC_ARM_NEEDS_DEGREES
               : LSC_ARM_NEEDS_NONE;
}

int lsc_arm_target(const lsc_arm *arm, const char *arg, lsc_servo *out, char *why,
                   size_t whylen)
{
    char text[SHOWN_CAP], what[48];
    value v;
    if (arg == NULL || out == NULL) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_target: no argument or no out");
    }
    const char *colon = strchr(arg, ':');
    size_t len = strlen(arg);
    if (arm == NULL && lsc_arm_needs_profile(arg) == LSC_ARM_NEEDS_NONE) {
        return parse_servo(arg, out, why, whylen); /* ID:POSITION */
    }
    if (colon == NULL) {
        return failf(LSC_EINVAL, why, whylen,
                     "'%s' is not JOINT:VALUE (base:30deg, 2:-15.5deg, 1:700)",
                     shown(text, arg, len));
    }
    size_t n = (size_t)(colon - arg);
    const arm_joint *aj = joint_named(arm, arg, n);
    long id = as_id(arg, n);
    const char *bad = parse_value(colon + 1, len - n - 1u, &v);
    if (aj == NULL && id < 0) {
        return failf(LSC_EINVAL, why, whylen,
                     arm == NULL ? "'%s' is not a servo id: a joint name needs an arm profile"
                                 : "'%s' is neither a joint of the arm profile nor a servo id",
                     shown(text, arg, n));
    }
    if (bad != NULL) {
        return failf(LSC_EINVAL, why, whylen, "'%s': %s", shown(text, arg, len), bad);
    }
    if (aj == NULL && v.deg) {
        return failf(LSC_EINVAL, why, whylen,
                     arm == NULL ? "'%s': servo %ld is not a joint of any arm profile, so it "
                                   "has no degrees: give a position"
                                 : "'%s': servo %ld is not a joint of the arm profile, so it "
                                   "has no degrees: give a position",
                     shown(text, arg, len), id);
    }
    if (!v.deg && (v.v < 0 || v.v > 65535)) {
        return failf(LSC_EINVAL, why, whylen, "'%s': a position is 0..65535",
                     shown(text, arg, len));
    }
    if (aj == NULL) {
        out->id = (uint8_t)id;
        out->position = (uint16_t)v.v;
        return LSC_OK;
    }
    uint16_t pos = v.deg ? 0u : (uint16_t)v.v;
    /* colon + 1 parsed as a value: at most 13 plain characters */
    (void)snprintf(what, sizeof what, "%s%s", v.deg ? "" : "position ", colon + 1);
    if (v.deg) {
        int32_t cdeg = (int32_t)v.v; /* |v.v| < 10^8: DIGITS_MAX */
        if (lsc_joint_to_pos(&aj->joint, cdeg, &pos) != 0 || cdeg < aj->joint.min_cdeg ||
            cdeg > aj->joint.max_cdeg) {
            return refuse(aj, what, why, whylen);
        }
        /* the angle is inside; the position it rounds to must be too */
        (void)snprintf(what, sizeof what, "%s (position %u)", colon + 1, pos);
    }
    if (!lsc_joint_allows_pos(&aj->joint, pos)) {
        return refuse(aj, what, why, whylen);
    }
    out->id = aj->joint.id;
    out->position = pos;
    return LSC_OK;
}

int lsc_arm_servo_id(const lsc_arm *arm, const char *arg, uint8_t *id, char *why,
                     size_t whylen)
{
    char text[SHOWN_CAP];
    unsigned long v = 0;
    if (arg == NULL || id == NULL) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_servo_id: no argument or no id");
    }
    const arm_joint *aj = joint_named(arm, arg, strlen(arg));
    if (aj != NULL) {
        *id = aj->joint.id;
        return LSC_OK;
    }
    if (arm != NULL && arg[0] != '\0' && !is_digit(arg[0])) {
        return failf(LSC_EINVAL, why, whylen,
                     "'%s' is neither a joint of the arm profile nor a servo id",
                     shown(text, arg, strlen(arg)));
    }

    if (parse_uint(arg, 255, "id", &v, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    *id = (uint8_t)v;
    return LSC_OK;
}

int lsc_arm_check(const lsc_arm *arm, const lsc_servo *servos, size_t n, char *why,
                  size_t whylen)
{
    char what[24];
    if (servos == NULL && n > 0) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_check: no servos");
    }
    for (size_t k = 0; k < n; k++) {
        const arm_joint *aj = joint_on(arm, servos[k].id);
        if (aj != NULL && !lsc_joint_allows_pos(&aj->joint, servos[k].position)) {
            (void)snprintf(what, sizeof what, "position %u", servos[k].position);
            return refuse(aj, what, why, whylen);
        }
    }
    return LSC_OK;
}

int lsc_arm_chain(const lsc_arm *arm, lsc_kin_chain *chain, int *joints, char *why,
                  size_t whylen)
{
    if (arm == NULL || chain == NULL) {
        return failf(LSC_EINVAL, why, whylen, "lsc_arm_chain: no arm profile or no chain");
    }
    const arm_chain *c = &arm->chain;
    if (c->chain_line == 0) {
        return failf(LSC_EINVAL, why, whylen,
                     "the arm profile states no geometry: add its chain: and links: lines "
                     "(docs/arm-profile.md, docs/kinematics.md)");
    }
    chain->base_mm = (float)c->length[0] / 100.0f;
    chain->upper_mm = (float)c->length[1] / 100.0f;
    chain->fore_mm = (float)c->length[2] / 100.0f;
    chain->tool_mm = (float)c->length[3] / 100.0f;
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        const lsc_joint *j = &arm->joints[c->joint[i]].joint;
        chain->min_deg[i] = (float)j->min_cdeg / 100.0f;
        chain->max_deg[i] = (float)j->max_cdeg / 100.0f;
    }
    for (size_t i = 0; joints != NULL && i < LSC_ARM_CHAIN_MAX; i++) {
        joints[i] = i < c->n ? (int)c->joint[i] : -1;
    }
    return LSC_OK;
}

int lsc_arm_degrees(const lsc_arm *arm, const lsc_servo *s, char *deg, size_t cap)
{
    const arm_joint *aj = s != NULL ? joint_on(arm, s->id) : NULL;
    int32_t cdeg;
    if (deg != NULL && cap > 0) {
        deg[0] = '\0';
        if (aj != NULL && lsc_joint_to_cdeg(&aj->joint, s->position, &cdeg) == 0) {
            degrees(deg, cap, cdeg);
        }
    }
    return index_of(arm, aj);
}

#endif
