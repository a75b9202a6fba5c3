/* lscctl: the connection to a controller, over the library's device layer
 * (lsc/device.h): opening the port of --port, the -v trace, and each error
 * of the device as one line on stderr with lscctl's hints (its options) and
 * an exit code. Every function that fails has already printed that line and
 * returns the exit code to use. */
#ifndef LSCCTL_PORT_H
#define LSCCTL_PORT_H

#include "lsc/device.h"
#include "lscctl.h"

typedef struct lscctl_link lscctl_link;

/* Opens o->port: "sim", a device path, hid, hid:SERIAL, or (NULL) the one
 * controller present, with --baud and --timeout. Returns 0 and *out, or an
 * exit code. */
int lscctl_link_open(const lscctl_opts *o, lscctl_link **out);
void lscctl_link_close(lscctl_link *l);

/* The device under the link, for the lsc_device_* calls. */
lsc_device *lscctl_link_device(lscctl_link *l);

/* The result r of an lsc_device_* call on the link's device: 0 when r >= 0,
 * else the exit code after printing the device's error with lscctl's hints
 * (EINVAL 2, ETIMEOUT 3, EBUSY 4, any other 1). */
int lscctl_link_check(lscctl_link *l, int r);

/* The commands without a reply (for play and record, lscctl_play.c). Each
 * returns 0 or an exit code (after printing why). */
int lscctl_link_move(lscctl_link *l, uint16_t time_ms, const lsc_servo *servos, size_t n);
int lscctl_link_run(lscctl_link *l, uint8_t group, uint16_t times);
int lscctl_link_unload(lscctl_link *l, const uint8_t *ids, size_t n);

/* move --wait: lets the move's time_ms pass, then reads the servos until
 * each is within tolerance of its target: exit 3 if that takes more than
 * --timeout after the move's time. A controller that does not answer
 * position reads (some LSC boards) ends the wait when the time has passed
 * (said with -v). */
int lscctl_link_settle(lscctl_link *l, const lsc_servo *targets, size_t n, uint16_t time_ms,
                        uint16_t tolerance);

/* For record and play (lscctl_play.c): the link's monotonic clock in ms (the
 * virtual controller's own with --port sim); a wait of up to ms that keeps
 * reading what arrives (0, or the exit code after printing why); and a
 * position read that returns 0, LSC_ETIMEOUT (no reply: nothing printed, so
 * that the caller can report it and retry) or the exit code after printing
 * why. */
uint32_t lscctl_link_now(lscctl_link *l);
int lscctl_link_idle(lscctl_link *l, uint32_t ms);
int lscctl_link_try_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out);

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
