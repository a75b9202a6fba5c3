/* Fuzz harness for the action group text parser, lsc_sim_groups_parse
 * (include/lsc/sim.h, docs/action-groups.md): the group-file loader.
 *
 * Input: byte 0 and byte 1 size the step and target arrays (0..255 each);
 * the rest is the text. Checked on every input:
 *  - nothing is written past either array (canaries);
 *  - on success: the result is the number of groups defined; every group's
 *    steps lie inside the steps used, every step's targets inside the targets
 *    used; times are 1..65535; ids are distinct within a step; and printing
 *    the groups back as text and parsing that gives the same groups;
 *  - on failure: LSC_EINVAL or LSC_ENOSPC, a line and column >= 1, a
 *    message, and the groups left empty.
 */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/sim.h"

#define MAX_ITEMS 256u

/* Checks the structure of a parsed g; returns how many groups it defines. */
static int check_groups(const lsc_sim_groups *g)
{
    int groups = 0;
    FUZZ_CHECK(g->nsteps <= g->steps_cap && g->ntargets <= g->targets_cap);
    for (size_t n = 0; n < LSC_SIM_GROUPS; n++) {
        if (g->group_steps[n] == 0) {
            continue;
        }
        groups++;
        FUZZ_CHECK((size_t)g->first_step[n] + g->group_steps[n] <= g->nsteps);
        for (size_t i = g->first_step[n]; i < (size_t)g->first_step[n] + g->group_steps[n]; i++) {
            const lsc_sim_step *s = &g->steps[i];
            FUZZ_CHECK(s->time_ms >= 1);
            FUZZ_CHECK((size_t)s->first + s->ntargets <= g->ntargets);
            bool seen[256] = {false};
            for (size_t t = s->first; t < (size_t)s->first + s->ntargets; t++) {
                FUZZ_CHECK(!seen[g->targets[t].id]);
                seen[g->targets[t].id] = true;
            }
        }
    }
    return groups;
}

/* Prints g as group text; returns its length. */
static size_t print_groups(const lsc_sim_groups *g, char *out, size_t cap)
{
    size_t len = 0;
    for (size_t n = 0; n < LSC_SIM_GROUPS; n++) {
        if (g->group_steps[n] == 0) {
            continue;
        }
        len += (size_t)snprintf(out + len, cap - len, "group %zu\n", n);
        for (size_t i = g->first_step[n]; i < (size_t)g->first_step[n] + g->group_steps[n]; i++) {
            const lsc_sim_step *s = &g->steps[i];
            len += (size_t)snprintf(out + len, cap - len, "step %u", (unsigned)s->time_ms);
            for (size_t t = s->first; t < (size_t)s->first + s->ntargets; t++) {
                len += (size_t)snprintf(out + len, cap - len, " %u:%u",
                                        (unsigned)g->targets[t].id,
                                        (unsigned)g->targets[t].position);
            }
            len += (size_t)snprintf(out + len, cap - len, "\n");
        }
    }
    FUZZ_CHECK(len < cap);
    return len;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lsc_sim_step steps[MAX_ITEMS + 4], steps2[MAX_ITEMS];
    static lsc_servo targets[MAX_ITEMS + 4], targets2[MAX_ITEMS];
    static char text[MAX_ITEMS * 96 + 4096];
    size_t nsteps = size > 0 ? data[0] : 0;
    size_t ntargets = size > 1 ? data[1] : 0;
    const char *in = size > 2 ? (const char *)data + 2 : "";
    size_t len = size > 2 ? size - 2 : 0;

    memset(steps, FUZZ_CANARY, sizeof steps);
    memset(targets, FUZZ_CANARY, sizeof targets);
    lsc_sim_groups g;
    FUZZ_CHECK(lsc_sim_groups_init(&g, steps, nsteps, targets, ntargets) == 0);
    lsc_sim_parse_error err = {0, 0, NULL};
    int r = lsc_sim_groups_parse(&g, in, len, &err);
    FUZZ_CHECK(fuzz_all_canary(&steps[nsteps], sizeof steps - nsteps * sizeof steps[0]));
    FUZZ_CHECK(fuzz_all_canary(&targets[ntargets], sizeof targets - ntargets * sizeof targets[0]));
    if (r < 0) {
        FUZZ_CHECK(r == LSC_EINVAL || r == LSC_ENOSPC);
        FUZZ_CHECK(err.line >= 1 && err.column >= 1 && err.message != NULL);
        FUZZ_CHECK(g.nsteps == 0 && g.ntargets == 0 && check_groups(&g) == 0);
        return 0;
    }
    FUZZ_CHECK(r == check_groups(&g));

    /* Printed back and parsed again: the same groups. */
    size_t tlen = print_groups(&g, text, sizeof text);
    lsc_sim_groups h;
    FUZZ_CHECK(lsc_sim_groups_init(&h, steps2, MAX_ITEMS, targets2, MAX_ITEMS) == 0);
    FUZZ_CHECK(lsc_sim_groups_parse(&h, text, tlen, NULL) == r);
    FUZZ_CHECK(h.nsteps == g.nsteps && h.ntargets == g.ntargets);
    FUZZ_CHECK(memcmp(h.group_steps, g.group_steps, sizeof g.group_steps) == 0);
    for (size_t n = 0; n < LSC_SIM_GROUPS; n++) {
        for (size_t i = 0; i < g.group_steps[n]; i++) {
            const lsc_sim_step *a = &g.steps[g.first_step[n] + i];
            const lsc_sim_step *b = &h.steps[h.first_step[n] + i];
            FUZZ_CHECK(a->time_ms == b->time_ms && a->ntargets == b->ntargets);
            for (size_t t = 0; t < a->ntargets; t++) {
                FUZZ_CHECK(g.targets[a->first + t].id == h.targets[b->first + t].id);
                FUZZ_CHECK(g.targets[a->first + t].position == h.targets[b->first + t].position);
            }
        }
    }
    return 0;
}
