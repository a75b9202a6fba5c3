/* lsc device: the bus of "lx:sim" (private): an in-process virtual bus of
 * servos (lsc/lxbus.h) as the port of the "lx:" entry (transport_lx.c), on
 * the real clock. Host only. */
#ifndef LSC_DEVICE_LXSIM_H
#define LSC_DEVICE_LXSIM_H

#include <stdbool.h>

#include "lsc/device.h"
#include "lsc/io.h"

#define LXSIM_NAME "sim"     /* "lx:sim", "lx:sim:IDS" */
#define LXSIM_IDS "1-6"      /* "lx:sim": an xArm's servos, as lsc-sim --lx 1-6 */

typedef struct lsc_dev_lxsim lsc_dev_lxsim;

/* Whether path (after "lx:") names the virtual bus: "sim" or "sim:IDS". */
bool lsc_dev_lxsim_claims(const char *path);

/* Opens the virtual bus path names for d: its servos (path "sim": 1..6;
 * "sim:IDS": the list, as lsc_device_parse_ids reads it), into *out, and
 * its port, on the real clock, into *port. 0, or an error after d's line
 * (LSC_EINVAL: a bad list; LSC_ENOSPC). */
int lsc_dev_lxsim_open(lsc_device *d, const char *path, lsc_dev_lxsim **out, lsc_io *port);

/* Frees s (NULL: nothing). */
void lsc_dev_lxsim_close(lsc_dev_lxsim *s);

/* The descriptor that polls readable while the bus has bytes to be read (a
 * timerfd), or -1 (none: a system out of descriptors, or not Linux). */
int lsc_dev_lxsim_fileno(const lsc_dev_lxsim *s);

/* The bus itself (lsc_device_lxbus, for tests). */
struct lsc_lxbus *lsc_dev_lxsim_bus(lsc_dev_lxsim *s);

#endif
