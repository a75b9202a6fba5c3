/* Serial transport: open/close, the termios backend and the poll()-based I/O
 * both backends share (contract in lsc/serial.h). Host only: compiles to
 * nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "serial_internal.h"

/* The calling thread's last lsc_serial_open: its errno and message, for
 * lsc_serial_os_errno(NULL) and lsc_serial_error_message(NULL). */
static __thread struct {
    int os_errno;
    char message[LSC_SERIAL_MESSAGE_MAX];
} last;

/* s in the closed state, error message empty. */
static void init(lsc_serial *s)
{
    s->fd = -1;
    s->sp = NULL;
    s->backend = LSC_SERIAL_AUTO;
    s->baud = 0;
    s->write_timeout_ms = 0;
    s->os_errno = 0;
    s->path[0] = '\0';
    s->message[0] = '\0';
}

static int speed_of(uint32_t baud, speed_t *out)
{
    static const struct {
        uint32_t baud;
        speed_t speed;
    } rates[] = {{1200, B1200},     {2400, B2400},     {4800, B4800},   {9600, B9600},
                 {19200, B19200},   {38400, B38400},   {57600, B57600}, {115200, B115200},
                 {230400, B230400}};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        if (rates[i].baud == baud) {
            *out = rates[i].speed;
            return 0;
        }
    }
    return LSC_EINVAL;
}

static int termios_open(lsc_serial *s)
{
    speed_t speed;
    if (speed_of(s->baud, &speed) != 0) {
        return lsc_serial_fail(s, LSC_EINVAL, 0, "unsupported baud rate (termios)");
    }
    lsc_port_error e;
    int fd;
    int r = lsc_port_open_locked(&e, NULL, s->path, &fd);
    if (r != 0) {
        return lsc_serial_keep(s, r, &e);
    }
    struct termios t;
    if (tcgetattr(fd, &t) != 0) {
        /* a file, /dev/null, /dev/random...: ENOTTY or EINVAL, none of them a port */
        r = lsc_serial_fail(s, LSC_ENODEV, errno, "not a serial port");
    }
    if (r == 0) {
        cfmakeraw(&t);
        t.c_cflag &= ~(tcflag_t)(CSIZE | PARENB | CSTOPB | CRTSCTS);
        t.c_cflag |= CS8 | CLOCAL | CREAD;
        t.c_iflag &= ~(tcflag_t)(IXON | IXOFF | IXANY);
        t.c_cc[VMIN] = 0;
        t.c_cc[VTIME] = 0;
        if (cfsetispeed(&t, speed) != 0 || cfsetospeed(&t, speed) != 0 ||
            tcsetattr(fd, TCSANOW, &t) != 0) {
            r = lsc_serial_fail(s, LSC_EIO, errno, "cannot configure 8N1");
        }
    }
    if (r != 0) {
        (void)close(fd);
        return r;
    }
    s->fd = fd;
    s->backend = LSC_SERIAL_TERMIOS;
    return 0;
}

/* Opens path into s (closed): 0, or an error recorded on s with nothing
 * left open. */
static int open_into(lsc_serial *s, const char *path, uint32_t baud, lsc_serial_backend b)
{
    lsc_port_error e;
    int r = lsc_port_set_path(&e, s->path, sizeof s->path, path, "serial port");
    if (r != 0) {
        return lsc_serial_keep(s, r, &e);
    }
    s->baud = baud == 0 ? LSC_SERIAL_BAUD_DEFAULT : baud;
    /* 1 s plus twice a whole frame's time on the wire */
    s->write_timeout_ms = 1000u + (uint32_t)(2u * LSC_FRAME_MAX * 10000u / s->baud);
    switch (b) {
    case LSC_SERIAL_TERMIOS:
        r = termios_open(s);
        break;
    case LSC_SERIAL_LIBSERIALPORT:
        r = lsc_serial_sp_open(s);
        break;
    case LSC_SERIAL_AUTO:
        r = lsc_serial_have_libserialport() ? lsc_serial_sp_open(s) : LSC_EINVAL;
        if (r != 0 && r != LSC_EBUSY) {
            r = termios_open(s); /* e.g. a pseudo-terminal libserialport refuses */
        }
        break;
    default:
        return lsc_serial_fail(s, LSC_EINVAL, 0, "unknown serial backend");
    }
    if (r == 0) {
        (void)tcflush(s->fd, TCIFLUSH);
        s->os_errno = 0;
        s->message[0] = '\0';
    }
    return r;
}

int lsc_serial_open(const char *path, uint32_t baud, lsc_serial_backend b, lsc_serial **out)
{
    last.os_errno = 0;
    last.message[0] = '\0';
    if (out == NULL) {
        (void)snprintf(last.message, sizeof last.message, "invalid argument: no place for the port");
        return LSC_EINVAL;
    }
    *out = NULL;
    lsc_serial *s = calloc(1, sizeof *s);
    if (s == NULL) {
        (void)snprintf(last.message, sizeof last.message, "out of memory");
        return LSC_ENOSPC;
    }
    init(s);
    int r = open_into(s, path, baud, b);
    if (r != 0) {
        last.os_errno = s->os_errno;
        memcpy(last.message, s->message, sizeof last.message);
        lsc_serial_close(s);
        return r;
    }
    *out = s;
    return 0;
}

int lsc_serial_fileno(const lsc_serial *s)
{
    return s == NULL ? -1 : s->fd;
}

void lsc_serial_close(lsc_serial *s)
{
    if (s == NULL) {
        return;
    }
    if (s->sp != NULL) {
        lsc_serial_sp_close(s);
    } else if (s->fd >= 0) {
        (void)close(s->fd); /* (the lock goes with the last descriptor: lsc_port_lock) */
    }
    free(s);
}

uint32_t lsc_serial_now_ms(void *ctx)
{
    (void)ctx;
    return lsc_port_now_ms();
}

static bool would_block(int err)
{
#if EAGAIN != EWOULDBLOCK
    if (err == EWOULDBLOCK) {
        return true;
    }
#endif
    return err == EAGAIN;
}

/* The error for errno err met on an open port. */
static int io_fail(lsc_serial *s, int err, const char *what)
{
    bool gone = err == EIO || err == ENXIO || err == ENODEV || err == EPIPE;
    return lsc_serial_fail(s, gone ? LSC_ENODEV : LSC_EIO, err, what);
}

/* poll() for events until deadline (ms, lsc_serial_now_ms); EINTR resumes
 * with the time left. Returns revents, 0 on timeout, or an error. */
static int wait_for(lsc_serial *s, short events, uint32_t timeout_ms)
{
    uint32_t start = lsc_serial_now_ms(NULL);
    for (;;) {
        uint32_t elapsed = lsc_serial_now_ms(NULL) - start;
        uint32_t left = elapsed >= timeout_ms ? 0 : timeout_ms - elapsed;
        struct pollfd p = {s->fd, events, 0};
        int r = poll(&p, 1, left > 0x7FFFFFFFu ? 0x7FFFFFFF : (int)left);
        if (r > 0) {
            if (p.revents & POLLNVAL) {
                return lsc_serial_fail(s, LSC_EIO, EBADF, "poll");
            }
            return p.revents;
        }
        if (r == 0) {
            return 0;
        }
        if (errno != EINTR) {
            return io_fail(s, errno, "poll");
        }
    }
}

int lsc_serial_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_serial *s = ctx;
    if (s == NULL || buf == NULL || cap == 0 || s->fd < 0) {
        return LSC_EINVAL;
    }
    if (cap > 0x7FFFFFFFu) {
        cap = 0x7FFFFFFFu;
    }
    uint32_t start = lsc_serial_now_ms(NULL);
    for (;;) {
        uint32_t elapsed = lsc_serial_now_ms(NULL) - start;
        int ev = wait_for(s, POLLIN, elapsed >= timeout_ms ? 0 : timeout_ms - elapsed);
        if (ev <= 0) {
            return ev;
        }
        ssize_t n = read(s->fd, buf, cap);
        if (n > 0) {
            return (int)n;
        }
        if (n == 0) {
            return lsc_serial_fail(s, LSC_ENODEV, 0, "end of file");
        }
        if (would_block(errno) || errno == EINTR) {
            if (ev & (POLLHUP | POLLERR)) {
                return lsc_serial_fail(s, LSC_ENODEV, 0, "hang-up");
            }
            if (elapsed >= timeout_ms) {
                return 0;
            }
            continue; /* woken without data: wait for the time left */
        }
        return io_fail(s, errno, "read");
    }
}

static void sleep_ms(uint32_t ms)
{
    struct timespec t = {(time_t)(ms / 1000u), (long)(ms % 1000u) * 1000000L};
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

/* A write of n bytes gave up after done were taken. What the kernel still
 * holds is flushed: it would otherwise go out whenever the line moves again,
 * in the middle of whatever is sent next. When part of a frame may have
 * reached the line, the port then stays silent for LSC_SERIAL_TORN_QUIET_MS
 * plus the time a 16-byte UART FIFO takes to empty, so that the controller
 * drops the torn frame on its frame gap before anything else is sent (by
 * this process or the next: the flock is held until the return). */
static int torn(lsc_serial *s, size_t done, size_t n)
{
    int held = 0;
#ifdef TIOCOUTQ
    if (ioctl(s->fd, TIOCOUTQ, &held) != 0 || held < 0) {
        held = 0;
    }
#endif
    (void)tcflush(s->fd, TCOFLUSH);
    size_t queued = (size_t)held;
    size_t went = done > queued ? done - queued : 0u;
    char earlier[80] = "";
    if (queued > done) {
        (void)snprintf(earlier, sizeof earlier, "; so were the last %zu bytes of earlier writes",
                       queued - done);
    }
    char what[192];
    (void)snprintf(what, sizeof what,
                   "write timed out: the line does not drain (%zu of %zu bytes went out, the "
                   "rest was discarded%s)",
                   went, n, earlier);
    if (done > 0 || queued > 0) {
        sleep_ms(LSC_SERIAL_TORN_QUIET_MS + (uint32_t)(16u * 10000u / s->baud));
    }
    return lsc_serial_fail(s, LSC_EIO, 0, what);
}

int lsc_serial_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_serial *s = ctx;
    if (s == NULL || (data == NULL && n > 0) || s->fd < 0 || n > 0x7FFFFFFFu) {
        return LSC_EINVAL;
    }
    uint32_t start = lsc_serial_now_ms(NULL);
    uint32_t limit = s->write_timeout_ms + (uint32_t)(n * 10000u / s->baud);
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(s->fd, data + done, n - done);
        if (w > 0) {
            done += (size_t)w;
            continue;
        }
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w < 0 && !would_block(errno)) {
            return io_fail(s, errno, "write");
        }
        uint32_t elapsed = lsc_serial_now_ms(NULL) - start;
        if (elapsed >= limit) {
            return torn(s, done, n);
        }
        int ev = wait_for(s, POLLOUT, limit - elapsed);
        if (ev < 0) {
            return ev;
        }
        if ((ev & (POLLHUP | POLLERR)) && !(ev & POLLOUT)) {
            return lsc_serial_fail(s, LSC_ENODEV, 0, "hang-up while writing");
        }
    }
    return (int)n;
}

void lsc_serial_get_io(lsc_serial *s, lsc_io *io)
{
    if (io == NULL) {
        return;
    }
    io->ctx = s;
    io->write = lsc_serial_write;
    io->read = lsc_serial_read;
    io->now_ms = lsc_serial_now_ms;
}

const char *lsc_serial_error_message(const lsc_serial *s)
{
    return s == NULL ? last.message : s->message;
}

int lsc_serial_os_errno(const lsc_serial *s)
{
    return s == NULL ? last.os_errno : s->os_errno;
}

lsc_serial_backend lsc_serial_backend_in_use(const lsc_serial *s)
{
    return s == NULL ? LSC_SERIAL_AUTO : s->backend;
}

#endif
