/*
 * lsc text: the text helpers the library's messages and front ends share:
 * text from outside made safe for a one-line message, the protocol's command
 * names, and the grammar of a list of servos (ids, ranges, joints' names,
 * "all") that lscctl's arguments use.
 *
 * Host only (lsc_escape_text and lsc_device_cmd_name are portable, no
 * allocation).
 */
#ifndef LSC_TEXT_H
#define LSC_TEXT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/arm.h"
#include "lsc/core.h"
#include "lsc/device.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Text from outside (a file's name, an argument, a device's serial number)
 * made safe to repeat in a one-line message, by the rules of the library's
 * own messages (those of lsc_device_error, lsc/arm.h and lsc/files.h): writes
 * s[0..n) (up to a NUL byte, if one comes first) into out[cap]: printable
 * ASCII as it is, a backslash as \\, any other byte (control characters,
 * DEL, bytes >= 0x80) as \xNN with upper-case hex digits. Cut to fit, never in
 * the middle of an escape; out is NUL-terminated when cap > 0 (4 * n + 1
 * bytes always suffice). s may be NULL when n is 0. Returns the length
 * written (without the NUL). Portable, no allocation. */
LSC_API size_t lsc_escape_text(char *out, size_t cap, const char *s, size_t n);

/* The name of command cmd as the messages use it, the protocol's own
 * ("servo_move", "get_battery_voltage", ...), or "unknown". Never NULL. */
LSC_API const char *lsc_device_cmd_name(uint8_t cmd);

/* The short name of a kind of controller as front ends show it ("serial",
 * "hid", "sim", "lscd", "lx"), or "unknown" for a value no kind has. Never
 * NULL. */
LSC_API const char *lsc_device_kind_name(lsc_device_kind kind);

/* ---- Lists of servos ---------------------------------------------------------- */


/* The servos of a list given in one argument (lscctl record --ids): items
 * separated by commas, each a joint's name of arm (lsc/arm.h; arm may be
 * NULL: ids only), a servo id 0..255 (decimal or 0x-hex) or a range of ids
 * LO-HI, both ends included: "1-6", "1-3,8", "base,shoulder,3-4". Writes the
 * ids, in the order listed, to ids[0..cap). Returns their number (1..cap), or
 * LSC_EINVAL with why (whylen bytes, may be NULL: one line, the text from
 * list escaped as lsc_escape_text does) naming the item and the reason: an
 * empty list or item, an item that is no joint and no id (a negative id:
 * "id '-5' is negative: use 0..255"), a range without an end or whose end is
 * below its start ("the range 5-3 is empty"), a servo listed twice (by its
 * joint's name or its id: "servo 6 listed twice"), more than cap servos
 * ("more than 32 servos"); list or ids NULL, or cap 0. Time: linear in the
 * list's length (each servo at most once). */
LSC_API int lsc_device_parse_ids(const lsc_arm *arm, const char *list, uint8_t *ids, size_t cap,
                                 char *why, size_t whylen);

/* The servos "all" stands for, into ids[0..cap): the arm profile's joints
 * (arm non-NULL), in the profile's order; else every id the board kind has:
 * 1..6 on a HID controller (the xArm, the LeArm: six servos; "hid",
 * "hid:SERIAL", a hidraw node, and lscd serving one: "lscd:hid",
 * "lscd:hid-SERIAL") and on a bus of servos (an xArm's: "lx:PATH", "lx:sim",
 * and lscd serving one: "lscd:lx-NAME"), 1..32 on anything else (a serial port: the channels of
 * the largest LSC board, the LSC-32; "sim"; lscd serving a serial port).
 * name is the controller's name as lsc_device_open takes it (NULL: $LSC_PORT).
 * Returns how many (may exceed cap: then only cap are written), or
 * LSC_ENODEV when name is NULL, $LSC_PORT is unset and there is no arm
 * (discovery decides the kind: lsc_device_all_ids of lsc_device_name after
 * the open), LSC_EINVAL (ids NULL with cap > 0). */
LSC_API int lsc_device_all_ids(const lsc_arm *arm, const char *name, uint8_t *ids, size_t cap);

/* A list of servos as lsc_device_parse_ids takes it (arm may be NULL), or
 * "all" alone: lsc_device_all_ids(arm, name). Returns the count, or
 * LSC_EINVAL with why as lsc_device_parse_ids ("all" more than cap servos
 * too), or LSC_ENODEV for "all" when the kind is not known before the open
 * (name NULL, $LSC_PORT unset, no arm: parse it again with the name
 * lsc_device_name gives after the open). */
LSC_API int lsc_device_parse_ids_all(const lsc_arm *arm, const char *name, const char *list,
                                     uint8_t *ids, size_t cap, char *why, size_t whylen);

#ifdef __cplusplus
}
#endif

#endif /* LSC_TEXT_H */
