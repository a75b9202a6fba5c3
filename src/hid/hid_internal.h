/* What the HID transport checks about a node before hidapi sees it: that it is
 * a hidraw character device and which USB ids its HID device has. Internal:
 * host only, not exported, not installed.
 *
 * The test seam: the checks read sysfs under a root given as a parameter
 * (lsc_hid_node_identify), so a test points them at a directory of its own
 * that imitates /sys/dev/char/MAJ:MIN. The transport calls
 * lsc_hid_node_identify_live, the only function of hid_live.c; a test program
 * linked with the static library may define that function itself (the hidapi
 * test double, tests/hid_double.c, does: its devices are regular files), and
 * the linker then leaves hid_live.c out. No global state is involved. */
#ifndef LSC_HID_INTERNAL_H
#define LSC_HID_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "lsc/hid.h"
#include "../port/port_internal.h"

/* An open HID controller (opaque in lsc/hid.h). */
struct lsc_hid {
    void *dev;                      /* hid_device *, NULL when closed */
    int lock_fd;                    /* the node, flock-ed; -1 when closed */
    int os_errno;
    uint32_t dropped;               /* input reports without a frame */
    uint8_t pending[LSC_HID_REPORT_SIZE]; /* a frame not yet handed to read */
    size_t pending_off, pending_len;
    char path[LSC_HID_PATH_MAX];
    char message[LSC_HID_MESSAGE_MAX];
};

/* A node as identified, and the file it was (for the check after the open). */
typedef struct lsc_hid_node {
    char path[LSC_HID_PATH_MAX]; /* the node, every symlink resolved */
    uint16_t bus, vid, pid;      /* from HID_ID in sysfs (bus 3 is USB) */
    dev_t dev, rdev;             /* stat of path */
    ino_t ino;
    mode_t type;                 /* st_mode & S_IFMT */
} lsc_hid_node;

/* The HID bus type of USB (linux/input.h BUS_USB). */
#define LSC_HID_BUS_USB 0x0003u

/* Identifies path: resolves its symlinks, then requires a character device
 * whose sysfs entry, SYSFS_ROOT/sys/dev/char/MAJ:MIN, has the subsystem
 * hidraw and a device/uevent with HID_ID=BUS:VID:PID (hex) on the USB bus.
 * sysfs_root "" is the system's. Opens no device node (opening one can have
 * effects: a serial port resets an Arduino). Returns 0 and fills *node, or
 * LSC_ENODEV recorded on e naming `shown` (the path as the caller gave it):
 * no such file, not a character device (a regular file, a directory, a FIFO,
 * a socket, a block device), not of the hidraw class, its ids unreadable, not
 * on USB; LSC_EACCES when a directory on the way cannot be searched; LSC_EINVAL
 * for a resolved path longer than LSC_HID_PATH_MAX - 1. Only Linux has the
 * sysfs these checks read: elsewhere every node is refused (LSC_ENODEV). */
int lsc_hid_node_identify(const char *sysfs_root, const char *path, const char *shown,
                          lsc_hid_node *node, lsc_port_error *e);

/* lsc_hid_node_identify with the system's sysfs (hid_live.c; see the top). */
int lsc_hid_node_identify_live(const char *path, lsc_hid_node *node, lsc_port_error *e);

/* Accepts a node identified as above when its USB ids are a known controller
 * (lsc_hid_is_known) or extra_vid:extra_pid (0:0: none). Returns 0, or
 * LSC_ENODEV recorded on e naming `shown` and the ids. */
int lsc_hid_node_accept(const lsc_hid_node *node, uint16_t extra_vid, uint16_t extra_pid,
                        const char *shown, lsc_port_error *e);

/* True if vid:pid names ids to accept besides the known ones (not 0:0, not
 * known) (hid_ids.c). */
bool lsc_hid_is_extra(uint16_t vid, uint16_t pid);

/* The known ids and extra_vid:extra_pid (when not 0:0 and not known) as text
 * for a message, "0483:5750" or "0483:5750 or 1234:5678", into out (cap
 * bytes, NUL-terminated, cut to fit). Defined in hid_ids.c beside the table. */
void lsc_hid_known_text(char *out, size_t cap, uint16_t extra_vid, uint16_t extra_pid);

/* 0 if the open descriptor fd is the file node describes (same device,
 * inode, type and device number), else LSC_ENODEV recorded on e: the node
 * was replaced between the check and the open. */
int lsc_hid_node_same(const lsc_hid_node *node, int fd, const char *shown, lsc_port_error *e);

#endif
