/* Helpers shared by the simulator's tests. */
#ifndef LSC_TEST_SIM_UTIL_H
#define LSC_TEST_SIM_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/lsc.h"

/* Loads group text into the static storage behind g (asserts it parses). */
void sim_util_load(lsc_sim *sim, lsc_sim_groups *g, const char *text);

/* Feeds an encoder's output (n > 0 asserted). */
void sim_util_feed(lsc_sim *sim, const uint8_t *frame, int n);

/* Asserts the controller has sent exactly these bytes by now (and drains them). */
void sim_util_expect(lsc_sim *sim, const uint8_t *bytes, size_t n);

/* Asserts nothing is readable now. */
void sim_util_expect_none(lsc_sim *sim);

/* Sends a position request for one id and returns the position replied. */
uint16_t sim_util_read_pos(lsc_sim *sim, uint8_t id);

#define SIM_EXPECT(sim, ...)                                                                \
    do {                                                                                    \
        const uint8_t expect_[] = {__VA_ARGS__};                                            \
        sim_util_expect((sim), expect_, sizeof expect_);                                    \
    } while (0)

#define SIM_FEED(sim, ...)                                                                  \
    do {                                                                                    \
        const uint8_t feed_[] = {__VA_ARGS__};                                              \
        sim_util_feed((sim), feed_, (int)sizeof feed_);                                     \
    } while (0)

#endif
