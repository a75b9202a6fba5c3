/* A test double of the hidapi functions the HID transport calls (tests only:
 * linked into a test program in place of libhidapi-hidraw, whose definitions
 * it takes precedence over). Each device is an xArm (0483:5750, "LOBOT")
 * backed by the project's virtual controller (src/sim) on a virtual clock,
 * with the report rules of the real link (docs/protocol.md, docs/hid.md):
 *  - hid_write must be 65 bytes, 0x00 first; the frame is taken from the
 *    payload by its LEN and fed to the controller (else: -1, as a USB stack
 *    refusing a report of the wrong size would);
 *  - each frame the controller sends is one 64-byte input report, padded
 *    with the device's padding byte (0x00 like a real arm, or any other to
 *    prove the padding is ignored);
 *  - hid_read_timeout returns a report when one is due within the timeout
 *    (the virtual clock jumps there); when one is due later it returns 0
 *    at once, the virtual clock moved on by the timeout (the arm runs
 *    faster than real time); when nothing will ever come it blocks for the
 *    timeout in real time and returns 0, as a silent device would.
 * The device's node is a real file (its path), so the transport's flock on
 * it is real. The double also stands in for the transport's node check
 * (lsc_hid_node_identify_live, src/hid/hid_internal.h): a device's path
 * passes as a hidraw node on USB with the device's ids (0483:5750 unless
 * set); every other path gets the real checks, against the system's sysfs. Devices come from hid_double_add, or, at the first call, from
 * $LSC_HID_DOUBLE (for lscctl):
 *   LSC_HID_DOUBLE="PATH|SERIAL|FLAGS;..."   FLAGS: words joined by ','
 *     deny         hid_open_path fails with EACCES
 *     mute-first   the first frame written is not answered
 *     notify       every reply is preceded by a notification report (7)
 *     garbage      every reply is preceded by a report that holds no frame
 *     unplug       after the first frame written, reads and writes fail (-1)
 *     silent       hid_open_path fails with errno 0 and hid_error "Success"
 *     pad=HH       padding byte (hex)
 *     run=G        group G is started at open (6, then its 8 on completion)
 *     id=VVVV:PPPP USB ids (hex) in place of 0483:5750
 * $LSC_HID_DOUBLE_LOG, if set, names a file each written report is appended
 * to as one line of hex. */
#ifndef LSC_TEST_HID_DOUBLE_H
#define LSC_TEST_HID_DOUBLE_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/sim.h"

#define HID_DOUBLE_DENY 0x01u
#define HID_DOUBLE_MUTE_FIRST 0x02u
#define HID_DOUBLE_NOTIFY 0x04u
#define HID_DOUBLE_GARBAGE 0x08u
#define HID_DOUBLE_UNPLUG 0x10u
#define HID_DOUBLE_SILENT 0x20u /* hid_open_path fails, errno 0, hid_error "Success" */

/* Forgets every device (open handles must be closed first). */
void hid_double_reset(void);
/* Adds a device; returns its index, or -1 if there is no room. */
int hid_double_add(const char *path, const char *serial, unsigned flags, uint8_t pad);
/* Sets device index's flags (HID_DOUBLE_...) from now on. */
void hid_double_set_flags(int index, unsigned flags);
/* Sets device index's USB ids (listing, hid_open, the node check). */
void hid_double_set_ids(int index, uint16_t vid, uint16_t pid);
/* hid_open_path calls since the last reset (refused ones too). */
unsigned hid_double_open_calls(void);
/* The device's virtual controller while it is open (else NULL). */
lsc_sim *hid_double_sim(int index);
/* The last report written (65 bytes; returns its length, 0 if none) and the
 * number of reports written, over all devices. */
size_t hid_double_last_write(uint8_t *out, size_t cap);
unsigned hid_double_writes(void);
/* hid_init calls minus hid_exit calls, and handles open now. */
int hid_double_inits(void);
int hid_double_open_handles(void);

#endif
