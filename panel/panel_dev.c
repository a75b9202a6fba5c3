/* lsc-panel: the device thread (panel.h). The only thread that calls the
 * device: it sleeps in wait_for_work until a command, a move or its next
 * deadline, then does what is due. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "panel.h"

#define READ_FAST_MS 150u   /* positions while something moves */
#define READ_SLOW_MS 2000u  /* positions while nothing does */
#define ACTIVE_MS 3000u     /* "something moves" lasts this long after a command */
#define MOVE_QUIET_MS 200u  /* no position read this soon after a slider's move */
#define BATTERY_MS 10000u   /* the battery, while a page listens */
#define RETRY_MS 5000u      /* after a read that failed */
#define IDLE_MS 1000u       /* the longest sleep (a page's arrival is noticed by then) */

/* ---- the buffer ---------------------------------------------------------------- */

void panel_buf_add(panel_buf *b, const char *s, size_t n)
{
    if (b->failed) {
        return;
    }
    if (b->len + n + 1u > b->cap) {
        size_t cap = b->cap ? b->cap : 256u;
        while (cap < b->len + n + 1u) {
            cap *= 2u;
        }
        char *d = realloc(b->data, cap);
        if (d == NULL) {
            b->failed = true;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

void panel_buf_str(panel_buf *b, const char *s)
{
    panel_buf_add(b, s, strlen(s));
}

void panel_buf_printf(panel_buf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) {
        panel_buf_add(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1u);
    }
}

void panel_buf_json(panel_buf *b, const char *s)
{
    panel_buf_add(b, "\"", 1);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\') {
            char e[2] = {'\\', (char)*c};
            panel_buf_add(b, e, 2);
        } else if (*c < 0x20u || *c == 0x7fu) {
            panel_buf_printf(b, "\\u%04x", *c);
        } else {
            panel_buf_add(b, (const char *)c, 1);
        }
    }
    panel_buf_add(b, "\"", 1);
}

void panel_buf_free(panel_buf *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}

/* ---- events -------------------------------------------------------------------- */

void panel_event_add(panel *p, const char *type, const char *data)
{
    pthread_mutex_lock(&p->ev_m);
    panel_event *e = &p->events[p->next_seq % PANEL_EVENTS];
    e->seq = p->next_seq++;
    (void)snprintf(e->type, sizeof e->type, "%s", type);
    (void)snprintf(e->data, sizeof e->data, "%s", data);
    if (strcmp(type, "battery") == 0) {
        (void)snprintf(p->last_battery, sizeof p->last_battery, "%s", data);
    } else if (strcmp(type, "positions") == 0) {
        (void)snprintf(p->last_positions, sizeof p->last_positions, "%s", data);
    } else if (strcmp(type, "where") == 0) {
        (void)snprintf(p->last_where, sizeof p->last_where, "%s", data);
    }
    pthread_cond_broadcast(&p->ev_cv);
    pthread_mutex_unlock(&p->ev_m);
}

static unsigned clients(panel *p)
{
    pthread_mutex_lock(&p->ev_m);
    unsigned n = p->clients;
    pthread_mutex_unlock(&p->ev_m);
    return n;
}

void panel_positions_json(const panel *p, const lsc_servo *s, size_t n, panel_buf *b)
{
    panel_buf_str(b, "{\"ids\":[");
    for (size_t i = 0; i < n; i++) {
        panel_buf_printf(b, "%s%u", i ? "," : "", s[i].id);
    }
    panel_buf_str(b, "],\"pos\":[");
    for (size_t i = 0; i < n; i++) {
        panel_buf_printf(b, "%s%u", i ? "," : "", s[i].position);
    }
    panel_buf_str(b, "],\"deg\":[");
    for (size_t i = 0; i < n; i++) {
        char deg[LSC_ARM_DEGREES_MAX];
        deg[0] = '\0';
        (void)lsc_arm_degrees(p->arm, &s[i], deg, sizeof deg);
        panel_buf_printf(b, deg[0] ? "%s\"%s\"" : "%snull", i ? "," : "", deg); /* "-30.00" */
    }
    panel_buf_str(b, "]}");
}

/* An event that says what failed: {"what":..., "message":...}. */
static void event_error(panel *p, const char *what)
{
    panel_buf b = {0};
    panel_buf_str(&b, "{\"what\":");
    panel_buf_json(&b, what);
    panel_buf_str(&b, ",\"message\":");
    panel_buf_json(&b, lsc_device_error(p->dev));
    panel_buf_str(&b, "}");
    if (!b.failed) {
        panel_event_add(p, "error", b.data);
    }
    panel_buf_free(&b);
}

/* ---- the device thread's state (its own: no lock) ------------------------------ */

typedef struct dev_state {
    uint64_t next_read;     /* positions due */
    uint64_t next_battery;  /* battery due */
    uint64_t active_until;  /* read fast until */
    uint64_t last_move;     /* a slider's last move */
    bool limp;              /* the servos are unloaded: they move by hand */
    bool group_running;
    uint64_t fd_quiet_until; /* the device's descriptor hung up: not polled until */
    lsc_kin_pose jog_to;     /* the last jog's target ... */
    uint64_t jog_until;      /* ... which the next jog starts from until its move's end */
    bool jog_valid;          /* ... unless something else moved the arm since */
} dev_state;

static uint64_t now_ms(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
}

static uint32_t until(uint64_t due, uint64_t now)
{
    return due <= now ? 0u : (due - now > IDLE_MS ? IDLE_MS : (uint32_t)(due - now));
}

/* How long the device thread may sleep: until the next read, the battery
 * (while a page listens), or the device's next deadline
 * (lsc_device_next_event_ms: a notification queued, input left unread, or
 * on "sim" the virtual controller's next event). What the controller sends
 * by itself wakes the thread through the device's descriptor. */
static uint32_t next_timeout(panel *p, const dev_state *st)
{
    uint64_t now = now_ms();
    uint32_t t = IDLE_MS;
    if (clients(p) > 0u) { /* both at most IDLE_MS */
        uint32_t r = until(st->next_read, now);
        uint32_t b = until(st->next_battery, now);
        t = r < b ? r : b;
    }
    uint32_t dev = lsc_device_next_event_ms(p->dev);
    return dev < t ? dev : t;
}

/* The one place the device thread sleeps: until a byte on the wake pipe (a
 * command or a move), the device's descriptor polls readable (a
 * notification), or timeout_ms. A descriptor that hung up or failed is left
 * out for RETRY_MS (else poll would return at once, again and again); the
 * next request says what became of the device. */
static void wait_for_work(panel *p, dev_state *st, uint32_t timeout_ms)
{
    struct pollfd fd[2] = {{.fd = p->wake[0], .events = POLLIN, .revents = 0},
                           {.fd = lsc_device_fileno(p->dev), .events = POLLIN, .revents = 0}};
    if (fd[1].fd >= 0 && now_ms() < st->fd_quiet_until) {
        fd[1].fd = -1; /* poll ignores it */
    }
    int r = poll(fd, 2, (int)timeout_ms);
    if (r > 0 && (fd[0].revents & POLLIN)) {
        char drain[64];
        while (read(p->wake[0], drain, sizeof drain) > 0) {
        }
    }
    if (r > 0 && (fd[1].revents & (POLLHUP | POLLERR | POLLNVAL))) {
        st->fd_quiet_until = now_ms() + RETRY_MS;
    }
}

static void wake(panel *p)
{
    char c = 1;
    ssize_t r = write(p->wake[1], &c, 1);
    (void)r; /* a full pipe wakes it already */
}

/* Lets the device read what arrived without waiting ("sim" follows the
 * real clock by itself), and turns queued notifications into events. */
static void pump(panel *p, dev_state *st)
{
    uint64_t now = now_ms();
    if (lsc_device_poll(p->dev, 0) < 0) {
        return; /* the next request says why */
    }
    lsc_notification n;
    while (lsc_device_notification(p->dev, 0, &n) == 0) {
        const char *kind = n.cmd == LSC_CMD_GROUP_RUN    ? "run"
                           : n.cmd == LSC_CMD_GROUP_STOP ? "stop"
                                                                : "complete";
        char data[96];
        (void)snprintf(data, sizeof data, "{\"kind\":\"%s\",\"group\":%u,\"times\":%u}", kind,
                       n.group, n.times);
        panel_event_add(p, "notification", data);
        st->group_running = n.cmd == LSC_CMD_GROUP_RUN;
        st->active_until = now + ACTIVE_MS;
        st->next_read = now;
        st->jog_valid = false; /* the arm moves by a group */
    }
}

/* The grasp point's pose as an event's JSON. */
static void pose_json(const lsc_kin_pose *w, panel_buf *b)
{
    panel_buf_printf(b, "{\"x\":%.1f,\"y\":%.1f,\"z\":%.1f,\"pitch\":%.1f,\"roll\":%.1f}",
                     (double)w->x_mm, (double)w->y_mm, (double)w->z_mm, (double)w->pitch_deg,
                     (double)w->roll_deg);
}

/* With a profile's geometry: where the grasp point is (lsc_device_where,
 * which reads the chain's joints), as an event when it changed; or why it
 * is not known ({"error": ...}: a joint outside its range, say). */
static void read_where(panel *p)
{
    lsc_kin_pose w;
    panel_buf b = {0};
    if (lsc_device_where(p->dev, NULL, &w) < 0) {
        panel_buf_str(&b, "{\"error\":");
        panel_buf_json(&b, lsc_device_error(p->dev));
        panel_buf_str(&b, "}");
    } else {
        pose_json(&w, &b);
    }
    pthread_mutex_lock(&p->ev_m);
    bool same = !b.failed && strcmp(b.data, p->last_where) == 0;
    pthread_mutex_unlock(&p->ev_m);
    if (!b.failed && !same) {
        panel_event_add(p, "where", b.data);
    }
    panel_buf_free(&b);
}

/* Reads the positions of the page's servos and sends them as an event; with
 * geometry, the grasp point's too when they changed. */
static int read_positions(panel *p, lsc_servo *out)
{
    int r = lsc_device_read(p->dev, p->ids, p->nids, out);
    if (r < 0) {
        return r;
    }
    panel_buf b = {0};
    panel_positions_json(p, out, p->nids, &b);
    pthread_mutex_lock(&p->ev_m);
    bool same = !b.failed && strcmp(b.data, p->last_positions) == 0;
    bool where_known = p->last_where[0] != '\0';
    pthread_mutex_unlock(&p->ev_m);
    if (!b.failed && !same) { /* only what changed */
        panel_event_add(p, "positions", b.data);
    }
    panel_buf_free(&b);
    if (p->geometry && (!same || !where_known)) {
        read_where(p);
    }
    return 0;
}

static void periodic(panel *p, dev_state *st)
{
    if (clients(p) == 0u) {
        return;
    }
    uint64_t now = now_ms();
    if (now >= st->next_battery) {
        uint16_t mv = 0;
        if (lsc_device_battery(p->dev, &mv) == 0) {
            char data[48];
            (void)snprintf(data, sizeof data, "{\"mv\":%u}", mv);
            panel_event_add(p, "battery", data);
            st->next_battery = now_ms() + BATTERY_MS;
        } else {
            event_error(p, "battery");
            st->next_battery = now_ms() + RETRY_MS;
        }
    }
    now = now_ms();
    if (now >= st->next_read) {
        if (now < st->last_move + MOVE_QUIET_MS) {
            st->next_read = st->last_move + MOVE_QUIET_MS; /* keep the line free for moves */
            return;
        }
        lsc_servo pos[LSC_PLAYER_SERVOS_MAX];
        bool fast = st->limp || st->group_running || now < st->active_until;
        if (read_positions(p, pos) == 0) {
            st->next_read = now_ms() + (fast ? READ_FAST_MS : READ_SLOW_MS);
        } else {
            event_error(p, "read");
            st->next_read = now_ms() + RETRY_MS;
        }
    }
}

/* ---- commands ------------------------------------------------------------------ */

static void fail(panel *p, panel_cmd *c, int r)
{
    c->result = r;
    c->cause = lsc_device_error_cause(p->dev);
    (void)snprintf(c->message, sizeof c->message, "%s", lsc_device_error(p->dev));
}

static void finish(panel *p, const panel_cmd *c)
{
    pthread_mutex_lock(&p->m);
    if (p->cmd == c) {
        p->cmd = NULL;
        p->cmd_done = true;
        pthread_cond_broadcast(&p->done_cv);
    }
    pthread_mutex_unlock(&p->m);
}

typedef struct play_ctx {
    panel *p;
    panel_cmd *cmd; /* until the play has started */
    const lsc_play_result *result;
    uint32_t count;
    uint64_t last_event;
} play_ctx;

static void play_event(play_ctx *x, bool done, int r)
{
    const lsc_play_result *res = x->result;
    panel_buf b = {0};
    panel_buf_printf(&b,
                     "{\"keyframe\":%lu,\"count\":%lu,\"frames\":%lu,\"elapsed_ms\":%lu,"
                     "\"total_ms\":%lu,\"done\":%s,\"stopped\":%s,\"error\":",
                     (unsigned long)res->keyframe, (unsigned long)x->count,
                     (unsigned long)res->frames, (unsigned long)(now_ms() - x->last_event),
                     (unsigned long)res->total_ms, done ? "true" : "false",
                     res->stopped ? "true" : "false");
    if (r < 0) {
        panel_buf_json(&b, lsc_device_error(x->p->dev));
    } else {
        panel_buf_str(&b, "null");
    }
    panel_buf_str(&b, "}");
    if (!b.failed) {
        panel_event_add(x->p, "play", b.data);
    }
    panel_buf_free(&b);
}

static bool on_play(void *user, const lsc_player_step *step, uint32_t elapsed_ms)
{
    play_ctx *x = user;
    panel *p = x->p;
    if (x->cmd != NULL) {
        finish(p, x->cmd); /* the play has begun: its request is answered */
        x->cmd = NULL;
    }
    (void)elapsed_ms;
    if (step != NULL) {
        play_event(x, false, 0);
    }
    pthread_mutex_lock(&p->m);
    /* a group Stop asked meanwhile stops the play too (then runs, below) */
    bool stop_asked = p->cmd != NULL && p->cmd->kind == PANEL_CMD_STOP;
    bool go = !p->play_stop && !p->stopping && !stop_asked;
    pthread_mutex_unlock(&p->m);
    return go;
}

static void free_action(lsc_action *a)
{
    lsc_action_free(a);
    free(a);
}

/* Plays c's action, which is the device thread's: c is answered (and gone)
 * once the play has begun. */
static void play(panel *p, panel_cmd *c, dev_state *st)
{
    lsc_action *a = c->action;
    lsc_play_result res;
    memset(&res, 0, sizeof res);
    play_ctx x = {.p = p, .cmd = c, .result = &res, .count = a->count, .last_event = now_ms()};
    lsc_player_config cfg = {.speed_pct = c->value, .times = 1, .lead_ms = 1000, .baud = 0};
    pthread_mutex_lock(&p->m);
    p->playing = true;
    p->play_stop = false;
    pthread_mutex_unlock(&p->m);
    int r = lsc_device_play(p->dev, a, &cfg, on_play, &x, &res);
    pthread_mutex_lock(&p->m);
    p->playing = false;
    pthread_mutex_unlock(&p->m);
    if (x.cmd != NULL) { /* refused before anything was sent */
        if (r < 0) {
            fail(p, c, r);
        }
        finish(p, c);
    }
    free_action(a);
    play_event(&x, true, r);
    st->jog_valid = false;
    st->active_until = now_ms() + ACTIVE_MS;
    st->next_read = 0;
}

/* A jog: the grasp point from where it is (or, while the last jog's move
 * runs, from that jog's target) by c->step along c->axis, the pitch kept
 * (or turned by c->step), through lsc_device_reach. Refused by the library
 * (nothing sent) when the target is out of reach or beyond a limit. */
static int jog(panel *p, const panel_cmd *c, dev_state *st, panel_buf *out)
{
    lsc_kin_pose from;
    uint64_t now = now_ms();
    if (st->jog_valid && now < st->jog_until) {
        from = st->jog_to;
    } else {
        int r = lsc_device_where(p->dev, NULL, &from);
        if (r < 0) {
            return r;
        }
    }
    lsc_reach rq;
    memset(&rq, 0, sizeof rq);
    rq.target.x_mm = from.x_mm + (c->axis == PANEL_AXIS_X ? (float)c->step : 0.0f);
    rq.target.y_mm = from.y_mm + (c->axis == PANEL_AXIS_Y ? (float)c->step : 0.0f);
    rq.target.z_mm = from.z_mm + (c->axis == PANEL_AXIS_Z ? (float)c->step : 0.0f);
    rq.target.pitch_deg = from.pitch_deg + (c->axis == PANEL_AXIS_PITCH ? (float)c->step : 0.0f);
    rq.target.has_pitch = true;
    rq.time_ms = c->value ? c->value : 1u; /* 0: at once, as a slider's move */
    int r = lsc_device_reach(p->dev, &rq, NULL);
    if (r < 0) {
        return r;
    }
    st->jog_to = from;
    st->jog_to.x_mm = rq.target.x_mm;
    st->jog_to.y_mm = rq.target.y_mm;
    st->jog_to.z_mm = rq.target.z_mm;
    st->jog_to.pitch_deg = rq.target.pitch_deg;
    st->jog_until = now_ms() + rq.time_ms;
    st->jog_valid = true;
    pose_json(&st->jog_to, out);
    return 0;
}

/* Runs c (not PLAY, which answers itself). */
static void run_cmd(panel *p, panel_cmd *c, dev_state *st)
{
    int r = 0;
    lsc_servo pos[LSC_PLAYER_SERVOS_MAX];
    switch (c->kind) {
    case PANEL_CMD_RUN:
        r = lsc_device_run(p->dev, c->group, c->value);
        break;
    case PANEL_CMD_STOP:
        r = lsc_device_stop(p->dev);
        break;
    case PANEL_CMD_SPEED:
        r = lsc_device_speed(p->dev, c->group, c->value);
        break;
    case PANEL_CMD_LIMP:
        r = lsc_device_unload(p->dev, p->ids, p->nids);
        st->limp = r == 0 ? true : st->limp;
        break;
    case PANEL_CMD_HOLD: /* a move to where they are gives them their torque back */
        r = lsc_device_read(p->dev, p->ids, p->nids, pos);
        if (r >= 0) {
            r = lsc_device_move(p->dev, 100, pos, p->nids);
        }
        st->limp = r == 0 ? false : st->limp;
        break;
    case PANEL_CMD_POSE: {
        lsc_action a;
        r = lsc_action_init(&a, p->ids, p->nids);
        if (r == 0) {
            r = lsc_device_take_keyframe(p->dev, &a, 1000, 0);
        }
        if (r == 0) {
            panel_buf_str(&c->out, "{\"ids\":[");
            for (size_t i = 0; i < a.nservos; i++) {
                panel_buf_printf(&c->out, "%s%u", i ? "," : "", a.ids[i]);
            }
            panel_buf_str(&c->out, "],\"pos\":[");
            for (size_t i = 0; i < a.nservos; i++) {
                panel_buf_printf(&c->out, "%s%u", i ? "," : "", a.words[1u + i]);
            }
            panel_buf_str(&c->out, "]}");
        }
        lsc_action_free(&a);
        break;
    }
    case PANEL_CMD_JOG:
        r = jog(p, c, st, &c->out);
        break;
    default:
        break;
    }
    if (c->kind != PANEL_CMD_JOG) {
        st->jog_valid = false; /* the arm moved otherwise, or may have */
    }
    if (r < 0) {
        fail(p, c, r);
    } else {
        c->result = 0;
    }
    st->active_until = now_ms() + ACTIVE_MS;
    st->next_read = 0;
    finish(p, c);
}

static void send_move(panel *p, dev_state *st)
{
    lsc_servo s[LSC_PLAYER_SERVOS_MAX];
    pthread_mutex_lock(&p->m);
    size_t n = p->move_n;
    uint16_t t = p->move_time;
    memcpy(s, p->move, n * sizeof s[0]);
    p->move_n = 0;
    pthread_mutex_unlock(&p->m);
    if (n == 0u) {
        return;
    }
    if (lsc_device_move(p->dev, t, s, n) < 0) {
        event_error(p, "move");
    }
    st->last_move = now_ms();
    st->active_until = st->last_move + ACTIVE_MS + t;
    st->limp = false;
    st->jog_valid = false;
}

static void *dev_main(void *arg)
{
    panel *p = arg;
    dev_state st;
    memset(&st, 0, sizeof st);
    for (;;) {
        wait_for_work(p, &st, next_timeout(p, &st));
        send_move(p, &st); /* first: a slider waits for nothing */
        pthread_mutex_lock(&p->m);
        bool stop = p->stopping;
        panel_cmd *c = p->cmd;
        pthread_mutex_unlock(&p->m);
        if (stop) {
            break;
        }
        pump(p, &st);
        if (c != NULL) {
            if (c->kind == PANEL_CMD_PLAY) {
                play(p, c, &st);
            } else {
                run_cmd(p, c, &st);
            }
            pump(p, &st);
        }
        periodic(p, &st);
    }
    pthread_mutex_lock(&p->m);
    p->exited = true;
    if (p->cmd != NULL) { /* taken by no one: its caller is told */
        if (p->cmd->kind == PANEL_CMD_PLAY) {
            free_action(p->cmd->action);
        }
        p->cmd->result = LSC_EIO;
        (void)snprintf(p->cmd->message, sizeof p->cmd->message, "lsc-panel is stopping");
        p->cmd = NULL;
        p->cmd_done = true;
        pthread_cond_broadcast(&p->done_cv);
    }
    pthread_mutex_unlock(&p->m);
    return NULL;
}

/* ---- the HTTP side's calls -------------------------------------------------------- */

void panel_dev_call(panel *p, panel_cmd *cmd)
{
    pthread_mutex_lock(&p->cmd_lock);
    pthread_mutex_lock(&p->m);
    if (p->exited) {
        if (cmd->kind == PANEL_CMD_PLAY) {
            free_action(cmd->action); /* handed over: nobody else frees it */
            cmd->action = NULL;
        }
        cmd->result = LSC_EIO;
        (void)snprintf(cmd->message, sizeof cmd->message, "lsc-panel is stopping");
        pthread_mutex_unlock(&p->m);
        pthread_mutex_unlock(&p->cmd_lock);
        return;
    }
    p->cmd = cmd;
    p->cmd_done = false;
    pthread_mutex_unlock(&p->m);
    wake(p);
    pthread_mutex_lock(&p->m);
    while (!p->cmd_done) { /* the device thread finishes every command it is given */
        pthread_cond_wait(&p->done_cv, &p->m);
    }
    pthread_mutex_unlock(&p->m);
    pthread_mutex_unlock(&p->cmd_lock);
}

/* Where servo id is in the move waiting, or move_n. Under p->m. */
static size_t move_slot(const panel *p, uint8_t id)
{
    size_t j = 0;
    while (j < p->move_n && p->move[j].id != id) {
        j++;
    }
    return j;
}

void panel_dev_move(panel *p, const lsc_servo *s, size_t n, uint16_t time_ms)
{
    pthread_mutex_lock(&p->m);
    size_t fresh = 0; /* servos of s not in the move waiting */
    for (size_t i = 0; i < n; i++) {
        fresh += move_slot(p, s[i].id) == p->move_n;
    }
    if (p->move_n + fresh > LSC_PLAYER_SERVOS_MAX) {
        p->move_n = 0; /* too many together: the latest alone */
    }
    for (size_t i = 0; i < n; i++) { /* merged with one not yet sent: each servo's latest */
        size_t j = move_slot(p, s[i].id);
        p->move[j] = s[i];
        p->move_n += j == p->move_n;
    }
    p->move_time = time_ms;
    pthread_mutex_unlock(&p->m);
    wake(p);
}

bool panel_dev_play_stop(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool playing = p->playing;
    p->play_stop = playing;
    pthread_mutex_unlock(&p->m);
    return playing;
}

bool panel_dev_playing(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool playing = p->playing;
    pthread_mutex_unlock(&p->m);
    return playing;
}

int panel_dev_start(panel *p)
{
    if (pipe(p->wake) != 0) {
        return -errno;
    }
    for (int i = 0; i < 2; i++) {
        (void)fcntl(p->wake[i], F_SETFL, O_NONBLOCK);
        (void)fcntl(p->wake[i], F_SETFD, FD_CLOEXEC);
    }
    int r = pthread_create(&p->thread, NULL, dev_main, p);
    return r == 0 ? 0 : -r;
}

void panel_set_stopping(panel *p)
{
    pthread_mutex_lock(&p->m);
    pthread_mutex_lock(&p->ev_m);
    p->stopping = true;
    pthread_cond_broadcast(&p->ev_cv);
    pthread_mutex_unlock(&p->ev_m);
    pthread_mutex_unlock(&p->m);
    wake(p);
}

void panel_dev_stop(panel *p)
{
    panel_set_stopping(p);
    (void)pthread_join(p->thread, NULL);
    (void)close(p->wake[0]);
    (void)close(p->wake[1]);
}
