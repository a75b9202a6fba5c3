/* lsc device: the entry of "sim", the built-in virtual controller: a model
 * (lsc/sim.h) with demo action groups, on the real clock by default, or on
 * its own virtual clock, which moves only while the device waits or reads
 * (both: realclock.c); and the waits that can never end on it (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"
#include "realclock.h"

#define SIM_STEPS 16u
#define SIM_TARGETS 32u

/* The action groups of the built-in virtual controller ("sim"). */
static const char sim_groups_text[] = "# lsc device \"sim\": demo action groups\n"
                                      "group 1\n"
                                      "step 500 1:1000 2:2000\n"
                                      "step 500 1:1500 2:1500\n"
                                      "group 2\n"
                                      "step 300 1:1200\n"
                                      "step 300 1:1800\n"
                                      "group 8\n"
                                      "step 1000 1:2000 2:1200 3:1500\n"
                                      "step 1000 1:1000 2:1800 3:1500\n"
                                      "step 500 1:1500 2:1500 3:1500\n";

typedef struct sim_state {
    lsc_sim sim;
    lsc_dev_realclock clock; /* the real clock, or (lsc_device_set_virtual_clock) its own */
    lsc_sim_groups groups;
    lsc_sim_step steps[SIM_STEPS];
    lsc_servo targets[SIM_TARGETS];
} sim_state;

static sim_state *st(const lsc_device *d)
{
    return d->state;
}

/* d's state if d is "sim" (its open never fails), else NULL. */
static sim_state *sim_of(const lsc_device *d)
{
    return d != NULL && d->t == &lsc_dev_transport_sim ? st(d) : NULL;
}

/* ---- The clock -------------------------------------------------------------------- */

/* The model's clock, for realclock.c. */
static uint64_t sim_now_us(const void *model)
{
    return lsc_sim_now_us(model);
}

static void sim_advance_us(void *model, uint64_t us)
{
    lsc_sim_advance_us(model, us);
}

static uint64_t sim_next_event_us(const void *model)
{
    return lsc_sim_next_event_us(model);
}

static const lsc_dev_clock_ops sim_clock = {sim_now_us, sim_advance_us, sim_next_event_us,
                                            LSC_SIM_TIME_NEVER};

int lsc_device_set_virtual_clock(lsc_device *d, bool on)
{
    sim_state *s = sim_of(d);
    if (s == NULL) {
        return LSC_EINVAL;
    }
    if (on != s->clock.virtual_clock) {
        lsc_dev_realclock_port(&s->clock, on, &d->port);
    }
    return 0;
}

/* ---- The entry -------------------------------------------------------------------- */

static bool claims(const char *name)
{
    return strcmp(name, "sim") == 0;
}

static int open_sim(lsc_device *d, const char *name)
{
    (void)name;
    int r = lsc_dev_state_alloc(d, sizeof(sim_state));
    if (r != 0) {
        return r;
    }
    sim_state *s = st(d);
    lsc_io io;
    (void)lsc_sim_init(&s->sim);
    (void)lsc_sim_groups_init(&s->groups, s->steps, SIM_STEPS, s->targets, SIM_TARGETS);
    (void)lsc_sim_groups_parse(&s->groups, sim_groups_text, sizeof sim_groups_text - 1u, NULL);
    lsc_sim_set_groups(&s->sim, &s->groups);
    (void)lsc_sim_io_init(&s->sim, &io);
    lsc_dev_realclock_init(&s->clock, &sim_clock, &s->sim, &io);
    lsc_dev_realclock_port(&s->clock, false, &d->port);
    return 0;
}

static void close_sim(lsc_device *d)
{
    sim_state *s = st(d);
    if (s != NULL) {
        lsc_dev_realclock_close(&s->clock);
    }
    free(s);
    d->state = NULL;
}

/* Its timer; -1 on its virtual clock. */
static int sim_fileno(const lsc_device *d)
{
    return lsc_dev_realclock_fileno(&st(d)->clock);
}

static const char *no_message(const lsc_device *d)
{
    (void)d; /* "sim" fails only by timeouts and bad replies */
    return "";
}

/* ms until the model's next event, on its clock (rounded up: at that time it
 * is due. A step lasts at most 65535 ms slowed 100 times (speed 1%): far
 * below LSC_DEVICE_FOREVER ms). */
static uint32_t to_ms(uint64_t us)
{
    return (uint32_t)((us + 999u) / 1000u);
}

static uint32_t next_event_ms(const lsc_device *d)
{
    uint64_t us = lsc_dev_realclock_next_us(&st(d)->clock);
    return us == LSC_DEV_REALCLOCK_NEVER ? LSC_DEVICE_FOREVER : to_ms(us);
}

uint32_t lsc_device_sim_next_event_ms(const lsc_device *d)
{
    const sim_state *s = sim_of(d);
    if (s == NULL) {
        return LSC_DEVICE_FOREVER;
    }
    uint64_t us = lsc_sim_next_event_us(&s->sim);
    return us == LSC_SIM_TIME_NEVER ? LSC_DEVICE_FOREVER : to_ms(us);
}

/* Nothing scheduled: only what it sent already can be read (nothing else
 * can come, and on its real clock a wait would be time lost). */
static bool quiet(const lsc_device *d)
{
    return lsc_sim_next_event_us(&st(d)->sim) == LSC_SIM_TIME_NEVER;
}

size_t lsc_device_groups(const lsc_device *d, uint8_t *out, size_t cap)
{
    const sim_state *s = sim_of(d);
    size_t n = 0;
    if (s == NULL) {
        return 0;
    }
    for (size_t g = 0; g < LSC_SIM_GROUPS; g++) {
        if (s->groups.group_steps[g] != 0) {
            if (out != NULL && n < cap) {
                out[n] = (uint8_t)g;
            }
            n++;
        }
    }
    return n;
}

/* The action groups of "sim", as "1, 2 and 8", into out (room for all 256:
 * LSC_SIM_GROUPS * 8 bytes). */
static void sim_groups(const lsc_device *d, char *out, size_t cap)
{
    uint8_t groups[LSC_SIM_GROUPS];
    size_t total = lsc_device_groups(d, groups, sizeof groups), len = 0;
    out[0] = '\0';
    for (size_t i = 0; i < total; i++) {
        len += (size_t)snprintf(out + len, cap - len, "%s%u",
                                i == 0 ? "" : i + 1u == total ? " and " : ", ", groups[i]);
    }
}

/* The built-in virtual controller does nothing on its own: only what was
 * sent to it can make it send anything. Why waiting longer cannot bring
 * what is waited for, or LSC_DEVICE_CAUSE_NONE when it may. */
static lsc_device_cause sim_cause(const lsc_device *d, uint32_t timeout_ms)
{
    const sim_state *s = st(d);
    /* a group that loops for ever sends nothing more: neither its end nor
     * any other notification can come */
    if (d->ran && d->run_forever && timeout_ms == LSC_DEVICE_FOREVER &&
        lsc_sim_group_running(&s->sim) == (int)d->run_group) {
        return LSC_DEVICE_CAUSE_SIM_FOREVER;
    }
    if (lsc_sim_next_event_us(&s->sim) != LSC_SIM_TIME_NEVER) {
        return LSC_DEVICE_CAUSE_NONE;
    }
    return d->ran && (d->run_group >= LSC_SIM_GROUPS || s->groups.group_steps[d->run_group] == 0)
               ? LSC_DEVICE_CAUSE_SIM_NO_GROUP
               : LSC_DEVICE_CAUSE_SIM_IDLE;
}

/* LSC_ETIMEOUT at once (after saying why) when sim_cause says so; else 0. */
static int hopeless(lsc_device *d, uint32_t timeout_ms)
{
    char groups[LSC_SIM_GROUPS * 8u]; /* "255 and " at most, each */
    lsc_device_cause cause = sim_cause(d, timeout_ms);
    if (cause == LSC_DEVICE_CAUSE_NONE) {
        return 0;
    }
    if (cause == LSC_DEVICE_CAUSE_SIM_FOREVER) {
        return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_SIM_FOREVER,
                            "group %u loops for ever (it was run with times 0) and nothing else "
                            "on the virtual controller (sim) can stop it, so a wait without "
                            "limit would never end: run it a number of times, or give the wait "
                            "a timeout",
                            d->run_group);
    }
    sim_groups(d, groups, sizeof groups);
    if (cause == LSC_DEVICE_CAUSE_SIM_NO_GROUP) {
        return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_SIM_NO_GROUP,
                            "the virtual controller (sim) has no group %u, so it never starts: "
                            "its groups are %s",
                            d->run_group, groups);
    }
    return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_SIM_IDLE,
                        "nothing runs on the virtual controller (sim, groups %s), so nothing "
                        "will arrive: run a group first, or serve it with lsc-sim",
                        groups);
}

/* The virtual controller is the arm of the profile. */
static void arm_set(lsc_device *d, const lsc_arm *a)
{
    if (a != NULL) {
        (void)lsc_arm_stand_in(a, &st(d)->sim);
    }
}

lsc_sim *lsc_device_sim(lsc_device *d)
{
    sim_state *s = sim_of(d);
    return s == NULL ? NULL : &s->sim;
}

static size_t all_ids(const char *name)
{
    (void)name;
    return DEVICE_BOARD_IDS;
}

const lsc_dev_transport lsc_dev_transport_sim = {
    .kind = LSC_DEVICE_SIM,
    .claims = claims,
    .open = open_sim,
    .close = close_sim,
    .fileno = sim_fileno,
    .message = no_message,
    .next_event_ms = next_event_ms,
    .quiet = quiet,
    .hopeless = hopeless,
    .arm_set = arm_set,
    .all_ids = all_ids,
    .ops = &lsc_dev_board_ops,
    .restart_grace_ms = 0u, /* it queues all that one frame makes it send at once */
    .name = "the virtual controller (sim)",
};

#endif
