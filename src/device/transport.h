/* lsc device: the transport table (private). One const entry per kind of
 * controller (transport_serial.c, transport_hid.c, transport_sim.c,
 * transport_lscd.c, transport_lx.c) holds what differs per kind; everything else under the
 * device is the same for every kind and never asks which kind it has. A new
 * kind is one file and one entry: its open, its close, and the ops of the
 * board it talks to (the boards that speak the LSC protocol share
 * lsc_dev_board_ops, one implementation over the client in link.c). One
 * more entry, which no name selects, is a device's while its port is closed
 * (reopen.c: lsc_device_close_port, a failed lsc_device_reopen): its calls
 * find nothing there. */
#ifndef LSC_DEVICE_TRANSPORT_H
#define LSC_DEVICE_TRANSPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"

/* The board's commands. Each is called after the device checked its
 * arguments (lsc_dev_begin, counts, repeats, the arm's limits, the entry's
 * bound). Send-only ones return 0 or the link's error (the device writes the
 * line); requests (one try, on the device's timeout) the count or the link's
 * error. NULL: the kind has no such thing: the call is refused (LSC_EINVAL,
 * "... has no ...; nothing was sent"), except halt: NULL is the shared one
 * (stop the group when the kind has groups, then hold where they are). */
typedef struct lsc_dev_ops {
    int (*move)(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n);
    int (*unload)(lsc_device *d, const uint8_t *ids, size_t n);
    int (*adjust_offset)(lsc_device *d, uint8_t id, int8_t offset);
    int (*run)(lsc_device *d, uint8_t group, uint16_t times);
    int (*stop)(lsc_device *d);
    int (*speed)(lsc_device *d, uint8_t group, uint16_t percent);
    int (*battery)(lsc_device *d, uint16_t *millivolts);
    int (*read_positions)(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out);
    int (*read_offsets)(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo_offset *out);
    /* its own line on failure */
    int (*halt)(lsc_device *d);
} lsc_dev_ops;

/* The board commands of the LSC protocol over d->client (link.c). */
extern const lsc_dev_ops lsc_dev_board_ops;
int lsc_dev_board_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n);
int lsc_dev_board_unload(lsc_device *d, const uint8_t *ids, size_t n);
int lsc_dev_board_adjust_offset(lsc_device *d, uint8_t id, int8_t offset);
int lsc_dev_board_run(lsc_device *d, uint8_t group, uint16_t times);
int lsc_dev_board_stop(lsc_device *d);
int lsc_dev_board_speed(lsc_device *d, uint8_t group, uint16_t percent);
int lsc_dev_board_battery(lsc_device *d, uint16_t *millivolts);
int lsc_dev_board_read_positions(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out);
int lsc_dev_board_read_offsets(lsc_device *d, const uint8_t *ids, size_t n,
                               lsc_servo_offset *out);
/* An lsc_dev_ops initializer: the board's commands above, with halt_fn as
 * its halt (NULL: the shared one). lsc_dev_board_ops is
 * LSC_DEV_BOARD_OPS(NULL); a kind that reaches a board but halts its own way
 * (lscd) uses it with its halt. */
#define LSC_DEV_BOARD_OPS(halt_fn)                                                                 \
    {                                                                                              \
        .move = lsc_dev_board_move, .unload = lsc_dev_board_unload,                                \
        .adjust_offset = lsc_dev_board_adjust_offset, .run = lsc_dev_board_run,                    \
        .stop = lsc_dev_board_stop, .speed = lsc_dev_board_speed,                                  \
        .battery = lsc_dev_board_battery, .read_positions = lsc_dev_board_read_positions,          \
        .read_offsets = lsc_dev_board_read_offsets, .halt = (halt_fn),                             \
    }

/* One kind of controller. Optional members may be NULL (said for each). */
typedef struct lsc_dev_transport {
    lsc_device_kind kind; /* lsc_device_kind_of's answer */
    /* Whether name is this kind's (lsc_dev_transport_of asks the entries in
     * turn; the last, serial, takes every name). NULL, and open NULL, only
     * for the closed port's entry, which no name selects. */
    bool (*claims)(const char *name);
    /* Opens name into d: sets d->state (the kind's own: a transport's
     * handle, or memory from lsc_dev_state_alloc) and d->port. 0, or an
     * error after its line (close is called after a failure too). An open
     * may hand d over to another entry (a busy serial port held by lscd). */
    int (*open)(lsc_device *d, const char *name);
    /* Closes and frees d->state (NULL after a failed allocation). */
    void (*close)(lsc_device *d);
    /* lsc_device_fileno: the descriptor that polls readable when something
     * is to be read (-1: none). */
    int (*fileno)(const lsc_device *d);
    /* The transport's own line for its last failure ("" if none). NULL
     * only when link_fail says every failure (the closed port's entry). */
    const char *(*message)(const lsc_device *d);
    /* Optional: input the transport holds that no descriptor tells of. */
    bool (*held)(const lsc_device *d);
    /* Optional: ms until the controller sends something of its own accord
     * (a model's next event); NULL: LSC_DEVICE_FOREVER. */
    uint32_t (*next_event_ms)(const lsc_device *d);
    /* Optional: called before lsc_device_poll(d, 0) reads what arrived. */
    void (*before_ready)(lsc_device *d);
    /* Optional: nothing can arrive that has not already (a wait reads what
     * is there and does not wait). */
    bool (*quiet)(const lsc_device *d);
    /* Optional: LSC_ETIMEOUT after its line when a wait that brought nothing
     * can never bring what it waits for (timeout_ms: the wait's); else 0. */
    int (*hopeless)(lsc_device *d, uint32_t timeout_ms);
    /* Optional: a bound of its own on `what` of n servos (a move, a hold,
     * keyframes): 0, or LSC_EINVAL after its line ("...advice; nothing was
     * sent"). */
    int (*bound)(lsc_device *d, size_t n, const char *what, const char *advice);
    /* Optional: the line for a link error err it says more of than the
     * common one (0: the common one). */
    int (*link_fail)(lsc_device *d, int err);
    /* Optional: the line for a request that timed out with nothing at all
     * arriving (NULL: the common one, which names the port's baud rate). */
    int (*silence)(lsc_device *d);
    /* Optional: the timeout changed (lsc_device_set_timeout). */
    void (*set_timeout)(lsc_device *d, uint32_t timeout_ms);
    /* Optional: halts told by others since the open (a play ends at one);
     * NULL: 0. */
    uint32_t (*halts)(const lsc_device *d);
    /* Optional: the device's arm profile changed (NULL: none now). */
    void (*arm_set)(lsc_device *d, const lsc_arm *arm);
    /* The ids "all" stands for on the controller name names: 1..N. */
    size_t (*all_ids)(const char *name);
    const lsc_dev_ops *ops;
    unsigned first_retries; /* times the first request of the open is sent again */
    uint32_t restart_grace_ms; /* how long a group's restart after a stop may take */
    bool line_baud; /* the open's baud rate is the line's (the player models it) */
    const char *name; /* the kind as lines name it: "the virtual controller (sim)" */
    /* Optional: the open's baud rate when none is given (0: LSC_SERIAL_BAUD_DEFAULT). */
    uint32_t baud;
    /* Optional: why a kind without a battery reading has none, and where to
     * look instead (NULL: the common line). */
    const char *no_battery;
    /* Optional: a whole frame of the LSC protocol given to
     * lsc_device_send_frame (its shape checked), on a kind that does not speak
     * that protocol: done as the call it stands for, or refused after its
     * line. NULL: the frame is written as it is. */
    int (*send_frame)(lsc_device *d, const uint8_t *frame, size_t n);
} lsc_dev_transport;

extern const lsc_dev_transport lsc_dev_transport_serial;
extern const lsc_dev_transport lsc_dev_transport_hid;
extern const lsc_dev_transport lsc_dev_transport_sim;
extern const lsc_dev_transport lsc_dev_transport_lscd;
extern const lsc_dev_transport lsc_dev_transport_lx;

/* The entry name selects (device.c: the one place that decides). */
const lsc_dev_transport *lsc_dev_transport_of(const char *name);

/* all_ids of a LSC board: the channels of the largest, the LSC-32 (32);
 * of the xArm's and the LeArm's HID boards: their servos (6); of a bus of
 * servos: 1..6, an xArm's servos. */
#define DEVICE_BOARD_IDS 32u
#define DEVICE_HID_IDS 6u
#define DEVICE_LX_IDS 6u

/* d->state = size zeroed bytes: 0, or LSC_ENOSPC after its line (device.c). */
int lsc_dev_state_alloc(lsc_device *d, size_t size);

/* The cause of a transport's failed open r: ACCESS when it was denied. */
lsc_device_cause lsc_dev_open_cause(int r);

/* name is longer than most bytes: its start, escaped, and the limit
 * (LSC_EINVAL after the line). */
int lsc_dev_too_long(lsc_device *d, const char *name, const char *what, unsigned most);

/* lscd at sock (a name or path) takes d over: d's entry is closed and d
 * becomes lscd's. 0, or the open's error (d untouched); its message goes to
 * why[cap] unless it is LSC_ENODEV (nobody there) (transport_lscd.c). */
int lsc_dev_lscd_take_over(lsc_device *d, const char *sock, char *why, size_t cap);

/* The open of a serial port (for the device name: a port's path, or a bus's
 * lx:PATH) failed with r: when busy, the port may be held by lscd, and then
 * its socket is the way in, the one of its NAME in lscd's directory or the
 * one its record names (lsc_lscd_recorded_socket; a serial port's path only:
 * lscd records no bus): d is taken over (0);
 * LSC_EBUSY with the line of which lscd holds it and why its socket cannot be
 * used; otherwise r with the serial layer's line (transport_lscd.c). */
int lsc_dev_serial_open_failed(lsc_device *d, int r, const char *name);

#endif
