/* The client transport to lscd (contract in lsc/lscd.h; the protocol in
 * docs/lscd-protocol.md). Host only: compiles to nothing elsewhere (the
 * Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "../util/escape.h"
#include "../util/sized.h"
#include "lscd_proto.h"

#ifndef MSG_NOSIGNAL
#define MSG_NOSIGNAL 0 /* (macOS: SO_NOSIGPIPE is set on the socket instead) */
#endif

/* Frames from the daemon waiting to be read (whole frames; what does not fit
 * is dropped and counted). */
#define RING_CAP 8192u
#define RECV_CHUNK 4096u
#define MESSAGE_MAX 512u
#define DEFAULT_TIMEOUT 1000u

struct lsc_lscd {
    /* (ordered by alignment: no padding) */
    size_t ring_head, ring_len;
    /* verdicts: frames written, verdicts received; those after wait_from
     * belong to the write that waits */
    uint64_t frames_sent, verdicts, wait_from;
    lsc_lscd_status_fn status_fn; /* a status request under way */
    void *status_user;
    lsc_parser rx; /* what the daemon sends */
    lsc_parser tx; /* what is written, counted as the daemon will */
    int fd;
    int open_error; /* the open's error: every call returns it (0: open) */
    uint32_t timeout_ms;
    uint32_t dropped_daemon, dropped_local;
    int verdict_error; /* the first error among the waiting write's verdicts */
    uint32_t lease_events;
    uint32_t lease_ms;
    uint32_t halts;  /* HALTED events */
    int halt_rc;     /* ... the last one's result */
    uint32_t pong;
    uint32_t next_token;
    int status_items;
    bool eof;          /* the daemon closed the connection */
    bool hello;        /* its greeting came */
    bool present;      /* it has its controller */
    bool gone_pending; /* the controller went: the next read says so */
    uint8_t verdict_cmd;
    uint8_t lease_state;
    bool pong_seen;
    bool status_end;
    char path[LSC_LSCD_PATH_MAX];
    char gone_why[4u * LSCD_ARGS_MAX + 1u]; /* escaped */
    char halt_why[4u * LSCD_ARGS_MAX + 1u]; /* the last HALTED's text, escaped */
    char verdict_why[4u * LSCD_ARGS_MAX + 1u]; /* verdict_error's text, escaped ("": none) */
    uint8_t rxbuf[LSC_FRAME_MAX];
    uint8_t txbuf[LSC_FRAME_MAX];
    char message[MESSAGE_MAX];
    uint8_t ring[RING_CAP]; /* frames from the daemon waiting to be read */
};

static uint32_t mono_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0;
    }
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int fail(lsc_lscd *s, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(s->message, sizeof s->message, fmt, ap);
    va_end(ap);
    return code;
}

/* The connection is over: every call from now on says so. */
static int closed(lsc_lscd *s)
{
    s->eof = true;
    return fail(s, LSC_ENODEV, "lscd at %s closed the connection (stopped or restarted): open it again",
                s->path);
}

static int known_error(int v)
{
    return (v < 0 && v >= LSC_EACCES) ? v : LSC_EIO;
}

/* ---- What the daemon sends ------------------------------------------------------- */

static void ring_put(lsc_lscd *s, const uint8_t *p, size_t n)
{
    if (n > RING_CAP - s->ring_len) {
        s->dropped_local++;
        return;
    }
    for (size_t i = 0; i < n; i++) {
        s->ring[(s->ring_head + s->ring_len + i) % RING_CAP] = p[i];
    }
    s->ring_len += n;
}

static size_t ring_get(lsc_lscd *s, uint8_t *buf, size_t cap)
{
    size_t n = s->ring_len < cap ? s->ring_len : cap;
    for (size_t i = 0; i < n; i++) {
        buf[i] = s->ring[(s->ring_head + i) % RING_CAP];
    }
    s->ring_head = (s->ring_head + n) % RING_CAP;
    s->ring_len -= n;
    return n;
}

/* Copies a control frame's text argument (from `at`) into out (NUL-terminated). */
static void take_text(const lsc_frame *f, size_t at, char *out, size_t cap)
{
    size_t n = f->nparams > at ? (size_t)f->nparams - at : 0u;
    if (n > cap - 1u) {
        n = cap - 1u;
    }
    if (n > 0u) {
        memcpy(out, f->params + at, n);
    }
    out[n] = '\0';
}

/* The same, escaped for a message (lsc_escape_text): a peer's words. */
static void take_shown(const lsc_frame *f, size_t at, char *out, size_t cap)
{
    char raw[LSCD_ARGS_MAX + 1u];
    take_text(f, at, raw, sizeof raw);
    (void)lsc_escape_text(out, cap, raw, strlen(raw));
}

static void on_status(lsc_lscd *s, const lsc_frame *f)
{
    char item[LSCD_ARGS_MAX + 1u];
    take_text(f, 1, item, sizeof item);
    char *eq = strchr(item, '=');
    const char *value = "";
    if (eq != NULL) {
        *eq = '\0';
        value = eq + 1;
    }
    s->status_items++;
    if (s->status_fn != NULL) {
        s->status_fn(s->status_user, item, value);
    }
}

static void on_control(lsc_lscd *s, const lsc_frame *f)
{
    const uint8_t *a = f->params + 1;
    size_t n = f->nparams > 0u ? (size_t)f->nparams - 1u : 0u;
    if (f->nparams == 0u) {
        return;
    }
    switch (f->params[0]) {
    case LSC_LSCD_EV_HELLO:
        if (n >= 2u) {
            s->hello = true;
            if (a[0] != LSC_LSCD_PROTOCOL) {
                s->open_error = fail(s, LSC_EREPLY,
                                     "lscd at %s speaks protocol %u, this library %u: "
                                     "update one of them",
                                     s->path, (unsigned)a[0], (unsigned)LSC_LSCD_PROTOCOL);
            }
            s->present = a[1] != 0u;
        }
        break;
    case LSC_LSCD_EV_VERDICT:
        if (n >= 2u) {
            s->verdicts++;
            int v = (int)(int8_t)a[1];
            if (s->verdicts > s->wait_from && v != 0 && s->verdict_error == 0) {
                s->verdict_error = known_error(v);
                s->verdict_cmd = a[0];
                take_shown(f, 3, s->verdict_why, sizeof s->verdict_why); /* (none: "") */
            }
        }
        break;
    case LSC_LSCD_EV_LEASE:
        if (n >= 5u) {
            s->lease_state = a[0];
            if (a[0] == LSC_LSCD_LEASE_GRANTED) {
                s->lease_ms = lsc_lscd_get_u32(a + 1);
            }
            s->lease_events++;
        }
        break;
    case LSC_LSCD_EV_CONTROLLER:
        if (n >= 1u) {
            s->present = a[0] != 0u;
            s->gone_pending = !s->present;
            if (!s->present) {
                take_shown(f, 2, s->gone_why, sizeof s->gone_why);
            }
        }
        break;
    case LSC_LSCD_EV_DROPPED:
        if (n >= 4u) {
            s->dropped_daemon = lsc_lscd_get_u32(a);
        }
        break;
    case LSC_LSCD_EV_STATUS:
        on_status(s, f);
        break;
    case LSC_LSCD_EV_HALTED:
        if (n >= 1u) {
            s->halt_rc = (int)(int8_t)a[0];
            take_shown(f, 2, s->halt_why, sizeof s->halt_why);
            s->halts++;
        }
        break;
    case LSC_LSCD_EV_STATUS_END:
        s->status_end = true;
        break;
    case LSC_LSCD_EV_PONG:
        if (n >= 4u) {
            s->pong = lsc_lscd_get_u32(a);
            s->pong_seen = true;
        }
        break;
    case LSC_LSCD_EV_ERROR:
        if (!s->hello && n >= 1u && a[0] == 0u) {
            /* instead of HELLO: lscd refused the connection (it is full) */
            char why[4u * LSCD_ARGS_MAX + 1u];
            take_shown(f, 2, why, sizeof why);
            s->open_error = fail(s, LSC_EBUSY, "lscd at %s refused the connection: %s", s->path,
                                 why);
        }
        break;
    default: /* anything newer: nothing to do */
        break;
    }
}

/* Parses bytes from the daemon: control frames act, others wait in the ring. */
static void take(lsc_lscd *s, const uint8_t *data, size_t n)
{
    while (n > 0u) {
        lsc_frame f;
        int r = 0;
        size_t used = lsc_parser_feed_buf(&s->rx, data, n, &f, &r);
        data += used;
        n -= used;
        if (r != 1) {
            continue;
        }
        if (f.cmd == LSC_LSCD_CMD) {
            on_control(s, &f);
        } else {
            uint8_t frame[LSC_FRAME_MAX];
            int len = lsc_encode_frame(frame, sizeof frame, f.cmd, f.params, f.nparams);
            if (len > 0) {
                ring_put(s, frame, (size_t)len);
            }
        }
    }
}

/* Waits up to timeout_ms for bytes from the daemon and takes what came.
 * Returns 0, or LSC_ENODEV (the connection closed), or LSC_EIO. */
static int pump(lsc_lscd *s, uint32_t timeout_ms)
{
    uint8_t buf[RECV_CHUNK];
    struct pollfd p = {s->fd, POLLIN, 0};
    int t = timeout_ms > (uint32_t)INT_MAX ? INT_MAX : (int)timeout_ms;
    if (s->eof) {
        return LSC_ENODEV;
    }
    int r = poll(&p, 1, t);
    if (r < 0) {
        return errno == EINTR ? 0 : fail(s, LSC_EIO, "lscd at %s: poll: %s", s->path, strerror(errno));
    }
    if (r == 0) {
        return 0;
    }
    for (;;) {
        ssize_t got = recv(s->fd, buf, sizeof buf, MSG_DONTWAIT);
        if (got > 0) {
            take(s, buf, (size_t)got);
            if ((size_t)got < sizeof buf) {
                return 0;
            }
            continue;
        }
        if (got == 0 || errno == ECONNRESET || errno == EPIPE) {
            return closed(s);
        }
        if (lscd_would_block(errno)) {
            return 0;
        }
        return fail(s, LSC_EIO, "lscd at %s: %s", s->path, strerror(errno));
    }
}

/* Time left until deadline (now_ms wraps: differences are taken mod 2^32). */
static uint32_t left_until(uint32_t start, uint32_t total)
{
    uint32_t spent = mono_ms() - start;
    return spent >= total ? 0u : total - spent;
}

static uint32_t add_sat(uint32_t a, uint32_t b)
{
    return a > UINT32_MAX - b ? UINT32_MAX : a + b;
}

/* Sends all n bytes within timeout_ms. */
static int send_all(lsc_lscd *s, const uint8_t *data, size_t n, uint32_t timeout_ms)
{
    uint32_t start = mono_ms();
    while (n > 0u) {
        ssize_t w = send(s->fd, data, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w > 0) {
            data += w;
            n -= (size_t)w;
            continue;
        }
        if (w < 0 && (errno == EPIPE || errno == ECONNRESET)) {
            return closed(s);
        }
        if (w < 0 && !lscd_would_block(errno)) {
            return fail(s, LSC_EIO, "lscd at %s: send: %s", s->path, strerror(errno));
        }
        /* the daemon is not reading (it holds back a client with a full queue):
         * wait for room, taking what it sends meanwhile */
        uint32_t left = left_until(start, timeout_ms);
        if (left == 0u) {
            return fail(s, LSC_EIO, "lscd at %s did not take a frame within %u ms", s->path,
                        (unsigned)timeout_ms);
        }
        struct pollfd p = {s->fd, POLLOUT | POLLIN, 0};
        int t = left > (uint32_t)INT_MAX ? INT_MAX : (int)left;
        if (poll(&p, 1, t) > 0 && (p.revents & POLLIN) != 0) {
            int r = pump(s, 0);
            if (r < 0) {
                return r;
            }
        }
    }
    return 0;
}

static int send_ctl(lsc_lscd *s, uint8_t op, const uint8_t *args, size_t n)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_lscd_encode_ctl(frame, sizeof frame, op, args, n);
    if (len < 0) {
        return len;
    }
    return send_all(s, frame, (size_t)len, add_sat(s->timeout_ms, LSC_LSCD_SLACK_MS));
}

/* The state every call checks first. */
static int usable(lsc_lscd *s)
{
    if (s == NULL) {
        return LSC_EINVAL;
    }
    if (s->open_error != 0) {
        return s->open_error;
    }
    if (s->eof) {
        return closed(s);
    }
    return 0;
}

/* ---- Opening ------------------------------------------------------------------------ */

/* A send during the open failed (r): lscd may have said why before it closed
 * the connection (it is full): that is the error, if it did. */
static int open_send_failed(lsc_lscd *s, int r)
{
    s->eof = false;
    (void)pump(s, 0);
    s->eof = true;
    return s->open_error != 0 ? s->open_error : r;
}

static int connect_error(lsc_lscd *s, int err)
{
    if (err == ENOENT || err == ECONNREFUSED || err == ENOTDIR) {
        return fail(s, LSC_ENODEV,
                    "no lscd at %s (%s): start it (lscd --port PORT, or systemctl start "
                    "lscd@NAME.socket)",
                    s->path, strerror(err));
    }
    if (err == EACCES || err == EPERM) {
        struct stat st;
        if (stat(s->path, &st) == 0) {
            return fail(s, LSC_EACCES,
                        "%s: %s (the socket is for its group, gid %u: add your user to "
                        "that group, then log in again)",
                        s->path, strerror(err), (unsigned)st.st_gid);
        }
        return fail(s, LSC_EACCES, "%s: %s", s->path, strerror(err));
    }
    if (err == EAGAIN || err == ETIMEDOUT) {
        return fail(s, LSC_ETIMEOUT, "lscd at %s does not accept connections (busy or stuck)",
                    s->path);
    }
    return fail(s, LSC_EIO, "%s: connect: %s", s->path, strerror(err));
}

static int do_open(lsc_lscd *s, const char *name, const lsc_lscd_options *opt)
{
    struct sockaddr_un addr;
    uint32_t connect_ms = opt->connect_timeout_ms != 0u ? opt->connect_timeout_ms
                                                         : LSC_LSCD_CONNECT_TIMEOUT;
    int r = lsc_lscd_socket_path(name, s->path, sizeof s->path);
    if (r < 0) {
        (void)snprintf(s->path, sizeof s->path, "%s", "?");
        return fail(s, r, "%s: not an lscd name (lscd:NAME, or lscd:PATH to its socket%s)",
                    name != NULL ? name : "(null)",
                    r == LSC_ENOSPC ? ", at most 107 bytes" : "");
    }
    s->fd = socket(AF_UNIX, SOCK_STREAM, 0);
    if (s->fd < 0) {
        return fail(s, LSC_EIO, "socket: %s", strerror(errno));
    }
    (void)fcntl(s->fd, F_SETFD, FD_CLOEXEC);
#ifdef SO_NOSIGPIPE
    {
        int one = 1;
        (void)setsockopt(s->fd, SOL_SOCKET, SO_NOSIGPIPE, &one, sizeof one);
    }
#endif
    /* a blocking connect waits for room in a full backlog up to the send timeout */
    struct timeval tv = {(time_t)(connect_ms / 1000u), (suseconds_t)((connect_ms % 1000u) * 1000u)};
    (void)setsockopt(s->fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    memcpy(addr.sun_path, s->path, strlen(s->path) + 1u);
    uint32_t start = mono_ms();
    while (connect(s->fd, (const struct sockaddr *)&addr, sizeof addr) != 0) {
        if (errno != EINTR) {
            return connect_error(s, errno);
        }
    }
    tv.tv_sec = 0;
    tv.tv_usec = 0;
    (void)setsockopt(s->fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    int fl = fcntl(s->fd, F_GETFL);
    if (fl < 0 || fcntl(s->fd, F_SETFL, fl | O_NONBLOCK) < 0) {
        return fail(s, LSC_EIO, "%s: fcntl: %s", s->path, strerror(errno));
    }
    /* the client's settings, then a PING: its PONG says they are in effect */
    uint8_t args[8];
    args[0] = opt->refuse_busy ? (uint8_t)(LSC_LSCD_MODE_ACK | LSC_LSCD_MODE_REFUSE)
                               : (uint8_t)LSC_LSCD_MODE_ACK;
    if ((r = send_ctl(s, LSC_LSCD_OP_MODE, args, 1)) < 0) {
        return open_send_failed(s, r);
    }
    lsc_lscd_put_u32(args, s->timeout_ms);
    if ((r = send_ctl(s, LSC_LSCD_OP_TIMEOUT, args, 4)) < 0) {
        return open_send_failed(s, r);
    }
    args[0] = opt->no_notifications ? (uint8_t)0 : (uint8_t)1;
    if ((r = send_ctl(s, LSC_LSCD_OP_SUBSCRIBE, args, 1)) < 0) {
        return open_send_failed(s, r);
    }
    uint32_t token = ++s->next_token;
    lsc_lscd_put_u32(args, token);
    if ((r = send_ctl(s, LSC_LSCD_OP_PING, args, 4)) < 0) {
        return open_send_failed(s, r);
    }
    for (;;) {
        if (s->open_error != 0) {
            return s->open_error;
        }
        if (s->hello && s->pong_seen && s->pong == token) {
            return 0;
        }
        uint32_t left = left_until(start, connect_ms);
        if (left == 0u) {
            if (s->rx.frames == 0u && s->rx.discarded > 0u) {
                return fail(s, LSC_EREPLY, "%s does not speak the lscd protocol", s->path);
            }
            return fail(s, LSC_ETIMEOUT, "lscd at %s did not answer within %u ms", s->path,
                        (unsigned)connect_ms);
        }
        r = pump(s, left);
        if (r < 0) {
            return r;
        }
        if (!s->hello && s->rx.frames > 0u && s->open_error == 0) {
            return fail(s, LSC_EREPLY, "%s does not speak the lscd protocol", s->path);
        }
    }
}

int lsc_lscd_open(const char *name, const lsc_lscd_options *opt, lsc_lscd **out)
{
    lsc_lscd_options o = {.size = sizeof o}; /* NULL: all defaults */
    lsc_lscd *s;
    if (out == NULL) {
        return LSC_EINVAL;
    }
    *out = NULL;
    s = calloc(1, sizeof *s);
    if (s == NULL) {
        return LSC_ENOSPC;
    }
    s->fd = -1;
    *out = s;
    if (opt != NULL && lsc_sized_size(opt) < LSC_SIZED_MIN(lsc_lscd_options, timeout_ms)) {
        s->open_error = fail(s, LSC_EINVAL,
                             "lsc_lscd_options.size is %lu, less than %lu: set it to "
                             "sizeof(lsc_lscd_options); nothing was sent",
                             (unsigned long)lsc_sized_size(opt),
                             (unsigned long)LSC_SIZED_MIN(lsc_lscd_options, timeout_ms));
        return s->open_error;
    }
    if (opt != NULL) {
        lsc_sized_take(&o, opt, sizeof o); /* beyond the caller's size: as if 0 */
    }
    opt = &o;
    s->timeout_ms = opt->timeout_ms != 0u ? opt->timeout_ms : DEFAULT_TIMEOUT;
    if (s->timeout_ms > LSCD_TIMEOUT_MAX) {
        s->timeout_ms = LSCD_TIMEOUT_MAX;
    }
    (void)lsc_parser_init(&s->rx, s->rxbuf, sizeof s->rxbuf);
    (void)lsc_parser_init(&s->tx, s->txbuf, sizeof s->txbuf);
    int r = do_open(s, name, opt);
    if (r < 0) {
        s->open_error = r;
        if (s->fd >= 0) {
            (void)close(s->fd);
            s->fd = -1;
        }
        return r;
    }
    s->message[0] = '\0';
    return 0;
}

void lsc_lscd_close(lsc_lscd *s)
{
    if (s == NULL) {
        return;
    }
    if (s->fd >= 0) {
        (void)close(s->fd);
    }
    free(s);
}

const char *lsc_lscd_error(const lsc_lscd *s)
{
    return s == NULL ? "out of memory" : s->message;
}

/* ---- The io -------------------------------------------------------------------------- */

uint32_t lsc_lscd_now_ms(void *ctx)
{
    (void)ctx;
    return mono_ms();
}

int lsc_lscd_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_lscd *s = ctx;
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    if (buf == NULL || cap == 0u) {
        return LSC_EINVAL;
    }
    if (cap > (size_t)INT_MAX) {
        cap = (size_t)INT_MAX;
    }
    uint32_t start = mono_ms();
    for (;;) {
        if (s->ring_len > 0u) {
            return (int)ring_get(s, buf, cap);
        }
        if (s->gone_pending) {
            s->gone_pending = false;
            return fail(s, LSC_ENODEV, "the controller of lscd at %s went away%s%s (lscd opens it "
                        "again when it is back)",
                        s->path, s->gone_why[0] != '\0' ? ": " : "", s->gone_why);
        }
        uint32_t left = left_until(start, timeout_ms);
        r = pump(s, left);
        if (r < 0) {
            return r;
        }
        if (left == 0u && s->ring_len == 0u && !s->gone_pending) {
            return 0;
        }
    }
}

int lsc_lscd_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_lscd *s = ctx;
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    if ((data == NULL && n > 0u) || n > (size_t)INT_MAX) {
        return LSC_EINVAL;
    }
    /* count the frames in data as the daemon will parse them (its parser is
     * this one), refusing control frames: those are this transport's own */
    lsc_parser saved = s->tx;
    uint8_t savedbuf[LSC_FRAME_MAX];
    memcpy(savedbuf, s->txbuf, sizeof savedbuf);
    uint64_t frames = 0;
    const uint8_t *p = data;
    size_t left = n;
    while (left > 0u) {
        lsc_frame f;
        int res = 0;
        size_t used = lsc_parser_feed_buf(&s->tx, p, left, &f, &res);
        p += used;
        left -= used;
        if (res == 1) {
            if (f.cmd == LSC_LSCD_CMD) {
                s->tx = saved;
                memcpy(s->txbuf, savedbuf, sizeof savedbuf);
                return fail(s, LSC_EINVAL,
                            "command 0x%02X is lscd's own: it cannot be sent to the controller",
                            (unsigned)LSC_LSCD_CMD);
            }
            frames++;
        }
    }
    uint32_t limit = add_sat(s->timeout_ms, LSC_LSCD_SLACK_MS);
    uint32_t start = mono_ms();
    if (s->verdicts > s->frames_sent) {
        s->frames_sent = s->verdicts; /* (never: one verdict per frame) */
    }
    s->wait_from = s->frames_sent;
    s->frames_sent += frames;
    s->verdict_error = 0;
    r = send_all(s, data, n, limit);
    if (r < 0) {
        return r;
    }
    /* one verdict per frame: done (for a request: its reply is here) or why not */
    while (s->verdicts < s->frames_sent) {
        uint32_t wait = left_until(start, limit);
        if (wait == 0u) {
            return fail(s, LSC_EIO, "lscd at %s did not confirm a frame within %u ms", s->path,
                        (unsigned)limit);
        }
        r = pump(s, wait);
        if (r < 0) {
            return r;
        }
    }
    if (s->verdict_error != 0) {
        switch (s->verdict_error) {
        case LSC_EBUSY:
            return fail(s, LSC_EBUSY, "another program holds the controller (a lease at lscd %s)",
                        s->path);
        case LSC_ENODEV:
            return fail(s, LSC_ENODEV, "the controller of lscd at %s is gone%s%s", s->path,
                        s->gone_why[0] != '\0' ? ": " : "", s->gone_why);
        case LSC_ETIMEOUT:
            return fail(s, LSC_ETIMEOUT,
                        "command %u through lscd at %s: no reply, or it could not be sent, "
                        "within %u ms",
                        (unsigned)s->verdict_cmd, s->path, (unsigned)s->timeout_ms);
        default:
            if (s->verdict_why[0] != '\0') { /* the device's line at lscd */
                return fail(s, s->verdict_error, "%s (lscd at %s)", s->verdict_why, s->path);
            }
            return fail(s, s->verdict_error, "lscd at %s: command %u: %s", s->path,
                        (unsigned)s->verdict_cmd, lsc_strerror(s->verdict_error));
        }
    }
    return (int)n;
}

void lsc_lscd_get_io(lsc_lscd *s, lsc_io *io)
{
    if (io == NULL) {
        return;
    }
    io->ctx = s;
    io->write = lsc_lscd_write;
    io->read = lsc_lscd_read;
    io->now_ms = lsc_lscd_now_ms;
}

int lsc_lscd_set_timeout(lsc_lscd *s, uint32_t timeout_ms)
{
    uint8_t args[4];
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    s->timeout_ms = timeout_ms != 0u ? timeout_ms : DEFAULT_TIMEOUT;
    if (s->timeout_ms > LSCD_TIMEOUT_MAX) {
        s->timeout_ms = LSCD_TIMEOUT_MAX;
    }
    lsc_lscd_put_u32(args, s->timeout_ms);
    return send_ctl(s, LSC_LSCD_OP_TIMEOUT, args, sizeof args);
}

/* ---- Lease and status --------------------------------------------------------------- */

/* Waits for a LEASE event after `seen` whose state is one of the two given. */
static int wait_lease(lsc_lscd *s, uint32_t seen, uint8_t a, uint8_t b, uint32_t limit)
{
    uint32_t start = mono_ms();
    for (;;) {
        if (s->lease_events != seen && (s->lease_state == a || s->lease_state == b)) {
            return 0;
        }
        uint32_t left = left_until(start, limit);
        if (left == 0u) {
            return fail(s, LSC_EIO, "lscd at %s did not answer within %u ms", s->path,
                        (unsigned)limit);
        }
        int r = pump(s, left);
        if (r < 0) {
            return r;
        }
        if (s->lease_events != seen && s->lease_state != a && s->lease_state != b) {
            seen = s->lease_events; /* an earlier lease's end: not the answer */
        }
    }
}

int lsc_lscd_lease(lsc_lscd *s, uint32_t ms, uint32_t wait_ms)
{
    uint8_t args[8];
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    uint32_t seen = s->lease_events;
    lsc_lscd_put_u32(args, ms);
    lsc_lscd_put_u32(args + 4, wait_ms);
    if ((r = send_ctl(s, LSC_LSCD_OP_LEASE, args, sizeof args)) < 0) {
        return r;
    }
    uint32_t limit = add_sat(wait_ms > s->timeout_ms ? wait_ms : s->timeout_ms, LSC_LSCD_SLACK_MS);
    r = wait_lease(s, seen, LSC_LSCD_LEASE_GRANTED, LSC_LSCD_LEASE_BUSY, limit);
    if (r < 0) {
        return r;
    }
    if (s->lease_state != LSC_LSCD_LEASE_GRANTED) {
        return fail(s, LSC_EBUSY, "another program holds the controller's lease (lscd at %s)",
                    s->path);
    }
    return 0;
}

uint32_t lsc_lscd_lease_ms(const lsc_lscd *s)
{
    return s != NULL ? s->lease_ms : 0u;
}

int lsc_lscd_release(lsc_lscd *s)
{
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    uint32_t seen = s->lease_events;
    if ((r = send_ctl(s, LSC_LSCD_OP_RELEASE, NULL, 0)) < 0) {
        return r;
    }
    r = wait_lease(s, seen, LSC_LSCD_LEASE_RELEASED, LSC_LSCD_LEASE_NONE,
                   add_sat(s->timeout_ms, LSC_LSCD_SLACK_MS));
    if (r < 0) {
        return r;
    }
    if (s->lease_state != LSC_LSCD_LEASE_RELEASED) {
        return fail(s, LSC_EINVAL, "no lease was held (lscd at %s)", s->path);
    }
    return 0;
}

int lsc_lscd_halt(lsc_lscd *s)
{
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    uint32_t seen = s->halts;
    if ((r = send_ctl(s, LSC_LSCD_OP_HALT, NULL, 0)) < 0) {
        return r;
    }
    /* the job under way (its timeout at most), then the halt's own */
    uint32_t limit = add_sat(add_sat(s->timeout_ms, s->timeout_ms), LSC_LSCD_SLACK_MS);
    uint32_t start = mono_ms();
    while (s->halts == seen) {
        uint32_t left = left_until(start, limit);
        if (left == 0u) {
            return fail(s, LSC_EIO, "lscd at %s did not answer the halt within %u ms", s->path,
                        (unsigned)limit);
        }
        if ((r = pump(s, left)) < 0) {
            return r;
        }
    }
    s->message[0] = '\0';
    return s->halt_rc == 0 ? 0 : fail(s, s->halt_rc, "%s", s->halt_why);
}

uint32_t lsc_lscd_halts(const lsc_lscd *s)
{
    return s != NULL ? s->halts : 0u;
}

int lsc_lscd_status(lsc_lscd *s, lsc_lscd_status_fn fn, void *user, uint32_t timeout_ms)
{
    int r = usable(s);
    if (r < 0) {
        return r;
    }
    if (timeout_ms == 0u) {
        timeout_ms = DEFAULT_TIMEOUT;
    }
    s->status_fn = fn;
    s->status_user = user;
    s->status_items = 0;
    s->status_end = false;
    r = send_ctl(s, LSC_LSCD_OP_STATUS, NULL, 0);
    uint32_t start = mono_ms();
    while (r == 0 && !s->status_end) {
        uint32_t left = left_until(start, timeout_ms);
        if (left == 0u) {
            r = fail(s, LSC_ETIMEOUT, "lscd at %s did not send its status within %u ms", s->path,
                     (unsigned)timeout_ms);
            break;
        }
        r = pump(s, left);
    }
    s->status_fn = NULL;
    s->status_user = NULL;
    return r < 0 ? r : s->status_items;
}

bool lsc_lscd_controller_present(const lsc_lscd *s)
{
    return s != NULL && s->open_error == 0 && !s->eof && s->present;
}

uint32_t lsc_lscd_dropped(const lsc_lscd *s)
{
    return s != NULL ? s->dropped_daemon + s->dropped_local : 0u;
}

void lscd_client_digest(const uint8_t *data, size_t n, size_t chunk,
                        void (*read_fn)(void *user, const uint8_t *p, size_t len), void *user,
                        lscd_client_facts *out)
{
    memset(out, 0, sizeof *out);
    lsc_lscd *s = calloc(1, sizeof *s);
    if (s == NULL) {
        out->open_error = LSC_ENOSPC;
        return;
    }
    s->fd = -1;
    (void)snprintf(s->path, sizeof s->path, "fuzz.sock");
    (void)lsc_parser_init(&s->rx, s->rxbuf, sizeof s->rxbuf);
    (void)lsc_parser_init(&s->tx, s->txbuf, sizeof s->txbuf);
    chunk = chunk == 0u ? 1u : chunk;
    for (size_t at = 0; at < n; at += chunk) {
        take(s, data + at, n - at < chunk ? n - at : chunk);
        for (;;) { /* what a client's reads would take between two chunks */
            uint8_t buf[LSC_FRAME_MAX];
            size_t got = s->ring_len > 0u ? ring_get(s, buf, sizeof buf) : 0u;
            if (got == 0u) {
                break;
            }
            out->bytes_read += got;
            if (read_fn != NULL) {
                read_fn(user, buf, got);
            }
        }
    }
    s->eof = true; /* the end of the connection: the next read says so */
    uint8_t buf[8];
    out->last_read = lsc_lscd_read(s, buf, sizeof buf, 0);
    out->frames_read = s->rx.frames;
    out->status_items = (size_t)s->status_items;
    out->hello = s->hello;
    out->open_error = s->open_error;
    (void)snprintf(out->message, sizeof out->message, "%s", lsc_lscd_error(s));
    lsc_lscd_close(s);
}

int lsc_lscd_fileno(const lsc_lscd *s)
{
    return s != NULL && s->open_error == 0 ? s->fd : -1;
}

bool lsc_lscd_input_pending(const lsc_lscd *s)
{
    return s != NULL && s->open_error == 0 && (s->ring_len > 0u || s->gone_pending);
}

#endif
