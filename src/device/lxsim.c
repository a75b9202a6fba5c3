/* lsc device: the bus of "lx:sim" (lxsim.h): an in-process virtual bus of
 * servos (lsc/lxbus.h) as the port of the "lx:" entry, on the real clock as
 * "sim" is (realclock.c): a reply nobody gives is waited for as long as on a
 * pseudo-terminal, and a timerfd polls readable while the bus has bytes to
 * be read. Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdlib.h>
#include <string.h>

#include "device_internal.h"
#include "lsc/lxbus.h"
#include "lxsim.h"
#include "realclock.h"

#define LXSIM_PREFIX_LEN 3u /* "sim" */

struct lsc_dev_lxsim {
    lsc_lxbus bus;
    lsc_dev_realclock clock;
};

/* The bus's clock, for realclock.c. */
static uint64_t bus_now_us(const void *bus)
{
    return lsc_lxbus_now_us(bus);
}

static void bus_advance_us(void *bus, uint64_t us)
{
    lsc_lxbus_advance_us(bus, us);
}

static uint64_t bus_next_event_us(const void *bus)
{
    return lsc_lxbus_next_event_us(bus);
}

static const lsc_dev_clock_ops bus_clock = {bus_now_us, bus_advance_us, bus_next_event_us,
                                            LSC_LXBUS_TIME_NEVER};

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
    (void)lsc_lxbus_init(&s->bus);
    for (int i = 0; i < n; i++) {
        (void)lsc_lxbus_add(&s->bus, ids[i]); /* (at most LSC_LXBUS_SERVOS, each valid) */
    }
    lsc_io io;
    (void)lsc_lxbus_io_init(&s->bus, &io);
    lsc_dev_realclock_init(&s->clock, &bus_clock, &s->bus, &io);
    lsc_dev_realclock_port(&s->clock, false, port);
    return 0;
}

void lsc_dev_lxsim_close(lsc_dev_lxsim *s)
{
    if (s != NULL) {
        lsc_dev_realclock_close(&s->clock);
    }
    free(s);
}

int lsc_dev_lxsim_fileno(const lsc_dev_lxsim *s)
{
    return lsc_dev_realclock_fileno(&s->clock);
}

lsc_lxbus *lsc_dev_lxsim_bus(lsc_dev_lxsim *s)
{
    return &s->bus;
}

#endif
