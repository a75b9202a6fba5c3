/* lscctl: the connection to a controller, over the library's device layer
 * (lsc/device.h): opening the port of --port, the -v trace, and each error
 * of the device as one line on stderr with lscctl's hints (its options) and
 * an exit code. Every function that fails has already printed that line and
 * returns the exit code to use. */
#ifndef LSCCTL_PORT_H
#define LSCCTL_PORT_H

#include "lsc/device.h"
#include "lsc/motion.h"
#include "lscctl.h"

typedef struct lscctl_link lscctl_link;

/* Opens o->port: "sim", a device path, hid, hid:SERIAL, or (NULL) the one
 * controller present, with --baud and --timeout. Returns 0 and *out, or an
 * exit code. */
int lscctl_link_open(const lscctl_opts *o, lscctl_link **out);
/* The arm profile of --arm or $LSC_ARM on d (none without one; on "sim" the
 * virtual controller then stands in for the arm). Returns 0 or the exit code
 * after saying why. */
int lscctl_set_arm(const lscctl_opts *o, lsc_device *d);
void lscctl_link_close(lscctl_link *l);

/* The device under the link, for the lsc_device_* calls. */
lsc_device *lscctl_link_device(lscctl_link *l);
/* The options the link was opened with. */
const lscctl_opts *lscctl_link_opts(const lscctl_link *l);

/* The result r of an lsc_device_* call on the link's device: 0 when r >= 0,
 * else the exit code after printing the device's error with lscctl's hints
 * (EINVAL 2, ETIMEOUT 3, EBUSY 4, any other 1). */
int lscctl_link_check(lscctl_link *l, int r);

/* The commands without a reply that need more than lscctl_link_check: run
 * (the group is kept for the wait's messages) and unload (record). Each
 * returns 0 or an exit code (after printing why). */
int lscctl_link_run(lscctl_link *l, uint8_t group, uint16_t times);
int lscctl_link_unload(lscctl_link *l, const uint8_t *ids, size_t n);

/* A move of n servos is refused before a port opens when --port (or
 * $LSC_PORT) names a HID controller and n is more than one HID report holds
 * (LSC_DEVICE_HID_MOVE_MAX: lsc_device_kind_of_name decides what a name
 * selects); what (may be "") starts the message, e.g. the file's name. No
 * port given: the device checks it after discovery. Returns 0 or exit 2
 * after saying why. */
int lscctl_hid_move_bound(const lscctl_opts *o, size_t n, const char *what);

/* The baud rate the port is opened at: --baud, else the kind's own (what
 * lsc_device_open takes for 0: 115200 on a bus of servos, lx:PATH; else
 * 9600). */
unsigned long lscctl_baud(const lscctl_opts *o);

/* move --wait: lets the move's time_ms pass, then reads the servos until
 * each is within tolerance of its target or has stopped short of it
 * (lsc_device_settle_ex, LSC_SETTLE_STRICT with --strict): exit 3 if that
 * takes more than --timeout after the move's time. A controller that does
 * not answer position reads (some LSC boards) ends the wait when the time
 * has passed (said with -v). */
int lscctl_link_settle(lscctl_link *l, const lsc_servo *targets, size_t n, uint16_t time_ms,
                        uint16_t tolerance);

/* The outcome r of a wait of lsc_device_settle_ex (or of a call that ends
 * with one: lsc_device_reach), res what it saw: servos that stopped short
 * are said on stderr (--json: a "stopped" line on stdout), exit 0, or 3 when
 * that was an error (--strict); no reads is said with -v; else as
 * lscctl_link_check. */
int lscctl_link_settled(lscctl_link *l, int r, const lsc_settle_result *res);

/* Waits for the end of an action group: any group's, or (any false) the end
 * of `group` after the controller reported that it started (6), so the stop
 * of a group that ran before it does not count. At most --timeout if it was
 * given, else without limit. run --wait on a real port with stderr on a
 * terminal says once, after 3 s without the start, that the board may have
 * no such group. */
int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out);

/* Calls fn for each notification until it returns false. Without --timeout
 * it waits without limit; with it, exit 3 after that long with none. */
int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user);

/* Prints the serial ports and HID controllers (text or JSON). */
int lscctl_list_ports(const lscctl_opts *o);

#endif
