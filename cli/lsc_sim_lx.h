/* lsc-sim --lx: a virtual bus of serial bus servos (lsc/lxbus.h) served on
 * lsc-sim's pseudo-terminal, and the --state file that keeps what the servos
 * keep at power-off across runs. Program code, not part of liblsc. */
#ifndef LSC_SIM_LX_H
#define LSC_SIM_LX_H

#include "lsc/lxbus.h"

/* Fills bus (initialised by the caller) with the servos of the --lx list
 * ids ("1-6", "1,3,5": 1..LSC_LXBUS_SERVOS distinct ids 0..253), or, when
 * state names a file that exists, with the servos it keeps (it must hold as
 * many as the list names; their ids may differ: a servo renamed keeps its new
 * id). A state file that does not exist yet is written at once. Returns -1 to
 * go on, or an exit status after printing why (2: invalid list or file; 1:
 * the file cannot be read or written). prog prefixes the messages. */
int lsc_sim_lx_setup(lsc_lxbus *bus, const char *prog, const char *ids, const char *state);

/* Serves bus on master in real time until a signal read from sig_fd that
 * stops it (SIGUSR2 power-cycles the bus instead). With state (not NULL),
 * what survives power-off is written to it atomically whenever it changes
 * and at the end. Returns the exit status (0, or 1 after printing why). */
int lsc_sim_lx_serve(lsc_lxbus *bus, const char *prog, int master, int sig_fd,
                     const char *state);

#endif
