/* lsc device: an in-process model on the real clock (realclock.h). Host
 * only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/timerfd.h>
#endif

#include "realclock.h"

/* The monotonic clock in us. */
static uint64_t real_us(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t); /* (cannot fail for this clock) */
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

/* The model's clock brought up to real time now (real_us()): what became
 * due meanwhile happens (what it sends waits to be read). The model may be
 * ahead (bytes written take their time on its line): then it waits. After
 * it, the model's time is at least now - base. */
static void sync_clock(lsc_dev_realclock *c, uint64_t now)
{
    uint64_t to = now - c->base_us, at = c->ops->now_us(c->model);
    if (to > at) {
        c->ops->advance_us(c->model, to - at);
    }
}

/* us from real time now until the model's next event (0: due), or
 * LSC_DEV_REALCLOCK_NEVER. */
static uint64_t due_us(const lsc_dev_realclock *c, uint64_t now)
{
    uint64_t next = c->ops->next_event_us(c->model);
    if (next == c->ops->never) {
        return LSC_DEV_REALCLOCK_NEVER;
    }
    uint64_t due = c->ops->now_us(c->model) + next, at = now - c->base_us;
    return due > at ? due - at : 0u;
}

/* The timer: readable when the model is due to send something (at once
 * when it has something to send), disarmed when nothing is scheduled. */
static void arm(lsc_dev_realclock *c)
{
#ifdef __linux__
    struct itimerspec t = {{0, 0}, {0, 0}};
    if (c->timer < 0) {
        return;
    }
    uint64_t next = c->ops->next_event_us(c->model);
    if (next != c->ops->never) {
        uint64_t at = c->base_us + c->ops->now_us(c->model) + next; /* > 0: base is */
        t.it_value.tv_sec = (time_t)(at / 1000000u);
        t.it_value.tv_nsec = (long)(at % 1000000u) * 1000L;
    }
    (void)timerfd_settime(c->timer, TFD_TIMER_ABSTIME, &t, NULL); /* (valid arguments) */
#else
    (void)c;
#endif
}

static int real_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_dev_realclock *c = ctx;
    sync_clock(c, real_us());
    int r = c->io.write(c->io.ctx, data, n);
    arm(c);
    return r;
}

/* What the model has sent by now; waits up to timeout_ms of real time for
 * it to send something (sleeping until its next event, or the end). */
static int real_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_dev_realclock *c = ctx;
    uint64_t until = real_us() + (uint64_t)timeout_ms * 1000u;
    int r;
    for (;;) {
        uint64_t now = real_us();
        sync_clock(c, now);
        r = c->io.read(c->io.ctx, buf, cap, 0);
        if (r != 0 || now >= until) {
            break;
        }
        uint64_t due = due_us(c, now), left = until - now;
        uint64_t us = due < left ? due : left;
        struct timespec t = {(time_t)(us / 1000000u), (long)(us % 1000000u) * 1000L};
        (void)nanosleep(&t, NULL); /* (a signal ends it early: the loop goes on) */
    }
    arm(c);
    return r;
}

static uint32_t real_now(void *ctx)
{
    lsc_dev_realclock *c = ctx;
    sync_clock(c, real_us());
    return (uint32_t)(c->ops->now_us(c->model) / 1000u);
}

void lsc_dev_realclock_init(lsc_dev_realclock *c, const lsc_dev_clock_ops *ops, void *model,
                            const lsc_io *io)
{
    c->ops = ops;
    c->model = model;
    c->io = *io;
    c->virtual_clock = false;
    c->timer = -1;
    c->base_us = 0;
#ifdef __linux__
    c->timer = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
#endif
}

void lsc_dev_realclock_close(lsc_dev_realclock *c)
{
    if (c->timer >= 0) {
        (void)close(c->timer);
    }
    c->timer = -1;
}

void lsc_dev_realclock_port(lsc_dev_realclock *c, bool virtual_clock, lsc_io *port)
{
    c->virtual_clock = virtual_clock;
    if (virtual_clock) {
        *port = c->io;
        return;
    }
    c->base_us = real_us() - c->ops->now_us(c->model);
    port->ctx = c;
    port->write = real_write;
    port->read = real_read;
    port->now_ms = real_now;
    arm(c);
}

int lsc_dev_realclock_fileno(const lsc_dev_realclock *c)
{
    return c->virtual_clock ? -1 : c->timer;
}

uint64_t lsc_dev_realclock_next_us(const lsc_dev_realclock *c)
{
    if (c->virtual_clock) {
        uint64_t us = c->ops->next_event_us(c->model);
        return us == c->ops->never ? LSC_DEV_REALCLOCK_NEVER : us;
    }
    return due_us(c, real_us());
}

#endif
