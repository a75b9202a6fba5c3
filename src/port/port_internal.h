/* What every host transport (serial, and the USB HID one) needs for the
 * device node it opens: claiming it for this process alone, and recording an
 * error that keeps the OS's errno and a message naming the path. Internal:
 * host only, not exported, not installed. Nothing here knows lsc_serial; a
 * transport keeps an lsc_port_error and copies it into its own fields.
 *
 * Errors are the LSC_E... codes of lsc/core.h. */
#ifndef LSC_PORT_INTERNAL_H
#define LSC_PORT_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "lsc/core.h"

/* Room for a message: a path of up to 255 bytes, what failed, strerror and a hint. */
#define LSC_PORT_MESSAGE_MAX 512u

/* A transport's last error. */
typedef struct lsc_port_error {
    int os_errno;                       /* the OS's errno, 0 if the error was not the OS's */
    bool open;                          /* set by the transport: the device is open, so an
                                           LSC_ENODEV means it went away */
    char message[LSC_PORT_MESSAGE_MAX]; /* "PATH: WHAT[: strerror(err)][ (hint)]" */
} lsc_port_error;

/* Records an error on e and returns code: os_errno = err (0: not an OS
 * error), message "PATH: WHAT: strerror(err)" (without the strerror part when
 * err is 0), followed by a hint for LSC_EACCES (how to get access: the
 * dialout group, a udev rule), LSC_EBUSY (another program has the port) and,
 * when e->open, LSC_ENODEV (the device went away). Truncated to fit. */
int lsc_port_fail(lsc_port_error *e, int code, int err, const char *path, const char *what);

/* The LSC_E... code for an errno met while opening or claiming a device:
 * EACCES/EPERM -> LSC_EACCES, EBUSY/EWOULDBLOCK -> LSC_EBUSY,
 * ENOENT/ENXIO/ENODEV/ENOTTY -> LSC_ENODEV, anything else -> LSC_EIO. */
int lsc_port_open_code(int err);

/* Claims the open descriptor fd of path for this process alone and makes it
 * non-blocking: flock(LOCK_EX | LOCK_NB) (another holder, root included, gives
 * LSC_EBUSY "port busy"; the kernel drops the lock when the last descriptor
 * closes, however the process ends) and, on a tty, TIOCEXCL (not a tty, e.g. a
 * hidraw node: the flock alone). Returns 0, or an
 * error recorded on e (fd is left open: the caller closes it, after
 * lsc_port_unlock). */
int lsc_port_lock(lsc_port_error *e, int fd, const char *path);

/* Undoes what a successful lsc_port_lock set on the tty before fd is closed
 * (the flock ends with the close by itself). */
void lsc_port_unlock(int fd);

#endif
