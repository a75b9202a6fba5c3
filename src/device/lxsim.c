/* lsc device: the bus of "lx:sim" (lxsim.h): an in-process virtual bus of
 * servos (lsc/lxbus.h) as the port of the "lx:" entry, on the real clock as
 * "sim" is (transport_sim.c): the bus's clock follows the monotonic clock,
 * so a reply nobody gives is waited for as long as on a pseudo-terminal, and
 * a timerfd polls readable while the bus has bytes to be read. Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/timerfd.h>
#endif

#include "device_internal.h"
#include "lsc/lxbus.h"
#include "lxsim.h"

#define LXSIM_PREFIX_LEN 3u /* "sim" */

struct lsc_dev_lxsim {
    lsc_lxbus bus;
    lsc_io io;        /* the bus's own port, on its virtual clock */
    int timer;        /* readable while bytes wait (-1: none) */
    uint64_t base_us; /* the monotonic time of the bus's time 0 */
};

/* The monotonic clock in us. */
static uint64_t real_us(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t); /* (cannot fail for this clock) */
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

/* The bus's clock brought up to real time now (real_us()): what became due
 * meanwhile happens. The bus may be ahead (with a baud rate set, bytes
 * written take their time on its line): then it waits. */
static void sync_clock(lsc_dev_lxsim *s, uint64_t now)
{
    uint64_t to = now - s->base_us, at = lsc_lxbus_now_us(&s->bus);
    if (to > at) {
        lsc_lxbus_advance_us(&s->bus, to - at);
    }
}

/* The timer: readable when the bus has (or is due to have) bytes to be
 * read, disarmed when it has none. */
static void arm(lsc_dev_lxsim *s)
{
#ifdef __linux__
    struct itimerspec t = {{0, 0}, {0, 0}};
    if (s->timer < 0) {
        return;
    }
    uint64_t next = lsc_lxbus_next_event_us(&s->bus);
    if (next != LSC_LXBUS_TIME_NEVER) {
        uint64_t at = s->base_us + lsc_lxbus_now_us(&s->bus) + next; /* > 0: base is */
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
    lsc_dev_lxsim *s = ctx;
    sync_clock(s, real_us());
    int r = s->io.write(s->io.ctx, data, n);
    arm(s);
    return r;
}

/* What the bus has sent by now; waits up to timeout_ms of real time for it
 * to send something (sleeping until its next byte is due, or the end). */
static int real_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_dev_lxsim *s = ctx;
    uint64_t until = real_us() + (uint64_t)timeout_ms * 1000u;
    int r;
    for (;;) {
        uint64_t now = real_us();
        sync_clock(s, now);
        r = s->io.read(s->io.ctx, buf, cap, 0);
        if (r != 0 || now >= until) {
            break;
        }
        /* the bus's next byte, in real time (it may be ahead of it) */
        uint64_t next = lsc_lxbus_next_event_us(&s->bus), left = until - now;
        uint64_t due = next == LSC_LXBUS_TIME_NEVER
                           ? left
                           : lsc_lxbus_now_us(&s->bus) + next - (now - s->base_us);
        uint64_t us = due < left ? due : left;
        struct timespec t = {(time_t)(us / 1000000u), (long)(us % 1000000u) * 1000L};
        (void)nanosleep(&t, NULL); /* (a signal ends it early: the loop goes on) */
    }
    arm(s);
    return r;
}

static uint32_t real_now(void *ctx)
{
    lsc_dev_lxsim *s = ctx;
    sync_clock(s, real_us());
    return (uint32_t)(lsc_lxbus_now_us(&s->bus) / 1000u);
}

bool lsc_dev_lxsim_claims(const char *path)
{
    return strncmp(path, LXSIM_NAME, LXSIM_PREFIX_LEN) == 0 &&
           (path[LXSIM_PREFIX_LEN] == '\0' || path[LXSIM_PREFIX_LEN] == ':');
}

int lsc_dev_lxsim_open(lsc_device *d, const char *path, lsc_dev_lxsim **out, lsc_io *port)
{
    const char *list = path[LXSIM_PREFIX_LEN] == ':' ? path + LXSIM_PREFIX_LEN + 1u : LXSIM_IDS;
    uint8_t ids[LSC_LXBUS_SERVOS];
    char why[DEVICE_MESSAGE_MAX / 2u];
    int n = lsc_device_parse_ids(NULL, list, ids, LSC_LXBUS_SERVOS, why, sizeof why);
    if (n < 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "lx:sim:IDS names the servos of the virtual bus (e.g. lx:sim:1-6): "
                            "%s",
                            why);
    }
    for (int i = 0; i < n; i++) {
        if (ids[i] > LSC_LX_ID_MAX) {
            return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                "lx:sim:IDS: id %u is not a servo's: use 0..253 (254 is the "
                                "broadcast id)",
                                ids[i]);
        }
    }
    lsc_dev_lxsim *s = calloc(1, sizeof *s);
    *out = s;
    if (s == NULL) {
        return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE, "out of memory");
    }
    s->timer = -1;
    (void)lsc_lxbus_init(&s->bus);
    for (int i = 0; i < n; i++) {
        (void)lsc_lxbus_add(&s->bus, ids[i]); /* (at most LSC_LXBUS_SERVOS, each valid) */
    }
    (void)lsc_lxbus_io_init(&s->bus, &s->io);
#ifdef __linux__
    /* none (out of descriptors): the real clock still, reads sleep, and
     * the fileno is -1 */
    s->timer = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
#endif
    s->base_us = real_us();
    port->ctx = s;
    port->write = real_write;
    port->read = real_read;
    port->now_ms = real_now;
    return 0;
}

void lsc_dev_lxsim_close(lsc_dev_lxsim *s)
{
    if (s != NULL && s->timer >= 0) {
        (void)close(s->timer);
    }
    free(s);
}

int lsc_dev_lxsim_fileno(const lsc_dev_lxsim *s)
{
    return s->timer;
}

lsc_lxbus *lsc_dev_lxsim_bus(lsc_dev_lxsim *s)
{
    return &s->bus;
}

#endif
