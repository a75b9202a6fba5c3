/* lsc device: the entry of "sim", the built-in virtual controller: a model
 * (lsc/sim.h) with demo action groups, on the real clock by default (its
 * clock follows the monotonic clock, a timerfd polls readable when it is due
 * to send something), or on its own virtual clock, which moves only while
 * the device waits or reads; and the waits that can never end on it
 * (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/timerfd.h>
#endif

#include "device_internal.h"

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
    lsc_io io;        /* the model's own port, on its virtual clock */
    bool virtual_clock; /* lsc_device_set_virtual_clock: d->port is io */
    int timer;        /* real clock: the timerfd of lsc_device_fileno (-1: none) */
    uint64_t base_us; /* real clock: the monotonic time of the model's time 0 */
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

/* The monotonic clock in us. */
static uint64_t real_us(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t); /* (cannot fail for this clock) */
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

/* The model's clock brought up to real time now (real_us()): what became
 * due meanwhile happens (its replies and notifications wait to be read).
 * The model may be ahead (bytes written take their time on its line): then
 * it waits. After it, the model's time is at least now - base. */
static void sync_clock(sim_state *s, uint64_t now)
{
    uint64_t to = now - s->base_us, at = lsc_sim_now_us(&s->sim);
    if (to > at) {
        lsc_sim_advance_us(&s->sim, to - at);
    }
}

/* The timer: readable when the model is due to send something (at once
 * when it has something to send), disarmed when nothing is scheduled. */
static void arm(sim_state *s)
{
#ifdef __linux__
    struct itimerspec t = {{0, 0}, {0, 0}};
    if (s->timer < 0) {
        return;
    }
    uint64_t next = lsc_sim_next_event_us(&s->sim);
    if (next != LSC_SIM_TIME_NEVER) {
        uint64_t at = s->base_us + lsc_sim_now_us(&s->sim) + next; /* > 0: base is */
        t.it_value.tv_sec = (time_t)(at / 1000000u);
        t.it_value.tv_nsec = (long)(at % 1000000u) * 1000L;
    }
    (void)timerfd_settime(s->timer, TFD_TIMER_ABSTIME, &t, NULL); /* (valid arguments) */
#else
    (void)s;
#endif
}

static int real_write(void *ctx, const uint8_t *data, size_t n)
{
    sim_state *s = ctx;
    sync_clock(s, real_us());
    int r = s->io.write(s->io.ctx, data, n);
    arm(s);
    return r;
}

/* Sleeps us (at most), woken early by a signal. */
static void sleep_us(uint64_t us)
{
    struct timespec t = {(time_t)(us / 1000000u), (long)(us % 1000000u) * 1000L};
    (void)nanosleep(&t, NULL);
}

/* What the model has sent by now; waits up to timeout_ms of real time for
 * it to send something. */
static int real_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    sim_state *s = ctx;
    uint64_t until = real_us() + (uint64_t)timeout_ms * 1000u;
    int r;
    for (;;) {
        uint64_t now = real_us();
        sync_clock(s, now);
        r = s->io.read(s->io.ctx, buf, cap, 0);
        if (r != 0 || now >= until) {
            break;
        }
        /* the model's next event, in real time (it may be ahead of it) */
        uint64_t next = lsc_sim_next_event_us(&s->sim), left = until - now;
        uint64_t due = next == LSC_SIM_TIME_NEVER
                           ? left
                           : lsc_sim_now_us(&s->sim) + next - (now - s->base_us);
        sleep_us(due < left ? due : left);
    }
    arm(s);
    return r;
}

static uint32_t real_now(void *ctx)
{
    sim_state *s = ctx;
    sync_clock(s, real_us());
    return (uint32_t)(lsc_sim_now_us(&s->sim) / 1000u);
}

/* The port of the model on its clock: the model's own (virtual), or one
 * that brings it up to real time first. */
static void use_clock(lsc_device *d)
{
    sim_state *s = st(d);
    if (s->virtual_clock) {
        d->port = s->io;
        return;
    }
    s->base_us = real_us() - lsc_sim_now_us(&s->sim);
    d->port.ctx = s;
    d->port.write = real_write;
    d->port.read = real_read;
    d->port.now_ms = real_now;
    arm(s);
}

int lsc_device_set_virtual_clock(lsc_device *d, bool on)
{
    sim_state *s = sim_of(d);
    if (s == NULL) {
        return LSC_EINVAL;
    }
    if (on != s->virtual_clock) {
        s->virtual_clock = on;
        use_clock(d);
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
    s->timer = -1;
    (void)lsc_sim_init(&s->sim);
    (void)lsc_sim_groups_init(&s->groups, s->steps, SIM_STEPS, s->targets, SIM_TARGETS);
    (void)lsc_sim_groups_parse(&s->groups, sim_groups_text, sizeof sim_groups_text - 1u, NULL);
    lsc_sim_set_groups(&s->sim, &s->groups);
    (void)lsc_sim_io_init(&s->sim, &s->io);
#ifdef __linux__
    /* none (out of descriptors): the real clock still, waits sleep, and
     * lsc_device_fileno is -1 as for the virtual clock */
    s->timer = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
#endif
    use_clock(d);
    return 0;
}

static void close_sim(lsc_device *d)
{
    sim_state *s = st(d);
    if (s != NULL && s->timer >= 0) {
        (void)close(s->timer);
    }
    free(s);
    d->state = NULL;
}

/* Its timer; -1 on its virtual clock. */
static int sim_fileno(const lsc_device *d)
{
    return st(d)->virtual_clock ? -1 : st(d)->timer;
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
    const sim_state *s = st(d);
    uint64_t us = lsc_sim_next_event_us(&s->sim);
    if (us == LSC_SIM_TIME_NEVER) {
        return LSC_DEVICE_FOREVER;
    }
    if (!s->virtual_clock) { /* due at the model's time now + us: how far in real time */
        uint64_t due = lsc_sim_now_us(&s->sim) + us, now = real_us() - s->base_us;
        us = due > now ? due - now : 0u;
    }
    return to_ms(us);
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
