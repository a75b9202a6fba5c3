/* Test-only interposer that lets libserialport 0.1.1 open pseudo-terminals.
 *
 * libserialport looks a port up under /sys/class/tty/<name> (lstat, through
 * glibc's __lxstat in Debian's build, then readlink) and reads the modem
 * lines with ioctl(TIOCMGET), which a pty refuses with ENOTTY. Linked into a
 * test program, these definitions take precedence over libc's for every
 * caller in the process (libserialport included), the same symbol
 * interposition LD_PRELOAD gives, but without LD_PRELOAD so it also works
 * under the sanitizers. They change nothing for other paths and other file
 * descriptors: they only answer what a pty cannot.
 *   - lstat of /sys/class/tty/pts/N: a symbolic link
 *   - readlink of it: ../../devices/virtual/tty/ptsN (a native, non-USB port)
 *   - ioctl TIOCMGET/TIOCMSET/TIOCMBIS/TIOCMBIC on a pty that refuses them:
 *     lines DTR|RTS|CTS|DSR, setting them succeeds
 * lsc_test_shim_hits counts the answers, so a test can prove the shim (and so
 * libserialport's own open path) was really used. */
#define _GNU_SOURCE 1
#include <dlfcn.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include "sp_pty_shim.h"

unsigned lsc_test_shim_hits;

static const char prefix[] = "/sys/class/tty/pts/";

/* Stores the next definition of name (libc's) in *fn (a function pointer of
 * size n): copied, as ISO C has no cast between object and function pointers. */
static void next_symbol(const char *name, void *fn, size_t n)
{
    void *sym = dlsym(RTLD_NEXT, name);
    memcpy(fn, &sym, n);
}

/* The pts number at the end of a /sys/class/tty/pts/N path, or -1. */
static int pts_number(const char *path)
{
    if (path == NULL || strncmp(path, prefix, sizeof prefix - 1u) != 0) {
        return -1;
    }
    const char *p = path + sizeof prefix - 1u;
    int n = 0;
    if (*p == '\0') {
        return -1;
    }
    for (; *p != '\0'; p++) {
        if (*p < '0' || *p > '9') {
            return -1;
        }
        n = n * 10 + (*p - '0');
    }
    return n;
}

int __lxstat(int ver, const char *path, struct stat *buf);
int __lxstat(int ver, const char *path, struct stat *buf)
{
    if (pts_number(path) >= 0) {
        memset(buf, 0, sizeof *buf);
        buf->st_mode = S_IFLNK | 0777;
        lsc_test_shim_hits++;
        return 0;
    }
    int (*real)(int, const char *, struct stat *) = NULL;
    next_symbol("__lxstat", &real, sizeof real);
    if (real == NULL) {
        return lstat(path, buf);
    }
    return real(ver, path, buf);
}

ssize_t readlink(const char *path, char *buf, size_t cap)
{
    int n = pts_number(path);
    if (n >= 0) {
        char target[64];
        int len = snprintf(target, sizeof target, "../../devices/virtual/tty/pts%d", n);
        size_t count = (size_t)len < cap ? (size_t)len : cap;
        memcpy(buf, target, count);
        lsc_test_shim_hits++;
        return (ssize_t)count;
    }
    ssize_t (*real)(const char *, char *, size_t) = NULL;
    next_symbol("readlink", &real, sizeof real);
    return real(path, buf, cap);
}

int ioctl(int fd, unsigned long request, ...)
{
    va_list ap;
    va_start(ap, request);
    void *arg = va_arg(ap, void *);
    va_end(ap);
    int (*real)(int, unsigned long, ...) = NULL;
    next_symbol("ioctl", &real, sizeof real);
    int r = real(fd, request, arg);
    bool modem = request == TIOCMGET || request == TIOCMSET || request == TIOCMBIS ||
                 request == TIOCMBIC;
    if (r != 0 && modem && (errno == ENOTTY || errno == EINVAL) && isatty(fd)) {
        if (request == TIOCMGET) {
            *(int *)arg = TIOCM_DTR | TIOCM_RTS | TIOCM_CTS | TIOCM_DSR;
        }
        lsc_test_shim_hits++;
        return 0;
    }
    return r;
}
