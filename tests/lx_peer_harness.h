/* The stand-in bus of tests/lxbus/lxbus_peer.py as a child process, for the
 * tests that talk to a bus they did not write (host only; POSIX). Test code
 * only (links to cmocka). Waits scale with LSC_TEST_TIME_SCALE (test_time.h).
 */
#ifndef LSC_TEST_LX_PEER_HARNESS_H
#define LSC_TEST_LX_PEER_HARNESS_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

typedef struct lx_peer {
    pid_t pid;
    int in; /* its stdin: closing it ends it (--watch-stdin) */
    bool echo;
    char dir[64], link[96], ctl[96];
} lx_peer;

/* Milliseconds on the monotonic clock. */
long lx_peer_now_ms(void);

/* Starts `python script` with servos ids ("1-3", "1,77") in a fresh
 * temporary directory, echoing what it is sent if echo, and waits for its
 * "ready" line: then p->link is its pseudo-terminal and p->ctl its control
 * socket. */
void lx_peer_start(lx_peer *p, const char *python, const char *script, const char *ids, bool echo);

/* Closes its stdin, asserts it exits with status 0, removes its directory. */
void lx_peer_stop(lx_peer *p);

/* One control command; asserts its answer starts with "ok"; the answer in
 * out[cap] (out may be NULL). */
void lx_peer_control_reply(const lx_peer *p, const char *cmd, char *out, size_t cap);

/* lx_peer_control_reply without the answer. */
void lx_peer_control(const lx_peer *p, const char *cmd);

#endif
