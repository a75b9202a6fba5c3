/*
 * The virtual controller under a "sim" device, for the library's own tests
 * and benchmarks (not part of the public API, not exported: they link the
 * static library). Host only.
 */
#ifndef LSC_DEVICE_SIM_H
#define LSC_DEVICE_SIM_H

#include <stdint.h>

#include "lsc/device.h"
#include "lsc/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* For "sim" only: how many ms on its clock until it sends something of its
 * own accord, 0 when that is due now; LSC_DEVICE_FOREVER when nothing is
 * scheduled (only a frame sent to it can make it send anything), for the
 * other kinds and NULL. lsc_device_next_event_ms says it for every kind, in
 * real ms. */
uint32_t lsc_device_sim_next_event_ms(const lsc_device *d);


/* The virtual controller of a "sim" device (NULL for any other, or NULL d):
 * for tests and demonstrations that act on it as the world would (hold a
 * servo with lsc_sim_block, run a group as its handle would). Valid until
 * lsc_device_close. */
lsc_sim *lsc_device_sim(lsc_device *d);

/* The virtual bus of an "lx:sim" device (NULL for any other, or NULL d):
 * for tests that act on it as the world would (a servo's temperature, a
 * late reply). Valid until lsc_device_close. */
struct lsc_lxbus *lsc_device_lxbus(lsc_device *d);

#ifdef __cplusplus
}
#endif

#endif /* LSC_DEVICE_SIM_H */
