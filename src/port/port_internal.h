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
#include <stdint.h>

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

/* A transport's own hints for lsc_port_fail_hinted, each starting " (". */
typedef struct lsc_port_hints {
    const char *access; /* LSC_EACCES */
    const char *busy;   /* LSC_EBUSY */
    const char *gone;   /* LSC_ENODEV while e->open */
} lsc_port_hints;

/* lsc_port_fail with hints (NULL: the serial ports') in place of the serial
 * ports' ones: the dialout group would not help with a hidraw node. */
int lsc_port_fail_hinted(lsc_port_error *e, const lsc_port_hints *hints, int code, int err,
                         const char *path, const char *what);

/* Copies path into dst (cap bytes) for a transport that opens it. An empty,
 * NULL or too long path is LSC_EINVAL, recorded on e with kind (what the
 * transport opens: "serial port", "hid") in the place of the path. */
int lsc_port_set_path(lsc_port_error *e, char *dst, size_t cap, const char *path,
                      const char *kind);

/* The LSC_E... code for an errno met while opening or claiming a device:
 * EACCES/EPERM -> LSC_EACCES, EBUSY/EWOULDBLOCK -> LSC_EBUSY,
 * ENOENT/ENXIO/ENODEV/ENOTTY -> LSC_ENODEV, anything else -> LSC_EIO. */
int lsc_port_open_code(int err);

/* Claims the open descriptor fd of path for this process alone and makes it
 * non-blocking. Returns 0, or an error recorded on e with hints (NULL: the
 * serial ports'); fd is left open: the caller closes it.
 *  - flock(LOCK_EX | LOCK_NB): another holder, root included, gives LSC_EBUSY
 *    ("port busy"). When the holder is this process itself (another of its
 *    descriptors on the same file holds the lock: an earlier open not closed
 *    yet; Linux, through /proc/self/fd and fdinfo), the hint says so in place
 *    of hints' busy ("this program has it open already"). The kernel drops the lock when the last descriptor of
 *    this open file closes, however the process ends (SIGKILL too). Nothing
 *    ever gives it up with LOCK_UN: a process that inherited the descriptor
 *    (fork) and closes its copy would take the lock from the opener, which
 *    still uses the port. On failure the lock goes when the caller closes fd.
 *  - On a tty (Linux, TIOCGEXCL): a tty another program marked exclusive
 *    (TIOCEXCL) is LSC_EBUSY too, also for root, whose open() TIOCEXCL does
 *    not stop. This never sets TIOCEXCL: the flag belongs to the tty, not to
 *    the descriptor, so a holder killed before it could clear it (SIGKILL
 *    cannot be caught) would leave every later non-root open failing with
 *    EBUSY for as long as anything else keeps the tty open (a pty's other
 *    side, a getty). Not a tty (a hidraw node): the flock alone. */
int lsc_port_lock(lsc_port_error *e, const lsc_port_hints *hints, int fd, const char *path);

/* Opens path read-write, non-blocking, close-on-exec, not as a controlling
 * terminal, and claims it (lsc_port_lock). Returns 0 and *fd, or an error
 * recorded on e with hints (NULL: the serial ports'), nothing left open and
 * e->open false: a directory is LSC_ENODEV ("a directory, not a device",
 * os_errno EISDIR), other open() errors as lsc_port_open_code says. */
int lsc_port_open_locked(lsc_port_error *e, const lsc_port_hints *hints, const char *path,
                         int *fd);

/* Milliseconds of CLOCK_MONOTONIC, wrapping at 2^32: every host transport's
 * lsc_io clock. */
uint32_t lsc_port_now_ms(void);

#endif
