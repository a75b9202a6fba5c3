/* lsc-sim as a child process on its pseudo-terminal, for the tests that talk
 * to it in real time (host only; POSIX). Test code only (links to cmocka). */
#ifndef LSC_TEST_SIM_PTY_H
#define LSC_TEST_SIM_PTY_H

#include <stddef.h>
#include <sys/types.h>

/* Starts the lsc-sim at path with extra arguments (NULL-terminated, at most
 * 6 used) and reads the first line it prints, the path of its
 * pseudo-terminal, into tty (size bytes, NUL-terminated, no newline). *pid is
 * the child's as soon as fork returns, before the read, so that a teardown
 * can end it when an assertion leaves the test early. */
void sim_pty_start(const char *path, const char *const *extra, pid_t *pid, char *tty,
                   size_t size);

/* Sends SIGTERM to *pid and asserts that lsc-sim exits with status 0; *pid
 * is -1 once the child is reaped. */
void sim_pty_stop(pid_t *pid);

#endif
