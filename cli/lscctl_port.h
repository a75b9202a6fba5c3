/* lscctl: the connection to a controller (a serial port or the built-in
 * virtual controller), with -v tracing. Every function that fails has
 * already printed one line on stderr and returns the exit code to use. */
#ifndef LSCCTL_PORT_H
#define LSCCTL_PORT_H

#include "lsc/client.h"
#include "lscctl.h"

typedef struct lscctl_link lscctl_link;

/* Opens o->port: "sim", a device path, or (NULL) the one port that looks
 * like a controller. Returns 0 and *out, or an exit code. */
int lscctl_link_open(const lscctl_opts *o, lscctl_link **out);
void lscctl_link_close(lscctl_link *l);

/* The commands without a reply, sent through the client (traced with -v).
 * Each returns 0 or an exit code (after printing why). */
int lscctl_link_move(lscctl_link *l, uint16_t time_ms, const lsc_servo *servos, size_t n);
int lscctl_link_run(lscctl_link *l, uint8_t group, uint16_t times);
int lscctl_link_stop(lscctl_link *l);
int lscctl_link_speed(lscctl_link *l, uint8_t group, uint16_t percent);
int lscctl_link_unload(lscctl_link *l, const uint8_t *ids, size_t n);
/* A raw frame: command cmd with n parameter bytes (send; 8 only with --force,
 * which the caller checked). */
int lscctl_link_send(lscctl_link *l, uint8_t cmd, const uint8_t *params, size_t n);

/* move --wait: lets the move's time_ms pass, then reads the servos until
 * each is within tolerance of its target: exit 3 if that takes more than
 * o->timeout_ms after the move's time. A controller that does not answer
 * position reads (some LSC boards) ends the wait when the time has passed. */
int lscctl_link_settle(lscctl_link *l, const lsc_servo *targets, size_t n, uint16_t time_ms,
                       uint16_t tolerance);

/* The xArm's servo offsets (23, 24); a timeout says LSC boards may not answer. */
int lscctl_link_read_offsets(lscctl_link *l, const uint8_t *ids, size_t n,
                             lsc_servo_offset *out);
int lscctl_link_adjust_offset(lscctl_link *l, uint8_t id, int8_t offset);

/* Requests and waits (o->timeout_ms) for the battery voltage / positions. */
int lscctl_link_battery(lscctl_link *l, uint16_t *millivolts);
int lscctl_link_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out);

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
 * of a group that ran before it does not count. At most
 * o->timeout_ms if --timeout was given, else without limit. */
int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out);

/* Calls fn for each notification until it returns false. Without --timeout
 * it waits without limit; with it, exit 3 after that long with none. */
int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user);

/* Prints the serial ports (text or JSON). */
int lscctl_list_ports(const lscctl_opts *o);

#endif
