/* Calibration: a profile's text with the settings the readings give
 * (include/lsc/calibrate.h). The text is parsed by arm_parse.c, rewritten
 * line by line (only the settings a step sets change; everything else is kept
 * as it was written), and the result parsed again before it is handed back.
 * Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c
 * under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/calibrate.h"

#define SETTINGS 5u  /* dir, offset, limits, open, closed: the order they are written in */
#define VALUE_MAX 24u /* a setting's value as text: "1000..1000", "+10000", "-1" */
#define FIELDS_MAX 8u /* NAME ID KIND and five settings: what arm_parse.c accepts */

static const char *const step_names[LSC_CALIB_STEPS] = {"home", "lean", "gripper-closed",
                                                        "gripper-open"};
static const char *const keys[SETTINGS] = {"dir", "offset", "limits", "open", "closed"};
enum { SET_DIR, SET_OFFSET, SET_LIMITS, SET_OPEN, SET_CLOSED };

/* The settings a step gives one joint. */
typedef struct edit {
    bool any;
    bool set[SETTINGS];
    char value[SETTINGS][VALUE_MAX];
} edit;

#ifdef __GNUC__
__attribute__((format(printf, 3, 4)))
#endif
static int fail(char *why, size_t whylen, const char *fmt, ...)
{
    if (why != NULL && whylen > 0) {
        va_list ap;
        va_start(ap, fmt);
        (void)vsnprintf(why, whylen, fmt, ap);
        va_end(ap);
    }
    return LSC_EINVAL;
}

const char *lsc_calib_step_name(lsc_calib_step step)
{
    return (unsigned)step < LSC_CALIB_STEPS ? step_names[step] : NULL;
}

int lsc_calib_step_parse(const char *name, lsc_calib_step *step)
{
    for (unsigned i = 0; name != NULL && step != NULL && i < LSC_CALIB_STEPS; i++) {
        if (strcmp(name, step_names[i]) == 0) {
            *step = (lsc_calib_step)i;
            return LSC_OK;
        }
    }
    return LSC_EINVAL;
}

/* The step's joints: their indexes in arm into idx[0..) and their number, or
 * an error. */
static int step_joints(const lsc_arm *arm, lsc_calib_step step, int *idx, char *why,
                       size_t whylen)
{
    lsc_kin_chain chain;
    int joints[LSC_ARM_CHAIN_MAX];
    if (arm == NULL || lsc_calib_step_name(step) == NULL) {
        return fail(why, whylen, "calibrate: no arm profile, or an unknown step");
    }
    if (lsc_arm_chain(arm, &chain, joints, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    if (step == LSC_CALIB_HOME || step == LSC_CALIB_LEAN) {
        memcpy(idx, joints, LSC_KIN_JOINTS * sizeof *idx);
        return LSC_KIN_JOINTS;
    }
    if (joints[LSC_ARM_GRIPPER] < 0) {
        return fail(why, whylen, "the profile's chain: line names no gripper: add the "
                                 "gripper's joint at its end");
    }
    idx[0] = joints[LSC_ARM_GRIPPER];
    return 1;
}

int lsc_calib_ids(const lsc_arm *arm, lsc_calib_step step, uint8_t *ids, size_t cap, char *why,
                  size_t whylen)
{
    int idx[LSC_KIN_JOINTS] = {0};
    int n = step_joints(arm, step, idx, why, whylen);
    if (n < 0) {
        return n;
    }
    if (ids == NULL || cap < (size_t)n) {
        return fail(why, whylen, "calibrate: room for %d servo ids is needed", n);
    }
    for (int i = 0; i < n; i++) {
        ids[i] = lsc_arm_joint(arm, (size_t)idx[i])->id;
    }
    return n;
}

/* ---- what the readings say ---------------------------------------------------- */

/* Joint i's reading, checked against its servo's range, into *pos. */
static int reading_of(const lsc_arm *arm, size_t i, const lsc_servo *readings, size_t n,
                      uint16_t *pos, char *why, size_t whylen)
{
    const lsc_joint *j = lsc_arm_joint(arm, i);
    for (size_t k = 0; k < n; k++) {
        if (readings[k].id != j->id) {
            continue;
        }
        if (readings[k].position < j->pos_min || readings[k].position > j->pos_max) {
            return fail(why, whylen, "servo %u (joint %s) reads %u, outside its range %u..%u: "
                                     "is this the arm's profile?",
                        j->id, lsc_arm_name(arm, i), readings[k].position, j->pos_min,
                        j->pos_max);
        }
        *pos = readings[k].position;
        return LSC_OK;
    }
    return fail(why, whylen, "no reading of servo %u (joint %s)", j->id, lsc_arm_name(arm, i));
}

/* How far positions a and b are apart on j, in centidegrees (rounded down). */
static long apart_cdeg(const lsc_joint *j, uint16_t a, uint16_t b)
{
    long d = a > b ? (long)a - (long)b : (long)b - (long)a;
    return d * (long)j->span_cdeg / ((long)j->pos_max - (long)j->pos_min);
}

static void set(edit *e, size_t key, const char *fmt, long a, long b)
{
    e->any = e->set[key] = true;
    (void)snprintf(e->value[key], VALUE_MAX, fmt, a, b);
}

/* Appends "NAME D.DD degrees" to a message being made in m[cap]. */
static void add_moved(char *m, size_t cap, const char *name, long cdeg)
{
    size_t used = strlen(m);
    (void)snprintf(m + used, cap - used, "%s%s %ld.%02ld degrees", used > 0 ? ", " : "", name,
                   cdeg / 100, cdeg % 100);
}

static int home_or_lean(const lsc_arm *arm, lsc_calib_step step, const int *idx,
                        const lsc_servo *readings, size_t n, edit *edits, char *why,
                        size_t whylen)
{
    char moved[LSC_KIN_JOINTS * (LSC_ARM_NAME_MAX + 24u)] = "";
    for (size_t q = 0; q < LSC_KIN_JOINTS; q++) {
        size_t i = (size_t)idx[q];
        const lsc_joint *j = lsc_arm_joint(arm, i);
        uint16_t pos = 0;
        if (reading_of(arm, i, readings, n, &pos, why, whylen) != 0) {
            return LSC_EINVAL;
        }
        if (step == LSC_CALIB_HOME) {
            long middle = (long)j->pos_min + ((long)j->pos_max - (long)j->pos_min) / 2;
            set(&edits[i], SET_OFFSET, "%+ld", (long)pos - middle, 0);
        } else if (apart_cdeg(j, pos, j->zero) < LSC_CALIB_LEAN_MIN_CDEG) {
            add_moved(moved, sizeof moved, lsc_arm_name(arm, i), apart_cdeg(j, pos, j->zero));
        } else {
            set(&edits[i], SET_DIR, "%+ld", pos > j->zero ? 1L : -1L, 0);
        }
    }
    if (moved[0] != '\0') {
        return fail(why, whylen, "lean further, then take this step again: %s from the zero "
                                 "(at least %d each)",
                    moved, LSC_CALIB_LEAN_MIN_CDEG / 100);
    }
    return LSC_OK;
}

static int gripper(const lsc_arm *arm, lsc_calib_step step, size_t i, const lsc_servo *readings,
                   size_t n, edit *e, char *why, size_t whylen)
{
    const lsc_joint *j = lsc_arm_joint(arm, i);
    lsc_arm_end_kind end = step == LSC_CALIB_GRIPPER_OPEN ? LSC_ARM_OPEN : LSC_ARM_CLOSED;
    lsc_arm_end_kind other = end == LSC_ARM_OPEN ? LSC_ARM_CLOSED : LSC_ARM_OPEN;
    uint16_t pos = 0, there = 0;
    if (reading_of(arm, i, readings, n, &pos, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    set(e, end == LSC_ARM_OPEN ? SET_OPEN : SET_CLOSED, "%ld", (long)pos, 0);
    if (lsc_arm_end(arm, i, other, &there) == 0) {
        if (apart_cdeg(j, pos, there) < LSC_CALIB_LEAN_MIN_CDEG) {
            return fail(why, whylen, "the gripper reads %u open and %u closed: %s, then take "
                                     "this step again (at least %d degrees apart)",
                        end == LSC_ARM_OPEN ? pos : there, end == LSC_ARM_OPEN ? there : pos,
                        end == LSC_ARM_OPEN ? "open it wider" : "close it further",
                        LSC_CALIB_LEAN_MIN_CDEG / 100);
        }
        set(e, SET_LIMITS, "%ld..%ld", (long)(pos < there ? pos : there),
            (long)(pos < there ? there : pos));
        return LSC_OK;
    }
    /* the limits as positions: widened to hold the reading */
    long lo = -1, hi = -1;
    for (long p = j->pos_min; p <= (long)j->pos_max; p++) {
        if (lsc_joint_allows_pos(j, (uint16_t)p)) {
            lo = lo < 0 ? p : lo;
            hi = p;
        }
    }
    if (pos < lo || pos > hi) {
        set(e, SET_LIMITS, "%ld..%ld", pos < lo ? (long)pos : lo, pos > hi ? (long)pos : hi);
    }
    return LSC_OK;
}

/* ---- the text ------------------------------------------------------------------ */

/* A text being made: counted when s is NULL, written when it is not. */
typedef struct buf {
    char *s;
    size_t len;
} buf;

static void put(buf *b, const char *s, size_t n)
{
    if (b->s != NULL) {
        memcpy(b->s + b->len, s, n);
    }
    b->len += n;
}

static void puts_(buf *b, const char *s)
{
    put(b, s, strlen(s));
}

typedef struct field {
    const char *s;
    size_t n;
} field;

/* The fields of line[0..n) before a comment, into f[FIELDS_MAX], their
 * number, and where the comment starts (n: none). line is a line of a
 * profile arm_parse.c accepted: it has at most FIELDS_MAX fields (a joint's line;
 * chain: has at most seven, links: five). */
static size_t fields(const char *line, size_t n, field *f, size_t *comment)
{
    size_t k = 0;
    *comment = n;
    for (size_t p = 0; p < n; p++) {
        if (line[p] == '#') {
            *comment = p;
            break;
        }
        bool blank = line[p] == ' ' || line[p] == '\t';
        if (!blank && (p == 0 || line[p - 1] == ' ' || line[p - 1] == '\t')) {
            f[k++] = (field){line + p, 0};
        }
        if (!blank) {
            f[k - 1].n++;
        }
    }
    return k;
}

/* The joint named f, or -1. */
static int joint_named(const lsc_arm *arm, const field *f)
{
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        const char *name = lsc_arm_name(arm, i);
        if (strlen(name) == f->n && memcmp(name, f->s, f->n) == 0) {
            return (int)i;
        }
    }
    return -1;
}

/* A joint's line[0..n) (without its newline and CR) with e's settings. */
static void rewrite_line(buf *b, const char *line, size_t n, const field *f, size_t k,
                         size_t comment, const edit *e)
{
    put(b, line, (size_t)(f[2].s + f[2].n - line)); /* NAME ID KIND as they were spaced */
    for (size_t s = 0; s < SETTINGS; s++) {
        size_t klen = strlen(keys[s]);
        if (e->set[s]) {
            puts_(b, " ");
            puts_(b, keys[s]);
            puts_(b, "=");
            puts_(b, e->value[s]);
            continue;
        }
        for (size_t t = 3; t < k; t++) {
            if (f[t].n > klen && f[t].s[klen] == '=' && memcmp(f[t].s, keys[s], klen) == 0) {
                puts_(b, " ");
                put(b, f[t].s, f[t].n);
            }
        }
    }
    if (comment < n) {
        puts_(b, "  ");
        put(b, line + comment, n - comment);
    }
}

static void make_text(buf *b, const char *text, size_t len, const lsc_arm *arm,
                      const edit *edits, const char *step, const char *stamp)
{
    static const char bom[] = "\xEF\xBB\xBF";
    char mine[48];
    size_t pos = 0;
    int mlen = snprintf(mine, sizeof mine, "# calibrate %s:", step);
    if (memcmp(text, bom, 3) == 0) { /* a profile has a joint: len > 3 */
        put(b, text, 3);
        pos = 3;
    }
    puts_(b, mine);
    puts_(b, " ");
    puts_(b, stamp);
    puts_(b, "\n");
    while (pos < len) {
        const char *line = text + pos, *nl = memchr(line, '\n', len - pos);
        size_t n = nl != NULL ? (size_t)(nl - line) : len - pos, body = n, comment = 0;
        field f[FIELDS_MAX];
        pos += n + (nl != NULL ? 1u : 0u);
        if (n >= (size_t)mlen && memcmp(line, mine, (size_t)mlen) == 0) {
            continue; /* the step's earlier stamp */
        }
        body -= body > 0 && line[body - 1] == '\r' ? 1u : 0u;
        size_t k = fields(line, body, f, &comment);
        int i = k >= 3 ? joint_named(arm, &f[0]) : -1;
        if (i >= 0 && edits[i].any) {
            rewrite_line(b, line, body, f, k, comment, &edits[i]);
            put(b, line + body, n - body); /* the CR */
        } else {
            put(b, line, n);
        }
        if (nl != NULL) {
            puts_(b, "\n");
        }
    }
}

static bool stamp_ok(const char *stamp)
{
    size_t n = strlen(stamp);
    for (size_t i = 0; i < n; i++) {
        if ((unsigned char)stamp[i] < 0x20 || (unsigned char)stamp[i] > 0x7e) {
            return false;
        }
    }
    return n <= LSC_CALIB_STAMP_MAX;
}

int lsc_calib_apply(const char *text, size_t len, const char *file, lsc_calib_step step,
                    const lsc_servo *readings, size_t n, const char *stamp, char **out,
                    size_t *outlen, char *why, size_t whylen)
{
    lsc_arm *arm = NULL, *check = NULL;
    edit edits[LSC_ARM_JOINTS_MAX];
    int idx[LSC_KIN_JOINTS] = {0};
    if (out != NULL) {
        *out = NULL;
    }
    if (outlen != NULL) {
        *outlen = 0;
    }
    if ((text == NULL && len > 0) || (readings == NULL && n > 0) || stamp == NULL ||
        out == NULL || outlen == NULL) {
        return fail(why, whylen, "calibrate: a NULL argument");
    }
    if (!stamp_ok(stamp)) {
        return fail(why, whylen, "calibrate: the stamp is one line of printable ASCII, at "
                                 "most %u bytes",
                    LSC_CALIB_STAMP_MAX);
    }
    int r = lsc_arm_parse(text, len, file, &arm, why, whylen);
    int count = r == 0 ? step_joints(arm, step, idx, why, whylen) : r;
    if (count < 0) {
        lsc_arm_free(arm);
        return count;
    }
    memset(edits, 0, sizeof edits);
    r = step <= LSC_CALIB_LEAN
            ? home_or_lean(arm, step, idx, readings, n, edits, why, whylen)
            : gripper(arm, step, (size_t)idx[0], readings, n, &edits[idx[0]], why, whylen);
    buf b = {NULL, 0};
    if (r == 0) {
        make_text(&b, text, len, arm, edits, step_names[step], stamp);
        b.s = malloc(b.len + 1u);
        if (b.s == NULL) {
            r = LSC_ENOSPC;
            (void)fail(why, whylen, "calibrate: out of memory");
        }
    }
    if (r == 0) {
        b.len = 0;
        make_text(&b, text, len, arm, edits, step_names[step], stamp);
        b.s[b.len] = '\0';
        /* what a step writes can still be refused: limits in degrees that
         * hold no position of the servo from its new zero */
        char reason[LSC_ARM_MESSAGE_MAX];
        r = lsc_arm_parse(b.s, b.len, file, &check, reason, sizeof reason);
        if (r == LSC_ENOSPC) {
            (void)fail(why, whylen, "calibrate: out of memory");
        } else if (r != 0) {
            (void)fail(why, whylen, "the calibrated profile would be refused (%s): is the arm "
                                    "in the step's pose?",
                       reason);
        }
        if (r != 0) {
            free(b.s);
            b.s = NULL;
        }
    }
    lsc_arm_free(check);
    lsc_arm_free(arm);
    *out = b.s;
    *outlen = r == 0 ? b.len : 0;
    return r;
}

#endif
