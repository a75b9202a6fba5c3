/* The virtual controller model (include/lsc/sim.h has the contract). */
#include "lsc/sim.h"

#include <limits.h>
#include <string.h>

/* ---- Logging and output queue --------------------------------------------- */

static void emit(lsc_sim *sim, lsc_sim_event_kind kind, const uint8_t *bytes, size_t len,
                 const char *text)
{
    if (sim->log != NULL) {
        lsc_sim_event ev;
        ev.kind = kind;
        ev.time_us = sim->now_us;
        ev.bytes = bytes;
        ev.len = len;
        ev.text = text;
        sim->log(sim->log_ctx, &ev);
    }
}

static uint64_t add_sat(uint64_t a, uint64_t b)
{
    return (b >= LSC_SIM_TIME_NEVER - 1u - a) ? LSC_SIM_TIME_NEVER - 1u : a + b;
}

/* Wire time of the first k bytes of a frame, rounded up to whole microseconds. */
static uint64_t wire_us(uint32_t baud, uint64_t k)
{
    return baud == 0u ? 0u : (k * 10000000u + baud - 1u) / baud;
}

/* Queues a frame the controller sends. A reply is subject to the drop and
 * corrupt faults; every frame to the delay. */
static void send_frame(lsc_sim *sim, uint8_t *frame, size_t len, bool reply)
{
    if (reply && sim->fault_drop > 0u) {
        sim->fault_drop--;
        sim->stats.dropped++;
        emit(sim, LSC_SIM_EV_DROPPED, frame, len, "reply dropped (fault injection)");
        return;
    }
    if (sim->nframes == LSC_SIM_OUT_FRAMES || LSC_SIM_OUT_BYTES - sim->out_bytes < len) {
        sim->stats.overflow++;
        emit(sim, LSC_SIM_EV_DROPPED, frame, len, "output queue full");
        return;
    }
    if (reply && sim->fault_corrupt > 0u) {
        size_t at = sim->fault_corrupt_offset < len ? sim->fault_corrupt_offset : len - 1u;
        sim->fault_corrupt--;
        frame[at] = (uint8_t)(frame[at] ^ sim->fault_corrupt_xor);
    }
    uint64_t due = add_sat(sim->now_us, (uint64_t)sim->fault_delay_ms * 1000u);
    if (due < sim->line_free_us) {
        due = sim->line_free_us;
    }
    lsc_sim_out *o = &sim->frames[(sim->frame_head + sim->nframes) % LSC_SIM_OUT_FRAMES];
    o->ready_us = due;
    o->len = (uint16_t)len;
    o->sent = 0;
    sim->nframes++;
    sim->line_free_us = add_sat(due, wire_us(sim->baud, len));
    size_t tail = (sim->out_head + sim->out_bytes) % LSC_SIM_OUT_BYTES;
    for (size_t i = 0; i < len; i++) {
        sim->out[(tail + i) % LSC_SIM_OUT_BYTES] = frame[i];
    }
    sim->out_bytes += len;
    sim->stats.frames_out++;
    emit(sim, LSC_SIM_EV_TX, frame, len, NULL);
}

/* Bytes of frame o readable at the current time (not counting those read). */
static size_t frame_ready(const lsc_sim *sim, const lsc_sim_out *o)
{
    if (sim->now_us < o->ready_us) {
        return 0;
    }
    if (sim->baud == 0u) {
        return (size_t)(o->len - o->sent);
    }
    uint64_t elapsed = sim->now_us - o->ready_us;
    if (elapsed >= wire_us(sim->baud, o->len)) {
        return (size_t)(o->len - o->sent);
    }
    /* byte k is readable once wire_us(k) = ceil(k * 1e7 / baud) <= elapsed, that
     * is once k <= elapsed * baud / 1e7 (elapsed is whole): k is the floor. No
     * overflow: elapsed * baud < len * 1e7 + baud here. */
    uint64_t k = elapsed * sim->baud / 10000000u;
    return k > o->sent ? (size_t)(k - o->sent) : 0u;
}

size_t lsc_sim_available(const lsc_sim *sim)
{
    size_t total = 0;
    if (sim == NULL) {
        return 0;
    }
    for (size_t i = 0; i < sim->nframes; i++) {
        const lsc_sim_out *o = &sim->frames[(sim->frame_head + i) % LSC_SIM_OUT_FRAMES];
        size_t r = frame_ready(sim, o);
        total += r;
        if (r < (size_t)(o->len - o->sent)) {
            break; /* later frames cannot be ahead of this one */
        }
    }
    return total;
}

size_t lsc_sim_read(lsc_sim *sim, uint8_t *buf, size_t cap)
{
    size_t got = 0;
    if (sim == NULL || buf == NULL) {
        return 0;
    }
    while (got < cap && sim->nframes > 0u) {
        lsc_sim_out *o = &sim->frames[sim->frame_head];
        size_t r = frame_ready(sim, o);
        if (r > cap - got) {
            r = cap - got;
        }
        for (size_t i = 0; i < r; i++) {
            buf[got++] = sim->out[sim->out_head];
            sim->out_head = (sim->out_head + 1u) % LSC_SIM_OUT_BYTES;
        }
        sim->out_bytes -= r;
        o->sent = (uint16_t)(o->sent + r);
        if (o->sent < o->len) {
            break;
        }
        sim->frame_head = (sim->frame_head + 1u) % LSC_SIM_OUT_FRAMES;
        sim->nframes--;
    }
    return got;
}

/* ---- Servos ---------------------------------------------------------------- */

/* Where the move puts the servo, held within the positions it can reach (its
 * range, or an object it is blocked by). */
static uint16_t held(const lsc_sim_channel *c, uint16_t at)
{
    if (at < c->lo) {
        return c->lo;
    }
    if (c->hi_end != 0u && at >= c->hi_end) {
        return (uint16_t)(c->hi_end - 1u);
    }
    return at;
}

/* Sets the positions channel c can reach: lo .. hi (hi UINT16_MAX: no end). */
static void set_reach(lsc_sim_channel *c, uint16_t lo, uint16_t hi)
{
    c->lo = lo;
    c->hi_end = hi == UINT16_MAX ? 0u : (uint16_t)(hi + 1u);
}

static uint16_t channel_position(const lsc_sim_channel *c, uint64_t now)
{
    if (c->dur_us == 0u || now >= c->start_us + c->dur_us) {
        return held(c, c->to);
    }
    int64_t span = (int64_t)c->to - (int64_t)c->from;
    int64_t done = (int64_t)(now - c->start_us);
    /* C99 division truncates towards zero: towards the start position */
    return held(c, (uint16_t)((int64_t)c->from + span * done / (int64_t)c->dur_us));
}

int lsc_sim_block(lsc_sim *sim, uint8_t id, uint16_t at, lsc_sim_block_side side)
{
    if (sim == NULL || (side != LSC_SIM_BLOCK_NONE && side != LSC_SIM_BLOCK_ABOVE &&
                        side != LSC_SIM_BLOCK_BELOW)) {
        return LSC_EINVAL;
    }
    lsc_sim_channel *c = &sim->ch[id];
    if (side == LSC_SIM_BLOCK_ABOVE) {
        set_reach(c, 0, at);
    } else if (side == LSC_SIM_BLOCK_BELOW) {
        set_reach(c, at, UINT16_MAX);
    } else {
        set_reach(c, 0, UINT16_MAX);
    }
    return 0;
}

static void move_servo(lsc_sim *sim, uint8_t id, uint16_t to, uint64_t dur_us, bool by_group)
{
    lsc_sim_channel *c = &sim->ch[id];
    c->from = channel_position(c, sim->now_us);
    c->to = to;
    c->start_us = sim->now_us;
    c->dur_us = dur_us > UINT32_MAX ? UINT32_MAX : (uint32_t)dur_us;
    c->powered = true;
    c->by_group = by_group;
}

/* Stops a servo where it is now. */
static void halt_servo(lsc_sim *sim, uint8_t id)
{
    lsc_sim_channel *c = &sim->ch[id];
    c->to = channel_position(c, sim->now_us);
    c->from = c->to;
    c->dur_us = 0;
    c->by_group = false;
}

int lsc_sim_set_servo(lsc_sim *sim, uint8_t id, uint16_t position, uint16_t pos_min,
                      uint16_t pos_max)
{
    if (sim == NULL || pos_min > pos_max) {
        return LSC_EINVAL;
    }
    lsc_sim_channel *c = &sim->ch[id];
    /* 0..0: no range */
    set_reach(c, pos_min, pos_max == 0u ? UINT16_MAX : pos_max);
    c->from = c->to = position;
    c->dur_us = 0;
    c->by_group = false;
    return 0;
}

uint16_t lsc_sim_position(const lsc_sim *sim, uint8_t id)
{
    return sim == NULL ? 0u : channel_position(&sim->ch[id], sim->now_us);
}

bool lsc_sim_powered(const lsc_sim *sim, uint8_t id)
{
    return sim != NULL && sim->ch[id].powered;
}

bool lsc_sim_moving(const lsc_sim *sim, uint8_t id)
{
    if (sim == NULL) {
        return false;
    }
    const lsc_sim_channel *c = &sim->ch[id];
    return c->dur_us != 0u && sim->now_us < c->start_us + c->dur_us;
}

/* ---- Action groups -------------------------------------------------------- */

static const lsc_sim_step *group_step(const lsc_sim *sim, uint8_t group, uint16_t index)
{
    return &sim->groups->steps[sim->groups->first_step[group] + index];
}

static bool group_exists(const lsc_sim *sim, uint8_t group)
{
    return sim->groups != NULL && group < LSC_SIM_GROUPS && sim->groups->group_steps[group] > 0u;
}

/* Starts step run_step of the running group at the current time. */
static void start_step(lsc_sim *sim)
{
    const lsc_sim_step *s = group_step(sim, sim->run_group, sim->run_step);
    uint64_t dur = (uint64_t)s->time_ms * 1000u * 100u / sim->speed[sim->run_group];
    if (dur < LSC_SIM_STEP_MIN_US) {
        dur = LSC_SIM_STEP_MIN_US;
    }
    for (uint16_t i = 0; i < s->ntargets; i++) {
        const lsc_servo *t = &sim->groups->targets[s->first + i];
        move_servo(sim, t->id, t->position, dur, true);
    }
    sim->step_end_us = add_sat(sim->now_us, dur);
}

static void send_u8_u16(lsc_sim *sim, int (*enc)(uint8_t *, size_t, uint8_t, uint16_t),
                        uint8_t a, uint16_t b)
{
    uint8_t frame[8];
    int n = enc(frame, sizeof frame, a, b);
    send_frame(sim, frame, (size_t)n, false);
}

/* Ends the running group now: stopped (7) or completed (8). */
static void end_group(lsc_sim *sim, bool stopped)
{
    sim->running = false;
    if (stopped) {
        uint8_t frame[4];
        int n = lsc_encode_group_stop(frame, sizeof frame);
        for (unsigned id = 0; id < LSC_SIM_SERVOS; id++) {
            if (sim->ch[id].by_group) {
                halt_servo(sim, (uint8_t)id);
            }
        }
        send_frame(sim, frame, (size_t)n, false);
    } else {
        send_u8_u16(sim, lsc_encode_group_complete, sim->run_group, sim->run_times);
    }
}

static void start_group(lsc_sim *sim, uint8_t group, uint16_t times)
{
    if (sim->running) {
        end_group(sim, true);
    }
    sim->running = true;
    sim->run_group = group;
    sim->run_times = times;
    sim->run_done = 0;
    sim->run_step = 0;
    send_u8_u16(sim, lsc_encode_group_run, group, times);
    start_step(sim);
}

/* The current step has ended at sim->now_us: start the next or finish. */
static void next_step(lsc_sim *sim)
{
    sim->run_step++;
    if (sim->run_step >= sim->groups->group_steps[sim->run_group]) {
        sim->run_step = 0;
        if (sim->run_times != 0u) {
            sim->run_done++;
            if (sim->run_done >= sim->run_times) {
                end_group(sim, false);
                return;
            }
        }
    }
    start_step(sim);
}

int lsc_sim_group_run(lsc_sim *sim, uint8_t group, uint16_t times)
{
    if (sim == NULL || !group_exists(sim, group)) {
        return LSC_EINVAL;
    }
    start_group(sim, group, times);
    return 0;
}

int lsc_sim_group_stop(lsc_sim *sim)
{
    if (sim == NULL || !sim->running) {
        return LSC_EINVAL;
    }
    end_group(sim, true);
    return 0;
}

int lsc_sim_group_running(const lsc_sim *sim)
{
    return (sim != NULL && sim->running) ? (int)sim->run_group : -1;
}

uint16_t lsc_sim_group_speed(const lsc_sim *sim, uint8_t group)
{
    return (sim == NULL || group >= LSC_SIM_GROUPS) ? 0u : sim->speed[group];
}

/* ---- Setup ------------------------------------------------------------------ */

int lsc_sim_init(lsc_sim *sim)
{
    if (sim == NULL) {
        return LSC_EINVAL;
    }
    memset(sim, 0, sizeof *sim);
    sim->battery_mv = LSC_SIM_BATTERY_DEFAULT;
    (void)lsc_parser_init(&sim->parser, sim->parser_buf, sizeof sim->parser_buf);
    for (unsigned id = 0; id < LSC_SIM_SERVOS; id++) {
        sim->ch[id].from = LSC_SIM_POSITION_DEFAULT;
        sim->ch[id].to = LSC_SIM_POSITION_DEFAULT;
        sim->ch[id].powered = true;
    }
    for (unsigned g = 0; g < LSC_SIM_GROUPS; g++) {
        sim->speed[g] = LSC_SIM_SPEED_DEFAULT;
    }
    sim->fault_corrupt_offset = 2;
    sim->fault_corrupt_xor = 0xFF;
    return 0;
}

void lsc_sim_set_groups(lsc_sim *sim, const lsc_sim_groups *g)
{
    if (sim == NULL) {
        return;
    }
    if (sim->running) {
        end_group(sim, true);
    }
    sim->groups = g;
}

void lsc_sim_set_battery(lsc_sim *sim, uint16_t millivolts)
{
    if (sim != NULL) {
        sim->battery_mv = millivolts;
    }
}

void lsc_sim_set_baud(lsc_sim *sim, uint32_t baud)
{
    if (sim != NULL) {
        sim->baud = baud;
    }
}

void lsc_sim_set_log(lsc_sim *sim, lsc_sim_log_fn fn, void *ctx)
{
    if (sim != NULL) {
        sim->log = fn;
        sim->log_ctx = ctx;
    }
}

void lsc_sim_fault_drop(lsc_sim *sim, uint32_t n)
{
    if (sim != NULL) {
        sim->fault_drop = n;
    }
}

void lsc_sim_fault_delay(lsc_sim *sim, uint32_t ms)
{
    if (sim != NULL) {
        sim->fault_delay_ms = ms;
    }
}

void lsc_sim_fault_corrupt(lsc_sim *sim, uint32_t n, uint8_t offset, uint8_t xor_mask)
{
    if (sim != NULL) {
        sim->fault_corrupt = n;
        sim->fault_corrupt_offset = offset;
        sim->fault_corrupt_xor = xor_mask;
    }
}

/* ---- Time ------------------------------------------------------------------- */

void lsc_sim_advance_us(lsc_sim *sim, uint64_t us)
{
    if (sim == NULL) {
        return;
    }
    uint64_t target = add_sat(sim->now_us, us);
    while (sim->running && sim->step_end_us <= target) {
        uint64_t end = sim->step_end_us;
        sim->now_us = end;
        next_step(sim);
        if (sim->step_end_us <= end) {
            break; /* the clock saturated: a step can no longer end later */
        }
    }
    sim->now_us = target;
}

void lsc_sim_advance_ms(lsc_sim *sim, uint32_t ms)
{
    lsc_sim_advance_us(sim, (uint64_t)ms * 1000u);
}

uint64_t lsc_sim_now_us(const lsc_sim *sim)
{
    return sim == NULL ? 0u : sim->now_us;
}

uint64_t lsc_sim_next_event_us(const lsc_sim *sim)
{
    uint64_t next = LSC_SIM_TIME_NEVER;
    if (sim == NULL) {
        return next;
    }
    if (sim->running) {
        next = sim->step_end_us - sim->now_us;
    }
    if (sim->nframes > 0u) {
        const lsc_sim_out *o = &sim->frames[sim->frame_head];
        if (frame_ready(sim, o) > 0u) {
            return 0;
        }
        uint64_t at = add_sat(o->ready_us, wire_us(sim->baud, (uint64_t)o->sent + 1u));
        uint64_t wait = at > sim->now_us ? at - sim->now_us : 0u;
        if (wait < next) {
            next = wait;
        }
    }
    return next;
}

/* ---- Commands from the host --------------------------------------------------- */

static void beep(lsc_sim *sim, const char *why)
{
    sim->stats.beeps++;
    emit(sim, LSC_SIM_EV_BEEP, NULL, 0, why);
}

static void ignore(lsc_sim *sim, const char *why)
{
    sim->stats.ignored++;
    emit(sim, LSC_SIM_EV_IGNORED, NULL, 0, why);
}

static const char *const bad_shape = "frame contradicts its command";

/* Obeys one well-formed frame, or beeps. */
static void handle_frame(lsc_sim *sim, const lsc_frame *f)
{
    /* a move carries up to LSC_MOVE_MAX servos, a position reply LSC_READ_MAX */
    lsc_servo servos[LSC_READ_MAX > LSC_MOVE_MAX ? LSC_READ_MAX : LSC_MOVE_MAX];
    uint8_t ids[LSC_UNLOAD_MAX];
    uint8_t reply[LSC_FRAME_MAX];
    uint16_t u16;
    uint8_t u8;
    int n;

    switch (f->cmd) {
    case LSC_CMD_SERVO_MOVE:
        n = lsc_decode_servo_move(f, &u16, servos, sizeof servos / sizeof servos[0]);
        if (n < 0) {
            beep(sim, bad_shape);
            return;
        }
        for (int i = 0; i < n; i++) {
            move_servo(sim, servos[i].id, servos[i].position, (uint64_t)u16 * 1000u, false);
        }
        return;
    case LSC_CMD_GROUP_RUN:
        if (lsc_decode_group_run(f, &u8, &u16) < 0) {
            beep(sim, bad_shape);
        } else if (!group_exists(sim, u8)) {
            ignore(sim, "run: no such action group");
        } else {
            start_group(sim, u8, u16);
        }
        return;
    case LSC_CMD_GROUP_STOP:
        if (lsc_decode_group_stop(f) < 0) {
            beep(sim, bad_shape);
        } else if (!sim->running) {
            ignore(sim, "stop: no action group is running");
        } else {
            end_group(sim, true);
        }
        return;
    case LSC_CMD_GROUP_SPEED:
        if (lsc_decode_group_speed(f, &u8, &u16) < 0) {
            beep(sim, bad_shape);
        } else if (u16 == 0u) {
            ignore(sim, "speed: 0 percent");
        } else if (u8 == LSC_GROUP_ALL) {
            for (unsigned g = 0; g < LSC_SIM_GROUPS; g++) {
                sim->speed[g] = u16;
            }
        } else {
            sim->speed[u8] = u16;
        }
        return;
    case LSC_CMD_BATTERY:
        if (lsc_decode_battery_request(f) < 0) {
            beep(sim, "battery reply sent to the controller");
            return;
        }
        n = lsc_encode_battery_reply(reply, sizeof reply, sim->battery_mv);
        send_frame(sim, reply, (size_t)n, true);
        return;
    case LSC_CMD_UNLOAD:
        n = lsc_decode_unload(f, ids, sizeof ids);
        if (n < 0) {
            beep(sim, bad_shape);
            return;
        }
        for (int i = 0; i < n; i++) {
            halt_servo(sim, ids[i]);
            sim->ch[ids[i]].powered = false;
        }
        return;
    case LSC_CMD_POS_READ:
        n = lsc_decode_pos_request(f, ids, sizeof ids);
        if (n < 0 || (size_t)n > LSC_READ_MAX) {
            beep(sim, bad_shape);
            return;
        }
        for (int i = 0; i < n; i++) {
            servos[i].id = ids[i];
            servos[i].position = channel_position(&sim->ch[ids[i]], sim->now_us);
        }
        n = lsc_encode_pos_reply(reply, sizeof reply, servos, (size_t)n);
        send_frame(sim, reply, (size_t)n, true);
        return;
    case LSC_CMD_OFFSET_READ: {
        lsc_servo_offset offs[LSC_OFFSET_MAX];
        n = lsc_decode_offset_request(f, ids, LSC_OFFSET_MAX);
        if (n < 0) {
            beep(sim, bad_shape);
            return;
        }
        for (int i = 0; i < n; i++) {
            offs[i].id = ids[i];
            offs[i].offset = sim->ch[ids[i]].offset;
        }
        n = lsc_encode_offset_reply(reply, sizeof reply, offs, (size_t)n);
        send_frame(sim, reply, (size_t)n, true);
        return;
    }
    case LSC_CMD_OFFSET_ADJUST: {
        int8_t offset;
        if (lsc_decode_offset_adjust(f, &u8, &offset) < 0) {
            beep(sim, bad_shape);
        } else {
            sim->ch[u8].offset = offset;
        }
        return;
    }
    case LSC_CMD_GROUP_COMPLETE:
        beep(sim, "command 8 from the host (erase on xArm): refused");
        return;
    default:
        beep(sim, "unknown command");
        return;
    }
}

int lsc_sim_feed(lsc_sim *sim, const uint8_t *data, size_t n)
{
    if (sim == NULL || (data == NULL && n > 0u) || n > (size_t)INT_MAX) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        lsc_frame f;
        if (sim->parser.len > 0u && !sim->parser.complete &&
            sim->now_us - sim->last_byte_us > (uint64_t)LSC_SIM_FRAME_GAP_MS * 1000u) {
            /* a header alone is noise; a frame that had its LEN is truncated */
            bool begun = sim->parser.len > 2u;
            lsc_parser_reset(&sim->parser);
            if (begun) {
                beep(sim, "frame left unfinished");
            }
        }
        sim->last_byte_us = sim->now_us;
        int r = lsc_parser_feed(&sim->parser, data[i], &f);
        if (r == 1) {
            uint8_t raw[LSC_FRAME_MAX];
            raw[0] = LSC_HEADER_BYTE;
            raw[1] = LSC_HEADER_BYTE;
            raw[2] = (uint8_t)(f.nparams + 2u);
            raw[3] = f.cmd;
            memcpy(raw + 4, f.params, f.nparams);
            sim->stats.frames_in++;
            emit(sim, LSC_SIM_EV_RX, raw, (size_t)f.nparams + 4u, NULL);
            handle_frame(sim, &f);
        } else if (r == LSC_ESYNC) {
            sim->stats.noise_bytes++;
            emit(sim, LSC_SIM_EV_NOISE, &data[i], 1, NULL);
        } else if (r < 0) {
            beep(sim, lsc_strerror(r));
        }
    }
    return (int)n;
}
