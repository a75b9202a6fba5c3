/* lsc device: the clock of "sim", the built-in virtual controller: real
 * time by default (its clock follows the monotonic clock, a timerfd polls
 * readable when it is due to send something), or its own virtual clock,
 * which moves only while the device waits or reads (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/timerfd.h>
#endif

#include "device_internal.h"

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
static void sync_clock(lsc_device *d, uint64_t now)
{
    uint64_t to = now - d->sim_base_us, at = lsc_sim_now_us(&d->sim);
    if (to > at) {
        lsc_sim_advance_us(&d->sim, to - at);
    }
}

/* The timer: readable when the model is due to send something (at once
 * when it has something to send), disarmed when nothing is scheduled. */
static void arm(lsc_device *d)
{
#ifdef __linux__
    struct itimerspec t = {{0, 0}, {0, 0}};
    if (d->sim_timer < 0) {
        return;
    }
    uint64_t next = lsc_sim_next_event_us(&d->sim);
    if (next != LSC_SIM_TIME_NEVER) {
        uint64_t at = d->sim_base_us + lsc_sim_now_us(&d->sim) + next; /* > 0: base is */
        t.it_value.tv_sec = (time_t)(at / 1000000u);
        t.it_value.tv_nsec = (long)(at % 1000000u) * 1000L;
    }
    (void)timerfd_settime(d->sim_timer, TFD_TIMER_ABSTIME, &t, NULL); /* (valid arguments) */
#else
    (void)d;
#endif
}

static int real_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_device *d = ctx;
    sync_clock(d, real_us());
    int r = d->sim_io.write(d->sim_io.ctx, data, n);
    arm(d);
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
    lsc_device *d = ctx;
    uint64_t until = real_us() + (uint64_t)timeout_ms * 1000u;
    int r;
    for (;;) {
        uint64_t now = real_us();
        sync_clock(d, now);
        r = d->sim_io.read(d->sim_io.ctx, buf, cap, 0);
        if (r != 0 || now >= until) {
            break;
        }
        /* the model's next event, in real time (it may be ahead of it) */
        uint64_t next = lsc_sim_next_event_us(&d->sim), left = until - now;
        uint64_t due = next == LSC_SIM_TIME_NEVER
                           ? left
                           : lsc_sim_now_us(&d->sim) + next - (now - d->sim_base_us);
        sleep_us(due < left ? due : left);
    }
    arm(d);
    return r;
}

static uint32_t real_now(void *ctx)
{
    lsc_device *d = ctx;
    sync_clock(d, real_us());
    return (uint32_t)(lsc_sim_now_us(&d->sim) / 1000u);
}

/* The port of the model on its clock: the model's own (virtual), or one
 * that brings it up to real time first. */
static void use_clock(lsc_device *d)
{
    if (d->sim_virtual) {
        d->port = d->sim_io;
        return;
    }
    d->sim_base_us = real_us() - lsc_sim_now_us(&d->sim);
    d->port.ctx = d;
    d->port.write = real_write;
    d->port.read = real_read;
    d->port.now_ms = real_now;
    arm(d);
}

void lsc_dev_sim_clock_open(lsc_device *d)
{
    (void)lsc_sim_io_init(&d->sim, &d->sim_io);
#ifdef __linux__
    /* none (out of descriptors): the real clock still, waits sleep, and
     * lsc_device_fileno is -1 as for the virtual clock */
    d->sim_timer = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
#endif
    use_clock(d);
}

void lsc_dev_sim_clock_close(lsc_device *d)
{
    if (d->sim_timer >= 0) {
        (void)close(d->sim_timer);
    }
}

int lsc_dev_sim_fileno(const lsc_device *d)
{
    return d->sim_virtual ? -1 : d->sim_timer;
}

uint32_t lsc_dev_sim_next_ms(const lsc_device *d)
{
    uint64_t us = lsc_sim_next_event_us(&d->sim);
    if (us == LSC_SIM_TIME_NEVER) {
        return LSC_DEVICE_FOREVER;
    }
    if (!d->sim_virtual) { /* due at the model's time now + us: how far in real time */
        uint64_t due = lsc_sim_now_us(&d->sim) + us, now = real_us() - d->sim_base_us;
        us = due > now ? due - now : 0u;
    }
    /* rounded up: at that time it is due. A step lasts at most 65535 ms
     * slowed 100 times (speed 1%): far below LSC_DEVICE_FOREVER ms */
    return (uint32_t)((us + 999u) / 1000u);
}

int lsc_device_set_virtual_clock(lsc_device *d, bool on)
{
    if (d == NULL || d->kind != LSC_DEVICE_SIM) {
        return LSC_EINVAL;
    }
    if (on != d->sim_virtual) {
        d->sim_virtual = on;
        use_clock(d);
    }
    return 0;
}

#endif
