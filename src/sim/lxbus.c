/* The virtual bus of serial bus servos (include/lsc/lxbus.h has the
 * contract); its text form is in lxbus_state.c. */
#include "lsc/lxbus.h"

#include <limits.h>
#include <string.h>

#include "lxbus_internal.h"

/* ---- Output ---------------------------------------------------------------- */

static void emit(lsc_lxbus *bus, lsc_sim_event_kind kind, const uint8_t *bytes, size_t len,
                 const char *text)
{
    if (bus->log != NULL) {
        lsc_sim_event ev;
        ev.kind = kind;
        ev.time_us = bus->now_us;
        ev.bytes = bytes;
        ev.len = len;
        ev.text = text;
        bus->log(bus->log_ctx, &ev);
    }
}

static uint64_t add_sat(uint64_t a, uint64_t b)
{
    return (b >= LSC_LXBUS_TIME_NEVER - 1u - a) ? LSC_LXBUS_TIME_NEVER - 1u : a + b;
}

/* Wire time of k bytes, rounded up to whole microseconds. */
static uint64_t wire_us(uint32_t baud, uint64_t k)
{
    return baud == 0u ? 0u : (k * 10000000u + baud - 1u) / baud;
}

/* Queues n bytes; byte k readable at at + wire time of k + 1 bytes (paced),
 * or at `at` (not). The caller checked there is room. */
static void push(lsc_lxbus *bus, const uint8_t *bytes, size_t n, uint64_t at, bool paced)
{
    for (size_t k = 0; k < n; k++) {
        size_t slot = (bus->out_head + bus->out_len) % LSC_LXBUS_OUT_BYTES;
        bus->out[slot] = bytes[k];
        bus->out_at[slot] = paced ? add_sat(at, wire_us(bus->baud, k + 1u)) : at;
        bus->out_len++;
    }
}

/* Queues a reply of n bytes, after the faults. */
static void send_reply(lsc_lxbus *bus, uint8_t *frame, size_t n)
{
    if (bus->fault_drop > 0u) {
        bus->fault_drop--;
        bus->stats.dropped++;
        emit(bus, LSC_SIM_EV_DROPPED, frame, n, "reply dropped (fault injection)");
        return;
    }
    if (LSC_LXBUS_OUT_BYTES - bus->out_len < n) {
        bus->stats.overflow++;
        emit(bus, LSC_SIM_EV_DROPPED, frame, n, "output queue full");
        return;
    }
    if (bus->fault_corrupt > 0u) {
        size_t at = bus->fault_corrupt_offset < n ? bus->fault_corrupt_offset : n - 1u;
        bus->fault_corrupt--;
        frame[at] = (uint8_t)(frame[at] ^ bus->fault_corrupt_xor);
    }
    uint64_t due = add_sat(bus->now_us, (uint64_t)bus->fault_delay_ms * 1000u);
    if (due < bus->line_free_us) {
        due = bus->line_free_us;
    }
    push(bus, frame, n, due, true);
    bus->line_free_us = add_sat(due, wire_us(bus->baud, n));
    bus->stats.frames_out++;
    emit(bus, LSC_SIM_EV_TX, frame, n, NULL);
}

size_t lsc_lxbus_available(const lsc_lxbus *bus)
{
    size_t n = 0;
    if (bus == NULL) {
        return 0;
    }
    while (n < bus->out_len &&
           bus->out_at[(bus->out_head + n) % LSC_LXBUS_OUT_BYTES] <= bus->now_us) {
        n++;
    }
    return n;
}

size_t lsc_lxbus_read(lsc_lxbus *bus, uint8_t *buf, size_t cap)
{
    size_t got = 0;
    if (bus == NULL || buf == NULL) {
        return 0;
    }
    while (got < cap && bus->out_len > 0u && bus->out_at[bus->out_head] <= bus->now_us) {
        buf[got++] = bus->out[bus->out_head];
        bus->out_head = (bus->out_head + 1u) % LSC_LXBUS_OUT_BYTES;
        bus->out_len--;
    }
    return got;
}

uint64_t lsc_lxbus_next_event_us(const lsc_lxbus *bus)
{
    if (bus == NULL || bus->out_len == 0u) {
        return LSC_LXBUS_TIME_NEVER;
    }
    uint64_t at = bus->out_at[bus->out_head];
    return at > bus->now_us ? at - bus->now_us : 0u;
}

/* ---- Servos ------------------------------------------------------------------ */

/* The commanded position now (servo mode). */
static int32_t commanded(const lsc_lxbus_servo *s, uint64_t now)
{
    if (s->dur_us == 0u || now >= s->start_us + s->dur_us) {
        return s->to;
    }
    int64_t span = (int64_t)s->to - (int64_t)s->from;
    int64_t done = (int64_t)(now - s->start_us);
    /* C99 division truncates towards zero: towards the start */
    return (int32_t)((int64_t)s->from + span * done / (int64_t)s->dur_us);
}

int32_t lsc_lxbus_shaft(const lsc_lxbus_servo *s, uint64_t now)
{
    if (s->mode == LSC_LX_MODE_MOTOR) {
        if (!s->torque) {
            return s->from;
        }
        /* speed units a second; a whole turn is LSC_LXBUS_TURN units, so the
         * time matters modulo 1500 s (speed * 1500 s is whole turns) */
        uint64_t t = (now - s->start_us) % (1000000u * (uint64_t)LSC_LXBUS_TURN);
        int64_t turned = (int64_t)s->speed * (int64_t)t / 1000000;
        int64_t p = ((int64_t)s->from + turned) % LSC_LXBUS_TURN;
        return (int32_t)(p < 0 ? p + LSC_LXBUS_TURN : p);
    }
    return commanded(s, now) + s->offset;
}

/* Freezes servo s where it is now: at rest at its commanded position (servo
 * mode), or turning on from where it is (motor mode). */
static void settle(lsc_lxbus_servo *s, uint64_t now)
{
    if (s->mode == LSC_LX_MODE_MOTOR) {
        s->from = lsc_lxbus_shaft(s, now);
        s->start_us = now;
    } else {
        s->from = s->to = commanded(s, now);
        s->dur_us = 0;
    }
}

/* Servo mode, at rest where the shaft is now. */
static void to_servo_mode(lsc_lxbus_servo *s, uint64_t now)
{
    int32_t at = lsc_lxbus_shaft(s, now);
    s->mode = LSC_LX_MODE_SERVO;
    s->from = s->to = at - s->offset;
    s->dur_us = 0;
}

static uint8_t faults(const lsc_lxbus *bus, const lsc_lxbus_servo *s)
{
    uint8_t f = 0;
    if (s->temp_c > s->temp_limit) {
        f |= LSC_LX_ALARM_TEMP;
    }
    if (bus->vin_mv < s->vin_min || bus->vin_mv > s->vin_max) {
        f |= LSC_LX_ALARM_VOLTAGE;
    }
    if (s->stalled) {
        f |= LSC_LX_ALARM_STALL;
    }
    return f;
}

/* The faults that hold the torque off. */
#define HOLD_OFF (LSC_LX_ALARM_TEMP | LSC_LX_ALARM_VOLTAGE)

/* After a change of temperature, supply or limits: a fault that holds the
 * torque off turns it off. */
static void check_faults(lsc_lxbus *bus)
{
    for (size_t i = 0; i < bus->nservos; i++) {
        lsc_lxbus_servo *s = &bus->servo[i];
        if ((faults(bus, s) & HOLD_OFF) != 0u && s->torque) {
            settle(s, bus->now_us);
            s->torque = false;
        }
    }
}

void lsc_lxbus_servo_fresh(lsc_lxbus_servo *s, uint8_t id)
{
    memset(s, 0, sizeof *s);
    s->id = id;
    s->limit_max = LSC_LX_POSITION_MAX;
    s->vin_min = LSC_LX_VIN_MIN;
    s->vin_max = LSC_LX_VIN_MAX;
    s->temp_limit = LSC_LX_TEMP_LIMIT_DEFAULT;
    s->led_on = true;
    s->alarm_mask = LSC_LX_ALARM_ALL;
    s->temp_c = LSC_LXBUS_TEMP_DEFAULT;
    s->from = s->to = LSC_LXBUS_POSITION_DEFAULT;
    s->move_pos = LSC_LXBUS_POSITION_DEFAULT;
}

void lsc_lxbus_servo_power_on(lsc_lxbus_servo *s, int32_t shaft)
{
    s->offset = s->offset_saved;
    s->mode = LSC_LX_MODE_SERVO;
    s->speed = 0;
    s->torque = false;
    s->alarm_mask = LSC_LX_ALARM_ALL;
    s->waiting = false;
    s->wait_pos = 0;
    s->wait_time = 0;
    s->from = s->to = shaft - s->offset;
    s->dur_us = 0;
    s->start_us = 0;
    int32_t at = s->to < 0 ? 0 : s->to > (int32_t)LSC_LX_POSITION_MAX ? (int32_t)LSC_LX_POSITION_MAX
                                                                       : s->to;
    s->move_pos = (uint16_t)at;
    s->move_time = 0;
}

/* ---- Setup ------------------------------------------------------------------------ */

int lsc_lxbus_init(lsc_lxbus *bus)
{
    if (bus == NULL) {
        return LSC_EINVAL;
    }
    memset(bus, 0, sizeof *bus);
    bus->vin_mv = LSC_LXBUS_VIN_DEFAULT;
    (void)lsc_lx_parser_init(&bus->parser);
    return 0;
}

int lsc_lxbus_add(lsc_lxbus *bus, uint8_t id)
{
    if (bus == NULL || id > LSC_LX_ID_MAX) {
        return LSC_EINVAL;
    }
    if (bus->nservos == LSC_LXBUS_SERVOS) {
        return LSC_ENOSPC;
    }
    lsc_lxbus_servo *s = &bus->servo[bus->nservos];
    lsc_lxbus_servo_fresh(s, id);
    s->start_us = bus->now_us;
    bus->changes++;
    return (int)bus->nservos++;
}

int lsc_lxbus_find(const lsc_lxbus *bus, uint8_t id)
{
    for (size_t i = 0; bus != NULL && i < bus->nservos; i++) {
        if (bus->servo[i].id == id) {
            return (int)i;
        }
    }
    return -1;
}

int16_t lsc_lxbus_position(const lsc_lxbus *bus, size_t i)
{
    if (bus == NULL || i >= bus->nservos) {
        return 0;
    }
    return (int16_t)lsc_lxbus_shaft(&bus->servo[i], bus->now_us);
}

bool lsc_lxbus_moving(const lsc_lxbus *bus, size_t i)
{
    if (bus == NULL || i >= bus->nservos) {
        return false;
    }
    const lsc_lxbus_servo *s = &bus->servo[i];
    if (s->mode == LSC_LX_MODE_MOTOR) {
        return s->torque && s->speed != 0;
    }
    return s->dur_us != 0u && bus->now_us < s->start_us + s->dur_us;
}

uint8_t lsc_lxbus_faults(const lsc_lxbus *bus, size_t i)
{
    return bus == NULL || i >= bus->nservos ? 0u : faults(bus, &bus->servo[i]);
}

bool lsc_lxbus_led_alarm(const lsc_lxbus *bus, size_t i)
{
    return (lsc_lxbus_faults(bus, i) & (bus != NULL && i < bus->nservos
                                            ? bus->servo[i].alarm_mask
                                            : 0u)) != 0u;
}

int lsc_lxbus_set_temp(lsc_lxbus *bus, size_t i, uint8_t celsius)
{
    if (bus == NULL || i >= bus->nservos) {
        return LSC_EINVAL;
    }
    bus->servo[i].temp_c = celsius;
    check_faults(bus);
    return 0;
}

int lsc_lxbus_set_vin(lsc_lxbus *bus, uint16_t millivolts)
{
    if (bus == NULL) {
        return LSC_EINVAL;
    }
    bus->vin_mv = millivolts;
    check_faults(bus);
    return 0;
}

int lsc_lxbus_set_stall(lsc_lxbus *bus, size_t i, bool stalled)
{
    if (bus == NULL || i >= bus->nservos) {
        return LSC_EINVAL;
    }
    bus->servo[i].stalled = stalled;
    return 0;
}

void lsc_lxbus_power_cycle(lsc_lxbus *bus)
{
    if (bus == NULL) {
        return;
    }
    for (size_t i = 0; i < bus->nservos; i++) {
        lsc_lxbus_servo *s = &bus->servo[i];
        lsc_lxbus_servo_power_on(s, lsc_lxbus_shaft(s, bus->now_us));
        s->start_us = bus->now_us;
    }
    bus->out_head = 0;
    bus->out_len = 0;
    bus->line_free_us = bus->now_us;
    lsc_lx_parser_reset(&bus->parser);
}

void lsc_lxbus_set_baud(lsc_lxbus *bus, uint32_t baud)
{
    if (bus != NULL) {
        bus->baud = baud;
    }
}

void lsc_lxbus_set_echo(lsc_lxbus *bus, bool echo)
{
    if (bus != NULL) {
        bus->echo = echo;
    }
}

void lsc_lxbus_set_log(lsc_lxbus *bus, lsc_sim_log_fn fn, void *ctx)
{
    if (bus != NULL) {
        bus->log = fn;
        bus->log_ctx = ctx;
    }
}

void lsc_lxbus_fault_drop(lsc_lxbus *bus, uint32_t n)
{
    if (bus != NULL) {
        bus->fault_drop = n;
    }
}

void lsc_lxbus_fault_delay(lsc_lxbus *bus, uint32_t ms)
{
    if (bus != NULL) {
        bus->fault_delay_ms = ms;
    }
}

void lsc_lxbus_fault_corrupt(lsc_lxbus *bus, uint32_t n, uint8_t offset, uint8_t xor_mask)
{
    if (bus != NULL) {
        bus->fault_corrupt = n;
        bus->fault_corrupt_offset = offset;
        bus->fault_corrupt_xor = xor_mask;
    }
}

void lsc_lxbus_advance_us(lsc_lxbus *bus, uint64_t us)
{
    if (bus != NULL) {
        bus->now_us = add_sat(bus->now_us, us);
    }
}

uint64_t lsc_lxbus_now_us(const lsc_lxbus *bus)
{
    return bus == NULL ? 0u : bus->now_us;
}

/* ---- Commands --------------------------------------------------------------------- */

/* The values a write carries (decoded and range-checked once a frame). */
typedef struct values {
    uint16_t a, b;
    uint8_t u8;
    int8_t s8;
    int16_t s16;
    bool on;
} values;

/* Decodes the write f into *v: 0, or LSC_EFRAME (values out of range). */
static int decode_write(const lsc_lx_frame *f, values *v)
{
    switch (f->cmd) {
    case LSC_LX_MOVE_TIME_WRITE:
    case LSC_LX_MOVE_TIME_WAIT_WRITE:
        return lsc_lx_decode_move_time(f, &v->a, &v->b);
    case LSC_LX_ID_WRITE:
        return lsc_lx_decode_id(f, &v->u8);
    case LSC_LX_OFFSET_ADJUST:
        return lsc_lx_decode_offset(f, &v->s8);
    case LSC_LX_ANGLE_LIMIT_WRITE:
        return lsc_lx_decode_angle_limit(f, &v->a, &v->b);
    case LSC_LX_VIN_LIMIT_WRITE:
        return lsc_lx_decode_vin_limit(f, &v->a, &v->b);
    case LSC_LX_TEMP_LIMIT_WRITE:
        return lsc_lx_decode_temp_limit(f, &v->u8);
    case LSC_LX_MOTOR_MODE_WRITE:
        return lsc_lx_decode_motor_mode(f, &v->u8, &v->s16);
    case LSC_LX_LOAD_WRITE:
        return lsc_lx_decode_load(f, &v->on);
    case LSC_LX_LED_CTRL_WRITE:
        return lsc_lx_decode_led_ctrl(f, &v->on);
    case LSC_LX_LED_ERROR_WRITE:
        return lsc_lx_decode_led_error(f, &v->u8);
    default: /* MOVE_START, MOVE_STOP, OFFSET_WRITE: no values */
        return 0;
    }
}

/* Starts a move of s to pos (held within its limits) over time_ms. NULL, or
 * why not. */
static const char *start_move(lsc_lxbus *bus, lsc_lxbus_servo *s, uint16_t pos, uint16_t time_ms)
{
    if (s->mode == LSC_LX_MODE_MOTOR) {
        return "a move in motor mode";
    }
    if ((faults(bus, s) & HOLD_OFF) != 0u) {
        return "a fault holds the torque off";
    }
    uint16_t to = pos < s->limit_min ? s->limit_min : pos > s->limit_max ? s->limit_max : pos;
    s->from = commanded(s, bus->now_us);
    s->to = to;
    s->start_us = bus->now_us;
    s->dur_us = (uint32_t)time_ms * 1000u;
    s->torque = true;
    return NULL;
}

/* Servo s obeys the write f (values v): NULL, or why it did not. */
static const char *obey(lsc_lxbus *bus, lsc_lxbus_servo *s, const lsc_lx_frame *f,
                        const values *v)
{
    uint64_t now = bus->now_us;
    const char *why = NULL;
    switch (f->cmd) {
    case LSC_LX_MOVE_TIME_WRITE:
        why = start_move(bus, s, v->a, v->b);
        if (why == NULL) {
            s->move_pos = v->a;
            s->move_time = v->b;
        }
        return why;
    case LSC_LX_MOVE_TIME_WAIT_WRITE:
        s->wait_pos = v->a;
        s->wait_time = v->b;
        s->waiting = true;
        return NULL;
    case LSC_LX_MOVE_START:
        if (!s->waiting) {
            return "start: nothing waits";
        }
        why = start_move(bus, s, s->wait_pos, s->wait_time);
        s->waiting = why != NULL;
        return why;
    case LSC_LX_MOVE_STOP:
        settle(s, now);
        if (s->mode == LSC_LX_MODE_MOTOR) {
            s->speed = 0;
        }
        return NULL;
    case LSC_LX_ID_WRITE:
        s->id = v->u8;
        break;
    case LSC_LX_OFFSET_ADJUST:
        s->offset = v->s8; /* the shaft moves with it at once */
        return NULL;
    case LSC_LX_OFFSET_WRITE:
        s->offset_saved = s->offset;
        break;
    case LSC_LX_ANGLE_LIMIT_WRITE:
        s->limit_min = v->a;
        s->limit_max = v->b;
        break;
    case LSC_LX_VIN_LIMIT_WRITE:
        s->vin_min = v->a;
        s->vin_max = v->b;
        break;
    case LSC_LX_TEMP_LIMIT_WRITE:
        s->temp_limit = v->u8;
        break;
    case LSC_LX_MOTOR_MODE_WRITE:
        if (v->u8 == LSC_LX_MODE_SERVO) {
            if (s->mode == LSC_LX_MODE_MOTOR) {
                to_servo_mode(s, now);
            }
            s->speed = v->s16;
            return NULL;
        }
        if ((faults(bus, s) & HOLD_OFF) != 0u) {
            return "a fault holds the torque off";
        }
        settle(s, now);
        s->from = lsc_lxbus_shaft(s, now);
        s->start_us = now;
        s->mode = LSC_LX_MODE_MOTOR;
        s->speed = v->s16;
        s->torque = true;
        return NULL;
    case LSC_LX_LOAD_WRITE:
        if (v->on && (faults(bus, s) & HOLD_OFF) != 0u) {
            return "a fault holds the torque off";
        }
        settle(s, now);
        s->torque = v->on;
        return NULL;
    case LSC_LX_LED_CTRL_WRITE:
        s->led_on = v->on;
        break;
    default: /* LSC_LX_LED_ERROR_WRITE */
        s->alarm_mask = v->u8;
        return NULL;
    }
    bus->changes++; /* what survives power-off changed */
    return NULL;
}

/* Servo s's reply to the read cmd into buf: its length. */
static int answer(const lsc_lxbus *bus, const lsc_lxbus_servo *s, uint8_t cmd, uint8_t *buf)
{
    const size_t cap = LSC_LX_FRAME_MAX;
    uint8_t id = s->id;
    switch (cmd) {
    case LSC_LX_MOVE_TIME_READ:
        return lsc_lx_encode_move_time(buf, cap, id, cmd, s->move_pos, s->move_time);
    case LSC_LX_MOVE_TIME_WAIT_READ:
        return lsc_lx_encode_move_time(buf, cap, id, cmd, s->wait_pos, s->wait_time);
    case LSC_LX_ID_READ:
        return lsc_lx_encode_id(buf, cap, id, cmd, id);
    case LSC_LX_OFFSET_READ:
        return lsc_lx_encode_offset(buf, cap, id, cmd, s->offset);
    case LSC_LX_ANGLE_LIMIT_READ:
        return lsc_lx_encode_angle_limit(buf, cap, id, cmd, s->limit_min, s->limit_max);
    case LSC_LX_VIN_LIMIT_READ:
        return lsc_lx_encode_vin_limit(buf, cap, id, cmd, s->vin_min, s->vin_max);
    case LSC_LX_TEMP_LIMIT_READ:
        return lsc_lx_encode_temp_limit(buf, cap, id, cmd, s->temp_limit);
    case LSC_LX_TEMP_READ:
        return lsc_lx_encode_temp(buf, cap, id, s->temp_c);
    case LSC_LX_VIN_READ:
        return lsc_lx_encode_vin(buf, cap, id, bus->vin_mv);
    case LSC_LX_POS_READ:
        return lsc_lx_encode_position(buf, cap, id,
                                      (int16_t)lsc_lxbus_shaft(s, bus->now_us));
    case LSC_LX_MOTOR_MODE_READ:
        return lsc_lx_encode_motor_mode(buf, cap, id, cmd, s->mode, s->speed);
    case LSC_LX_LOAD_READ:
        return lsc_lx_encode_load(buf, cap, id, cmd, s->torque);
    case LSC_LX_LED_CTRL_READ:
        return lsc_lx_encode_led_ctrl(buf, cap, id, cmd, s->led_on);
    default: /* LSC_LX_LED_ERROR_READ */
        return lsc_lx_encode_led_error(buf, cap, id, cmd, s->alarm_mask);
    }
}

static void ignore(lsc_lxbus *bus, const char *why)
{
    bus->stats.ignored++;
    emit(bus, LSC_SIM_EV_IGNORED, NULL, 0, why);
}

/* Whether a frame to id reaches servo s. */
static bool reaches(uint8_t id, const lsc_lxbus_servo *s)
{
    return id == LSC_LX_BROADCAST || id == s->id;
}

static void handle(lsc_lxbus *bus, const lsc_lx_frame *f)
{
    bus->stats.frames_in++;
    emit(bus, LSC_SIM_EV_RX, bus->parser.buf, f->nparams + 6u, NULL);
    if (f->reply) {
        ignore(bus, "a servo's reply, sent by the host");
        return;
    }
    if (lsc_lx_len(f->cmd, true) != 0u) {
        /* a read: every servo it reaches answers at once */
        if (f->id == LSC_LX_BROADCAST && f->cmd != LSC_LX_ID_READ) {
            ignore(bus, "a read to 254: no servo answers it");
            return;
        }
        uint8_t acc[LSC_LX_FRAME_MAX], one[LSC_LX_FRAME_MAX];
        memset(acc, 0xFF, sizeof acc); /* the idle line: every bit high */
        int len = 0;
        unsigned answers = 0;
        for (size_t i = 0; i < bus->nservos; i++) {
            if (!reaches(f->id, &bus->servo[i])) {
                continue;
            }
            len = answer(bus, &bus->servo[i], f->cmd, one);
            for (int k = 0; k < len; k++) {
                acc[k] = (uint8_t)(acc[k] & one[k]); /* a 0 wins on the wire */
            }
            answers++;
        }
        if (answers == 0u) {
            ignore(bus, "no servo has that id");
            return;
        }
        if (answers > 1u) {
            bus->stats.collisions++;
        }
        send_reply(bus, acc, (size_t)len);
        return;
    }
    values v;
    memset(&v, 0, sizeof v);
    if (decode_write(f, &v) != 0) {
        ignore(bus, "values outside the document's ranges");
        return;
    }
    const char *why = "no servo has that id";
    bool obeyed = false;
    for (size_t i = 0; i < bus->nservos; i++) {
        if (reaches(f->id, &bus->servo[i])) {
            const char *no = obey(bus, &bus->servo[i], f, &v);
            obeyed = obeyed || no == NULL;
            why = no != NULL ? no : why;
        }
    }
    if (f->cmd == LSC_LX_VIN_LIMIT_WRITE || f->cmd == LSC_LX_TEMP_LIMIT_WRITE) {
        check_faults(bus);
    }
    if (!obeyed) {
        ignore(bus, why);
    }
}

int lsc_lxbus_feed(lsc_lxbus *bus, const uint8_t *data, size_t n)
{
    if (bus == NULL || (data == NULL && n > 0u) || n > (size_t)INT_MAX) {
        return LSC_EINVAL;
    }
    if (bus->echo && n > 0u) {
        /* the host hears its own bytes first, as it sends them */
        size_t room = LSC_LXBUS_OUT_BYTES - bus->out_len;
        push(bus, data, n < room ? n : room, bus->now_us, false);
    }
    for (size_t i = 0; i < n; i++) {
        lsc_lx_parser *p = &bus->parser;
        if (p->len > 0u && !p->complete &&
            bus->now_us - bus->last_byte_us > (uint64_t)LSC_LXBUS_FRAME_GAP_MS * 1000u) {
            lsc_lx_parser_reset(p);
            bus->stats.bad_frames++;
            emit(bus, LSC_SIM_EV_BEEP, NULL, 0, "frame left unfinished");
        }
        bus->last_byte_us = bus->now_us;
        uint32_t sums = p->bad_checksums;
        lsc_lx_frame f;
        int r = lsc_lx_parser_feed(p, data[i], &f);
        if (r == 1) {
            handle(bus, &f);
        } else if (r == LSC_ESYNC) {
            bus->stats.noise_bytes++;
            emit(bus, LSC_SIM_EV_NOISE, &data[i], 1, NULL);
        } else if (r < 0) {
            bus->stats.bad_frames++;
            emit(bus, LSC_SIM_EV_BEEP, NULL, 0,
                 p->bad_checksums != sums ? "checksum failed" : "malformed frame");
        }
    }
    return (int)n;
}

/* ---- The lsc_io adapter ------------------------------------------------------------- */

static int bus_io_write(void *ctx, const uint8_t *data, size_t n)
{
    lsc_lxbus *bus = ctx;
    if ((data == NULL && n > 0u) || n > (size_t)INT_MAX) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        /* the byte is on the host's side of the line until it has crossed it */
        lsc_lxbus_advance_us(bus, wire_us(bus->baud, 1));
        (void)lsc_lxbus_feed(bus, &data[i], 1);
    }
    return (int)n;
}

static int bus_io_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lsc_lxbus *bus = ctx;
    uint64_t left = (uint64_t)timeout_ms * 1000u;
    if (buf == NULL || cap == 0u) {
        return LSC_EINVAL;
    }
    if (cap > (size_t)INT_MAX) {
        cap = (size_t)INT_MAX;
    }
    for (;;) {
        size_t got = lsc_lxbus_read(bus, buf, cap);
        if (got > 0u) {
            return (int)got;
        }
        if (left == 0u) {
            return 0;
        }
        uint64_t step = lsc_lxbus_next_event_us(bus);
        if (step > left) {
            step = left;
        }
        lsc_lxbus_advance_us(bus, step);
        left -= step;
    }
}

static uint32_t bus_io_now_ms(void *ctx)
{
    const lsc_lxbus *bus = ctx;
    return (uint32_t)(lsc_lxbus_now_us(bus) / 1000u);
}

int lsc_lxbus_io_init(lsc_lxbus *bus, lsc_io *io)
{
    if (bus == NULL || io == NULL) {
        return LSC_EINVAL;
    }
    io->ctx = bus;
    io->write = bus_io_write;
    io->read = bus_io_read;
    io->now_ms = bus_io_now_ms;
    return 0;
}
