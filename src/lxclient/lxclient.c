/* The bus client: requests and replies of the bus-servo protocol over a
 * caller-supplied lsc_io (contract in lsc/lxclient.h). */
#include "lsc/lxclient.h"

/* Bytes asked of io.read at a time (on the stack). */
#define CHUNK 16u

/* What a wait looks for, and what it found. */
typedef struct wait_state {
    uint8_t id, cmd;  /* the reply awaited; cmd 0: none (a drain) */
    bool collect;     /* ID_READ to the broadcast: every answer, until the timeout */
    bool done;        /* the reply was taken */
    bool bad;         /* bytes came that formed no good frame */
    uint8_t answers;  /* collect: good ID_READ answers */
    uint8_t first;    /* collect: the first one's id */
    uint8_t n;        /* the reply's parameters */
    uint8_t params[LSC_LX_PARAMS_MAX];
    uint8_t *late;    /* a scan's bitmap of ids whose answer came late, or NULL */
} wait_state;

static void wait_init(wait_state *w, uint8_t id, uint8_t cmd, uint8_t *late)
{
    w->id = id;
    w->cmd = cmd;
    w->collect = id == LSC_LX_BROADCAST;
    w->done = false;
    w->bad = false;
    w->answers = 0;
    w->first = 0;
    w->n = 0;
    w->late = late;
}

/* lsc_lxclient_init sets io's three functions, or none. */
static bool usable(const lsc_lxclient *c)
{
    return c != NULL && c->io.write != NULL;
}

int lsc_lxclient_init(lsc_lxclient *c, const lsc_io *io)
{
    if (c == NULL) {
        return LSC_EINVAL;
    }
    c->io.ctx = NULL;
    c->io.write = NULL;
    c->io.read = NULL;
    c->io.now_ms = NULL;
    c->timeout_ms = LSC_LXCLIENT_TIMEOUT_MS;
    c->last_rx_ms = 0;
    c->trace = NULL;
    c->trace_user = NULL;
    c->replies = 0;
    c->strays = 0;
    c->echoes = 0;
    (void)lsc_lx_parser_init(&c->parser);
    if (io == NULL || io->write == NULL || io->read == NULL || io->now_ms == NULL) {
        return LSC_EINVAL;
    }
    c->io = *io;
    c->last_rx_ms = c->io.now_ms(c->io.ctx);
    return 0;
}

void lsc_lxclient_set_timeout(lsc_lxclient *c, uint32_t timeout_ms)
{
    if (c != NULL) {
        c->timeout_ms = timeout_ms;
    }
}

void lsc_lxclient_set_trace(lsc_lxclient *c, lsc_trace_fn fn, void *user)
{
    if (c != NULL) {
        c->trace = fn;
        c->trace_user = user;
    }
}

/* ---- Receiving --------------------------------------------------------------- */

static void set_bit(uint8_t *map, uint8_t id)
{
    map[id / 8u] = (uint8_t)(map[id / 8u] | (1u << (id % 8u)));
}

static bool get_bit(const uint8_t *map, uint8_t id)
{
    return ((unsigned)map[id / 8u] >> (id % 8u) & 1u) != 0u;
}

static void on_frame(lsc_lxclient *c, wait_state *w, const lsc_lx_frame *f)
{
    if (c->trace != NULL) {
        c->trace(c->trace_user, LSC_TRACE_RX, c->parser.buf, c->parser.len);
    }
    if (!f->reply) {
        c->echoes++; /* a request: the host's own, heard back */
        return;
    }
    if (w->collect && f->cmd == LSC_LX_ID_READ) {
        w->first = w->answers == 0 ? f->id : w->first;
        w->answers = (uint8_t)(w->answers + (w->answers < UINT8_MAX));
        c->replies++;
        return;
    }
    if (!w->done && f->cmd == w->cmd && f->id == w->id) {
        w->done = true;
        /* nparams <= LSC_LX_PARAMS_MAX (the parser's lengths); a whole
         * LSC_LX_PARAMS_MAX is copied: params + LSC_LX_PARAMS_MAX lies within
         * the parser's buffer, and no bound of the loop depends on the frame */
        w->n = f->nparams;
        for (size_t i = 0; i < sizeof w->params; i++) {
            w->params[i] = f->params[i];
        }
        c->replies++;
        return;
    }
    c->strays++;
    if (w->late != NULL && f->cmd == LSC_LX_ID_READ) {
        set_bit(w->late, f->id); /* the parser allows a reply's id 0..253 only */
    }
}

static void on_bytes(lsc_lxclient *c, wait_state *w, const uint8_t *bytes, size_t n)
{
    c->last_rx_ms = c->io.now_ms(c->io.ctx);
    for (size_t i = 0; i < n; i++) {
        lsc_lx_frame f;
        int r = lsc_lx_parser_feed(&c->parser, bytes[i], &f);
        if (r == 1) {
            on_frame(c, w, &f);
        } else if (r < 0) {
            w->bad = true;
        }
    }
}

/* True while the parser holds part of a frame that the gap may drop. */
static bool gap_pending(const lsc_lxclient *c)
{
    return !c->parser.complete && c->parser.len > 0;
}

/* One io.read: > 0 bytes processed, 0 nothing, < 0 transport error. While a
 * partial frame is pending, a read waits at most the gap; one that finds
 * nothing when the line has been silent for the gap since the last bytes
 * drops the partial frame. */
static int read_once(lsc_lxclient *c, wait_state *w, uint32_t timeout_ms)
{
    bool pending = gap_pending(c);
    if (pending && timeout_ms > LSC_LXCLIENT_GAP_MS) {
        timeout_ms = LSC_LXCLIENT_GAP_MS;
    }
    uint8_t chunk[CHUNK];
    int r = c->io.read(c->io.ctx, chunk, sizeof chunk, timeout_ms);
    if (r < 0) {
        return r;
    }
    if ((size_t)r > sizeof chunk) {
        return LSC_EIO;
    }
    if (r > 0) {
        on_bytes(c, w, chunk, (size_t)r);
    } else if (pending &&
               (uint32_t)(c->io.now_ms(c->io.ctx) - c->last_rx_ms) >= LSC_LXCLIENT_GAP_MS) {
        lsc_lx_parser_reset(&c->parser);
        w->bad = true;
    }
    return r;
}

/* The most reads a wait of timeout_ms makes (saturating, 32-bit for AVR). */
static uint32_t read_budget(uint32_t timeout_ms)
{
    const uint32_t max_ms =
        (UINT32_MAX - LSC_LXCLIENT_WAIT_READS_MIN) / LSC_LXCLIENT_READS_PER_MS;
    return timeout_ms > max_ms ? UINT32_MAX
                               : LSC_LXCLIENT_WAIT_READS_MIN + LSC_LXCLIENT_READS_PER_MS * timeout_ms;
}

/* Reads until the reply is taken (unless collecting) or timeout_ms passed or
 * the read budget is spent. Returns 0 (taken), LSC_ETIMEOUT, LSC_EREPLY (bad
 * bytes and no reply) or a transport error. Collecting returns 0. */
static int run(lsc_lxclient *c, wait_state *w, uint32_t timeout_ms)
{
    uint32_t start = c->io.now_ms(c->io.ctx);
    for (uint32_t reads = read_budget(timeout_ms); reads > 0 && !w->done; reads--) {
        uint32_t elapsed = c->io.now_ms(c->io.ctx) - start;
        uint32_t left = elapsed >= timeout_ms ? 0 : timeout_ms - elapsed;
        int r = read_once(c, w, left);
        if (r < 0) {
            return r;
        }
        if (left == 0) {
            break;
        }
    }
    return w->done || w->collect ? 0 : w->bad ? LSC_EREPLY : LSC_ETIMEOUT;
}

/* Reads what has already arrived (see lsc/lxclient.h). */
static int drain(lsc_lxclient *c, uint8_t *late)
{
    wait_state w;
    wait_init(&w, 0, 0, late);
    uint32_t start = c->io.now_ms(c->io.ctx);
    for (uint32_t reads = 0; reads < LSC_LXCLIENT_DRAIN_READS; reads++) {
        int r = read_once(c, &w, 0);
        if (r <= 0) {
            return r;
        }
        if ((uint32_t)(c->io.now_ms(c->io.ctx) - start) >= LSC_LXCLIENT_DRAIN_MS) {
            break;
        }
    }
    return 0;
}

/* ---- Sending ------------------------------------------------------------------- */

/* Writes the frame in buf[0..len) (len: the encoder's result), and tells the
 * parser its echo may come. */
static int send_frame(lsc_lxclient *c, const uint8_t *buf, int len)
{
    if (len < 0) {
        return len;
    }
    if (c->trace != NULL) {
        c->trace(c->trace_user, LSC_TRACE_TX, buf, (size_t)len);
    }
    /* a partial frame pending stays: a late answer split across the drain
     * still completes (and is counted, never taken); garbage before the
     * reply is resynchronised by the parser, and dropped on the gap */
    (void)lsc_lx_parser_expect_echo(&c->parser, buf, (size_t)len);
    int r = c->io.write(c->io.ctx, buf, (size_t)len);
    if (r < 0) {
        return r;
    }
    return r == len ? 0 : LSC_EIO;
}

/* Drains, sends the request in buf[0..len), waits for w's reply. */
static int request(lsc_lxclient *c, const uint8_t *buf, int len, wait_state *w,
                   uint32_t timeout_ms)
{
    if (len < 0) {
        return len;
    }
    int r = drain(c, w->late);
    if (r < 0) {
        return r;
    }
    r = send_frame(c, buf, len);
    if (r < 0) {
        return r;
    }
    return run(c, w, timeout_ms);
}

/* A read of cmd from id (ok: the caller's outputs are there): on 0, *f is
 * the reply (its params in w). */
static int ask_ms(lsc_lxclient *c, bool ok, uint8_t id, uint8_t cmd, wait_state *w,
                  lsc_lx_frame *f, uint32_t timeout_ms)
{
    uint8_t buf[LSC_LX_FRAME_MIN];
    wait_init(w, id, cmd, w->late);
    f->id = id;
    f->cmd = 0; /* no command: a decoder refuses it when no reply came */
    f->reply = true;
    f->params = w->params;
    f->nparams = 0;
    if (!ok || !usable(c) || id == LSC_LX_BROADCAST) {
        return LSC_EINVAL;
    }
    int r = request(c, buf, lsc_lx_encode_request(buf, sizeof buf, id, cmd), w, timeout_ms);
    if (r == 0) {
        f->cmd = cmd;
        f->nparams = w->n;
    }
    return r;
}

/* The same, waiting the client's timeout. */
static int ask(lsc_lxclient *c, bool ok, uint8_t id, uint8_t cmd, wait_state *w, lsc_lx_frame *f)
{
    return ask_ms(c, ok, id, cmd, w, f, usable(c) ? c->timeout_ms : 0u);
}

/* A typed read's result: the request's error, else the decoder's (a reply
 * the decoder refuses is LSC_EREPLY). */
static int decoded(int r, int d)
{
    return r != 0 ? r : d != 0 ? LSC_EREPLY : 0;
}

/* ---- Writes ------------------------------------------------------------------------ */

static int write_frame(lsc_lxclient *c, const uint8_t *buf, int len)
{
    return usable(c) ? send_frame(c, buf, len) : LSC_EINVAL;
}

int lsc_lxclient_move(lsc_lxclient *c, uint8_t id, uint16_t position, uint16_t time_ms)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf, lsc_lx_encode_move_time(buf, sizeof buf, id, LSC_LX_MOVE_TIME_WRITE,
                                                       position, time_ms));
}

int lsc_lxclient_move_preset(lsc_lxclient *c, uint8_t id, uint16_t position, uint16_t time_ms)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf,
                       lsc_lx_encode_move_time(buf, sizeof buf, id, LSC_LX_MOVE_TIME_WAIT_WRITE,
                                               position, time_ms));
}

int lsc_lxclient_move_start(lsc_lxclient *c, uint8_t id)
{
    uint8_t buf[LSC_LX_FRAME_MIN];
    return write_frame(c, buf, lsc_lx_encode_request(buf, sizeof buf, id, LSC_LX_MOVE_START));
}

int lsc_lxclient_move_stop(lsc_lxclient *c, uint8_t id)
{
    uint8_t buf[LSC_LX_FRAME_MIN];
    return write_frame(c, buf, lsc_lx_encode_request(buf, sizeof buf, id, LSC_LX_MOVE_STOP));
}

int lsc_lxclient_write_id(lsc_lxclient *c, uint8_t id, uint8_t new_id)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    int len = id == LSC_LX_BROADCAST
                  ? LSC_EINVAL /* every servo on the bus would take the id */
                  : lsc_lx_encode_id(buf, sizeof buf, id, LSC_LX_ID_WRITE, new_id);
    return write_frame(c, buf, len);
}

int lsc_lxclient_adjust_offset(lsc_lxclient *c, uint8_t id, int8_t offset)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf,
                       lsc_lx_encode_offset(buf, sizeof buf, id, LSC_LX_OFFSET_ADJUST, offset));
}

int lsc_lxclient_save_offset(lsc_lxclient *c, uint8_t id)
{
    uint8_t buf[LSC_LX_FRAME_MIN];
    return write_frame(c, buf, lsc_lx_encode_request(buf, sizeof buf, id, LSC_LX_OFFSET_WRITE));
}

int lsc_lxclient_write_limits(lsc_lxclient *c, uint8_t id, uint16_t min, uint16_t max)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(
        c, buf, lsc_lx_encode_angle_limit(buf, sizeof buf, id, LSC_LX_ANGLE_LIMIT_WRITE, min, max));
}

int lsc_lxclient_write_vin_limits(lsc_lxclient *c, uint8_t id, uint16_t min_mv, uint16_t max_mv)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf,
                       lsc_lx_encode_vin_limit(buf, sizeof buf, id, LSC_LX_VIN_LIMIT_WRITE, min_mv,
                                               max_mv));
}

int lsc_lxclient_write_temp_limit(lsc_lxclient *c, uint8_t id, uint8_t celsius)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(
        c, buf, lsc_lx_encode_temp_limit(buf, sizeof buf, id, LSC_LX_TEMP_LIMIT_WRITE, celsius));
}

int lsc_lxclient_write_mode(lsc_lxclient *c, uint8_t id, uint8_t mode, int16_t speed)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(
        c, buf, lsc_lx_encode_motor_mode(buf, sizeof buf, id, LSC_LX_MOTOR_MODE_WRITE, mode, speed));
}

int lsc_lxclient_write_torque(lsc_lxclient *c, uint8_t id, bool on)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf, lsc_lx_encode_load(buf, sizeof buf, id, LSC_LX_LOAD_WRITE, on));
}

int lsc_lxclient_write_led(lsc_lxclient *c, uint8_t id, bool on)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf,
                       lsc_lx_encode_led_ctrl(buf, sizeof buf, id, LSC_LX_LED_CTRL_WRITE, on));
}

int lsc_lxclient_write_alarms(lsc_lxclient *c, uint8_t id, uint8_t mask)
{
    uint8_t buf[LSC_LX_FRAME_MAX];
    return write_frame(c, buf,
                       lsc_lx_encode_led_error(buf, sizeof buf, id, LSC_LX_LED_ERROR_WRITE, mask));
}

/* ---- Reads --------------------------------------------------------------------------- */

/* Each typed read: the request, then the decoder on what came (on an error the
 * frame has no command, the decoder refuses it and writes nothing). */
#define READ(ok, cmd, decode_call)                                                             \
    wait_state w;                                                                              \
    lsc_lx_frame f;                                                                            \
    w.late = NULL;                                                                             \
    int r = ask(c, (ok), id, (cmd), &w, &f);                                                   \
    return decoded(r, (decode_call))

int lsc_lxclient_read_position(lsc_lxclient *c, uint8_t id, int16_t *position)
{
    READ(position != NULL, LSC_LX_POS_READ, lsc_lx_decode_position(&f, position));
}

int lsc_lxclient_read_move(lsc_lxclient *c, uint8_t id, bool preset, uint16_t *position,
                           uint16_t *time_ms)
{
    READ(position != NULL && time_ms != NULL, preset ? LSC_LX_MOVE_TIME_WAIT_READ : LSC_LX_MOVE_TIME_READ,
         lsc_lx_decode_move_time(&f, position, time_ms));
}

int lsc_lxclient_read_id(lsc_lxclient *c, uint8_t id)
{
    uint8_t got = 0;
    READ(true, LSC_LX_ID_READ, lsc_lx_decode_id(&f, &got));
}

int lsc_lxclient_read_offset(lsc_lxclient *c, uint8_t id, int8_t *offset)
{
    READ(offset != NULL, LSC_LX_OFFSET_READ, lsc_lx_decode_offset(&f, offset));
}

int lsc_lxclient_read_limits(lsc_lxclient *c, uint8_t id, uint16_t *min, uint16_t *max)
{
    READ(min != NULL && max != NULL, LSC_LX_ANGLE_LIMIT_READ, lsc_lx_decode_angle_limit(&f, min, max));
}

int lsc_lxclient_read_vin_limits(lsc_lxclient *c, uint8_t id, uint16_t *min_mv, uint16_t *max_mv)
{
    READ(min_mv != NULL && max_mv != NULL, LSC_LX_VIN_LIMIT_READ, lsc_lx_decode_vin_limit(&f, min_mv, max_mv));
}

int lsc_lxclient_read_temp_limit(lsc_lxclient *c, uint8_t id, uint8_t *celsius)
{
    READ(celsius != NULL, LSC_LX_TEMP_LIMIT_READ, lsc_lx_decode_temp_limit(&f, celsius));
}

int lsc_lxclient_read_temp(lsc_lxclient *c, uint8_t id, uint8_t *celsius)
{
    READ(celsius != NULL, LSC_LX_TEMP_READ, lsc_lx_decode_temp(&f, celsius));
}

int lsc_lxclient_read_vin(lsc_lxclient *c, uint8_t id, uint16_t *millivolts)
{
    READ(millivolts != NULL, LSC_LX_VIN_READ, lsc_lx_decode_vin(&f, millivolts));
}

int lsc_lxclient_read_mode(lsc_lxclient *c, uint8_t id, uint8_t *mode, int16_t *speed)
{
    READ(mode != NULL && speed != NULL, LSC_LX_MOTOR_MODE_READ, lsc_lx_decode_motor_mode(&f, mode, speed));
}

int lsc_lxclient_read_torque(lsc_lxclient *c, uint8_t id, bool *on)
{
    READ(on != NULL, LSC_LX_LOAD_READ, lsc_lx_decode_load(&f, on));
}

int lsc_lxclient_read_led(lsc_lxclient *c, uint8_t id, bool *on)
{
    READ(on != NULL, LSC_LX_LED_CTRL_READ, lsc_lx_decode_led_ctrl(&f, on));
}

int lsc_lxclient_read_alarms(lsc_lxclient *c, uint8_t id, uint8_t *mask)
{
    READ(mask != NULL, LSC_LX_LED_ERROR_READ, lsc_lx_decode_led_error(&f, mask));
}

/* ---- Who is there ---------------------------------------------------------------------- */

int lsc_lxclient_whois(lsc_lxclient *c, lsc_lx_whois *out)
{
    if (!usable(c)) {
        return LSC_EINVAL;
    }
    uint8_t buf[LSC_LX_FRAME_MIN];
    wait_state w;
    wait_init(&w, LSC_LX_BROADCAST, LSC_LX_ID_READ, NULL);
    int r = request(c, buf, lsc_lx_encode_request(buf, sizeof buf, LSC_LX_BROADCAST, LSC_LX_ID_READ),
                    &w, c->timeout_ms);
    if (r < 0) {
        return r;
    }
    if (out != NULL) {
        out->id = w.first;
        out->answers = w.answers;
        out->garbled = w.bad;
    }
    return w.answers == 1 && !w.bad ? 0 : w.answers == 0 && !w.bad ? LSC_ETIMEOUT : LSC_EREPLY;
}

bool lsc_lx_scan_found(const lsc_lx_scan *s, uint8_t id)
{
    return s != NULL && id <= LSC_LX_ID_MAX && get_bit(s->found, id);
}

bool lsc_lx_scan_garbled(const lsc_lx_scan *s, uint8_t id)
{
    return s != NULL && id <= LSC_LX_ID_MAX && get_bit(s->garbled, id);
}

/* r, but 0 for the ends of a wait that heard no reply (a scan goes on). */
static int transport_error(int r)
{
    return r == LSC_EREPLY || r == LSC_ETIMEOUT ? 0 : r;
}

/* Asks id; marks it found or garbled. Returns 0 or a transport error. */
static int scan_one(lsc_lxclient *c, uint8_t id, uint32_t ms, uint8_t *late, lsc_lx_scan *out)
{
    wait_state w;
    lsc_lx_frame f;
    w.late = late;
    int r = ask_ms(c, true, id, LSC_LX_ID_READ, &w, &f, ms);
    uint8_t got = 0;
    r = decoded(r, lsc_lx_decode_id(&f, &got));
    if (r == 0) {
        set_bit(out->found, id);
        out->count++;
    } else if (r == LSC_EREPLY) {
        set_bit(out->garbled, id);
    }
    return transport_error(r);
}

int lsc_lxclient_scan(lsc_lxclient *c, const uint8_t *ids, size_t n, uint32_t per_id_ms,
                      lsc_lx_scan *out)
{
    size_t count = ids == NULL ? LSC_LX_ID_MAX + 1u : n;
    bool ok = usable(c) && out != NULL;
    for (size_t i = 0; ok && ids != NULL && i < n; i++) {
        ok = ids[i] <= LSC_LX_ID_MAX;
    }
    if (!ok) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < sizeof out->found; i++) {
        out->found[i] = 0;
        out->garbled[i] = 0;
    }
    out->count = 0;
    out->asked = 0;
    uint8_t late[32] = {0}, asked[32] = {0};
    uint32_t ms = per_id_ms == 0 ? LSC_LXCLIENT_SCAN_TIMEOUT_MS : per_id_ms;
    bool listen = false;
    for (size_t i = 0; i < count; i++) {
        uint8_t id = (uint8_t)(ids == NULL ? i : ids[i]);
        int r = scan_one(c, id, ms, late, out);
        if (r < 0) {
            return r;
        }
        out->asked++;
        set_bit(asked, id);
        listen = !get_bit(out->found, id);
    }
    /* the last id asked did not answer: its answer, or another late one, may
     * still be on its way; listened for at most LSC_LXCLIENT_TIMEOUT_MS, so
     * that a longer timeout (a front end's 1 s) keeps a whole scan under 3 s */
    if (listen) {
        wait_state w;
        wait_init(&w, 0, 0, late);
        uint32_t listen_ms =
            c->timeout_ms < LSC_LXCLIENT_TIMEOUT_MS ? c->timeout_ms : LSC_LXCLIENT_TIMEOUT_MS;
        int r = transport_error(run(c, &w, listen_ms));
        if (r < 0) {
            return r;
        }
    }
    /* a good answer that came late from an id asked: that id is there; ask
     * it again, longer (an id not asked is not the scan's business) */
    for (unsigned id = 0; id <= LSC_LX_ID_MAX; id++) {
        if (get_bit(late, (uint8_t)id) && get_bit(asked, (uint8_t)id) &&
            !get_bit(out->found, (uint8_t)id)) {
            out->garbled[id / 8u] = (uint8_t)(out->garbled[id / 8u] & ~(1u << (id % 8u)));
            int r = scan_one(c, (uint8_t)id, c->timeout_ms, NULL, out);
            if (r < 0) {
                return r;
            }
        }
    }
    return (int)out->count;
}

/* ---- The safe operations --------------------------------------------------------------- */

int lsc_lxclient_info(lsc_lxclient *c, uint8_t id, lsc_lx_info *out)
{
    lsc_lx_info i;
    if (out == NULL) {
        return LSC_EINVAL;
    }
    i.id = id;
    int r = lsc_lxclient_read_position(c, id, &i.position);
    r = r != 0 ? r : lsc_lxclient_read_temp(c, id, &i.temp_c);
    r = r != 0 ? r : lsc_lxclient_read_vin(c, id, &i.vin_mv);
    r = r != 0 ? r : lsc_lxclient_read_offset(c, id, &i.offset);
    r = r != 0 ? r : lsc_lxclient_read_limits(c, id, &i.limit_min, &i.limit_max);
    r = r != 0 ? r : lsc_lxclient_read_vin_limits(c, id, &i.vin_min_mv, &i.vin_max_mv);
    r = r != 0 ? r : lsc_lxclient_read_temp_limit(c, id, &i.temp_limit_c);
    r = r != 0 ? r : lsc_lxclient_read_mode(c, id, &i.mode, &i.speed);
    r = r != 0 ? r : lsc_lxclient_read_torque(c, id, &i.torque);
    r = r != 0 ? r : lsc_lxclient_read_led(c, id, &i.led);
    r = r != 0 ? r : lsc_lxclient_read_alarms(c, id, &i.alarms);
    if (r == 0) {
        *out = i;
    }
    return r;
}

const char *lsc_lx_refusal_str(lsc_lx_refusal why)
{
    switch (why) {
    case LSC_LX_DONE:
        return "done";
    case LSC_LX_BAD_ARGUMENT:
        return "a value is outside the bus-servo protocol's ranges; nothing was sent";
    case LSC_LX_ID_TAKEN:
        return "a servo already answers at the new id (two servos would share it); nothing was "
               "written";
    case LSC_LX_ID_ABSENT:
        return "no servo answers at that id; nothing was written";
    case LSC_LX_ID_GARBLED:
        return "the answers at that id collide (several servos share it): connect the servo "
               "alone to the bus; nothing was written";
    case LSC_LX_NO_SERVO:
        return "no servo answers on the bus; nothing was written";
    case LSC_LX_NOT_ALONE:
        return "more than one servo answers on the bus: connect the servo whose id you want to "
               "set alone; nothing was written";
    case LSC_LX_NOT_READ_BACK:
        return "written, but the servo did not answer with the new value";
    case LSC_LX_OUT_OF_RANGE:
        return "the result would leave the bus-servo protocol's range; nothing was written";
    }
    return "unknown refusal";
}

/* Stores why (when wanted) and returns r. */
static int because(lsc_lx_refusal *why, lsc_lx_refusal value, int r)
{
    if (why != NULL) {
        *why = value;
    }
    return r;
}

/* Writes new_id to servo id (it answers there, alone), then reads it back. */
static int write_and_check_id(lsc_lxclient *c, uint8_t id, uint8_t new_id, lsc_lx_refusal *why)
{
    int r = lsc_lxclient_write_id(c, id, new_id);
    if (r < 0) {
        return because(why, LSC_LX_DONE, r);
    }
    r = lsc_lxclient_read_id(c, new_id);
    return because(why, r == 0 ? LSC_LX_DONE : LSC_LX_NOT_READ_BACK, r);
}

int lsc_lxclient_change_id(lsc_lxclient *c, uint8_t old_id, uint8_t new_id, lsc_lx_refusal *why)
{
    if (!usable(c) || old_id > LSC_LX_ID_MAX || new_id > LSC_LX_ID_MAX || old_id == new_id) {
        return because(why, LSC_LX_BAD_ARGUMENT, LSC_EINVAL);
    }
    int r = lsc_lxclient_read_id(c, new_id);
    if (r == 0 || r == LSC_EREPLY) {
        return because(why, LSC_LX_ID_TAKEN, LSC_EINVAL);
    }
    if (r != LSC_ETIMEOUT) {
        return because(why, LSC_LX_DONE, r);
    }
    /* two servos sharing old_id answer ID_READ with the same bytes; their
     * positions more likely differ, and then their answers collide */
    int16_t pos;
    r = lsc_lxclient_read_id(c, old_id);
    r = r != 0 ? r : lsc_lxclient_read_position(c, old_id, &pos);
    if (r == LSC_ETIMEOUT || r == LSC_EREPLY) {
        return because(why, r == LSC_ETIMEOUT ? LSC_LX_ID_ABSENT : LSC_LX_ID_GARBLED, LSC_EINVAL);
    }
    if (r != 0) {
        return because(why, LSC_LX_DONE, r);
    }
    return write_and_check_id(c, old_id, new_id, why);
}

int lsc_lxclient_set_id_alone(lsc_lxclient *c, uint8_t new_id, uint32_t per_id_ms,
                              uint8_t *old_id, lsc_lx_refusal *why)
{
    if (!usable(c) || new_id > LSC_LX_ID_MAX) {
        return because(why, LSC_LX_BAD_ARGUMENT, LSC_EINVAL);
    }
    lsc_lx_whois who;
    int r = lsc_lxclient_whois(c, &who);
    if (r == LSC_ETIMEOUT || r == LSC_EREPLY) {
        return because(why, r == LSC_ETIMEOUT ? LSC_LX_NO_SERVO : LSC_LX_NOT_ALONE, LSC_EINVAL);
    }
    if (r != 0) {
        return because(why, LSC_LX_DONE, r);
    }
    /* colliding answers can look like one id: every id asked alone too */
    lsc_lx_scan scan;
    r = lsc_lxclient_scan(c, NULL, 0, per_id_ms, &scan);
    if (r < 0) {
        return because(why, LSC_LX_DONE, r);
    }
    bool garbled = false;
    for (size_t i = 0; i < sizeof scan.garbled; i++) {
        garbled = garbled || scan.garbled[i] != 0;
    }
    if (r != 1 || garbled || !get_bit(scan.found, who.id)) {
        return because(why, r == 0 && !garbled ? LSC_LX_NO_SERVO : LSC_LX_NOT_ALONE, LSC_EINVAL);
    }
    if (old_id != NULL) {
        *old_id = who.id;
    }
    if (who.id == new_id) {
        return because(why, LSC_LX_DONE, 0);
    }
    return write_and_check_id(c, who.id, new_id, why);
}

int lsc_lxclient_offset_change(lsc_lxclient *c, uint8_t id, int delta, bool save, int8_t *offset,
                               lsc_lx_refusal *why)
{
    if (!usable(c) || id > LSC_LX_ID_MAX || delta < -2 * LSC_LX_OFFSET_MAX ||
        delta > 2 * LSC_LX_OFFSET_MAX) {
        return because(why, LSC_LX_BAD_ARGUMENT, LSC_EINVAL);
    }
    int8_t now = 0;
    int r = lsc_lxclient_read_offset(c, id, &now);
    if (r != 0) {
        return because(why, LSC_LX_DONE, r);
    }
    int want = now + delta;
    if (want < -LSC_LX_OFFSET_MAX || want > LSC_LX_OFFSET_MAX) {
        return because(why, LSC_LX_OUT_OF_RANGE, LSC_EINVAL);
    }
    r = delta != 0 ? lsc_lxclient_adjust_offset(c, id, (int8_t)want) : 0;
    r = r == 0 && save ? lsc_lxclient_save_offset(c, id) : r;
    if (r != 0) {
        return because(why, LSC_LX_DONE, r);
    }
    r = lsc_lxclient_read_offset(c, id, &now);
    r = r == 0 && now != want ? LSC_EREPLY : r;
    if (r == 0 && offset != NULL) {
        *offset = now;
    }
    return because(why, r == 0 ? LSC_LX_DONE : LSC_LX_NOT_READ_BACK, r);
}

int lsc_lxclient_move_together(lsc_lxclient *c, const lsc_servo *servos, size_t n,
                               uint16_t time_ms)
{
    uint8_t seen[32] = {0};
    bool ok = usable(c) && servos != NULL && n > 0 && time_ms <= LSC_LX_TIME_MAX;
    for (size_t i = 0; ok && i < n; i++) {
        ok = servos[i].id <= LSC_LX_ID_MAX && servos[i].position <= LSC_LX_POSITION_MAX &&
             !get_bit(seen, servos[i].id);
        if (ok) {
            set_bit(seen, servos[i].id);
        }
    }
    if (!ok) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        int r = lsc_lxclient_move_preset(c, servos[i].id, servos[i].position, time_ms);
        if (r != 0) {
            return r;
        }
    }
    return lsc_lxclient_move_start(c, LSC_LX_BROADCAST);
}
