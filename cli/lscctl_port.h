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

/* Sends one whole frame as it is (any command: send --force may send 8). */
int lscctl_link_send(lscctl_link *l, const uint8_t *frame, size_t n);

/* Requests and waits (o->timeout_ms) for the battery voltage / positions. */
int lscctl_link_battery(lscctl_link *l, uint16_t *millivolts);
int lscctl_link_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out);

/* Waits for the end of an action group (any group, or `group`): at most
 * o->timeout_ms if --timeout was given, else without limit. */
int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out);

/* Calls fn for each notification until it returns false. Without --timeout
 * it waits without limit; with it, exit 3 after that long with none. */
int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user);

/* Prints the serial ports (text or JSON). */
int lscctl_list_ports(const lscctl_opts *o);

#endif
