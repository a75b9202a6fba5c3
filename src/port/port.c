/* Claiming a device node and recording its errors, for every host transport
 * (contract in port_internal.h). Host only: compiles to nothing elsewhere (the
 * Arduino IDE builds every .c under src/). */
#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "port_internal.h"

int lsc_port_fail(lsc_port_error *e, int code, int err, const char *path, const char *what)
{
    e->os_errno = err;
    const char *hint = "";
    if (code == LSC_EACCES) {
        hint = " (add your user to the dialout group: sudo usermod -aG dialout $USER, then "
               "log in again; or give the device a udev rule with MODE=\"0660\" GROUP=\"dialout\")";
    } else if (code == LSC_EBUSY) {
        hint = " (port busy: another program has it open; close that program first)";
    } else if (code == LSC_ENODEV && e->open) {
        hint = " (the device went away: unplugged or closed)";
    }
    if (err != 0) {
        (void)snprintf(e->message, sizeof e->message, "%s: %s: %s%s", path, what, strerror(err),
                       hint);
    } else {
        (void)snprintf(e->message, sizeof e->message, "%s: %s%s", path, what, hint);
    }
    return code;
}

int lsc_port_open_code(int err)
{
    switch (err) {
    case EACCES:
    case EPERM:
        return LSC_EACCES;
    case EBUSY:
    case EWOULDBLOCK:
        return LSC_EBUSY;
    case ENOENT:
    case ENXIO:
    case ENODEV:
    case ENOTTY:
        return LSC_ENODEV;
    default:
        return LSC_EIO;
    }
}

int lsc_port_lock(lsc_port_error *e, int fd, const char *path)
{
    /* flock stops every other opener, root included; TIOCEXCL makes a
     * non-root open() itself fail with EBUSY. */
    int r;
    do {
        r = flock(fd, LOCK_EX | LOCK_NB);
    } while (r != 0 && errno == EINTR);
    if (r != 0) {
        return lsc_port_fail(e, lsc_port_open_code(errno), errno, path, "cannot lock");
    }
    /* a hidraw node is no tty: the flock alone (the HID transport) */
    if (isatty(fd) && ioctl(fd, TIOCEXCL) != 0) {
        int err = errno;
        return lsc_port_fail(e, err == ENOTTY ? LSC_ENODEV : LSC_EIO, err, path,
                             "not usable as a serial port (TIOCEXCL)");
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        int err = errno;
        lsc_port_unlock(fd);
        return lsc_port_fail(e, LSC_EIO, err, path, "fcntl");
    }
    return 0;
}

void lsc_port_unlock(int fd)
{
    (void)ioctl(fd, TIOCNXCL);
}

#else
typedef int lsc_port_empty_unit; /* ISO C forbids an empty translation unit */
#endif
