/* lscctl: what record, play and convert share (lscctl_record.c,
 * lscctl_play.c, lscctl_convert.c; lscctl_teach.c): an action file read for
 * them, and the signal that asked to end. */
#ifndef LSCCTL_TEACH_H
#define LSCCTL_TEACH_H

#include <signal.h>

#include "lsc/files.h"
#include "lscctl.h"

/* The signal that asked to end (0: none). */
extern volatile sig_atomic_t lscctl_interrupted;

/* sig sets lscctl_interrupted instead of ending the program. */
void lscctl_catch_signal(int sig);

/* Reads path (its group --group, else its only one); prints why and returns
 * exit 2 if it cannot be played. */
int lscctl_load_action(const lscctl_opts *o, const char *path, lsc_action *a);

#endif
