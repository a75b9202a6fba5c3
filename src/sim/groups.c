/* Action group text: the parser (docs/action-groups.md has the format). */
#include "lsc/sim.h"

#include <string.h>

#define STEPS_USABLE 65535u

int lsc_sim_groups_init(lsc_sim_groups *g, lsc_sim_step *steps, size_t steps_cap,
                        lsc_servo *targets, size_t targets_cap)
{
    if (g == NULL || (steps == NULL && steps_cap > 0u) || (targets == NULL && targets_cap > 0u)) {
        return LSC_EINVAL;
    }
    memset(g, 0, sizeof *g);
    g->steps = steps;
    g->steps_cap = steps_cap > STEPS_USABLE ? STEPS_USABLE : steps_cap;
    g->targets = targets;
    g->targets_cap = targets_cap;
    return 0;
}

/* The parse in progress. */
typedef struct cursor {
    const char *text;
    size_t len;
    size_t pos;        /* next character */
    size_t line_start; /* offset of the current line */
    uint32_t line;
    lsc_sim_parse_error *err;
} cursor;

static bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

static bool at_end_of_line(const cursor *c)
{
    return c->pos >= c->len || c->text[c->pos] == '\n' || c->text[c->pos] == '#';
}

static void skip_blanks(cursor *c)
{
    while (c->pos < c->len && is_blank(c->text[c->pos])) {
        c->pos++;
    }
}

/* Records an error at offset `at` of the current line; returns code. */
static int fail(cursor *c, size_t at, int code, const char *message)
{
    if (c->err != NULL) {
        c->err->line = c->line;
        c->err->column = (uint32_t)(at - c->line_start + 1u);
        c->err->message = message;
    }
    return code;
}

/* Reads a decimal number 0..max ending at a blank, the end of line, a '#'
 * or the character `stop`. Returns 0 or LSC_EINVAL (with the error set). */
static int read_number(cursor *c, uint32_t max, char stop, uint32_t *out, const char *what)
{
    size_t start = c->pos;
    uint32_t v = 0;
    if (c->pos >= c->len || c->text[c->pos] < '0' || c->text[c->pos] > '9') {
        return fail(c, start, LSC_EINVAL, what);
    }
    while (c->pos < c->len && c->text[c->pos] >= '0' && c->text[c->pos] <= '9') {
        v = v * 10u + (uint32_t)(c->text[c->pos] - '0');
        if (v > max) {
            return fail(c, start, LSC_EINVAL, what);
        }
        c->pos++;
    }
    if (!at_end_of_line(c) && !is_blank(c->text[c->pos]) && c->text[c->pos] != stop) {
        return fail(c, start, LSC_EINVAL, what);
    }
    *out = v;
    return 0;
}

/* Length of the word at the cursor (up to a blank, end of line or '#'). */
static size_t word_len(const cursor *c)
{
    size_t n = 0;
    while (c->pos + n < c->len && !is_blank(c->text[c->pos + n]) &&
           c->text[c->pos + n] != '\n' && c->text[c->pos + n] != '#') {
        n++;
    }
    return n;
}

static bool word_is(const cursor *c, size_t n, const char *kw)
{
    return n == strlen(kw) && memcmp(c->text + c->pos, kw, n) == 0;
}

/* Checks the group being closed has a step; `open` is its number or -1. */
static int close_group(cursor *c, const lsc_sim_groups *g, int open, uint32_t open_line,
                       size_t open_col)
{
    if (open >= 0 && g->group_steps[open] == 0u) {
        c->line = open_line;
        c->line_start = 0;
        return fail(c, open_col, LSC_EINVAL, "group has no steps");
    }
    return 0;
}

static int parse_group_line(cursor *c, lsc_sim_groups *g, int *open)
{
    uint32_t number;
    int r = read_number(c, LSC_SIM_GROUPS - 1u, '\0', &number,
                        "group number must be 0..254");
    if (r < 0) {
        return r;
    }
    if (g->group_steps[number] > 0u || *open == (int)number) {
        return fail(c, c->pos - 1u, LSC_EINVAL, "group defined twice");
    }
    *open = (int)number;
    g->first_step[number] = (uint16_t)g->nsteps;
    return 0;
}

static int parse_step_line(cursor *c, lsc_sim_groups *g, int open, size_t kw_at)
{
    uint32_t time_ms;
    if (open < 0) {
        return fail(c, kw_at, LSC_EINVAL, "step before any group line");
    }
    if (at_end_of_line(c)) {
        return fail(c, c->pos, LSC_EINVAL, "step needs a time in ms (1..65535)");
    }
    int r = read_number(c, 65535u, '\0', &time_ms, "step time must be 1..65535 ms");
    if (r < 0) {
        return r;
    }
    if (time_ms == 0u) {
        return fail(c, c->pos - 1u, LSC_EINVAL, "step time must be 1..65535 ms");
    }
    if (g->nsteps >= g->steps_cap) {
        return fail(c, kw_at, LSC_ENOSPC, "too many steps for the storage given");
    }
    lsc_sim_step *s = &g->steps[g->nsteps];
    s->first = (uint32_t)g->ntargets;
    s->ntargets = 0;
    s->time_ms = (uint16_t)time_ms;
    skip_blanks(c);
    while (!at_end_of_line(c)) {
        size_t at = c->pos;
        uint32_t id;
        uint32_t position;
        r = read_number(c, 255u, ':', &id, "target must be ID:POSITION (id 0..255)");
        if (r < 0) {
            return r;
        }
        if (c->pos >= c->len || c->text[c->pos] != ':') {
            return fail(c, at, LSC_EINVAL, "target must be ID:POSITION (id 0..255)");
        }
        c->pos++;
        r = read_number(c, 65535u, '\0', &position, "position must be 0..65535");
        if (r < 0) {
            return r;
        }
        for (uint16_t i = 0; i < s->ntargets; i++) {
            if (g->targets[s->first + i].id == id) {
                return fail(c, at, LSC_EINVAL, "servo listed twice in one step");
            }
        }
        if (g->ntargets >= g->targets_cap) {
            return fail(c, at, LSC_ENOSPC, "too many targets for the storage given");
        }
        g->targets[g->ntargets].id = (uint8_t)id;
        g->targets[g->ntargets].position = (uint16_t)position;
        g->ntargets++;
        s->ntargets++;
        skip_blanks(c);
    }
    g->nsteps++;
    g->group_steps[open]++;
    return 0;
}

int lsc_sim_groups_parse(lsc_sim_groups *g, const char *text, size_t len,
                         lsc_sim_parse_error *err)
{
    cursor c;
    int open = -1;
    uint32_t open_line = 0;
    size_t open_col = 0;
    int r = 0;
    int count = 0;

    if (err != NULL) {
        err->line = 0;
        err->column = 0;
        err->message = "no error";
    }
    if (g == NULL || (text == NULL && len > 0u)) {
        if (err != NULL) {
            err->message = "invalid argument";
        }
        return LSC_EINVAL;
    }
    c.text = text;
    c.len = len;
    c.pos = 0;
    c.line_start = 0;
    c.line = 1;
    c.err = err;
    g->nsteps = 0;
    g->ntargets = 0;
    memset(g->first_step, 0, sizeof g->first_step);
    memset(g->group_steps, 0, sizeof g->group_steps);

    while (r == 0 && c.pos < c.len) {
        skip_blanks(&c);
        if (!at_end_of_line(&c)) {
            size_t kw_at = c.pos;
            size_t n = word_len(&c);
            if (word_is(&c, n, "group")) {
                c.pos += n;
                skip_blanks(&c);
                r = close_group(&c, g, open, open_line, open_col);
                if (r == 0) {
                    open_line = c.line;
                    open_col = kw_at - c.line_start;
                    r = parse_group_line(&c, g, &open);
                    count += r == 0 ? 1 : 0;
                }
            } else if (word_is(&c, n, "step")) {
                c.pos += n;
                skip_blanks(&c);
                r = parse_step_line(&c, g, open, kw_at);
            } else {
                r = fail(&c, kw_at, LSC_EINVAL, "expected 'group N' or 'step MS ID:POS...'");
            }
            skip_blanks(&c);
            if (r == 0 && !at_end_of_line(&c)) {
                r = fail(&c, c.pos, LSC_EINVAL, "unexpected text at end of line");
            }
        }
        /* skip a comment and the newline */
        while (r == 0 && c.pos < c.len && c.text[c.pos] != '\n') {
            c.pos++;
        }
        if (c.pos < c.len) {
            c.pos++;
            c.line++;
            c.line_start = c.pos;
        }
    }
    if (r == 0) {
        r = close_group(&c, g, open, open_line, open_col);
    }
    if (r < 0) {
        g->nsteps = 0;
        g->ntargets = 0;
        memset(g->group_steps, 0, sizeof g->group_steps);
        return r;
    }
    return count;
}
