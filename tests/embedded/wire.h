/* The host side of the embedded tests: the virtual controller (lsc/sim.h)
 * that firmware in an emulator talks to, with a log of the exchange.
 *
 * The log goes to stdout, one line per event, for the test to compare:
 *   "> 55 55 02 0F"       a frame the controller received from the firmware
 *   "< 55 55 04 0F 4C 1D" a frame the controller sent
 *   "! beep: <why>"       a malformed frame from the firmware
 *   "! ignored: <why>"    a command that changed nothing
 *   "! noise: 3A"         a byte outside any frame
 *   "! dropped: ..."      a frame the controller did not send
 * No times are printed, so the log does not depend on emulation speed. */
#ifndef LSC_TEST_WIRE_H
#define LSC_TEST_WIRE_H

#include "lsc/lxbus.h"
#include "lsc/sim.h"

/* Storage for the action groups a test loads. */
typedef struct wire_groups {
    lsc_sim_groups groups;
    lsc_sim_step steps[64];
    lsc_servo targets[256];
} wire_groups;

/* Sets sim up: power-on state, logging to stdout. Returns 0 or an LSC_E code. */
int wire_init(lsc_sim *sim);

/* Sets bus up as a bus of servos heard from a pin (the host's echo, 115200
 * baud), logging as above: "> " frames from the firmware, "< " replies. */
int wire_init_bus(lsc_lxbus *bus);

/* Loads the group text file at path into g and hands it to sim. Prints why
 * and returns a negative code if it cannot. */
int wire_load_groups(lsc_sim *sim, wire_groups *g, const char *path);

#endif
