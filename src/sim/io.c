/* The lsc_io adapter over the model: the `sim` port. */
#include "lsc/sim.h"

#include <limits.h>

static int sim_io_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_sim *sim = ctx;
    if (data == NULL && n > 0u) {
        return LSC_EINVAL;
    }
    if (n > (size_t)INT_MAX) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        /* the byte is on the host's side of the line until it has crossed it */
        if (sim->baud != 0u) {
            lsc_sim_advance_us(sim, (10000000u + sim->baud - 1u) / sim->baud);
        }
        (void)lsc_sim_feed(sim, &data[i], 1);
    }
    return (int)n;
}

static int sim_io_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_sim *sim = ctx;
    uint64_t left = (uint64_t)timeout_ms * 1000u;
    if (buf == NULL || cap == 0u) {
        return LSC_EINVAL;
    }
    if (cap > (size_t)INT_MAX) {
        cap = (size_t)INT_MAX;
    }
    for (;;) {
        size_t got = lsc_sim_read(sim, buf, cap);
        if (got > 0u) {
            return (int)got;
        }
        if (left == 0u) {
            return 0;
        }
        uint64_t step = lsc_sim_next_event_us(sim);
        if (step > left) {
            step = left;
        }
        lsc_sim_advance_us(sim, step);
        left -= step;
    }
}

static uint32_t sim_io_now_ms(void *ctx)
{
    const lsc_sim *sim = ctx;
    return (uint32_t)(lsc_sim_now_us(sim) / 1000u);
}

int lsc_sim_io_init(lsc_sim *sim, lsc_io *io)
{
    if (sim == NULL || io == NULL) {
        return LSC_EINVAL;
    }
    io->ctx = sim;
    io->write = sim_io_write;
    io->read = sim_io_read;
    io->now_ms = sim_io_now_ms;
    return 0;
}
