/* Arm profiles: the format (docs/arm-profile.md, include/lsc/arm.h's
 * lsc_arm_parse): a profile's text into an lsc_arm, each error as one line
 * FILE:LINE:COLUMN: reason. The conversions and the limit checks are
 * lsc/units.h's. Host only: compiles to nothing elsewhere (the Arduino IDE
 * builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arm_internal.h"

#define TOKENS_MAX 10u /* NAME ID KIND and at most five key=value, plus extras to report */
#define LENGTH_MAX 1000000L /* hundredths of a mm: 10 m */

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
    lsc_armi_msg m = lsc_armi_msg_start(w->why, w->whylen);
    char pos[48];
    va_list ap;
    (void)snprintf(pos, sizeof pos, ":%zu:%zu: ", w->line, col);
    lsc_armi_msg_text(&m, w->file, strlen(w->file));
    lsc_armi_msg_text(&m, pos, strlen(pos));
    va_start(ap, fmt);
    lsc_armi_msg_vf(&m, fmt, ap);
    va_end(ap);
    return LSC_EINVAL;
}

/* The angle of position p through j, rounded down (*lo) and up (*hi): limits
 * lo..hi keep p in. p is within j's range. */
static void pos_angles(const lsc_joint *j, long p, int32_t *lo, int32_t *hi)
{
    long num = (p - (long)j->zero) * j->direction * j->span_cdeg;
    long range = (long)j->pos_max - (long)j->pos_min;
    *lo = (int32_t)lsc_armi_floor_div(num, range);
    *hi = (int32_t)-lsc_armi_floor_div(-num, range);
}

/* The angle of an end of the limits: degrees as written (lo = hi), or a
 * position's angle rounded outwards (pos_angles). */
static int limit_end(const where *w, const token *t, const char *s, size_t n,
                     const lsc_joint *j, int32_t *lo, int32_t *hi)
{
    lsc_armi_value v;
    const char *bad = lsc_armi_parse_value(s, n, &v);
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
    lsc_armi_value lo, hi, span;
    if (dots == NULL || slash == NULL || slash < dots ||
        lsc_armi_parse_value(t->s, (size_t)(dots - t->s), &lo) != NULL ||
        lsc_armi_parse_value(dots + 2, (size_t)(slash - dots - 2), &hi) != NULL ||
        lsc_armi_parse_value(slash + 1, t->n - (size_t)(slash + 1 - t->s), &span) != NULL ||
        lo.deg || hi.deg || !span.deg) {
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
    lsc_armi_value v;
    const char *bad = lsc_armi_parse_value(t->s + 7, t->n - 7, &v);
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
    if (t != NULL && !lsc_armi_positions(j, &plo, &phi)) { /* the whole range keeps them all */
        lsc_armi_degrees(lo, sizeof lo, j->min_cdeg);
        lsc_armi_degrees(hi, sizeof hi, j->max_cdeg);
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
    lsc_armi_value v;
    uint16_t pos = 0;
    const char *bad = lsc_armi_parse_value(t->s + klen + 1, t->n - klen - 1, &v);
    if (bad != NULL) {
        return at(w, t->col + klen + 1, "%s: %s", key, bad);
    }
    if (v.deg ? (v.v < -LSC_UNITS_CDEG_MAX || v.v > LSC_UNITS_CDEG_MAX ||
                 lsc_joint_to_pos(j, (int32_t)v.v, &pos) != 0)
              : (v.v < j->pos_min || v.v > j->pos_max)) {
        return at(w, t->col + klen + 1, "%s: %s is outside the servo's range %u..%u", key,
                  lsc_armi_shown(text, t->s + klen + 1, t->n - klen - 1), j->pos_min, j->pos_max);
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
                      lsc_armi_shown(text, tok[i].s, tok[i].n));
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
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || lsc_armi_is_digit(c) || c == '_' ||
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
    if (lsc_armi_span_id(tok[1].s, tok[1].n, &id, why, sizeof why) != 0) {
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
                      lsc_armi_shown(text, tok[i].s, tok[i].n));
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
    for (; i < n && lsc_armi_is_digit(s[i]); i++) {
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
        for (i++; i < n && lsc_armi_is_digit(s[i]); i++, frac++) {
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
                      lsc_armi_shown(text, tok[i].s, tok[i].n));
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
        return lsc_armi_file_fail(LSC_EINVAL, w->why, w->whylen, "", w->file,
                                  ": no joints: a profile names at least one (see "
                                  "docs/arm-profile.md)");
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
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_parse: no text or no out");
    }
    if (len >= 3 && memcmp(text, bom, 3) == 0) { /* a UTF-8 byte-order mark */
        text += 3;
        len -= 3;
    }
    lsc_arm *arm = malloc(sizeof *arm);
    if (arm == NULL) {
        return lsc_armi_oom(why, whylen);
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

#endif
