/* lsc device: the entry of "lx:PATH", a bus of serial bus servos on a
 * serial port or pseudo-terminal (a BusLinker, any USB-serial adapter wired
 * to the servos, lsc-sim --lx), at 115200 baud unless the open's baud rate
 * says otherwise; or of "lx:sim" and "lx:sim:IDS", a virtual bus of servos
 * in the process (lxsim.c), on the real clock. Its state: the port
 * (lsc/serial.h, or the virtual bus) and the bus client
 * (lsc/lxclient.h), which holds every check of the bus protocol. The board's
 * commands map onto the bus: a move is MOVE_TIME_WAIT_WRITE to each servo and
 * one broadcast MOVE_START (lsc_lxclient_move_together), a read is POS_READ
 * to each, unload turns torque off, a halt is one broadcast MOVE_STOP. A bus has no action groups, no battery
 * reading of a board and sends nothing of its own accord: those calls are
 * refused, and waits for notifications end at once (contract in
 * lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"
#include "lsc/arm.h"
#include "lsc/bus.h"
#include "lsc/lxbus.h"
#include "lsc/lxclient.h"
#include "lsc/units.h"
#include "lxsim.h"

#define LX_PREFIX "lx:"
#define LX_PREFIX_LEN 3u
#define LX_BAUD 115200u

typedef struct lx_state {
    lsc_serial *serial;
    lsc_dev_lxsim *sim; /* "lx:sim": the virtual bus instead of serial */
    lsc_lxclient bus;
    uint8_t failed_id;  /* the servo the last failed request asked */
    bool asking;        /* a request (not a write) failed */
} lx_state;

static lx_state *st(const lsc_device *d)
{
    return d->state;
}

/* ---- The bus client's transport: the device's own io (guarded writes,
 * interruptible reads), looked up at each call (it is set after the open) -- */

static int fwd_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_device *d = ctx;
    return d->io.write(d->io.ctx, data, n);
}

static int fwd_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_device *d = ctx;
    return d->io.read(d->io.ctx, buf, cap, timeout_ms);
}

/* (the port's clock, which d->io's is: set by the open, before d->io) */
static uint32_t fwd_now(void *ctx)
{
    lsc_device *d = ctx;
    return d->port.now_ms(d->port.ctx);
}

static void fwd_trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    lsc_device *d = user;
    if (d->trace != NULL) {
        d->trace(d->trace_user, dir, frame, n);
    }
}

/* ---- The entry -------------------------------------------------------------------- */

static bool claims(const char *name)
{
    return strncmp(name, LX_PREFIX, LX_PREFIX_LEN) == 0;
}

static int open_lx(lsc_device *d, const char *name)
{
    const char *path = name + LX_PREFIX_LEN;
    if (path[0] == '\0') {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "lx: needs the path of the bus's serial port, e.g. "
                            "lx:/dev/ttyUSB0");
    }
    if (strlen(path) >= LSC_SERIAL_PATH_MAX) {
        return lsc_dev_too_long(d, path, "a serial port's path", LSC_SERIAL_PATH_MAX - 1u);
    }
    int r = lsc_dev_state_alloc(d, sizeof(lx_state));
    if (r != 0) {
        return r;
    }
    lx_state *s = st(d);
    if (lsc_dev_lxsim_claims(path)) {
        r = lsc_dev_lxsim_open(d, path, &s->sim, &d->port);
        if (r != 0) {
            return r;
        }
    } else {
        r = lsc_serial_open(path, d->baud, LSC_SERIAL_AUTO, &s->serial);
        if (r != 0) { /* (held by lscd, lscd --port lx:PATH: through it) */
            return lsc_dev_serial_open_failed(d, r, name);
        }
        lsc_serial_get_io(s->serial, &d->port);
    }
    lsc_io io = {d, fwd_write, fwd_read, fwd_now};
    (void)lsc_lxclient_init(&s->bus, &io); /* (complete io: cannot fail) */
    lsc_lxclient_set_timeout(&s->bus, d->timeout_ms);
    lsc_lxclient_set_trace(&s->bus, fwd_trace, d);
    return 0;
}

static void close_lx(lsc_device *d)
{
    lx_state *s = st(d);
    if (s != NULL) {
        lsc_serial_close(s->serial);
        lsc_dev_lxsim_close(s->sim);
    }
    free(s);
    d->state = NULL;
}

static int lx_fileno(const lsc_device *d)
{
    const lx_state *s = st(d);
    return s->sim != NULL ? lsc_dev_lxsim_fileno(s->sim) : lsc_serial_fileno(s->serial);
}

static const char *message(const lsc_device *d)
{
    const lx_state *s = st(d);
    /* (the virtual bus takes every write: it fails only by timeouts and bad
     * replies, whose lines are the common ones) */
    return s->sim != NULL ? "the virtual bus (lx:sim) did not take the bytes"
                          : lsc_serial_error_message(s->serial);
}

static void set_timeout(lsc_device *d, uint32_t timeout_ms)
{
    lsc_lxclient_set_timeout(&st(d)->bus, timeout_ms);
}

/* A bus sends nothing unasked: a wait reads what is there and does not wait. */
static bool quiet(const lsc_device *d)
{
    (void)d;
    return true;
}

static int hopeless(lsc_device *d, uint32_t timeout_ms)
{
    (void)timeout_ms;
    return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_WAIT_TIMEOUT,
                        "%s is a bus of servos: it has no action groups and sends nothing of "
                        "its own accord, so there is nothing to wait for (settle waits for "
                        "servos by reading their positions)",
                        d->shown);
}

/* The lines of the bus for a request: which servo did not answer, or
 * answered garbled (a write's failure, and the port's: the common lines). */
static int link_fail(lsc_device *d, int err)
{
    const lx_state *s = st(d);
    if (!s->asking) {
        return 0;
    }
    if (err == LSC_ETIMEOUT) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NO_REPLY,
                            "no reply from servo %u on %s within %lu ms: check its id (lscctl "
                            "servo scan), its power and the baud rate (%lu); or raise the "
                            "timeout",
                            s->failed_id, d->shown, (unsigned long)d->timeout_ms,
                            (unsigned long)d->baud);
    }
    if (err == LSC_EREPLY) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NOISE,
                            "bad reply from servo %u on %s (a checksum that failed, or a value "
                            "out of range): two servos may share its id (lscctl servo scan), "
                            "or check the wiring and the baud rate (%lu)",
                            s->failed_id, d->shown, (unsigned long)d->baud);
    }
    return 0;
}

static size_t all_ids(const char *name)
{
    (void)name;
    return DEVICE_LX_IDS;
}

/* ---- The board's commands on a bus ------------------------------------------------ */

/* An argument the bus cannot carry: the line, LSC_EINVAL (nothing sent). */
static int out_of_range(lsc_device *d, const char *what, unsigned long value, unsigned long max)
{
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "%s %lu is out of range for bus servos (0..%lu); nothing was sent", what,
                        value, max);
}

static int lx_move(lsc_device *d, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    if (time_ms > LSC_LX_TIME_MAX) {
        return out_of_range(d, "a move's time (ms)", time_ms, LSC_LX_TIME_MAX);
    }
    for (size_t i = 0; i < n; i++) {
        if (servos[i].id > LSC_LX_ID_MAX) {
            return out_of_range(d, "servo id", servos[i].id, LSC_LX_ID_MAX);
        }
        if (servos[i].position > LSC_LX_POSITION_MAX) {
            return out_of_range(d, "position", servos[i].position, LSC_LX_POSITION_MAX);
        }
    }
    st(d)->asking = false;
    return lsc_lxclient_move_together(&st(d)->bus, servos, n, time_ms);
}

/* Torque off: to each of ids[0..n), or to every servo (n 0: the broadcast). */
static int lx_unload(lsc_device *d, const uint8_t *ids, size_t n)
{
    lx_state *s = st(d);
    s->asking = false;
    for (size_t i = 0; i < n; i++) {
        if (ids[i] > LSC_LX_ID_MAX) {
            return out_of_range(d, "servo id", ids[i], LSC_LX_ID_MAX);
        }
    }
    if (n == 0) {
        return lsc_lxclient_write_torque(&s->bus, LSC_LX_BROADCAST, false);
    }
    for (size_t i = 0; i < n; i++) {
        int r = lsc_lxclient_write_torque(&s->bus, ids[i], false);
        if (r != 0) {
            return r;
        }
    }
    return 0;
}

static int lx_adjust_offset(lsc_device *d, uint8_t id, int8_t offset)
{
    if (id > LSC_LX_ID_MAX) {
        return out_of_range(d, "servo id", id, LSC_LX_ID_MAX);
    }
    if (offset > LSC_LX_OFFSET_MAX || offset < -LSC_LX_OFFSET_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "offset %d is out of range for bus servos (-%d..%d); nothing was "
                            "sent",
                            offset, LSC_LX_OFFSET_MAX, LSC_LX_OFFSET_MAX);
    }
    st(d)->asking = false;
    return lsc_lxclient_adjust_offset(&st(d)->bus, id, offset);
}

/* ids checked before anything is asked: 0..253 and at least one. */
static int check_ids(lsc_device *d, const uint8_t *ids, size_t n)
{
    if (ids == NULL || n == 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "a read on a bus of servos names the servos to read; nothing was "
                            "sent");
    }
    for (size_t i = 0; i < n; i++) {
        if (ids[i] > LSC_LX_ID_MAX) {
            return out_of_range(d, "servo id", ids[i], LSC_LX_ID_MAX);
        }
    }
    return 0;
}

/* The bus client for a request to servo id: a failure's line names it. */
static lsc_lxclient *asking(lsc_device *d, uint8_t id)
{
    lx_state *s = st(d);
    s->asking = true;
    s->failed_id = id;
    return &s->bus;
}

/* POS_READ to each. A shaft a little below 0 (an offset, a hand) reads
 * negative: it is given as 0, the nearest position a move can command. */
static int lx_read_positions(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo *out)
{
    int r = check_ids(d, ids, n);
    for (size_t i = 0; i < n && r == 0; i++) {
        int16_t pos = 0;
        r = lsc_lxclient_read_position(asking(d, ids[i]), ids[i], &pos);
        out[i] = (lsc_servo){.id = ids[i], .position = pos < 0 ? 0u : (uint16_t)pos};
    }
    return r == 0 ? (int)n : r;
}

static int lx_read_offsets(lsc_device *d, const uint8_t *ids, size_t n, lsc_servo_offset *out)
{
    int r = check_ids(d, ids, n);
    for (size_t i = 0; i < n && r == 0; i++) {
        int8_t offset = 0;
        r = lsc_lxclient_read_offset(asking(d, ids[i]), ids[i], &offset);
        out[i] = (lsc_servo_offset){.id = ids[i], .offset = offset};
    }
    return r == 0 ? (int)n : r;
}

/* Halt: one broadcast MOVE_STOP, every servo stops where it is (a moving
 * one mid-way, one in motor mode too), whatever ids the bus has; nothing is
 * read. */
static int lx_halt(lsc_device *d)
{
    st(d)->asking = false;
    int r = lsc_lxclient_move_stop(&st(d)->bus, LSC_LX_BROADCAST);
    return r == 0 ? 0 : lsc_dev_link_fail(d, r);
}

/* A board's frame (a front end's: lscd forwards its clients' frames): a
 * move, an unload or an offset adjustment is done on the bus as the call it
 * stands for; a group's run, stop or speed is refused as those calls are
 * (a bus has no action groups); anything else is refused, nothing sent. */
static int lx_send_frame(lsc_device *d, const uint8_t *frame, size_t n)
{
    const lsc_frame f = {frame[3], (uint8_t)(n - 4u), frame + 4};
    lsc_servo servos[LSC_MOVE_MAX];
    uint8_t ids[UINT8_MAX + 1u], id = 0;
    uint16_t time_ms = 0;
    int8_t offset = 0;
    int r;
    switch (f.cmd) {
    case LSC_CMD_SERVO_MOVE:
        r = lsc_decode_servo_move(&f, &time_ms, servos, LSC_MOVE_MAX);
        if (r >= 0) {
            return lsc_device_move(d, time_ms, servos, (size_t)r);
        }
        break;
    case LSC_CMD_UNLOAD:
        r = lsc_decode_unload(&f, ids, sizeof ids);
        if (r >= 0) {
            return lsc_device_unload(d, ids, (size_t)r);
        }
        break;
    case LSC_CMD_OFFSET_ADJUST:
        r = lsc_decode_offset_adjust(&f, &id, &offset);
        if (r >= 0) {
            return lsc_device_adjust_offset(d, id, offset);
        }
        break;
    case LSC_CMD_GROUP_RUN:
    case LSC_CMD_GROUP_STOP:
    case LSC_CMD_GROUP_SPEED: /* (refused with their common line: a bus has no groups) */
        return lsc_device_stop(d);
    default:
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "%s is a bus of servos: a board's frame of command %u (%s) has no "
                            "meaning there (a bus takes moves, unloads and offset adjustments "
                            "as frames); nothing was sent",
                            d->shown, f.cmd, lsc_device_cmd_name(f.cmd));
    }
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "a malformed frame of command %u (%s) for %s; nothing was sent", f.cmd,
                        lsc_device_cmd_name(f.cmd), d->shown);
}

static const lsc_dev_ops lx_ops = {
    .move = lx_move,
    .unload = lx_unload,
    .adjust_offset = lx_adjust_offset,
    .read_positions = lx_read_positions,
    .read_offsets = lx_read_offsets,
    .halt = lx_halt,
    /* no action groups (run, stop, speed), no battery: refused */
};

lsc_lxclient *lsc_device_lxclient(lsc_device *d)
{
    return d != NULL && d->t == &lsc_dev_transport_lx ? &st(d)->bus : NULL;
}

lsc_lxbus *lsc_device_lxbus(lsc_device *d)
{
    lsc_lxclient *c = lsc_device_lxclient(d);
    return c != NULL && st(d)->sim != NULL ? lsc_dev_lxsim_bus(st(d)->sim) : NULL;
}

int lsc_device_lx_result(lsc_device *d, int r, const char *what, uint8_t id, int why)
{
    if (d == NULL || d->t != &lsc_dev_transport_lx || what == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (r >= 0) {
        return r;
    }
    if (r == LSC_EINVAL) { /* refused: nothing was written */
        return lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NONE, "%s on %s: %s", what, d->shown,
                            lsc_lx_refusal_str(why != LSC_LX_DONE ? (lsc_lx_refusal)why
                                                                  : LSC_LX_BAD_ARGUMENT));
    }
    (void)asking(d, id);
    r = lsc_dev_link_fail(d, r);
    if (why == LSC_LX_NOT_READ_BACK) {
        char line[DEVICE_MESSAGE_MAX];
        (void)snprintf(line, sizeof line, "%s", d->message);
        (void)lsc_dev_fail(d, r, d->cause, "%s on %s: %s: %s", what, d->shown,
                           lsc_lx_refusal_str(LSC_LX_NOT_READ_BACK), line);
    }
    return r;
}

/* ---- An arm's servo replaced -------------------------------------------------------- */

/* d's bus client after lsc_dev_begin, or NULL (d no bus, or arm NULL). */
static lsc_lxclient *arm_bus(lsc_device *d, const lsc_arm *arm)
{
    if (d == NULL || d->t != &lsc_dev_transport_lx || arm == NULL) {
        return NULL;
    }
    lsc_dev_begin(d);
    return &st(d)->bus;
}

int lsc_device_lx_replace(lsc_device *d, const lsc_arm *arm, const char *joint, uint8_t *old_id,
                          lsc_lx_refusal *why)
{
    lsc_lx_refusal unwanted;
    why = why != NULL ? why : &unwanted;
    *why = LSC_LX_BAD_ARGUMENT; /* (until the bus is asked) */
    lsc_lxclient *c = arm_bus(d, arm);
    if (c == NULL || joint == NULL) {
        return LSC_EINVAL;
    }
    char shown[4u * LSC_ARM_NAME_MAX + 1u], what[4u * LSC_ARM_NAME_MAX + 32u];
    (void)lsc_escape_text(shown, sizeof shown, joint, LSC_ARM_NAME_MAX);
    int i = lsc_arm_find(arm, joint);
    if (i < 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "the arm profile has no joint '%s'; nothing was written", shown);
    }
    const lsc_joint *j = lsc_arm_joint(arm, (size_t)i);
    uint16_t a = 0, b = 0, lo, hi;
    /* (a valid profile's limits lie within its servo's range: they convert) */
    (void)lsc_joint_to_pos(j, j->min_cdeg, &a);
    (void)lsc_joint_to_pos(j, j->max_cdeg, &b);
    lo = a < b ? a : b;
    hi = a < b ? b : a;
    if (hi > LSC_LX_POSITION_MAX || lo == hi) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "joint %s's limits (positions %u..%u) are no bus servo's angle "
                            "limits (0 <= min < max <= 1000); nothing was written",
                            shown, lo, hi);
    }
    (void)snprintf(what, sizeof what, "servo replace %s (servo %u)", shown, j->id);
    int r = lsc_lxclient_set_id_alone(c, j->id, 0, old_id, why); /* (it sets *why) */
    if (r == 0) {
        r = lsc_lxclient_write_limits(c, j->id, lo, hi);
    }
    if (r == 0) {
        r = lsc_lxclient_read_limits(c, j->id, &a, &b);
        *why = r == 0 && a == lo && b == hi ? LSC_LX_DONE : LSC_LX_NOT_READ_BACK;
    }
    if (r == 0 && *why != LSC_LX_DONE) {
        return lsc_dev_fail(d, LSC_EREPLY, LSC_DEVICE_CAUSE_NONE,
                            "%s on %s: its limits written as %u..%u read back as %u..%u", what,
                            d->shown, lo, hi, a, b);
    }
    return lsc_device_lx_result(d, r, what, j->id, (int)*why);
}

int lsc_device_lx_check_arm(lsc_device *d, const lsc_arm *arm)
{
    lsc_lxclient *c = arm_bus(d, arm);
    if (c == NULL) {
        return LSC_EINVAL;
    }
    size_t n = lsc_arm_count(arm);
    uint8_t ids[LSC_ARM_JOINTS_MAX];
    for (size_t i = 0; i < n; i++) {
        ids[i] = lsc_arm_joint(arm, i)->id;
        if (ids[i] > LSC_LX_ID_MAX) {
            return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                "joint %s is on servo %u: bus servos have 0..253; nothing was "
                                "sent",
                                lsc_arm_name(arm, i), ids[i]);
        }
    }
    lsc_lx_scan found;
    int r = lsc_lxclient_scan(c, ids, n, 0, &found);
    if (r < 0) {
        return lsc_device_lx_result(d, r, "the arm's scan", 0, LSC_LX_DONE);
    }
    for (size_t i = 0; i < n; i++) {
        if (lsc_lx_scan_garbled(&found, ids[i])) {
            return lsc_dev_fail(d, LSC_EREPLY, LSC_DEVICE_CAUSE_NONE,
                                "joint %s: the answers at servo %u on %s collide: two servos "
                                "share its id (connect one at a time: lscctl servo id NEW)",
                                lsc_arm_name(arm, i), ids[i], d->shown);
        }
        if (!lsc_lx_scan_found(&found, ids[i])) {
            return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_NO_REPLY,
                                "joint %s: no servo answers at id %u on %s: check that it is "
                                "connected and powered, and its id (lscctl servo scan)",
                                lsc_arm_name(arm, i), ids[i], d->shown);
        }
    }
    return (int)n;
}

const lsc_dev_transport lsc_dev_transport_lx = {
    .kind = LSC_DEVICE_LX,
    .claims = claims,
    .open = open_lx,
    .close = close_lx,
    .fileno = lx_fileno,
    .message = message,
    .quiet = quiet,
    .hopeless = hopeless,
    .link_fail = link_fail,
    .set_timeout = set_timeout,
    .all_ids = all_ids,
    .send_frame = lx_send_frame,
    .ops = &lx_ops,
    .restart_grace_ms = 0u, /* no groups */
    .line_baud = true,
    .baud = LX_BAUD,
    .no_battery = "a bus has no battery reading; a servo's supply voltage: lscctl servo info "
                  "ID",
    .name = "a bus of servos",
};

#endif
