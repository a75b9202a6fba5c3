/* Which node the HID transport may hand to hidapi (contract in hid_internal.h):
 * a hidraw character device whose HID device has a known controller's USB
 * ids. Host only: compiles to nothing elsewhere (the Arduino IDE builds every
 * .c under src/). Needs no hidapi. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/sysmacros.h>
#endif

#include "hid_internal.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

/* Room for a sysfs path: the root (a test's temporary directory) and
 * /sys/dev/char/MAJ:MIN/device/uevent. */
#define SYSFS_PATH_MAX 512u
/* A HID device's uevent is a few hundred bytes (DRIVER, HID_ID, HID_NAME,
 * HID_PHYS, HID_UNIQ, MODALIAS); more is not read. */
#define UEVENT_MAX 4096u

static int refuse(lsc_port_error *e, const char *shown, const char *what)
{
    e->open = false;
    return lsc_port_fail(e, LSC_ENODEV, 0, shown, what);
}

/* What a file of type `type` is, for a message. */
static const char *kind_of(mode_t type)
{
    switch (type) {
    case S_IFREG: return "a regular file";
    case S_IFDIR: return "a directory";
    case S_IFIFO: return "a FIFO";
    case S_IFSOCK: return "a socket";
    case S_IFBLK: return "a block device";
    case S_IFLNK: return "a symbolic link";
    default: return "a file of unknown type";
    }
}

/* Copies s into out (cap bytes), every byte outside printable ASCII as '?':
 * text read from sysfs or a file name goes into a one-line message. */
static void printable(char *out, size_t cap, const char *s, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n && s[i] != '\0' && k + 1u < cap; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20u && c < 0x7Fu) {
            out[k++] = s[i];
        } else {
            out[k++] = '?';
        }
    }
    if (cap > 0u) {
        out[k] = '\0';
    }
}

/* Parses 1..max_digits hex digits at *p up to `end` (not included); returns
 * true and the value, advancing *p. */
static bool hex_field(const char **p, char end, size_t max_digits, unsigned long *out)
{
    unsigned long v = 0;
    size_t n = 0;
    const char *s = *p;
    for (; *s != end; s++, n++) {
        char c = *s;
        unsigned d;
        if (c >= '0' && c <= '9') {
            d = (unsigned)(c - '0');
        } else if (c >= 'a' && c <= 'f') {
            d = (unsigned)(c - 'a') + 10u;
        } else if (c >= 'A' && c <= 'F') {
            d = (unsigned)(c - 'A') + 10u;
        } else {
            return false;
        }
        if (n == max_digits) {
            return false;
        }
        v = v * 16u + d;
    }
    if (n == 0u) {
        return false;
    }
    *out = v;
    *p = s;
    return true;
}

/* Finds HID_ID=BUS:VID:PID in a uevent's text (NUL-terminated). */
static bool parse_hid_id(const char *text, lsc_hid_node *node)
{
    for (const char *line = text; *line != '\0';) {
        const char *nl = strchr(line, '\n');
        if (strncmp(line, "HID_ID=", 7) == 0) {
            const char *p = line + 7;
            unsigned long bus, vid, pid;
            char last = nl != NULL ? '\n' : '\0';
            if (!hex_field(&p, ':', 8, &bus) || *p++ != ':' || !hex_field(&p, ':', 8, &vid) ||
                *p++ != ':' || !hex_field(&p, last, 8, &pid) || bus > 0xFFFFu ||
                vid > 0xFFFFu || pid > 0xFFFFu) {
                return false;
            }
            node->bus = (uint16_t)bus;
            node->vid = (uint16_t)vid;
            node->pid = (uint16_t)pid;
            return true;
        }
        if (nl == NULL) {
            break;
        }
        line = nl + 1;
    }
    return false;
}

/* Reads the regular file at path into buf (cap bytes, NUL-terminated; the
 * rest cut). Returns 0 or an errno. Never blocks: a FIFO is refused. */
static int read_small(const char *path, char *buf, size_t cap)
{
    int fd;
    do {
        fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        return errno;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        (void)close(fd);
        return EINVAL;
    }
    size_t len = 0;
    while (len + 1u < cap) {
        ssize_t n = read(fd, buf + len, cap - 1u - len);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            int err = errno;
            (void)close(fd);
            return err;
        }
        if (n == 0) {
            break;
        }
        len += (size_t)n;
    }
    buf[len] = '\0';
    (void)close(fd);
    return 0;
}

#ifdef __linux__
/* Checks sysfs for the character device rdev: the hidraw class, and the USB
 * ids of its HID device. */
static int check_sysfs(const char *root, dev_t rdev, const char *shown, lsc_hid_node *node,
                       lsc_port_error *e)
{
    char dir[SYSFS_PATH_MAX], file[SYSFS_PATH_MAX + 32u], link[PATH_MAX], what[LSC_PORT_MESSAGE_MAX / 2u];
    int w = snprintf(dir, sizeof dir, "%s/sys/dev/char/%u:%u", root, (unsigned)major(rdev),
                     (unsigned)minor(rdev));
    if (w < 0 || (size_t)w >= sizeof dir) {
        return refuse(e, shown, "cannot check it: the sysfs path is too long");
    }
    (void)snprintf(file, sizeof file, "%s/subsystem", dir);
    ssize_t n = readlink(file, link, sizeof link - 1u);
    if (n < 0) {
        (void)snprintf(what, sizeof what,
                       "a character device (%u:%u) without a sysfs class, not a hidraw node",
                       (unsigned)major(rdev), (unsigned)minor(rdev));
        return refuse(e, shown, what);
    }
    link[n] = '\0';
    const char *slash = strrchr(link, '/');
    const char *subsystem = slash != NULL ? slash + 1 : link;
    if (strcmp(subsystem, "hidraw") != 0) {
        char name[64];
        printable(name, sizeof name, subsystem, strlen(subsystem));
        (void)snprintf(what, sizeof what, "a character device of class '%s', not a hidraw node",
                       name);
        return refuse(e, shown, what);
    }
    (void)snprintf(file, sizeof file, "%s/device/uevent", dir);
    char text[UEVENT_MAX] = {0};
    int err = read_small(file, text, sizeof text);
    if (err != 0) {
        (void)snprintf(what, sizeof what,
                       "a hidraw node whose USB ids cannot be read (%s/sys/dev/char/%u:%u/"
                       "device/uevent: %s)",
                       root, (unsigned)major(rdev), (unsigned)minor(rdev), strerror(err));
        return refuse(e, shown, what);
    }
    if (!parse_hid_id(text, node)) {
        return refuse(e, shown, "a hidraw node whose USB ids cannot be read (no HID_ID in "
                                "its sysfs uevent)");
    }
    if (node->bus != LSC_HID_BUS_USB) {
        (void)snprintf(what, sizeof what,
                       "not a USB device: a hidraw node on HID bus %04x (ids %04x:%04x); "
                       "the controllers are USB devices",
                       (unsigned)node->bus, (unsigned)node->vid, (unsigned)node->pid);
        return refuse(e, shown, what);
    }
    return 0;
}
#else
static int check_sysfs(const char *root, dev_t rdev, const char *shown, lsc_hid_node *node,
                       lsc_port_error *e)
{
    (void)root;
    (void)rdev;
    (void)node;
    return refuse(e, shown, "cannot check that it is a HID controller: the check reads Linux's "
                            "sysfs, which this system does not have");
}
#endif

int lsc_hid_node_identify(const char *sysfs_root, const char *path, const char *shown,
                          lsc_hid_node *node, lsc_port_error *e)
{
    char real[PATH_MAX];
    memset(node, 0, sizeof *node);
    e->open = false;
    if (realpath(path, real) == NULL) {
        int err = errno;
        int code = err == EACCES || err == EPERM ? LSC_EACCES : LSC_ENODEV;
        return lsc_port_fail_hinted(e, NULL, code, err, shown,
                                    code == LSC_EACCES ? "cannot reach it" : "cannot find it");
    }
    if (strlen(real) >= sizeof node->path) {
        return lsc_port_fail(e, LSC_EINVAL, 0, shown, "its path is too long");
    }
    struct stat st;
    if (stat(real, &st) != 0) {
        int err = errno;
        return lsc_port_fail(e, LSC_ENODEV, err, shown, "cannot find it");
    }
    if (!S_ISCHR(st.st_mode)) {
        char what[96];
        (void)snprintf(what, sizeof what, "%s, not a %s", kind_of(st.st_mode & S_IFMT),
                       S_ISBLK(st.st_mode) ? "hidraw node" : "device");
        int r = refuse(e, shown, what);
        e->os_errno = S_ISDIR(st.st_mode) ? EISDIR : 0; /* as the serial transport says it */
        return r;
    }
    int r = check_sysfs(sysfs_root != NULL ? sysfs_root : "", st.st_rdev, shown, node, e);
    if (r != 0) {
        return r;
    }
    memcpy(node->path, real, strlen(real) + 1u); /* fits: checked above */
    node->dev = st.st_dev;
    node->rdev = st.st_rdev;
    node->ino = st.st_ino;
    node->type = st.st_mode & S_IFMT;
    return 0;
}

int lsc_hid_node_accept(const lsc_hid_node *node, uint16_t extra_vid, uint16_t extra_pid,
                        const char *shown, lsc_port_error *e)
{
    if (lsc_hid_is_known(node->vid, node->pid) ||
        ((extra_vid != 0u || extra_pid != 0u) && node->vid == extra_vid &&
         node->pid == extra_pid)) {
        return 0;
    }
    char known[64];
    lsc_hid_known_text(known, sizeof known, extra_vid, extra_pid);
    char what[LSC_PORT_MESSAGE_MAX / 2u];
    (void)snprintf(what, sizeof what,
                   "not a known servo controller: USB %04x:%04x (known: %s); nothing sent "
                   "(if it is one: lscctl --hid-id %04x:%04x)",
                   (unsigned)node->vid, (unsigned)node->pid, known, (unsigned)node->vid,
                   (unsigned)node->pid);
    return refuse(e, shown, what);
}

int lsc_hid_node_same(const lsc_hid_node *node, int fd, const char *shown, lsc_port_error *e)
{
    struct stat st;
    if (fstat(fd, &st) != 0 || st.st_dev != node->dev || st.st_ino != node->ino ||
        (st.st_mode & S_IFMT) != node->type || st.st_rdev != node->rdev) {
        return refuse(e, shown, "the node changed while it was being opened");
    }
    return 0;
}

#endif
