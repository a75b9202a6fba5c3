/* lsc device: an in-process model (the virtual controller of "sim", the
 * virtual bus of "lx:sim") on the real clock (private): the model's clock
 * follows the monotonic clock, so a reply nobody gives is waited for as long
 * as on a real line, and a timerfd polls readable when the model is due to
 * send something. Or the model's own virtual clock, which moves only while
 * its port waits or reads. Host only. */
#ifndef LSC_DEVICE_REALCLOCK_H
#define LSC_DEVICE_REALCLOCK_H

#include <stdbool.h>
#include <stdint.h>

#include "lsc/io.h"

#define LSC_DEV_REALCLOCK_NEVER UINT64_MAX /* lsc_dev_realclock_next_us: none */

/* A model's clock (lsc_sim_now_us, ..., lsc_lxbus_now_us, ...). */
typedef struct lsc_dev_clock_ops {
    uint64_t (*now_us)(const void *model);
    void (*advance_us)(void *model, uint64_t us);
    uint64_t (*next_event_us)(const void *model); /* from now; never: none */
    uint64_t never;
} lsc_dev_clock_ops;

typedef struct lsc_dev_realclock {
    const lsc_dev_clock_ops *ops;
    void *model;
    lsc_io io;          /* the model's own port, on its virtual clock */
    bool virtual_clock; /* lsc_dev_realclock_port gave io itself */
    int timer;          /* real clock: readable when the model is due (-1: none) */
    uint64_t base_us;   /* real clock: the monotonic time of the model's time 0 */
} lsc_dev_realclock;

/* Sets c up for model (its clock: ops; its own port: io), with a timer
 * (none when the system has no descriptor left, or not Linux: waits sleep,
 * the fileno is -1). lsc_dev_realclock_port gives its port. */
void lsc_dev_realclock_init(lsc_dev_realclock *c, const lsc_dev_clock_ops *ops, void *model,
                            const lsc_io *io);

/* Closes c's timer. */
void lsc_dev_realclock_close(lsc_dev_realclock *c);

/* The model's port into *port: its own on its virtual clock (virtual_clock),
 * else one that brings the model up to real time first, the model's time
 * now being real time now. */
void lsc_dev_realclock_port(lsc_dev_realclock *c, bool virtual_clock, lsc_io *port);

/* The timer to poll, or -1 (none, or the virtual clock). */
int lsc_dev_realclock_fileno(const lsc_dev_realclock *c);

/* us until the model's next event, on the clock of its port (real: 0 when
 * due); LSC_DEV_REALCLOCK_NEVER when nothing is scheduled. */
uint64_t lsc_dev_realclock_next_us(const lsc_dev_realclock *c);

#endif
