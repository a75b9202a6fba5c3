/* Signals as bytes on a pipe, for a program that waits in poll (lsc-sim,
 * lscd): the handler only writes the signal's number, so the program sees a
 * signal as its read end becoming readable. Program code, not part of liblsc;
 * one pipe a process. */
#ifndef LSC_SIGNAL_PIPE_H
#define LSC_SIGNAL_PIPE_H

#include <stddef.h>

/* Makes the pipe (both ends close-on-exec and non-blocking), handles each of
 * sigs[0..n) by writing its number as one byte to the pipe (none when the
 * pipe is full: signals are pending already), and ignores SIGPIPE. Returns
 * the read end, or -1 with errno set when the pipe could not be made or a
 * signal could not be handled. Call it once. */
int signal_pipe_open(const int *sigs, size_t n);

#endif
