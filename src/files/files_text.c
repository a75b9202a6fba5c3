/* lsc's action-group text (docs/action-groups.md): read with the virtual
 * controller's own parser (src/sim/groups.c), the one group of a file or one
 * group chosen by its number; written as one group. */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "files_internal.h"
#include "lsc/sim.h"

/* Index of id in a->ids, or -1. */
static int id_index(const lsc_action *a, uint8_t id)
{
    for (int i = 0; i < a->nservos; i++) {
        if (a->ids[i] == id) {
            return i;
        }
    }
    return -1;
}

/* The group's keyframes: each step moves some servos; the others keep the
 * position of the step before. The first step must place every servo. */
static int to_keyframes(const lsc_sim_groups *g, size_t group, lsc_action *a,
                        lsc_file_error *err)
{
    size_t first = g->first_step[group], nsteps = g->group_steps[group];
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    size_t n = 0;
    for (size_t s = first; s < first + nsteps; s++) {
        const lsc_sim_step *st = &g->steps[s];
        for (size_t t = st->first; t < st->first + st->ntargets; t++) {
            uint8_t id = g->targets[t].id;
            if (memchr(ids, id, n) != NULL) {
                continue;
            }
            if (n == LSC_PLAYER_SERVOS_MAX) {
                return lsc_files_fail(err, s - first + 1u,
                                      "step %zu: more than %u servos in one group",
                                      s - first + 1u, LSC_PLAYER_SERVOS_MAX);
            }
            ids[n++] = id;
        }
    }
    if (n == 0) {
        return lsc_files_fail(err, 1, "step 1: the group moves no servo");
    }
    (void)lsc_action_init(a, ids, n);
    uint16_t pos[LSC_PLAYER_SERVOS_MAX];
    bool placed[LSC_PLAYER_SERVOS_MAX] = {false};
    for (size_t s = first; s < first + nsteps; s++) {
        const lsc_sim_step *st = &g->steps[s];
        for (size_t t = st->first; t < st->first + st->ntargets; t++) {
            int i = id_index(a, g->targets[t].id);
            pos[i] = g->targets[t].position;
            placed[i] = true;
        }
        for (size_t i = 0; s == first && i < n; i++) {
            if (!placed[i]) {
                return lsc_files_fail(err, 1,
                                      "step 1: servo %u has no position (the first step must "
                                      "place every servo the group moves)",
                                      a->ids[i]);
            }
        }
        if (lsc_action_append(a, st->time_ms, pos) != 0) {
            return lsc_files_oom(err);
        }
    }
    return 0;
}

/* "1, 2, 3" (the first few, then "..."): the groups g defines, into buf. */
static void list_groups(const lsc_sim_groups *g, char *buf, size_t size)
{
    size_t used = 0;
    unsigned listed = 0;
    buf[0] = '\0';
    for (size_t n = 0; n < LSC_SIM_GROUPS && used < size; n++) {
        if (g->group_steps[n] == 0u) {
            continue;
        }
        int w = listed == 8u ? snprintf(buf + used, size - used, ", ...")
                             : snprintf(buf + used, size - used, "%s%zu", listed ? ", " : "", n);
        if (w < 0 || listed++ == 8u) {
            break;
        }
        used += (size_t)w;
    }
}

/* The group the caller asked for (group >= 0) or the file's only one (-1):
 * its index in g, or an error. r: the number of groups g defines. */
static int choose_group(const lsc_sim_groups *g, int r, int group, size_t *out,
                        lsc_file_error *err)
{
    char list[64];
    list_groups(g, list, sizeof list);
    if (r == 0) {
        return lsc_files_fail(err, 0, "no group in the file (it needs one 'group N' line and "
                                      "its steps)");
    }
    if (group >= 0) {
        if (g->group_steps[group] == 0u) {
            return lsc_files_fail(err, 0, "no group %d in the file (it holds group%s %s)", group,
                                  r > 1 ? "s" : "", list);
        }
        *out = (size_t)group;
        return 0;
    }
    if (r != 1) {
        return lsc_files_fail(err, 0, "%d groups: an action file holds one; read one of them "
                                      "by its number (groups %s)",
                              r, list);
    }
    size_t n = 0;
    while (g->group_steps[n] == 0u) {
        n++;
    }
    *out = n;
    return 0;
}

/* The groups g defines (r of them), ascending, into out[0..cap); returns r. */
static int groups_of(const lsc_sim_groups *g, int r, uint8_t *out, size_t cap)
{
    size_t n = 0;
    for (size_t k = 0; k < LSC_SIM_GROUPS; k++) {
        if (g->group_steps[k] != 0u && n < cap) {
            out[n++] = (uint8_t)k;
        }
    }
    return r;
}

/* Parses text's groups: then lists them into out[0..cap) (out non-NULL), or
 * reads group `group` (-1: the only one) into a. */
static int parse(const char *text, size_t len, int group, lsc_action *a, uint8_t *out,
                 size_t cap, lsc_file_error *err)
{
    /* every step needs a line of its own, every target at least 4 characters;
     * the parser takes at most 65535 steps (LSC_ACTION_KEYFRAMES_MAX): it
     * answers LSC_ENOSPC, "too many steps", at the next */
    size_t lines = 1;
    for (size_t i = 0; i < len && lines < LSC_ACTION_KEYFRAMES_MAX; i++) {
        lines += text[i] == '\n';
    }
    lsc_sim_step *steps = calloc(lines, sizeof *steps);
    lsc_servo *targets = calloc(len / 4u + 1u, sizeof *targets);
    lsc_sim_groups *g = malloc(sizeof *g);
    int r;
    if (steps == NULL || targets == NULL || g == NULL) {
        r = lsc_files_oom(err);
    } else {
        lsc_sim_parse_error pe = {0, 0, NULL};
        (void)lsc_sim_groups_init(g, steps, lines, targets, len / 4u + 1u);
        r = lsc_sim_groups_parse(g, text, len, &pe);
        if (r == LSC_ENOSPC && strstr(pe.message, "steps") != NULL) {
            r = lsc_files_fail(err, pe.line, "line %u: more than %u steps (the most keyframes "
                                             "an action holds)",
                               (unsigned)pe.line, LSC_ACTION_KEYFRAMES_MAX);
        } else if (r < 0) {
            r = lsc_files_fail(err, pe.line, "line %u:%u: %s", (unsigned)pe.line,
                               (unsigned)pe.column, pe.message);
        } else if (out != NULL) {
            r = groups_of(g, r, out, cap);
        } else {
            size_t chosen = 0;
            r = choose_group(g, r, group, &chosen, err);
            if (r == 0) {
                r = to_keyframes(g, chosen, a, err);
            }
        }
    }
    free(steps);
    free(targets);
    free(g);
    return r;
}

int lsc_files_text_parse(const char *text, size_t len, int group, lsc_action *a,
                         lsc_file_error *err)
{
    return parse(text, len, group, a, NULL, 0, err);
}

int lsc_files_text_groups(const char *text, size_t len, uint8_t *out, size_t cap,
                          lsc_file_error *err)
{
    uint8_t none[1];
    return parse(text, len, -1, NULL, out != NULL ? out : none, out != NULL ? cap : 0u, err);
}

int lsc_files_text_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                          lsc_file_error *err)
{
    int group = lsc_file_group_number(name); /* action.c */
    if (a->count == 0) {
        return lsc_files_fail(err, 0, "no keyframes: a group needs at least one step");
    }
    lsc_outbuf_printf(b, "# %u keyframes, written by lsc (docs/action-groups.md)\ngroup %d\n",
                      (unsigned)a->count, group >= 0 ? group : 1);
    for (uint32_t k = 0; k < a->count; k++) {
        const uint16_t *w = lsc_action_row(a, k);
        if (w[0] == 0) {
            return lsc_files_fail(err, k + 1u,
                                  "keyframe %u: time 0 ms cannot be a step (1..65535 ms)",
                                  (unsigned)(k + 1u));
        }
        lsc_outbuf_printf(b, "step %u", w[0]);
        for (size_t i = 0; i < a->nservos; i++) {
            lsc_outbuf_printf(b, " %u:%u", a->ids[i], w[1 + i]);
        }
        lsc_outbuf_put(b, "\n", 1);
    }
    return 0;
}
#endif
