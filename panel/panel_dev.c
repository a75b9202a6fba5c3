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
#define REOPEN_FIRST_MS 250u /* the first attempt to open a controller that went away ... */
#define REOPEN_MAX_MS 2000u  /* ... then twice as long each time, up to this */

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
    } else if (strcmp(type, "link") == 0) {
        (void)snprintf(p->last_link, sizeof p->last_link, "%s", data);
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
    bool lost;               /* the controller went away: open it again */
    uint64_t reopen_at;      /* ... next at */
    uint32_t reopen_ms;      /* ... after this (doubling) */
    uint32_t halts_seen;     /* through lscd: the halts it told of, so far */
    uint8_t run_group;       /* a group run whose start has not been heard ... */
    uint64_t run_deadline;   /* ... by then (0: none awaited) */
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

/* Whether an error means the controller (or lscd) went away: the device is
 * opened again (panel_dev.c's reopen), rather than asked again. */
static bool gone(int r)
{
    return r == LSC_ENODEV || r == LSC_EIO;
}

/* Notes r's verdict on the link. */
static int note(dev_state *st, int r)
{
    st->lost = st->lost || gone(r);
    return r;
}

static bool link_up(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool up = p->link_up;
    pthread_mutex_unlock(&p->m);
    return up;
}

/* Through lscd: whether another program halted the controller since the
 * last look (lsc_lscd_halts; the panel's own halts are counted as seen);
 * then the page is told. */
static bool halted_elsewhere(panel *p, dev_state *st)
{
    lsc_lscd *l = lsc_device_lscd(p->dev);
    uint32_t n = l != NULL ? lsc_lscd_halts(l) : 0u;
    if (n == st->halts_seen) {
        return false;
    }
    st->halts_seen = n;
    panel_event_add(p, "notification", "{\"kind\":\"halted\",\"group\":0,\"times\":0}");
    return true;
}

/* How long the device thread may sleep: until the next read, the battery
 * (while a page listens), a group's start awaited, the device's next
 * deadline (lsc_device_next_event_ms: a notification queued, input left
 * unread, or on "sim" the virtual controller's next event), or while the
 * controller is away its next opening. What the controller sends by itself
 * wakes the thread through the device's descriptor. */
static uint32_t next_timeout(panel *p, const dev_state *st)
{
    uint64_t now = now_ms();
    pthread_mutex_lock(&p->m);
    /* work already waiting (its wake-up byte may have been read by a play) */
    bool waiting = p->cmd != NULL || p->move_n > 0u || p->stopping;
    pthread_mutex_unlock(&p->m);
    if (waiting) {
        return 0;
    }
    if (!link_up(p)) {
        return until(st->reopen_at, now);
    }
    uint32_t t = IDLE_MS;
    if (clients(p) > 0u) { /* both at most IDLE_MS */
        uint32_t r = until(st->next_read, now);
        uint32_t b = until(st->next_battery, now);
        t = r < b ? r : b;
    }
    if (st->run_deadline != 0u) {
        uint32_t g = until(st->run_deadline, now);
        t = g < t ? g : t;
    }
    uint32_t dev = lsc_device_next_event_ms(p->dev);
    return dev < t ? dev : t;
}

/* The one place the device thread sleeps: until a byte on the wake pipe (a
 * command or a move), the device's descriptor polls readable (a
 * notification), or timeout_ms. A descriptor that hung up or failed means
 * the controller (or lscd) went away. */
static void wait_for_work(panel *p, dev_state *st, uint32_t timeout_ms)
{
    bool up = link_up(p);
    struct pollfd fd[2] = {{.fd = p->wake[0], .events = POLLIN, .revents = 0},
                           {.fd = up ? lsc_device_fileno(p->dev) : -1, .events = POLLIN,
                            .revents = 0}};
    int r = poll(fd, 2, (int)timeout_ms);
    if (r > 0 && (fd[0].revents & POLLIN)) {
        char drain[64];
        while (read(p->wake[0], drain, sizeof drain) > 0) {
        }
    }
    if (r > 0 && fd[1].fd >= 0 && (fd[1].revents & (POLLHUP | POLLERR | POLLNVAL)) &&
        !(fd[1].revents & POLLIN)) {
        st->lost = true; /* nothing left to read: the other end is gone */
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
    int r = note(st, lsc_device_poll(p->dev, 0));
    if (r < 0 && st->lost) {
        return;
    }
    (void)halted_elsewhere(p, st);
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
        if (n.cmd == LSC_CMD_GROUP_RUN && n.group == st->run_group) {
            st->run_deadline = 0; /* it started */
        }
        st->active_until = now + ACTIVE_MS;
        st->next_read = now;
        st->jog_valid = false; /* the arm moves by a group */
    }
    if (st->run_deadline != 0u && now_ms() >= st->run_deadline) {
        /* the board ignores a run of a group it does not have: say so */
        char data[96];
        (void)snprintf(data, sizeof data,
                       "{\"kind\":\"never-started\",\"group\":%u,\"times\":0}", st->run_group);
        panel_event_add(p, "notification", data);
        st->run_deadline = 0;
    }
}

/* The link's state as an event: {"up":true} or {"up":false,"message":...}. */
static void event_link(panel *p, bool up, const char *why)
{
    panel_buf b = {0};
    panel_buf_printf(&b, "{\"up\":%s,\"message\":", up ? "true" : "false");
    panel_buf_json(&b, why);
    panel_buf_str(&b, "}");
    if (!b.failed) {
        panel_event_add(p, "link", b.data);
    }
    panel_buf_free(&b);
}

/* The controller (or lscd) went away: closes the device; reopen() opens it
 * again. Until then every request is answered 503. */
static void link_lost(panel *p, dev_state *st)
{
    char why[PANEL_MSG_MAX];
    const char *e = lsc_device_error(p->dev);
    (void)snprintf(why, sizeof why, "%s", e[0] ? e : "the controller hung up");
    lsc_device_close(p->dev);
    p->dev = NULL;
    pthread_mutex_lock(&p->m);
    p->link_up = false;
    (void)snprintf(p->link_why, sizeof p->link_why, "%s", why);
    pthread_mutex_unlock(&p->m);
    event_link(p, false, why);
    st->lost = false;
    st->reopen_ms = REOPEN_FIRST_MS;
    st->reopen_at = now_ms() + REOPEN_FIRST_MS;
    st->group_running = false;
    st->run_deadline = 0;
    st->jog_valid = false;
}

/* Opens the controller again, by the name it was opened as, once
 * st->reopen_at has come; on failure tries again later, twice as long
 * after, up to REOPEN_MAX_MS. Through lscd a controller that lscd has lost
 * answers LSC_ENODEV: the link is up again only once it answers (a battery
 * read that is not refused as gone). */
static void reopen(panel *p, dev_state *st)
{
    uint64_t now = now_ms();
    if (now < st->reopen_at) {
        return;
    }
    lsc_device *d = NULL;
    int r = lsc_device_open(p->dev_name, p->cfg, &d);
    if (r == 0 && p->arm != NULL) {
        r = lsc_device_set_arm(d, p->arm);
    }
    uint16_t mv;
    if (r == 0) {
        int probe = lsc_device_battery(d, &mv);
        r = gone(probe) ? probe : 0;
    }
    if (r != 0) {
        char why[PANEL_MSG_MAX];
        (void)snprintf(why, sizeof why, "%s", d ? lsc_device_error(d) : "out of memory");
        lsc_device_close(d);
        pthread_mutex_lock(&p->m);
        bool changed = strcmp(why, p->link_why) != 0;
        (void)snprintf(p->link_why, sizeof p->link_why, "%s", why);
        pthread_mutex_unlock(&p->m);
        if (changed) {
            event_link(p, false, why);
        }
        st->reopen_ms = st->reopen_ms * 2u > REOPEN_MAX_MS ? REOPEN_MAX_MS : st->reopen_ms * 2u;
        st->reopen_at = now_ms() + st->reopen_ms;
        return;
    }
    p->dev = d;
    pthread_mutex_lock(&p->m);
    p->link_up = true;
    p->link_why[0] = '\0';
    pthread_mutex_unlock(&p->m);
    event_link(p, true, "");
    st->halts_seen = 0; /* a new connection to lscd counts from 0 */
    st->next_read = 0;
    st->next_battery = 0;
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
    if (now >= st->next_battery && !st->lost) {
        uint16_t mv = 0;
        if (note(st, lsc_device_battery(p->dev, &mv)) == 0) {
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
    if (now >= st->next_read && !st->lost) {
        if (now < st->last_move + MOVE_QUIET_MS) {
            st->next_read = st->last_move + MOVE_QUIET_MS; /* keep the line free for moves */
            return;
        }
        lsc_servo pos[LSC_PLAYER_SERVOS_MAX];
        bool fast = st->limp || st->group_running || now < st->active_until;
        if (note(st, read_positions(p, pos)) == 0) {
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
    dev_state *st;
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
        panel_buf_json(&b, x->p->dev ? lsc_device_error(x->p->dev) : "the controller went away");
    } else {
        panel_buf_str(&b, "null");
    }
    panel_buf_str(&b, "}");
    if (!b.failed) {
        panel_event_add(x->p, "play", b.data);
    }
    panel_buf_free(&b);
}

/* Whether the play must end: Stop play, Halt, a group's Stop (which then
 * runs), lsc-panel stopping. Under p->m. */
static bool play_must_end(const panel *p)
{
    bool stop_asked = p->cmd != NULL &&
                      (p->cmd->kind == PANEL_CMD_STOP || p->cmd->kind == PANEL_CMD_HALT);
    return p->play_stop || p->stopping || stop_asked;
}

static bool on_play(void *user, const lsc_player_step *step, uint32_t elapsed_ms)
{
    (void)elapsed_ms; /* "sim" follows the real clock: nothing to pace */
    play_ctx *x = user;
    panel *p = x->p;
    if (x->cmd != NULL) {
        finish(p, x->cmd); /* the play has begun: its request is answered */
        x->cmd = NULL;
    }
    if (step != NULL) {
        play_event(x, false, 0);
    }
    pthread_mutex_lock(&p->m);
    bool go = !play_must_end(p);
    pthread_mutex_unlock(&p->m);
    return go && !halted_elsewhere(p, x->st); /* another program's halt ends it too */
}

static void free_action(lsc_action *a)
{
    lsc_action_free(a);
    free(a);
}

/* The play slot is free again: whoever waits for the play's end is told. */
static void play_over(panel *p)
{
    pthread_mutex_lock(&p->m);
    p->playing = false;
    p->play_busy = false;
    pthread_cond_broadcast(&p->done_cv);
    pthread_mutex_unlock(&p->m);
}

/* Plays c's action, which is the device thread's: c is answered (and gone)
 * once the play has begun. A play stopped before it began is refused
 * (nothing sent). */
static void play(panel *p, panel_cmd *c, dev_state *st)
{
    lsc_action *a = c->action;
    lsc_play_result res;
    memset(&res, 0, sizeof res);
    play_ctx x = {.p = p,
                  .st = st,
                  .cmd = c,
                  .result = &res,
                  .count = a->count,
                  .last_event = now_ms()};
    lsc_player_config cfg = {.speed_pct = c->value, .times = 1, .lead_ms = 1000, .baud = 0};
    pthread_mutex_lock(&p->m);
    bool refused = play_must_end(p);
    p->playing = !refused;
    pthread_mutex_unlock(&p->m);
    if (refused) {
        c->result = LSC_EBUSY;
        (void)snprintf(c->message, sizeof c->message,
                       "the play was stopped before it began: nothing was sent");
        free_action(a);
        play_over(p);
        finish(p, c);
        return;
    }
    int r = note(st, lsc_device_play(p->dev, a, &cfg, on_play, &x, &res));
    if (x.cmd != NULL) { /* refused before anything was sent */
        if (r < 0) {
            fail(p, c, r);
        }
        finish(p, c);
    }
    free_action(a);
    play_event(&x, true, r);
    play_over(p);
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

/* Holds the page's servos where they are (lsc_device_hold: even one beyond
 * its limits, which it names), or with halt stops everything first
 * (lsc_device_halt: a group, a move under way). out: {"held":N} and, when
 * some joint is beyond its limits, "beyond":[ids] and the library's
 * "message". */
static int hold(panel *p, bool halt, panel_buf *out)
{
    lsc_hold_result res;
    memset(&res, 0, sizeof res);
    int r = halt ? lsc_device_halt(p->dev) : lsc_device_hold(p->dev, p->ids, p->nids, &res);
    if (r < 0) {
        return r;
    }
    panel_buf_printf(out, "{\"ok\":true,\"beyond\":[");
    for (size_t i = 0; i < res.nbeyond; i++) {
        panel_buf_printf(out, "%s%u", i ? "," : "", res.beyond[i]);
    }
    panel_buf_str(out, "],\"message\":");
    panel_buf_json(out, r == LSC_HOLD_BEYOND ? lsc_device_error(p->dev) : "");
    panel_buf_str(out, "}");
    return 0;
}

/* The time a board takes at most to announce a group's start after a run
 * (lsc_device_start_ms): a start not heard by then never came. */
static uint32_t start_ms(panel *p)
{
    return lsc_device_start_ms(p->dev);
}

/* Runs c (not PLAY, which answers itself). */
static void run_cmd(panel *p, panel_cmd *c, dev_state *st)
{
    int r = 0;
    switch (c->kind) {
    case PANEL_CMD_RUN:
        r = lsc_device_run(p->dev, c->group, c->value);
        if (r == 0) { /* its start is awaited (pump says when it never came) */
            st->run_group = c->group;
            st->run_deadline = now_ms() + start_ms(p);
        }
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
    case PANEL_CMD_HOLD:
    case PANEL_CMD_HALT:
        r = hold(p, c->kind == PANEL_CMD_HALT, &c->out);
        if (c->kind == PANEL_CMD_HALT && lsc_device_lscd(p->dev) != NULL) {
            st->halts_seen = lsc_lscd_halts(lsc_device_lscd(p->dev)); /* its own */
        }
        st->limp = r == 0 ? false : st->limp;
        st->run_deadline = c->kind == PANEL_CMD_HALT ? 0u : st->run_deadline;
        break;
    case PANEL_CMD_POSE: {
        lsc_action a;
        r = lsc_action_init(&a, p->ids, p->nids);
        if (r == 0) {
            r = lsc_device_take_keyframe(p->dev, &a, 1000, 0);
        }
        if (r == 0) { /* {"ids":[..],"pos":[..],"deg":[..]} */
            lsc_servo pos[LSC_PLAYER_SERVOS_MAX];
            for (size_t i = 0; i < a.nservos && i < LSC_PLAYER_SERVOS_MAX; i++) {
                pos[i].id = a.ids[i];
                pos[i].position = a.words[1u + i];
            }
            panel_positions_json(p, pos, a.nservos, &c->out);
        }
        lsc_action_free(&a);
        break;
    }
    case PANEL_CMD_JOG:
        r = jog(p, c, st, &c->out);
        break;
    case PANEL_CMD_CALIBRATE:
        r = panel_calibrate(p, c);
        break;
    default:
        break;
    }
    if (c->kind != PANEL_CMD_JOG) {
        st->jog_valid = false; /* the arm moved otherwise, or may have */
    }
    if (note(st, r) < 0 && c->kind == PANEL_CMD_CALIBRATE) {
        c->result = r; /* panel_calibrate said why */
    } else if (r < 0) {
        fail(p, c, r);
    } else {
        c->result = 0;
    }
    st->active_until = now_ms() + ACTIVE_MS;
    st->next_read = 0;
    finish(p, c);
}

/* Tells the requests whose move was taken its result. Under p->m. */
static void moves_done(panel *p, panel_move_wait *w, int r, const char *why)
{
    for (; w != NULL; w = w->next) {
        w->result = r;
        (void)snprintf(w->message, sizeof w->message, "%s", why);
        w->done = true;
    }
    pthread_cond_broadcast(&p->done_cv);
}

static void send_move(panel *p, dev_state *st)
{
    lsc_servo s[LSC_PLAYER_SERVOS_MAX];
    pthread_mutex_lock(&p->m);
    size_t n = p->move_n;
    uint16_t t = p->move_time;
    memcpy(s, p->move, n * sizeof s[0]);
    p->move_n = 0;
    panel_move_wait *w = p->move_waiters;
    p->move_waiters = NULL;
    pthread_mutex_unlock(&p->m);
    if (n == 0u) {
        return;
    }
    int r = note(st, lsc_device_move(p->dev, t, s, n));
    if (r < 0) {
        event_error(p, "move");
    }
    pthread_mutex_lock(&p->m);
    moves_done(p, w, r, r < 0 ? lsc_device_error(p->dev) : "");
    pthread_mutex_unlock(&p->m);
    st->last_move = now_ms();
    st->active_until = st->last_move + ACTIVE_MS + t;
    st->limp = false;
    st->jog_valid = false;
}

/* While the controller is away: the move waiting and a command are
 * answered that it is (503), and it is opened again when due. */
static void away(panel *p, dev_state *st, panel_cmd *c)
{
    pthread_mutex_lock(&p->m);
    char why[PANEL_MSG_MAX];
    (void)snprintf(why, sizeof why, "reconnecting to the controller: %.440s", p->link_why);
    p->move_n = 0;
    moves_done(p, p->move_waiters, LSC_ENODEV, why);
    p->move_waiters = NULL;
    pthread_mutex_unlock(&p->m);
    if (c != NULL) {
        if (c->kind == PANEL_CMD_PLAY) {
            free_action(c->action);
            play_over(p);
        }
        c->result = LSC_ENODEV;
        (void)snprintf(c->message, sizeof c->message, "%s", why);
        finish(p, c);
    }
    reopen(p, st);
}

static void *dev_main(void *arg)
{
    panel *p = arg;
    dev_state st;
    memset(&st, 0, sizeof st);
    for (;;) {
        wait_for_work(p, &st, next_timeout(p, &st));
        pthread_mutex_lock(&p->m);
        bool stop = p->stopping;
        bool up = p->link_up;
        panel_cmd *c = p->cmd;
        pthread_mutex_unlock(&p->m);
        if (stop) {
            break;
        }
        if (up && st.lost) {
            link_lost(p, &st);
            up = false;
        }
        if (!up) {
            away(p, &st, c);
            continue;
        }
        send_move(p, &st); /* first: a slider waits for nothing */
        if (!st.lost) {
            pump(p, &st);
        }
        if (c != NULL && !st.lost) {
            if (c->kind == PANEL_CMD_PLAY) {
                play(p, c, &st);
            } else {
                run_cmd(p, c, &st);
            }
            if (!st.lost) {
                pump(p, &st);
            }
        }
        if (!st.lost) {
            periodic(p, &st);
        }
        if (st.lost) {
            link_lost(p, &st);
            wake(p); /* what waits is answered at once */
        }
    }
    pthread_mutex_lock(&p->m);
    p->exited = true;
    moves_done(p, p->move_waiters, LSC_EIO, "lsc-panel is stopping");
    p->move_waiters = NULL;
    p->move_n = 0;
    if (p->cmd != NULL) { /* taken by no one: its caller is told */
        if (p->cmd->kind == PANEL_CMD_PLAY) {
            free_action(p->cmd->action);
            p->play_busy = false;
        }
        p->cmd->result = LSC_EIO;
        (void)snprintf(p->cmd->message, sizeof p->cmd->message, "lsc-panel is stopping");
        p->cmd = NULL;
        p->cmd_done = true;
    }
    pthread_cond_broadcast(&p->done_cv);
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
            p->play_busy = false;
            pthread_cond_broadcast(&p->done_cv);
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

void panel_dev_move(panel *p, const lsc_servo *s, size_t n, uint16_t time_ms,
                    panel_move_wait *w)
{
    memset(w, 0, sizeof *w);
    pthread_mutex_lock(&p->m);
    if (p->play_busy || !p->link_up || p->exited) {
        w->result = p->play_busy ? LSC_EBUSY : !p->link_up ? LSC_ENODEV : LSC_EIO;
        (void)snprintf(w->message, sizeof w->message, "%s%.440s",
                       p->play_busy  ? "a play is running: stop it first"
                       : p->link_up ? "lsc-panel is stopping"
                                    : "reconnecting to the controller: ",
                       p->play_busy || p->link_up ? "" : p->link_why);
        pthread_mutex_unlock(&p->m);
        return;
    }
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
    w->next = p->move_waiters;
    p->move_waiters = w;
    pthread_mutex_unlock(&p->m);
    wake(p);
    pthread_mutex_lock(&p->m);
    while (!w->done) { /* the device thread answers every move it is given */
        pthread_cond_wait(&p->done_cv, &p->m);
    }
    pthread_mutex_unlock(&p->m);
}

bool panel_dev_play_reserve(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool free_slot = !p->play_busy;
    if (free_slot) {
        p->play_busy = true;
        p->play_stop = false;
    }
    pthread_mutex_unlock(&p->m);
    return free_slot;
}

void panel_dev_play_release(panel *p)
{
    play_over(p);
}

/* Drops the move not yet sent (Stop play, Halt): its requests are told.
 * Under p->m. */
static void drop_moves(panel *p, const char *why)
{
    p->move_n = 0;
    moves_done(p, p->move_waiters, LSC_EBUSY, why);
    p->move_waiters = NULL;
}

bool panel_dev_play_stop(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool busy = p->play_busy;
    p->play_stop = busy;
    drop_moves(p, "Stop play: the move was not sent");
    pthread_mutex_unlock(&p->m);
    wake(p);
    pthread_mutex_lock(&p->m);
    while (p->play_busy && !p->exited) { /* the play ends within one of its checks */
        pthread_cond_wait(&p->done_cv, &p->m);
    }
    pthread_mutex_unlock(&p->m);
    return busy;
}

/* Halt's first step, before its command: a play ends (or never begins), the
 * move waiting is dropped. */
void panel_dev_halt_asked(panel *p)
{
    pthread_mutex_lock(&p->m);
    p->play_stop = p->play_busy;
    drop_moves(p, "Halt: the move was not sent");
    pthread_mutex_unlock(&p->m);
    wake(p);
}

bool panel_dev_play_busy(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool busy = p->play_busy;
    pthread_mutex_unlock(&p->m);
    return busy;
}

bool panel_dev_link(panel *p, char *why, size_t cap)
{
    pthread_mutex_lock(&p->m);
    bool up = p->link_up;
    (void)snprintf(why, cap, "reconnecting to the controller: %.440s", p->link_why);
    pthread_mutex_unlock(&p->m);
    return up;
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
    p->link_up = true;
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
    panel_calibrate_free(p);
    (void)close(p->wake[0]);
    (void)close(p->wake[1]);
}
