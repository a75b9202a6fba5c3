/* The client: request/reply over a caller-supplied lsc_io (contract in lsc/client.h). */
#include "lsc/client.h"

/* Bytes asked of io.read at a time (on the stack). */
#define CHUNK 32u

/* What a frame means to the waiting call: MATCH_NONE (not its answer),
 * MATCH_DONE (the answer; the wait ends), LSC_EREPLY (its command, wrong
 * shape: discarded, the wait goes on) or another negative code (the wait ends
 * with that error). */
#define MATCH_NONE 0
#define MATCH_DONE 1
typedef int (*match_fn)(void *ctx, const lsc_frame *f);

typedef struct wait_state {
    match_fn match;
    void *ctx;
    int result; /* set by the matcher's MATCH_DONE or error */
    bool done;
    bool bad;   /* a wrong-shape or malformed frame was seen */
    int notes;  /* notifications parsed */
} wait_state;

static bool usable(const lsc_client *c)
{
    return c != NULL && c->io.write != NULL && c->io.read != NULL && c->io.now_ms != NULL;
}

int lsc_client_init_checked(lsc_client *c, const lsc_io *io, size_t size, size_t rx_max)
{
    if (c == NULL) {
        return LSC_EINVAL;
    }
    if (size != sizeof *c || rx_max != sizeof c->rxbuf) {
        /* the caller's lsc_client is laid out otherwise: only its first
         * member, io, is where this library has it; cleared, every other
         * call refuses c */
        c->io.ctx = NULL;
        c->io.write = NULL;
        c->io.read = NULL;
        c->io.now_ms = NULL;
        return LSC_EINVAL;
    }
    c->io.ctx = NULL;
    c->io.write = NULL;
    c->io.read = NULL;
    c->io.now_ms = NULL;
    c->notify = NULL;
    c->notify_user = NULL;
    c->trace = NULL;
    c->trace_user = NULL;
    c->gap_ms = LSC_CLIENT_GAP_MS;
    c->last_rx_ms = 0;
    c->notifications = 0;
    c->unexpected = 0;
    (void)lsc_parser_init(&c->parser, c->rxbuf, sizeof c->rxbuf);
    if (io == NULL || io->write == NULL || io->read == NULL || io->now_ms == NULL) {
        return LSC_EINVAL;
    }
    c->io = *io;
    c->last_rx_ms = c->io.now_ms(c->io.ctx);
    return 0;
}

void lsc_client_set_notify(lsc_client *c, lsc_notify_fn fn, void *user)
{
    if (c != NULL) {
        c->notify = fn;
        c->notify_user = user;
    }
}

void lsc_client_set_trace(lsc_client *c, lsc_trace_fn fn, void *user)
{
    if (c != NULL) {
        c->trace = fn;
        c->trace_user = user;
    }
}

void lsc_client_set_gap(lsc_client *c, uint32_t gap_ms)
{
    if (c != NULL) {
        c->gap_ms = gap_ms;
    }
}

/* ---- Receiving ------------------------------------------------------------ */

/* If f is a notification, delivers it and returns true. */
static bool notify(lsc_client *c, const lsc_frame *f, lsc_notification *n)
{
    n->cmd = f->cmd;
    n->group = 0;
    n->times = 0;
    int r;
    switch (f->cmd) {
    case LSC_CMD_GROUP_RUN:
        r = lsc_decode_group_run(f, &n->group, &n->times);
        break;
    case LSC_CMD_GROUP_STOP:
        r = lsc_decode_group_stop(f);
        break;
    case LSC_CMD_GROUP_COMPLETE:
        r = lsc_decode_group_complete(f, &n->group, &n->times);
        break;
    default:
        return false;
    }
    if (r != 0) {
        return false; /* the parser checks these lengths: cannot happen */
    }
    c->notifications++;
    if (c->notify != NULL) {
        c->notify(c->notify_user, n);
    }
    return true;
}

static void on_frame(lsc_client *c, wait_state *w, const lsc_frame *f)
{
    if (c->trace != NULL) {
        c->trace(c->trace_user, LSC_TRACE_RX, c->parser.buf, c->parser.len);
    }
    lsc_notification n;
    bool is_note = notify(c, f, &n);
    w->notes += is_note;
    int m = MATCH_NONE;
    if (!w->done && w->match != NULL) {
        m = w->match(w->ctx, f);
    }
    if (m == MATCH_DONE || (m < 0 && m != LSC_EREPLY)) {
        w->done = true;
        w->result = m == MATCH_DONE ? 0 : m;
    } else if (!is_note) {
        c->unexpected++;
        w->bad = w->bad || m == LSC_EREPLY;
    }
}

/* Parses n received bytes (all of them, even after the wait is done). */
static void on_bytes(lsc_client *c, wait_state *w, const uint8_t *bytes, size_t n)
{
    c->last_rx_ms = c->io.now_ms(c->io.ctx);
    while (n > 0) {
        lsc_frame f;
        int r;
        size_t k = lsc_parser_feed_buf(&c->parser, bytes, n, &f, &r);
        bytes += k;
        n -= k;
        if (r == 1) {
            on_frame(c, w, &f);
        } else if (r == LSC_EFRAME || r == LSC_ETOOBIG) {
            w->bad = true;
        }
    }
}

/* True while the parser holds part of a frame that the gap may drop. */
static bool gap_pending(const lsc_client *c)
{
    return c->gap_ms > 0 && !c->parser.complete && c->parser.len > 0;
}

/* The frame gap (see lsc/client.h): a read that found nothing proves the line
 * silent since the last bytes arrived, because every byte that came in between
 * would have been read. Only then is a partial frame dropped, never because
 * the caller read late. */
static void on_silence(lsc_client *c)
{
    if (gap_pending(c) && (uint32_t)(c->io.now_ms(c->io.ctx) - c->last_rx_ms) >= c->gap_ms) {
        lsc_parser_reset(&c->parser);
    }
}

/* One io.read: > 0 bytes processed, 0 nothing, < 0 transport error. While a
 * partial frame is pending, the wait is cut short to end when the gap is
 * reached, so that a reply arriving later in a long wait is not glued to it. */
static int read_once(lsc_client *c, wait_state *w, uint32_t timeout_ms)
{
    if (gap_pending(c)) {
        uint32_t quiet = c->io.now_ms(c->io.ctx) - c->last_rx_ms;
        uint32_t to_gap = quiet >= c->gap_ms ? 0 : c->gap_ms - quiet;
        timeout_ms = to_gap < timeout_ms ? to_gap : timeout_ms;
    }
    uint8_t chunk[CHUNK];
    int r = c->io.read(c->io.ctx, chunk, sizeof chunk, timeout_ms);
    if (r < 0) {
        return r;
    }
    if (r == 0) {
        on_silence(c);
    }
    if ((size_t)r > sizeof chunk) {
        return LSC_EIO;
    }
    if (r > 0) {
        on_bytes(c, w, chunk, (size_t)r);
    }
    return r;
}

/* The most reads a wait of timeout_ms makes (lsc/client.h): the clock alone
 * would not end it if it never advanced while input kept coming. 32-bit
 * arithmetic (AVR), saturating: beyond 2^32 reads the clock has to work. */
static uint32_t read_budget(uint32_t timeout_ms)
{
    const uint32_t max_ms = (UINT32_MAX - LSC_CLIENT_WAIT_READS_MIN) / LSC_CLIENT_READS_PER_MS;
    return timeout_ms > max_ms ? UINT32_MAX
                               : LSC_CLIENT_WAIT_READS_MIN + LSC_CLIENT_READS_PER_MS * timeout_ms;
}

/* Reads until the matcher is done or timeout_ms passed (or the read budget is
 * spent); once: return after the first read that brought bytes. Returns 0 (or
 * the matcher's error) when done, LSC_ETIMEOUT/LSC_EREPLY when the time ran
 * out, or a transport error. */
static int run(lsc_client *c, wait_state *w, uint32_t timeout_ms, bool once)
{
    uint32_t start = c->io.now_ms(c->io.ctx);
    for (uint32_t reads = read_budget(timeout_ms); reads > 0; reads--) {
        uint32_t elapsed = c->io.now_ms(c->io.ctx) - start;
        uint32_t left = elapsed >= timeout_ms ? 0 : timeout_ms - elapsed;
        int r = read_once(c, w, left);
        if (r < 0) {
            return r;
        }
        if (w->done) {
            return w->result;
        }
        if ((r > 0 && once) || left == 0) {
            break;
        }
    }
    return w->bad ? LSC_EREPLY : LSC_ETIMEOUT;
}

/* Processes input that arrived before a request, so a late reply to an earlier
 * request is not taken for this one's (notifications in it are delivered):
 * until a read finds nothing, for at most LSC_CLIENT_DRAIN_MS and
 * LSC_CLIENT_DRAIN_READS reads. */
static int drain(lsc_client *c)
{
    wait_state w = {NULL, NULL, 0, false, false, 0};
    uint32_t start = c->io.now_ms(c->io.ctx);
    for (uint32_t reads = 0; reads < LSC_CLIENT_DRAIN_READS; reads++) {
        int r = read_once(c, &w, 0);
        if (r <= 0) {
            return r;
        }
        if ((uint32_t)(c->io.now_ms(c->io.ctx) - start) >= LSC_CLIENT_DRAIN_MS) {
            break;
        }
    }
    return 0;
}

void lsc_client_get_counts(const lsc_client *c, lsc_client_counts *out)
{
    if (out == NULL) {
        return;
    }
    bool ok = c != NULL;
    out->frames = ok ? c->parser.frames : 0;
    out->notifications = ok ? c->notifications : 0;
    out->unexpected = ok ? c->unexpected : 0;
    out->discarded = ok ? c->parser.discarded : 0;
    out->malformed = ok ? c->parser.errors : 0;
    out->pending = ok && !c->parser.complete ? (uint32_t)c->parser.len : 0;
}

/* ---- Sending ---------------------------------------------------------------- */

/* Writes the frame encoded in buf (len is the encoder's result). */
static int send_frame(lsc_client *c, const uint8_t *buf, int len)
{
    if (len < 0) {
        return len;
    }
    if (c->trace != NULL) {
        c->trace(c->trace_user, LSC_TRACE_TX, buf, (size_t)len);
    }
    int r = c->io.write(c->io.ctx, buf, (size_t)len);
    if (r < 0) {
        return r;
    }
    return r == len ? 0 : LSC_EIO;
}

int lsc_client_move(lsc_client *c, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    return send_frame(c, buf, lsc_encode_servo_move(buf, sizeof buf, time_ms, servos, n));
}

int lsc_client_move_one(lsc_client *c, uint8_t id, uint16_t position, uint16_t time_ms)
{
    lsc_servo s = {id, position};
    return lsc_client_move(c, time_ms, &s, 1);
}

int lsc_client_run_group(lsc_client *c, uint8_t group, uint16_t times)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MIN + 3];
    return send_frame(c, buf, lsc_encode_group_run(buf, sizeof buf, group, times));
}

int lsc_client_stop_group(lsc_client *c)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MIN];
    return send_frame(c, buf, lsc_encode_group_stop(buf, sizeof buf));
}

int lsc_client_set_group_speed(lsc_client *c, uint8_t group, uint16_t percent)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MIN + 3];
    return send_frame(c, buf, lsc_encode_group_speed(buf, sizeof buf, group, percent));
}

int lsc_client_unload(lsc_client *c, const uint8_t *ids, size_t n)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    return send_frame(c, buf, lsc_encode_unload(buf, sizeof buf, ids, n));
}

int lsc_client_send_raw(lsc_client *c, uint8_t cmd, const uint8_t *params, size_t n)
{
    if (!usable(c) || cmd == LSC_CMD_GROUP_COMPLETE) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    return send_frame(c, buf, lsc_encode_frame(buf, sizeof buf, cmd, params, n));
}

/* Drains stale input, sends the encoded frame, waits for the matcher. */
static int request(lsc_client *c, const uint8_t *buf, int len, match_fn m, void *ctx,
                   uint32_t timeout_ms)
{
    if (len < 0) {
        return len;
    }
    int r = drain(c);
    if (r < 0) {
        return r;
    }
    r = send_frame(c, buf, len);
    if (r < 0) {
        return r;
    }
    wait_state w = {m, ctx, 0, false, false, 0};
    return run(c, &w, timeout_ms, false);
}

/* ---- Commands with a reply ---------------------------------------------------- */

static int match_battery(void *ctx, const lsc_frame *f)
{
    if (f->cmd != LSC_CMD_BATTERY) {
        return MATCH_NONE;
    }
    return lsc_decode_battery_reply(f, ctx) == 0 ? MATCH_DONE : LSC_EREPLY;
}

int lsc_client_get_battery(lsc_client *c, uint16_t *mv, uint32_t timeout_ms)
{
    if (!usable(c) || mv == NULL) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MIN];
    uint16_t got = 0;
    int r = request(c, buf, lsc_encode_battery_request(buf, sizeof buf), match_battery, &got,
                    timeout_ms);
    if (r == 0) {
        *mv = got;
    }
    return r;
}

/* A read of n servos (positions, offsets): the ids asked and where the
 * reply goes (lsc_servo or lsc_servo_offset). */
typedef struct list_wait {
    const uint8_t *ids;
    size_t n;
    void *out;
} list_wait;

/* Whether the n items at items (stride bytes apart, the id first) carry
 * exactly the ids asked, in order. */
static bool ids_in_order(const list_wait *p, const uint8_t *items, size_t stride)
{
    for (size_t i = 0; i < p->n; i++) {
        if (items[i * stride] != p->ids[i]) {
            return false;
        }
    }
    return true;
}

/* Sends the request in buf[0..len) (or returns the encoder's error) and
 * waits for the reply m takes. Returns p->n or an error. */
static int read_list(lsc_client *c, const uint8_t *buf, int len, match_fn m, list_wait *p,
                     uint32_t timeout_ms)
{
    int r = request(c, buf, len, m, p, timeout_ms);
    return r == 0 ? (int)p->n : r;
}

static int match_positions(void *ctx, const lsc_frame *f)
{
    const list_wait *p = ctx;
    lsc_servo *out = p->out;
    if (f->cmd != LSC_CMD_POS_READ) {
        return MATCH_NONE;
    }
    if (f->nparams != 3u * p->n + 1u || f->params[0] != p->n ||
        !ids_in_order(p, &f->params[1], 3)) {
        return LSC_EREPLY;
    }
    for (size_t i = 0; i < p->n; i++) {
        const uint8_t *at = &f->params[1u + 3u * i];
        out[i].id = at[0];
        out[i].position = (uint16_t)(at[1] | (at[2] << 8));
    }
    return MATCH_DONE;
}

int lsc_client_read_positions(lsc_client *c, const uint8_t *ids, size_t n, lsc_servo *out,
                              uint32_t timeout_ms)
{
    if (!usable(c) || out == NULL) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    list_wait p = {ids, n, out};
    return read_list(c, buf, lsc_encode_pos_request(buf, sizeof buf, ids, n), match_positions,
                     &p, timeout_ms);
}

static int match_offsets(void *ctx, const lsc_frame *f)
{
    const list_wait *p = ctx;
    lsc_servo_offset got[LSC_OFFSET_MAX];
    if (f->cmd != LSC_CMD_OFFSET_READ) {
        return MATCH_NONE;
    }
    int n = lsc_decode_offset_reply(f, got, LSC_OFFSET_MAX);
    if (n < 0 || (size_t)n != p->n || !ids_in_order(p, &got[0].id, sizeof got[0])) {
        return LSC_EREPLY;
    }
    for (size_t i = 0; i < p->n; i++) {
        ((lsc_servo_offset *)p->out)[i] = got[i];
    }
    return MATCH_DONE;
}

int lsc_client_read_offsets(lsc_client *c, const uint8_t *ids, size_t n, lsc_servo_offset *out,
                            uint32_t timeout_ms)
{
    if (!usable(c) || out == NULL) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    list_wait p = {ids, n, out};
    return read_list(c, buf, lsc_encode_offset_request(buf, sizeof buf, ids, n), match_offsets,
                     &p, timeout_ms);
}

int lsc_client_adjust_offset(lsc_client *c, uint8_t id, int8_t offset)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[8];
    return send_frame(c, buf, lsc_encode_offset_adjust(buf, sizeof buf, id, offset));
}

typedef struct raw_wait {
    uint8_t cmd;
    uint8_t *reply;
    size_t cap;
    int got;
} raw_wait;

static int match_raw(void *ctx, const lsc_frame *f)
{
    raw_wait *w = ctx;
    if (f->cmd != w->cmd) {
        return MATCH_NONE;
    }
    if (f->nparams > w->cap) {
        return LSC_ENOSPC;
    }
    for (size_t i = 0; i < f->nparams; i++) {
        w->reply[i] = f->params[i];
    }
    w->got = f->nparams;
    return MATCH_DONE;
}

int lsc_client_request_raw(lsc_client *c, uint8_t cmd, const uint8_t *params, size_t n,
                           uint8_t reply_cmd, uint8_t *reply, size_t cap, uint32_t timeout_ms)
{
    bool note = reply_cmd == LSC_CMD_GROUP_RUN || reply_cmd == LSC_CMD_GROUP_STOP ||
                reply_cmd == LSC_CMD_GROUP_COMPLETE;
    if (!usable(c) || note || cmd == LSC_CMD_GROUP_COMPLETE || (reply == NULL && cap > 0)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_FRAME_MAX];
    raw_wait w = {reply_cmd, reply, cap, 0};
    int r = request(c, buf, lsc_encode_frame(buf, sizeof buf, cmd, params, n), match_raw, &w,
                    timeout_ms);
    return r == 0 ? w.got : r;
}

/* ---- Notifications -------------------------------------------------------------- */

int lsc_client_poll(lsc_client *c, uint32_t timeout_ms)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    wait_state w = {NULL, NULL, 0, false, false, 0};
    int r = run(c, &w, timeout_ms, true);
    return r == LSC_ETIMEOUT || r == LSC_EREPLY ? w.notes : r;
}

static int match_group_end(void *ctx, const lsc_frame *f)
{
    lsc_notification *out = ctx;
    if (f->cmd == LSC_CMD_GROUP_STOP && lsc_decode_group_stop(f) == 0) {
        out->cmd = LSC_CMD_GROUP_STOP;
        out->group = 0;
        out->times = 0;
        return MATCH_DONE;
    }
    if (f->cmd == LSC_CMD_GROUP_COMPLETE &&
        lsc_decode_group_complete(f, &out->group, &out->times) == 0) {
        out->cmd = LSC_CMD_GROUP_COMPLETE;
        return MATCH_DONE;
    }
    return MATCH_NONE;
}

int lsc_client_wait_group(lsc_client *c, uint32_t timeout_ms, lsc_notification *out)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    lsc_notification got = {0, 0, 0};
    wait_state w = {match_group_end, &got, 0, false, false, 0};
    int r = run(c, &w, timeout_ms, false);
    if (r == LSC_EREPLY) {
        r = LSC_ETIMEOUT; /* malformed input is not an answer to anything here */
    }
    if (r == 0 && out != NULL) {
        *out = got;
    }
    return r;
}
