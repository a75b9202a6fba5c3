/* HID transport: the xArm's USB HID link through hidapi (contract in
 * lsc/hid.h). Host only: compiles to nothing elsewhere (the Arduino IDE
 * builds every .c under src/). Without hidapi (LSC_HAVE_HIDAPI unset) every
 * call fails with "built without HID support". */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <wchar.h>

#include "lsc/hid.h"
#include "hid_internal.h"
#include "../util/sized.h" /* lsc_hid_info grows */

#if LSC_HID_MESSAGE_MAX != LSC_PORT_MESSAGE_MAX
#error "lsc_hid's message must hold a port message"
#endif

#ifdef LSC_HAVE_HIDAPI
#include <hidapi.h>
#define HAVE_HIDAPI 1
#else
#define HAVE_HIDAPI 0
#endif

/* The calling thread's last open: its errno and message, for
 * lsc_hid_os_errno(NULL) and lsc_hid_error_message(NULL). */
static __thread struct {
    int os_errno;
    char message[LSC_HID_MESSAGE_MAX];
} last;

/* h in the closed state, message empty. */
static void init(lsc_hid *h)
{
    memset(h, 0, sizeof *h);
    h->dev = NULL;
    h->lock_fd = -1;
}

/* Closes what h has open (h stays allocated). */
static void shut(lsc_hid *h);

/* The HID transport's own hints: the serial ports' (the dialout group) would
 * not help with a hidraw node. */
static const lsc_port_hints hid_hints = {
    " (the udev rule 60-lsc.rules gives the logged-in user (uaccess) and the plugdev group "
    "access to hidraw 0483:5750: the lscctl package installs it as "
    "/lib/udev/rules.d/60-lsc.rules; from a source install, copy debian/lscctl.lsc.udev to "
    "/etc/udev/rules.d/60-lsc.rules; then unplug and replug the arm. Or sudo usermod -aG "
    "plugdev $USER and log in again. fwupd can also hold the node: sudo systemctl stop fwupd)",
    " (port busy: another program has the arm open; close it first)",
    " (the device went away: unplugged?)",
};

/* Keeps the port's record e of an error on h. Returns code. */
static int keep(lsc_hid *h, int code, const lsc_port_error *e)
{
    h->os_errno = e->os_errno;
    memcpy(h->message, e->message, sizeof h->message);
    return code;
}

/* Records an error on h: OS errno err (0: none) and "path: what[: strerror]
 * (hint)" (src/port's formatter with the HID hints). */
static int fail(lsc_hid *h, int code, int err, const char *what)
{
    lsc_port_error e;
    e.open = h->dev != NULL;
    return keep(h,
                lsc_port_fail_hinted(&e, &hid_hints, code, err,
                                     h->path[0] != '\0' ? h->path : "hid", what),
                &e);
}

static int set_path(lsc_hid *h, const char *path)
{
    lsc_port_error e;
    int r = lsc_port_set_path(&e, h->path, sizeof h->path, path, "hid");
    return r == 0 ? 0 : keep(h, r, &e);
}

bool lsc_hid_available(void)
{
    return HAVE_HIDAPI != 0;
}

uint32_t lsc_hid_now_ms(void *ctx)
{
    (void)ctx;
    return lsc_port_now_ms();
}

void lsc_hid_get_io(lsc_hid *h, lsc_io *io)
{
    if (io == NULL) {
        return;
    }
    io->ctx = h;
    io->write = lsc_hid_write;
    io->read = lsc_hid_read;
    io->now_ms = lsc_hid_now_ms;
}

const char *lsc_hid_error_message(const lsc_hid *h)
{
    return h == NULL ? last.message : h->message;
}

int lsc_hid_os_errno(const lsc_hid *h)
{
    return h == NULL ? last.os_errno : h->os_errno;
}

/* How one of the opens fills a new handle: 0, or an error recorded on h with
 * nothing left open. */
typedef int (*open_fn)(lsc_hid *h, const char *name, uint16_t vid, uint16_t pid);

/* A new handle opened by fn into *out; a failure leaves *out NULL and its
 * errno and message the thread's. */
static int open_new(open_fn fn, const char *name, uint16_t vid, uint16_t pid, lsc_hid **out)
{
    last.os_errno = 0;
    last.message[0] = '\0';
    if (out == NULL) {
        (void)snprintf(last.message, sizeof last.message,
                       "invalid argument: no place for the handle");
        return LSC_EINVAL;
    }
    *out = NULL;
    lsc_hid *h = calloc(1, sizeof *h);
    if (h == NULL) {
        (void)snprintf(last.message, sizeof last.message, "out of memory");
        return LSC_ENOSPC;
    }
    init(h);
    int r = fn(h, name, vid, pid);
    if (r != 0) {
        last.os_errno = h->os_errno;
        memcpy(last.message, h->message, sizeof last.message);
        lsc_hid_close(h);
        return r;
    }
    *out = h;
    return 0;
}

static int open_path_into(lsc_hid *h, const char *path, uint16_t vid, uint16_t pid);
static int open_serial_into(lsc_hid *h, const char *serial, uint16_t vid, uint16_t pid);

int lsc_hid_open_path(const char *path, lsc_hid **out)
{
    return open_new(open_path_into, path, 0, 0, out);
}

int lsc_hid_open_path_extra(const char *path, uint16_t vid, uint16_t pid, lsc_hid **out)
{
    return open_new(open_path_into, path, vid, pid, out);
}

int lsc_hid_open_serial(const char *serial, lsc_hid **out)
{
    return open_new(open_serial_into, serial, 0, 0, out);
}

int lsc_hid_open_serial_extra(const char *serial, uint16_t vid, uint16_t pid, lsc_hid **out)
{
    return open_new(open_serial_into, serial, vid, pid, out);
}

void lsc_hid_close(lsc_hid *h)
{
    if (h != NULL) {
        shut(h);
        free(h);
    }
}

uint32_t lsc_hid_reports_dropped(const lsc_hid *h)
{
    return h == NULL ? 0u : h->dropped;
}

int lsc_hid_fileno(const lsc_hid *h)
{
    return h == NULL || h->dev == NULL ? -1 : h->lock_fd;
}

int lsc_hid_fileno_drain(lsc_hid *h)
{
    int n = 0;
    uint8_t report[LSC_HID_REPORT_SIZE];
    int fd = lsc_hid_fileno(h);
    /* (non-blocking: the node was opened O_NONBLOCK) one report per read */
    while (fd >= 0 && n < 256 && read(fd, report, sizeof report) > 0) {
        n++;
    }
    return n;
}

bool lsc_hid_input_pending(const lsc_hid *h)
{
    return h != NULL && h->pending_off < h->pending_len;
}

static void put_message(char *message, size_t cap, const char *fmt, ...)
{
    if (message == NULL || cap == 0u) {
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(message, cap, fmt, ap);
    va_end(ap);
}

#if HAVE_HIDAPI

/* The length of the frame at the start of a report of n bytes, or 0 if it
 * holds none (no header, LEN below 2, or a frame longer than the report). */
static size_t frame_length(const uint8_t *r, size_t n)
{
    if (n < 4u || r[0] != LSC_HEADER_BYTE || r[1] != LSC_HEADER_BYTE || r[2] < 2u ||
        (size_t)r[2] + 2u > n) {
        return 0;
    }
    return (size_t)r[2] + 2u;
}

/* Hands out what is left of the last report's frame. */
static int take_pending(lsc_hid *h, uint8_t *buf, size_t cap)
{
    size_t n = h->pending_len - h->pending_off;
    if (n > cap) {
        n = cap;
    }
    memcpy(buf, h->pending + h->pending_off, n);
    h->pending_off += n;
    return (int)n;
}

/* hidapi's wide string as UTF-8 into out (cap bytes, NUL-terminated; a
 * character that does not fit whole is left out with everything after it). */
static void utf8_of(char *out, size_t cap, const wchar_t *w)
{
    size_t n = 0;
    for (; w != NULL && *w != L'\0'; w++) {
        unsigned long c = (unsigned long)*w;
        uint8_t b[4];
        size_t k;
        if (c < 0x80u) {
            b[0] = (uint8_t)c;
            k = 1;
        } else if (c < 0x800u) {
            b[0] = (uint8_t)(0xC0u | (c >> 6));
            b[1] = (uint8_t)(0x80u | (c & 0x3Fu));
            k = 2;
        } else if (c < 0x10000u) {
            b[0] = (uint8_t)(0xE0u | (c >> 12));
            b[1] = (uint8_t)(0x80u | ((c >> 6) & 0x3Fu));
            b[2] = (uint8_t)(0x80u | (c & 0x3Fu));
            k = 3;
        } else if (c < 0x110000u) {
            b[0] = (uint8_t)(0xF0u | (c >> 18));
            b[1] = (uint8_t)(0x80u | ((c >> 12) & 0x3Fu));
            b[2] = (uint8_t)(0x80u | ((c >> 6) & 0x3Fu));
            b[3] = (uint8_t)(0x80u | (c & 0x3Fu));
            k = 4;
        } else {
            b[0] = '?';
            k = 1;
        }
        if (n + k >= cap) {
            break;
        }
        memcpy(out + n, b, k);
        n += k;
    }
    out[n] = '\0';
}

/* Appends the devices with ids vid:pid to out[*n..cap) (elements of size
 * bytes, the caller's out[0].size), counting every one in *n (capped at
 * INT_MAX). */
static void list_ids(void *out, size_t size, size_t cap, size_t *n, uint16_t vid, uint16_t pid)
{
    struct hid_device_info *all = hid_enumerate(vid, pid);
    for (const struct hid_device_info *d = all; d != NULL; d = d->next) {
        if (*n < cap) {
            lsc_hid_info i;
            memset(&i, 0, sizeof i);
            i.size = sizeof i;
            (void)snprintf(i.path, sizeof i.path, "%s", d->path != NULL ? d->path : "");
            utf8_of(i.serial, sizeof i.serial, d->serial_number);
            utf8_of(i.product, sizeof i.product, d->product_string);
            utf8_of(i.manufacturer, sizeof i.manufacturer, d->manufacturer_string);
            i.vid = d->vendor_id;
            i.pid = d->product_id;
            lsc_sized_give_nth(out, size, *n, &i, sizeof i);
        }
        if (*n < (size_t)INT_MAX) {
            (*n)++;
        }
    }
    hid_free_enumeration(all);
}

/* Lists the devices with ids vid:pid (0:0: the known ones), then those with
 * extra_vid:extra_pid (unless 0:0 or known): lsc_hid_list's contract. */
static int list_some(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                     uint16_t extra_vid, uint16_t extra_pid, char *message, size_t msgcap)
{
    put_message(message, msgcap, "%s", "");
    if (out == NULL && cap > 0u) {
        put_message(message, msgcap, "%s", "invalid argument");
        return LSC_EINVAL;
    }
    size_t size = cap > 0u ? lsc_sized_size(out) : 0u;
    if (cap > 0u && size < LSC_SIZED_MIN(lsc_hid_info, path)) {
        put_message(message, msgcap,
                    "lsc_hid_info.size is %lu, less than %lu: set out[0].size to "
                    "sizeof(lsc_hid_info); nothing was listed",
                    (unsigned long)size, (unsigned long)LSC_SIZED_MIN(lsc_hid_info, path));
        return LSC_EINVAL;
    }
    if (hid_init() != 0) {
        char why[LSC_HID_MESSAGE_MAX];
        utf8_of(why, sizeof why, hid_error(NULL));
        put_message(message, msgcap, "hid_init failed: %s", why);
        return LSC_EIO;
    }
    size_t n = 0;
    if (vid != 0u || pid != 0u) {
        list_ids(out, size, cap, &n, vid, pid);
    } else {
        size_t count;
        const lsc_hid_id *known = lsc_hid_known_ids(&count);
        for (size_t k = 0; k < count; k++) {
            list_ids(out, size, cap, &n, known[k].vid, known[k].pid);
        }
    }
    if (lsc_hid_is_extra(extra_vid, extra_pid)) {
        list_ids(out, size, cap, &n, extra_vid, extra_pid);
    }
    return (int)n;
}

int lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid, char *message,
                 size_t msgcap)
{
    return list_some(out, cap, vid, pid, 0, 0, message, msgcap);
}

/* Opens and locks the node for this process alone: hidraw has no TIOCEXCL,
 * and hidapi keeps its descriptor to itself, so the lock is on a descriptor
 * of our own (flock locks the node for every other open file description). */
static int lock_node(lsc_hid *h)
{
    lsc_port_error e;
    int r = lsc_port_open_locked(&e, &hid_hints, h->path, &h->lock_fd);
    return r == 0 ? 0 : keep(h, r, &e);
}

/* Checks the node at h->path (hid_internal.h): a hidraw node of a known
 * controller or of extra_vid:extra_pid. On success h->path is the node's
 * resolved path and *node what was checked. Opens nothing. */
static int check_node(lsc_hid *h, uint16_t extra_vid, uint16_t extra_pid, lsc_hid_node *node)
{
    lsc_port_error e;
    int r = lsc_hid_node_identify_live(h->path, node, &e);
    if (r == 0) {
        r = lsc_hid_node_accept(node, extra_vid, extra_pid, h->path, &e);
    }
    if (r != 0) {
        return keep(h, r, &e);
    }
    memcpy(h->path, node->path, sizeof h->path);
    return 0;
}

static int open_path_into(lsc_hid *h, const char *path, uint16_t vid, uint16_t pid)
{
    lsc_hid_node node;
    int r = set_path(h, path);
    if (r == 0) {
        r = check_node(h, vid, pid, &node);
    }
    if (r == 0) {
        r = lock_node(h);
    }
    if (r != 0) {
        return r;
    }
    lsc_port_error e;
    r = lsc_hid_node_same(&node, h->lock_fd, h->path, &e);
    if (r != 0) {
        shut(h);
        return keep(h, r, &e);
    }
    errno = 0;
    if (hid_init() == 0) {
        h->dev = hid_open_path(h->path);
    }
    if (h->dev == NULL) {
        int err = errno;
        char why[LSC_HID_MESSAGE_MAX / 2u];
        char what[LSC_HID_MESSAGE_MAX / 2u + 32u];
        utf8_of(why, sizeof why, hid_error(NULL));
        /* hidapi's text, unless it says nothing ("Success": errno was 0) */
        if (why[0] == '\0' || strcmp(why, "Success") == 0) {
            (void)snprintf(what, sizeof what, "%s", "hidapi cannot open it");
        } else {
            (void)snprintf(what, sizeof what, "hidapi cannot open it (%s)", why);
        }
        shut(h);
        return fail(h, err != 0 ? lsc_port_open_code(err) : LSC_EIO, err, what);
    }
    return 0;
}

#define LIST_MAX 16u

static int open_serial_into(lsc_hid *h, const char *serial, uint16_t vid, uint16_t pid)
{
    lsc_hid_info found[LIST_MAX];
    char msg[LSC_HID_MESSAGE_MAX];
    found[0].size = sizeof found[0];
    int n = list_some(found, LIST_MAX, 0, 0, vid, pid, msg, sizeof msg);
    if (n < 0) {
        return fail(h, n, 0, msg);
    }
    size_t count = (size_t)n < LIST_MAX ? (size_t)n : LIST_MAX;
    bool any = serial == NULL || serial[0] == '\0';
    size_t match = count, matches = 0;
    char serials[LSC_HID_MESSAGE_MAX / 2u] = "";
    size_t len = 0;
    for (size_t i = 0; i < count; i++) {
        if (any || strcmp(found[i].serial, serial) == 0) {
            match = matches++ == 0 ? i : match;
        }
        int w = snprintf(serials + len, sizeof serials - len, "%s%s", i == 0 ? "" : ", ",
                         found[i].serial[0] != '\0' ? found[i].serial : "(none)");
        len += w > 0 && (size_t)w < sizeof serials - len ? (size_t)w : 0u;
    }
    if (count == 0) {
        char ids[64];
        char what[128];
        lsc_hid_known_text(ids, sizeof ids, vid, pid);
        (void)snprintf(what, sizeof what, "no HID controller (USB %s) is present", ids);
        return fail(h, LSC_ENODEV, 0, what);
    }
    if (matches == 0) {
        char what[LSC_HID_MESSAGE_MAX];
        (void)snprintf(what, sizeof what,
                       "no HID controller has serial number '%.64s' (present: %s)", serial,
                       serials);
        return fail(h, LSC_ENODEV, 0, what);
    }
    if (any && matches > 1u) {
        char what[LSC_HID_MESSAGE_MAX];
        (void)snprintf(what, sizeof what,
                       "%zu HID controllers are present (serial numbers %s): choose one by "
                       "its serial number",
                       matches, serials);
        return fail(h, LSC_EINVAL, 0, what);
    }
    return open_path_into(h, found[match].path, vid, pid);
}

static void shut(lsc_hid *h)
{
    if (h->dev != NULL) {
        hid_close(h->dev);
        h->dev = NULL;
    }
    if (h->lock_fd >= 0) {
        (void)close(h->lock_fd); /* ends the flock */
        h->lock_fd = -1;
    }
    h->pending_off = h->pending_len = 0;
}

/* An error of hidapi on the open device: errno kept, hidapi's text shown. */
static int dev_fail(lsc_hid *h, const char *op)
{
    int err = errno;
    char why[LSC_HID_MESSAGE_MAX / 2u];
    char what[LSC_HID_MESSAGE_MAX / 2u + 32u];
    utf8_of(why, sizeof why, hid_error(h->dev));
    (void)snprintf(what, sizeof what, "%s failed (%s)", op, why);
    /* on an open hidraw node a failed read or write means the device is gone */
    return fail(h, LSC_ENODEV, err == EINTR || err == EAGAIN ? 0 : err, what);
}

int lsc_hid_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_hid *h = ctx;
    if (h == NULL || h->dev == NULL || data == NULL) {
        return LSC_EINVAL;
    }
    if (n > LSC_HID_REPORT_SIZE || frame_length(data, n) != n) {
        return fail(h, LSC_EINVAL, 0,
                    "not one whole frame of at most 64 bytes (a HID report holds one frame)");
    }
    uint8_t report[LSC_HID_REPORT_SIZE + 1u] = {0}; /* 0x00: no report id */
    memcpy(report + 1, data, n);
    errno = 0;
    int w = hid_write(h->dev, report, sizeof report);
    if (w < 0) {
        return dev_fail(h, "write");
    }
    if ((size_t)w != sizeof report) {
        return fail(h, LSC_EIO, 0, "write: the report was not sent whole");
    }
    return (int)n;
}

int lsc_hid_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_hid *h = ctx;
    if (h == NULL || h->dev == NULL || buf == NULL || cap == 0u) {
        return LSC_EINVAL;
    }
    if (cap > (size_t)INT_MAX) {
        cap = (size_t)INT_MAX;
    }
    if (h->pending_off < h->pending_len) {
        return take_pending(h, buf, cap);
    }
    uint32_t start = lsc_hid_now_ms(NULL);
    for (;;) {
        uint32_t spent = lsc_hid_now_ms(NULL) - start;
        uint32_t left = spent >= timeout_ms ? 0u : timeout_ms - spent;
        uint8_t report[LSC_HID_REPORT_SIZE];
        errno = 0;
        int got = hid_read_timeout(h->dev, report, sizeof report,
                                   left > (uint32_t)INT_MAX ? INT_MAX : (int)left);
        if (got < 0) {
            return dev_fail(h, "read");
        }
        if (got == 0) {
            return 0;
        }
        size_t len = frame_length(report, (size_t)got);
        if (len == 0u) {
            h->dropped++; /* no frame in it: the next report starts afresh */
            if (left == 0u) {
                return 0;
            }
            continue;
        }
        memcpy(h->pending, report, len);
        h->pending_off = 0;
        h->pending_len = len;
        return take_pending(h, buf, cap);
    }
}

#else /* !HAVE_HIDAPI */

static const char no_hid[] = "built without HID support (lsc was configured without hidapi: "
                             "install the Debian package libhidapi-dev, then configure and "
                             "build lsc again)";


int lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid, char *message,
                 size_t msgcap)
{
    (void)out;
    (void)cap;
    (void)vid;
    (void)pid;
    put_message(message, msgcap, "%s", no_hid);
    return LSC_EINVAL;
}

static int open_path_into(lsc_hid *h, const char *path, uint16_t vid, uint16_t pid)
{
    (void)vid;
    (void)pid;
    (void)set_path(h, path);
    return fail(h, LSC_EINVAL, 0, no_hid);
}

static int open_serial_into(lsc_hid *h, const char *serial, uint16_t vid, uint16_t pid)
{
    (void)serial;
    return open_path_into(h, "hid", vid, pid);
}

static void shut(lsc_hid *h)
{
    (void)h;
}

int lsc_hid_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    (void)data;
    (void)n;
    return LSC_EINVAL;
}

int lsc_hid_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)buf;
    (void)cap;
    (void)timeout_ms;
    return LSC_EINVAL;
}
#endif

#endif
