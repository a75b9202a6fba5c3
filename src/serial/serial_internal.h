/* Shared between the serial transport's sources (not part of the API). */
#ifndef LSC_SERIAL_INTERNAL_H
#define LSC_SERIAL_INTERNAL_H

#include "lsc/serial.h"

/* Records an error on s: errno value err (0: none), message from fmt and the
 * path; returns code. For OS errors the message ends with strerror(err). */
int lsc_serial_fail(lsc_serial *s, int code, int err, const char *what);

/* The LSC_E... code for an errno value met while opening. */
int lsc_serial_open_code(int err);

/* Locks fd for this process alone (flock + TIOCEXCL) and makes it non-blocking.
 * Returns 0 or an error recorded on s. */
int lsc_serial_claim(lsc_serial *s, int fd);

/* Undoes a successful lsc_serial_claim's TIOCEXCL before fd is closed: the
 * flag belongs to the tty, not to fd, so while another descriptor keeps the
 * tty open (a simulator's pty, a getty) it would outlive the close and make
 * every later non-root open fail with EBUSY. (flock ends with the close.) */
void lsc_serial_unclaim(int fd);

/* libserialport backend: opens and configures s->path at s->baud, sets s->fd
 * and s->sp. Returns 0 or an error recorded on s (nothing left open). Without
 * libserialport: LSC_EINVAL. */
int lsc_serial_sp_open(lsc_serial *s);
void lsc_serial_sp_close(lsc_serial *s);

#endif
