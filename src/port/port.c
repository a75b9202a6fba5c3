/* Claiming a device node and recording its errors, for every host transport
 * (contract in port_internal.h). Host only: compiles to nothing elsewhere (the
 * Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "port_internal.h"

/* The serial ports' hints (lsc_port_fail_hinted's defaults). */
static const lsc_port_hints serial_hints = {
    " (add your user to the dialout group: sudo usermod -aG dialout $USER, then log in again; "
    "or give the device a udev rule with MODE=\"0660\" GROUP=\"dialout\")",
    " (port busy: another program has it open; close that program first)",
    " (the device went away: unplugged or closed)",
};

int lsc_port_fail_hinted(lsc_port_error *e, const lsc_port_hints *hints, int code, int err,
                         const char *path, const char *what)
{
    const lsc_port_hints *h = hints != NULL ? hints : &serial_hints;
    e->os_errno = err;
    const char *hint = "";
    if (code == LSC_EACCES) {
        hint = h->access;
    } else if (code == LSC_EBUSY) {
        hint = h->busy;
    } else if (code == LSC_ENODEV && e->open) {
        hint = h->gone;
    }
    if (err != 0) {
        (void)snprintf(e->message, sizeof e->message, "%s: %s: %s%s", path, what, strerror(err),
                       hint);
    } else {
        (void)snprintf(e->message, sizeof e->message, "%s: %s%s", path, what, hint);
    }
    return code;
}

int lsc_port_fail(lsc_port_error *e, int code, int err, const char *path, const char *what)
{
    return lsc_port_fail_hinted(e, NULL, code, err, path, what);
}

int lsc_port_set_path(lsc_port_error *e, char *dst, size_t cap, const char *path,
                      const char *kind)
{
    if (path == NULL || path[0] == '\0' || strlen(path) >= cap) {
        e->open = false;
        return lsc_port_fail(e, LSC_EINVAL, 0, kind, "invalid device path (empty or too long)");
    }
    memcpy(dst, path, strlen(path) + 1u);
    return 0;
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

/* True if the tty behind fd is marked exclusive (TIOCEXCL) by someone. */
static bool marked_exclusive(int fd)
{
#ifdef TIOCGEXCL
    int excl = 0;
    return ioctl(fd, TIOCGEXCL, &excl) == 0 && excl != 0;
#else
    (void)fd; /* no way to ask: a non-root open() of such a tty fails anyway */
    return false;
#endif
}

/* The busy hint when this process holds the lock itself. */
static const char held_here_hint[] =
    " (port busy: this program has it open already, through an earlier open that is not "
    "closed: use that one, or close it first)";

/* True if descriptor n of this process holds a flock (Linux: the "lock:"
 * lines of /proc/self/fdinfo/N name the locks its open file holds). */
static bool holds_flock(int n)
{
    char name[64], text[2048];
    (void)snprintf(name, sizeof name, "/proc/self/fdinfo/%d", n);
    int f = open(name, O_RDONLY | O_CLOEXEC);
    if (f < 0) {
        return false;
    }
    ssize_t got = read(f, text, sizeof text - 1u);
    (void)close(f);
    if (got <= 0) {
        return false;
    }
    text[got] = '\0';
    return strstr(text, "FLOCK") != NULL;
}

/* True if another descriptor of this process, on the same file as fd, holds
 * its flock: the port is busy because this program opened it before (and
 * did not close it), not because another program has it. Where /proc tells
 * nothing (not Linux), false. No state is kept: the descriptors are looked
 * at when a lock is refused. */
static bool locked_here(int fd)
{
    struct stat mine;
    if (fstat(fd, &mine) != 0) {
        return false;
    }
    DIR *dir = opendir("/proc/self/fd");
    if (dir == NULL) {
        return false;
    }
    bool found = false;
    const struct dirent *ent;
    while (!found && (ent = readdir(dir)) != NULL) {
        char *end = NULL;
        long n = strtol(ent->d_name, &end, 10);
        struct stat st;
        if (end == ent->d_name || *end != '\0' || n < 0 || n > INT_MAX || n == fd ||
            n == dirfd(dir)) {
            continue;
        }
        found = fstat((int)n, &st) == 0 && st.st_dev == mine.st_dev &&
                st.st_ino == mine.st_ino && holds_flock((int)n);
    }
    (void)closedir(dir);
    return found;
}

int lsc_port_lock(lsc_port_error *e, const lsc_port_hints *hints, int fd, const char *path)
{
    int r;
    do {
        r = flock(fd, LOCK_EX | LOCK_NB);
    } while (r != 0 && errno == EINTR);
    if (r != 0) {
        int err = errno;
        int code = lsc_port_open_code(err);
        if (code == LSC_EBUSY && locked_here(fd)) {
            lsc_port_hints here = hints != NULL ? *hints : serial_hints;
            here.busy = held_here_hint;
            return lsc_port_fail_hinted(e, &here, code, err, path, "cannot lock");
        }
        return lsc_port_fail_hinted(e, hints, code, err, path, "cannot lock");
    }
    if (marked_exclusive(fd)) {
        return lsc_port_fail_hinted(e, hints, LSC_EBUSY, 0, path,
                                    "marked exclusive (TIOCEXCL) by another program, or left so "
                                    "by one that was killed (unplugging the adapter clears it)");
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        return lsc_port_fail(e, LSC_EIO, errno, path, "fcntl");
    }
    return 0;
}

int lsc_port_open_locked(lsc_port_error *e, const lsc_port_hints *hints, const char *path,
                         int *fd)
{
    int f;
    e->open = false;
    do {
        f = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    } while (f < 0 && errno == EINTR);
    if (f < 0 && errno == EISDIR) {
        /* "Is a directory" alone does not tell a newcomer what went wrong */
        int r = lsc_port_fail(e, LSC_ENODEV, 0, path, "a directory, not a device");
        e->os_errno = EISDIR;
        return r;
    }
    if (f < 0) {
        return lsc_port_fail_hinted(e, hints, lsc_port_open_code(errno), errno, path,
                                    "cannot open");
    }
    int r = lsc_port_lock(e, hints, f, path);
    if (r != 0) {
        (void)close(f);
        return r;
    }
    *fd = f;
    return 0;
}

uint32_t lsc_port_now_ms(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

#endif
