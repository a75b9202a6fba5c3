/*
 * lsc HID transport (host only): the Hiwonder/LewanSoul xArm, LeArm and Bus
 * Servo Controller over USB HID, through hidapi's hidraw backend.
 *
 * The link (docs/protocol.md, "The USB HID link"): USB VID 0x0483, PID
 * 0x5750, product "LOBOT", a serial-number string per arm; no report IDs;
 * 64-byte reports. One frame per report both ways:
 *  - write: one whole frame per call (what lsc_client does), sent as a
 *    65-byte hid_write: 0x00 (no report ID), then the frame, zero-padded to
 *    64 bytes. A frame longer than 64 bytes (a move of more than 19 servos)
 *    is refused with LSC_EINVAL, and nothing is sent.
 *  - read: each input report holds one frame at offset 0; its length comes
 *    from LEN and the padding is ignored. Notifications (6, 7, 8) come as
 *    reports of their own and pass through to the client like replies. A
 *    report that holds no frame (no 55 55 header, or a LEN that does not fit
 *    the report) is dropped and counted (lsc_hid_reports_dropped).
 *
 * Which nodes: before hidapi sees a path, lsc_hid_open_path resolves its
 * symbolic links and requires a hidraw character device (Linux: stat, then
 * sysfs /sys/dev/char/MAJ:MIN: class hidraw) whose HID device is on USB with
 * a known controller's ids (HID_ID in its sysfs uevent; lsc_hid_known_ids:
 * 0483:5750), or the ids the caller names (lsc_hid_open_path_extra). Anything
 * else is refused with LSC_ENODEV before any open, hidapi's or lsc's, and so
 * before anything is written: a regular file, a directory, a FIFO, a socket,
 * a block device, /dev/null, a serial port, a keyboard's hidraw node. The
 * node is opened through its resolved path (the message then names it), and
 * the descriptor opened must be the file checked. lsc_hid_open_serial picks
 * among listed controllers and opens the path through the same checks. The
 * checks read Linux's sysfs: on other systems every path is refused.
 *
 * Exclusive access: hidraw has no TIOCEXCL, so the node (/dev/hidrawN) is
 * opened and flock(LOCK_EX|LOCK_NB)-ed beside hidapi's own descriptor; a
 * second opener, in this or another process, gets LSC_EBUSY ("port busy").
 *
 * Timing of real arms (observed by other programs, docs/protocol.md): a position read can
 * take ~450 ms to be answered, and the first request after the device is
 * opened can go unanswered. Use a reply timeout of at least 1000 ms (lscctl's
 * default) and send the first request again once if it timed out: lscctl
 * does exactly that over HID (LSC_HID_FIRST_RETRIES).
 *
 * Memory: an lsc_hid is opaque: the opens allocate it and lsc_hid_close
 * frees it (hidapi allocates while a device is open). Threads: one thread per
 * lsc_hid at a time; listing and opening call hidapi's hid_init, which is not
 * thread-safe.
 *
 * Errors: negative LSC_E... codes. After a failure the handle keeps the OS
 * errno (lsc_hid_os_errno, 0 if not an OS error) and a message naming the
 * device and the cause (lsc_hid_error_message); a failed open leaves no
 * handle, and its errno and message are the calling thread's:
 * lsc_hid_os_errno(NULL) and lsc_hid_error_message(NULL) say them until its
 * next open (LSC_ENOSPC: out of memory):
 *   LSC_EINVAL   bad argument; a frame that does not fit a report; several
 *                controllers and no serial number to choose; or this build
 *                has no HID support ("built without HID support")
 *   LSC_ENODEV   no such device, no controller present, or it went away (a
 *                read or write failed: unplugged); or the path is not a
 *                controller's node (not a hidraw character device, not on
 *                USB, ids neither known nor named: see "Which nodes"), and
 *                nothing was opened or sent
 *   LSC_EACCES   permission denied (the message names the fix: the udev rule
 *                of the lscctl package, the uaccess tag / plugdev group, and
 *                that fwupd can hold the node)
 *   LSC_EBUSY    the device is open elsewhere
 *   LSC_EIO      any other failure
 */
#ifndef LSC_HID_H
#define LSC_HID_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_HID_VID 0x0483u         /* the xArm's USB vendor id (STMicroelectronics) */
#define LSC_HID_PID 0x5750u         /* ... and product id ("LOBOT"); lsc_hid_known_ids */
#define LSC_HID_REPORT_SIZE 64u     /* payload bytes of a report (no report id) */
#define LSC_HID_PATH_MAX 256u
#define LSC_HID_STRING_MAX 128u
#define LSC_HID_MESSAGE_MAX 512u
#define LSC_HID_FIRST_RETRIES 1u    /* times lscctl resends a first request that timed out */

/* One HID controller as listed. Strings are UTF-8, "" when the device has
 * none. A struct that grows: fields are only ever added at the end (see
 * lsc_hid_list for its size). */
typedef struct lsc_hid_info {
    size_t size;                      /* sizeof(lsc_hid_info) in the caller's headers */
    char path[LSC_HID_PATH_MAX];      /* e.g. /dev/hidraw3 */
    char serial[LSC_HID_STRING_MAX];  /* the USB serial number */
    char product[LSC_HID_STRING_MAX]; /* "LOBOT" on an xArm */
    char manufacturer[LSC_HID_STRING_MAX];
    uint16_t vid, pid;
} lsc_hid_info;

/* A known controller's USB ids (lsc_hid_known_ids). */
typedef struct lsc_hid_id {
    uint16_t vid, pid;
    const char *what; /* the controllers with these ids, for messages */
} lsc_hid_id;

/* An open HID controller (opaque). */
typedef struct lsc_hid lsc_hid;

/* True if this build has the HID transport (hidapi). Without it every call
 * below fails with LSC_EINVAL and the message "built without HID support". */
LSC_API bool lsc_hid_available(void);

/* The USB ids of the known HID controllers: a read-only table of *count
 * entries (count may be NULL), the same for the life of the program. The
 * first is LSC_HID_VID:LSC_HID_PID (the xArm, LeArm and Bus Servo Controller,
 * product "LOBOT"). STMicroelectronics' 0483:5750 is also the id of its USB
 * HID examples: another STM32 gadget may carry it. */
LSC_API const lsc_hid_id *lsc_hid_known_ids(size_t *count);

/* True if vid:pid is in lsc_hid_known_ids. */
LSC_API bool lsc_hid_is_known(uint16_t vid, uint16_t pid);

/* Lists the HID devices with USB ids vid:pid (0:0 = those of every known
 * controller, in the order of lsc_hid_known_ids) into out[0..cap). The
 * caller sets out[0].size to sizeof(lsc_hid_info), the size of every
 * element and the array's stride: element i is written at
 * (char *)out + i * out[0].size, at most that many bytes of it, with its
 * size set to it. Returns how many exist (may exceed cap: only cap are
 * written), or a negative error; message (msgcap bytes, may be NULL) then
 * receives its text. out NULL with cap 0 only counts. A size below
 * offsetof(lsc_hid_info, path) + LSC_HID_PATH_MAX with cap > 0 is
 * LSC_EINVAL, nothing listed. Strings are truncated to fit, always
 * NUL-terminated. */
LSC_API int lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                         char *message, size_t msgcap);

/* Opens the device at path (as listed, e.g. /dev/hidraw3, or a symbolic
 * link to it), exclusively, once it passed the checks of "Which nodes" (a
 * known controller's ids), into *out. Returns 0 or an error with *out NULL
 * (nothing left open; lsc_hid_error_message(NULL) says why): a path that is
 * not a known controller's hidraw node is LSC_ENODEV, with nothing opened or
 * sent. */
LSC_API int lsc_hid_open_path(const char *path, lsc_hid **out);

/* lsc_hid_open_path that also accepts a node whose USB ids are vid:pid: a
 * controller the known table lacks (a clone, a new board), named by its
 * owner. 0:0 names none (lsc_hid_open_path); the ids hold for this call
 * only. Every other check stays. */
LSC_API int lsc_hid_open_path_extra(const char *path, uint16_t vid, uint16_t pid,
                                    lsc_hid **out);

/* Opens the known controller (lsc_hid_known_ids) whose serial number is
 * serial, or (serial NULL or "") the only one present: none is LSC_ENODEV,
 * several is LSC_EINVAL (the message lists their serial numbers). The path
 * found is opened as by lsc_hid_open_path. */
LSC_API int lsc_hid_open_serial(const char *serial, lsc_hid **out);

/* lsc_hid_open_serial among the known controllers and those with USB ids
 * vid:pid (0:0: none; see lsc_hid_open_path_extra). */
LSC_API int lsc_hid_open_serial_extra(const char *serial, uint16_t vid, uint16_t pid,
                                      lsc_hid **out);

/* Closes the device and frees h. h may be NULL. */
LSC_API void lsc_hid_close(lsc_hid *h);

/* Fills *io with the device's transport (write, read, now_ms as described at
 * the top; now_ms is CLOCK_MONOTONIC). Valid until h is closed. */
LSC_API void lsc_hid_get_io(lsc_hid *h, lsc_io *io);

/* The same functions, for callers that wrap them (ctx is the lsc_hid *). */
LSC_API int lsc_hid_write(void *ctx, const uint8_t *data, size_t n);
LSC_API int lsc_hid_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms);
LSC_API uint32_t lsc_hid_now_ms(void *ctx);

/* For a program's own event loop (hidapi keeps its descriptor to itself):
 * the descriptor of the node that the open locks (flock), or -1 for NULL. The kernel's hidraw driver gives every open
 * descriptor of a node its own copy of each input report, so it polls
 * readable when a report arrived, and POLLHUP or POLLERR when the device
 * went away. The reports themselves are read through lsc_hid_read: call
 * lsc_hid_fileno_drain first, then lsc_hid_read until it returns 0; a report
 * that comes later makes the descriptor readable again (one that comes in
 * between may make it readable once with nothing left to read). */
LSC_API int lsc_hid_fileno(const lsc_hid *h);
/* Reads away the copies that made lsc_hid_fileno readable (at most 256; no
 * waiting); returns how many were read, 0 for NULL. */
LSC_API int lsc_hid_fileno_drain(lsc_hid *h);
/* True when part of a frame already received waits for lsc_hid_read (a
 * read with less room than the frame): no descriptor tells of it. */
LSC_API bool lsc_hid_input_pending(const lsc_hid *h);

/* The last error's message ("" if none). Never NULL; h NULL: the calling
 * thread's last open's ("" after one that succeeded). */
LSC_API const char *lsc_hid_error_message(const lsc_hid *h);
/* The last error's OS errno (0 if none or not an OS error); h NULL: the
 * calling thread's last open's. */
LSC_API int lsc_hid_os_errno(const lsc_hid *h);
/* Input reports dropped because they held no frame, since the open. */
LSC_API uint32_t lsc_hid_reports_dropped(const lsc_hid *h);

#ifdef __cplusplus
}
#endif

#endif /* LSC_HID_H */
