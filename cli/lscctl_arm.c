/* lscctl: arm profiles (docs/arm-profile.md) and the JOINT:VALUE arguments
 * that use them. The conversions and the limit check are lsc/units.h's. */
#include "lscctl_arm.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "lscctl_parse.h"

#define TOKENS_MAX 8u /* NAME ID KIND and at most three key=value, plus extras to report */
#define DIGITS_MAX 6u /* of a value's whole part: keeps every value far from overflow */

typedef struct token {
    const char *s;
    size_t n;
    size_t col; /* 1-based */
} token;

/* A value as written: a position (whole number) or an angle (deg). */
typedef struct value {
    bool deg;
    long v; /* position, or centidegrees */
} value;

static int failf(char *why, size_t whylen, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int failf(char *why, size_t whylen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, whylen, fmt, ap);
    va_end(ap);
    return -1;
}

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static bool is_name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || is_digit(c) || c == '_' ||
           c == '-';
}

/* s[0..n): [+-]DIGITS[.D[D]]deg or [+-]DIGITS. Returns NULL, or why not. */
static const char *parse_value(const char *s, size_t n, value *out)
{
    size_t i = 0, digits = 0, frac = 0;
    long whole = 0, cents = 0;
    bool neg = false;
    if (i < n && (s[i] == '+' || s[i] == '-')) {
        neg = s[i++] == '-';
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

/* s[0..n) as a servo id: decimal or 0x-hex, 0..255 (lscctl_parse_uint's rules
 * and reasons; at most 15 characters). */
static int span_id(const char *s, size_t n, unsigned long *id, char *why, size_t whylen)
{
    char text[16];
    if (n >= sizeof text) {
        return failf(why, whylen, "id: use 0..255");
    }
    memcpy(text, s, n);
    text[n] = '\0';
    return lscctl_parse_uint(text, 255, "id", id, why, whylen);
}

/* ---- the profile ---------------------------------------------------------- */

typedef struct where {
    const char *file;
    size_t line;
    char *why;
    size_t whylen;
} where;

static int at(const where *w, size_t col, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int at(const where *w, size_t col, const char *fmt, ...)
{
    char msg[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return failf(w->why, w->whylen, "%s:%zu:%zu: %s", w->file, w->line, col, msg);
}

static long floor_div(long num, long den) /* den > 0 */
{
    return num >= 0 ? num / den : -((-num + den - 1) / den);
}

/* The angle of an end of the limits: degrees as written (lo = hi), or a
 * position's exact angle through the joint rounded down (lo) and up (hi),
 * so that the limits keep that position in. */
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
        return 0;
    }
    if (v.v < j->pos_min || v.v > j->pos_max) {
        return at(w, t->col, "limits: position %ld is outside the servo's range %u..%u", v.v,
                  j->pos_min, j->pos_max);
    }
    long num = (v.v - (long)j->zero) * j->direction * j->span_cdeg;
    long range = (long)j->pos_max - (long)j->pos_min;
    *lo = (int32_t)floor_div(num, range);
    *hi = (int32_t)-floor_div(-num, range);
    return 0;
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
    const char *dots = NULL, *slash = memchr(t->s, '/', t->n);
    for (size_t i = 0; i + 1 < t->n; i++) {
        if (t->s[i] == '.' && t->s[i + 1] == '.') {
            dots = t->s + i;
            break;
        }
    }
    value lo, hi, span;
    if (dots == NULL || slash == NULL || slash < dots ||
        parse_value(t->s, (size_t)(dots - t->s), &lo) != NULL ||
        parse_value(dots + 2, (size_t)(slash - dots - 2), &hi) != NULL ||
        parse_value(slash + 1, t->n - (size_t)(slash + 1 - t->s), &span) != NULL || lo.deg ||
        hi.deg || !span.deg) {
        return at(w, t->col, "kind: use pwm (500..2500 over 180 degrees), bus (0..1000 over "
                             "240 degrees) or MIN..MAX/SPANdeg (0..4095/360deg)");
    }
    if (lo.v < 0 || hi.v > LSC_UNITS_POS_MAX || lo.v >= hi.v || span.v < 1 ||
        span.v > LSC_UNITS_CDEG_MAX ||
        lsc_joint_init_range(j, id, (uint16_t)lo.v, (uint16_t)hi.v, (int32_t)span.v) != 0) {
        return at(w, t->col, "kind: positions are 0 <= MIN < MAX <= %d and the span is "
                             "0.01deg..360deg",
                  LSC_UNITS_POS_MAX);
    }
    return 0;
}

/* The key=value settings of a joint, in the order dir, offset, limits. */
static int parse_settings(const where *w, const token *tok, size_t ntok, lsc_joint *j)
{
    static const char *const keys[] = {"dir", "offset", "limits"};
    const token *set[3] = {NULL, NULL, NULL};
    for (size_t i = 3; i < ntok; i++) {
        const char *eq = memchr(tok[i].s, '=', tok[i].n);
        size_t k = 0, klen = eq != NULL ? (size_t)(eq - tok[i].s) : tok[i].n;
        while (k < 3 && !(strlen(keys[k]) == klen && memcmp(tok[i].s, keys[k], klen) == 0)) {
            k++;
        }
        if (eq == NULL || k == 3) {
            return at(w, tok[i].col, "'%.*s': settings are dir=+1|-1, offset=VALUE and "
                                     "limits=LOW..HIGH",
                      (int)(tok[i].n > 40 ? 40 : tok[i].n), tok[i].s);
        }
        if (set[k] != NULL) {
            return at(w, tok[i].col, "%s is given twice", keys[k]);
        }
        set[k] = &tok[i];
    }
    if (set[0] != NULL) {
        const char *v = set[0]->s + 4;
        size_t n = set[0]->n - 4;
        if ((n == 2 && memcmp(v, "+1", 2) == 0) || (n == 1 && v[0] == '1')) {
            j->direction = 1;
        } else if (n == 2 && memcmp(v, "-1", 2) == 0) {
            j->direction = -1;
        } else {
            return at(w, set[0]->col + 4, "dir: use +1 or -1");
        }
    }
    if (set[1] != NULL) {
        value v;
        const char *bad = parse_value(set[1]->s + 7, set[1]->n - 7, &v);
        if (bad != NULL) {
            return at(w, set[1]->col + 7, "offset: %s", bad);
        }
        lsc_joint servo = *j; /* the offset is the servo's: before any direction */
        servo.direction = 1;
        uint16_t zero = 0;
        long z = (long)j->zero + v.v;
        if (v.deg ? lsc_joint_to_pos(&servo, (int32_t)v.v, &zero) != 0
                  : (z < j->pos_min || z > j->pos_max)) {
            return at(w, set[1]->col + 7,
                      "offset: the joint's zero would be outside the servo's range %u..%u",
                      j->pos_min, j->pos_max);
        }
        j->zero = v.deg ? zero : (uint16_t)z;
    }
    /* the limits: the whole range after dir and offset, unless given */
    int32_t a = 0, b = 0, a_hi, b_hi;
    (void)lsc_joint_to_cdeg(j, j->pos_min, &a);
    (void)lsc_joint_to_cdeg(j, j->pos_max, &b);
    a_hi = a;
    b_hi = b;
    if (set[2] != NULL) {
        const char *s = set[2]->s + 7, *dots = NULL;
        size_t n = set[2]->n - 7;
        for (size_t i = 0; i + 1 < n && dots == NULL; i++) {
            dots = s[i] == '.' && s[i + 1] == '.' ? s + i : NULL;
        }
        if (dots == NULL) {
            return at(w, set[2]->col + 7, "limits: write LOW..HIGH (-90deg..90deg, 100..900)");
        }
        if (limit_end(w, set[2], s, (size_t)(dots - s), j, &a, &a_hi) != 0 ||
            limit_end(w, set[2], dots + 2, n - (size_t)(dots + 2 - s), j, &b, &b_hi) != 0) {
            return -1;
        }
    }
    j->min_cdeg = a < b ? a : b;
    j->max_cdeg = a < b ? b_hi : a_hi;
    return 0;
}

/* One joint line: tok[0..ntok). */
static int parse_joint(lscctl_arm *arm, const where *w, const token *tok, size_t ntok,
                       size_t eol_col)
{
    char why[160];
    unsigned long id;
    lscctl_arm_joint *aj = &arm->joints[arm->n];
    if (ntok < 3) {
        return at(w, ntok == 0 ? eol_col : tok[ntok - 1].col + tok[ntok - 1].n,
                  "a joint is NAME ID KIND [dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]");
    }
    if (ntok > 6) {
        return at(w, tok[6].col, "too many fields: a joint has at most three settings");
    }
    if (tok[0].n > LSCCTL_ARM_NAME_MAX || !((tok[0].s[0] >= 'a' && tok[0].s[0] <= 'z') ||
                                            (tok[0].s[0] >= 'A' && tok[0].s[0] <= 'Z'))) {
        return at(w, tok[0].col, "a joint's name starts with a letter and has at most %u "
                                 "characters",
                  LSCCTL_ARM_NAME_MAX);
    }
    for (size_t i = 0; i < tok[0].n; i++) {
        if (!is_name_char(tok[0].s[i])) {
            return at(w, tok[0].col + i, "a joint's name has letters, digits, _ and - only");
        }
    }
    if (span_id(tok[1].s, tok[1].n, &id, why, sizeof why) != 0) {
        return at(w, tok[1].col, "%s", why);
    }
    if (arm->n == LSCCTL_ARM_JOINTS_MAX) {
        return at(w, tok[0].col, "too many joints: at most %u", LSCCTL_ARM_JOINTS_MAX);
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
    if (parse_kind(w, &tok[2], &aj->joint, (uint8_t)id) != 0 ||
        parse_settings(w, tok, ntok, &aj->joint) != 0) {
        return -1;
    }
    memcpy(aj->name, tok[0].s, tok[0].n);
    aj->name[tok[0].n] = '\0';
    arm->n++;
    return 0;
}

int lscctl_arm_parse(lscctl_arm *arm, const char *text, size_t len, const char *file,
                     char *why, size_t whylen)
{
    where w = {file, 0, why, whylen};
    size_t pos = 0;
    arm->n = 0;
    while (pos < len) {
        token tok[TOKENS_MAX];
        size_t ntok = 0, start = pos;
        bool comment = false;
        w.line++;
        for (; pos < len && text[pos] != '\n'; pos++) {
            char c = text[pos];
            size_t col = pos - start + 1u;
            if (c == '#') {
                comment = true;
            } else if (comment || c == ' ' || c == '\t' || (c == '\r' && (pos + 1 == len ||
                                                                         text[pos + 1] == '\n'))) {
                continue;
            } else if ((unsigned char)c < 0x20 || (unsigned char)c == 0x7f) {
                return at(&w, col, "unexpected byte 0x%02X", (unsigned char)c);
            } else if (pos > start && text[pos - 1] != ' ' && text[pos - 1] != '\t') {
                tok[ntok - 1].n++; /* inside a token */
            } else if (ntok == TOKENS_MAX) {
                return at(&w, col, "too many fields: a joint has at most three settings");
            } else {
                tok[ntok++] = (token){text + pos, 1, col};
            }
        }
        if (ntok > 0 && parse_joint(arm, &w, tok, ntok, pos - start + 1u) != 0) {
            return -1;
        }
        pos++; /* the newline */
    }
    if (arm->n == 0) {
        return failf(why, whylen, "%s: no joints: a profile names at least one "
                                  "(see docs/arm-profile.md)",
                     file);
    }
    return 0;
}

int lscctl_arm_load(lscctl_arm *arm, const char *path, char *why, size_t whylen)
{
    static char text[LSCCTL_ARM_FILE_MAX + 1u];
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return failf(why, whylen, "cannot read the arm profile %s: %s", path, strerror(errno));
    }
    size_t n = fread(text, 1, sizeof text, f);
    bool err = ferror(f) != 0;
    (void)fclose(f);
    if (err) {
        return failf(why, whylen, "cannot read the arm profile %s", path);
    }
    if (n > LSCCTL_ARM_FILE_MAX) {
        return failf(why, whylen, "%s: longer than %u bytes: not an arm profile", path,
                     LSCCTL_ARM_FILE_MAX);
    }
    return lscctl_arm_parse(arm, text, n, path, why, whylen);
}

/* s[0..n) as a servo id (at most 7 characters, the first a digit), or -1. */
static long as_id(const char *s, size_t n)
{
    char why[96];
    unsigned long id;
    if (n == 0 || n >= 8u || !is_digit(s[0])) {
        return -1;
    }
    return span_id(s, n, &id, why, sizeof why) == 0 ? (long)id : -1;
}

const lscctl_arm_joint *lscctl_arm_by_id(const lscctl_arm *arm, uint8_t id)
{
    for (size_t i = 0; arm != NULL && i < arm->n; i++) {
        if (arm->joints[i].joint.id == id) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

const lscctl_arm_joint *lscctl_arm_find(const lscctl_arm *arm, const char *name, size_t len)
{
    long id = as_id(name, len);
    if (id >= 0) {
        return lscctl_arm_by_id(arm, (uint8_t)id);
    }
    for (size_t i = 0; arm != NULL && i < arm->n; i++) {
        if (strlen(arm->joints[i].name) == len && memcmp(arm->joints[i].name, name, len) == 0) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

/* cdeg as degrees with two decimals ("-15.50") into out[cap]. */
static void degrees(char *out, size_t cap, int32_t cdeg)
{
    long a = cdeg < 0 ? -(long)cdeg : (long)cdeg;
    snprintf(out, cap, "%s%ld.%02ld", cdeg < 0 ? "-" : "", a / 100, a % 100);
}

const lscctl_arm_joint *lscctl_arm_angle(const lscctl_arm *arm, const lsc_servo *s, char *deg,
                                         size_t cap)
{
    const lscctl_arm_joint *aj = lscctl_arm_by_id(arm, s->id);
    int32_t cdeg;
    deg[0] = '\0';
    if (aj != NULL && lsc_joint_to_cdeg(&aj->joint, s->position, &cdeg) == 0) {
        degrees(deg, cap, cdeg);
    }
    return aj;
}

/* "joint base (servo 6) takes -90.00..90.00 deg (positions 125..875)" */
static int refuse(const lscctl_arm_joint *aj, const char *what, char *why, size_t whylen)
{
    const lsc_joint *j = &aj->joint;
    char lo[LSCCTL_ARM_DEGREES_MAX], hi[LSCCTL_ARM_DEGREES_MAX];
    uint16_t plo = 0, phi = 0;
    degrees(lo, sizeof lo, j->min_cdeg);
    degrees(hi, sizeof hi, j->max_cdeg);
    /* the positions inside the limits, as far as the servo's range goes */
    for (uint32_t p = j->pos_min, seen = 0; p <= j->pos_max; p++) {
        if (lsc_joint_allows_pos(j, (uint16_t)p)) {
            plo = seen++ == 0 ? (uint16_t)p : plo;
            phi = (uint16_t)p;
        }
    }
    return failf(why, whylen, "%s is outside the limits of joint %s (servo %u): %sdeg..%sdeg, "
                              "positions %u..%u",
                 what, aj->name, j->id, lo, hi, plo, phi);
}

int lscctl_arm_target(const lscctl_arm *arm, const char *arg, lsc_servo *out, char *why,
                      size_t whylen)
{
    const char *colon = strchr(arg, ':');
    value v;
    size_t len = strlen(arg);
    if (arm == NULL && !(len >= 3 && memcmp(arg + len - 3, "deg", 3) == 0)) {
        return lscctl_parse_servo(arg, out, why, whylen); /* ID:POSITION as always */
    }
    if (colon == NULL) {
        return failf(why, whylen, "'%.40s' is not JOINT:VALUE (base:30deg, 2:-15.5deg, 1:700)",
                     arg);
    }
    size_t n = (size_t)(colon - arg);
    const lscctl_arm_joint *aj = lscctl_arm_find(arm, arg, n);
    long id = as_id(arg, n);
    const char *bad = parse_value(colon + 1, strlen(colon + 1), &v);
    if (aj == NULL && id < 0) {
        return failf(why, whylen, arm == NULL ? "'%.*s' is not a servo id: a joint name needs "
                                                "an arm profile (--arm FILE)"
                                              : "'%.*s' is neither a joint of the arm profile "
                                                "nor a servo id",
                     (int)(n > 40 ? 40 : n), arg);
    }
    if (bad != NULL) {
        return failf(why, whylen, "'%.40s': %s", arg, bad);
    }
    if (aj == NULL && v.deg) {
        return failf(why, whylen, "'%.40s': servo %ld is not a joint of %s, so it has no "
                                  "degrees: give a position",
                     arg, id, arm == NULL ? "any arm profile (--arm FILE)" : "the arm profile");
    }
    if (!v.deg && (v.v < 0 || v.v > 65535)) {
        return failf(why, whylen, "'%.40s': a position is 0..65535", arg);
    }
    char what[48];
    if (aj == NULL) {
        out->id = (uint8_t)id;
        out->position = (uint16_t)v.v;
        return 0;
    }
    snprintf(what, sizeof what, "%s%.24s", v.deg ? "" : "position ", colon + 1);
    if (v.deg) {
        /* lsc_joint_allows, with the one conversion kept: lsc_joint_to_pos
         * refuses an angle beyond the servo's range, then the limits */
        int32_t cdeg = (int32_t)v.v; /* |v.v| < 10^8: DIGITS_MAX */
        if (lsc_joint_to_pos(&aj->joint, cdeg, &out->position) != 0 ||
            cdeg < aj->joint.min_cdeg || cdeg > aj->joint.max_cdeg) {
            return refuse(aj, what, why, whylen);
        }
    } else {
        if (!lsc_joint_allows_pos(&aj->joint, (uint16_t)v.v)) {
            return refuse(aj, what, why, whylen);
        }
        out->position = (uint16_t)v.v;
    }
    out->id = aj->joint.id;
    return 0;
}

int lscctl_arm_id(const lscctl_arm *arm, const char *arg, uint8_t *id, char *why, size_t whylen)
{
    const lscctl_arm_joint *aj = lscctl_arm_find(arm, arg, strlen(arg));
    unsigned long v;
    if (aj != NULL) {
        *id = aj->joint.id;
        return 0;
    }
    if (arm != NULL && arg[0] != '\0' && !is_digit(arg[0])) {
        return failf(why, whylen, "'%.40s' is neither a joint of the arm profile nor a servo id",
                     arg);
    }
    if (lscctl_parse_uint(arg, 255, "id", &v, why, whylen) != 0) {
        return -1;
    }
    *id = (uint8_t)v;
    return 0;
}
