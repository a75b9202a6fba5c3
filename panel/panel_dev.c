/* lsc-panel: the device thread (panel.h, panel_dev.h). The only thread that
 * calls the device: it sleeps in wait_for_work until a command, a move or
 * its next deadline, then does what is due (the commands: panel_cmd.c). */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "panel_dev.h"

#define READ_FAST_MS 150u   /* positions while something moves */
#define READ_SLOW_MS 2000u  /* positions while nothing does */
#define MOVE_QUIET_MS 200u  /* no position read this soon after a slider's move */
#define BATTERY_MS 10000u   /* the battery, while a page listens */
#define RETRY_MS 5000u      /* after a read that failed */
#define IDLE_MS 1000u       /* the longest sleep (a page's arrival is noticed by then) */
#define REOPEN_FIRST_MS 250u /* the first attempt to open a controller that went away ... */
#define REOPEN_MAX_MS 2000u  /* ... then twice as long each time, up to this */

/* An event that says what failed: {"what":..., "message":...}. */
void dev_event_error(panel *p, const char *what)
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

uint64_t dev_now_ms(void)
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
int dev_note(dev_state *st, int r)
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
bool dev_halted_elsewhere(panel *p, dev_state *st)
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
 * unread, a running group's next step), or while the
 * controller is away its next opening. What the controller sends by itself
 * wakes the thread through the device's descriptor. */
static uint32_t next_timeout(panel *p, const dev_state *st)
{
    uint64_t now = dev_now_ms();
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
    if (panel_event_clients(p) > 0u) { /* both at most IDLE_MS */
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

/* Lets the device read what arrived without waiting, and turns queued
 * notifications into events. */
static void pump(panel *p, dev_state *st)
{
    uint64_t now = dev_now_ms();
    int r = dev_note(st, lsc_device_poll(p->dev, 0));
    if (r < 0 && st->lost) {
        return;
    }
    (void)dev_halted_elsewhere(p, st);
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
    if (st->run_deadline != 0u && dev_now_ms() >= st->run_deadline) {
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

/* The controller (or lscd) went away: lets go of its port (so that a USB
 * adapter plugged in again gets its old name); reopen() opens it again into
 * the same handle. Until then every request is answered 503. */
static void link_lost(panel *p, dev_state *st)
{
    char why[PANEL_MSG_MAX];
    const char *e = lsc_device_error(p->dev);
    (void)snprintf(why, sizeof why, "%s", e[0] ? e : "the controller hung up");
    lsc_device_close_port(p->dev); /* the handle stays: reopen() opens it again */
    pthread_mutex_lock(&p->m);
    p->link_up = false;
    (void)snprintf(p->link_why, sizeof p->link_why, "%s", why);
    pthread_mutex_unlock(&p->m);
    event_link(p, false, why);
    st->lost = false;
    st->reopen_ms = REOPEN_FIRST_MS;
    st->reopen_at = dev_now_ms() + REOPEN_FIRST_MS;
    st->group_running = false;
    st->run_deadline = 0;
    st->jog_valid = false;
}

/* Opens the controller again (lsc_device_reopen: by the name it was opened as), once
 * st->reopen_at has come; on failure tries again later, twice as long
 * after, up to REOPEN_MAX_MS. Through lscd a controller that lscd has lost
 * answers LSC_ENODEV: the link is up again only once it answers (a battery
 * read that is not refused as gone). */
static void reopen(panel *p, dev_state *st)
{
    uint64_t now = dev_now_ms();
    if (now < st->reopen_at) {
        return;
    }
    int r = lsc_device_reopen(p->dev); /* the same name, settings and arm profile */
    uint16_t mv;
    if (r == 0) {
        int probe = lsc_device_battery(p->dev, &mv);
        r = gone(probe) ? probe : 0;
    }
    if (r != 0) {
        char why[PANEL_MSG_MAX];
        (void)snprintf(why, sizeof why, "%s", lsc_device_error(p->dev));
        pthread_mutex_lock(&p->m);
        bool changed = strcmp(why, p->link_why) != 0;
        (void)snprintf(p->link_why, sizeof p->link_why, "%s", why);
        pthread_mutex_unlock(&p->m);
        if (changed) {
            event_link(p, false, why);
        }
        st->reopen_ms = st->reopen_ms * 2u > REOPEN_MAX_MS ? REOPEN_MAX_MS : st->reopen_ms * 2u;
        st->reopen_at = dev_now_ms() + st->reopen_ms;
        return;
    }
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
void dev_pose_json(const lsc_kin_pose *w, panel_buf *b)
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
        dev_pose_json(&w, &b);
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
    if (panel_event_clients(p) == 0u) {
        return;
    }
    uint64_t now = dev_now_ms();
    if (now >= st->next_battery && !st->lost) {
        uint16_t mv = 0;
        int r = dev_note(st, lsc_device_battery(p->dev, &mv));
        if (r == 0) {
            char data[48];
            (void)snprintf(data, sizeof data, "{\"mv\":%u}", mv);
            panel_event_add(p, "battery", data);
            st->next_battery = dev_now_ms() + BATTERY_MS;
        } else if (r == LSC_EINVAL) { /* refused: the kind has none (a bus) */
            panel_buf b = {0};
            panel_buf_str(&b, "{\"mv\":null,\"why\":");
            panel_buf_json(&b, lsc_device_error(p->dev));
            panel_buf_str(&b, "}");
            if (!b.failed) {
                panel_event_add(p, "battery", b.data);
            }
            panel_buf_free(&b);
            st->next_battery = UINT64_MAX; /* not asked again (until a reopen) */
        } else {
            dev_event_error(p, "battery");
            st->next_battery = dev_now_ms() + RETRY_MS;
        }
    }
    now = dev_now_ms();
    if (now >= st->next_read && !st->lost) {
        if (now < st->last_move + MOVE_QUIET_MS) {
            st->next_read = st->last_move + MOVE_QUIET_MS; /* keep the line free for moves */
            return;
        }
        lsc_servo pos[LSC_PLAYER_SERVOS_MAX];
        bool fast = st->limp || st->group_running || now < st->active_until;
        if (dev_note(st, read_positions(p, pos)) == 0) {
            st->next_read = dev_now_ms() + (fast ? READ_FAST_MS : READ_SLOW_MS);
        } else {
            dev_event_error(p, "read");
            st->next_read = dev_now_ms() + RETRY_MS;
        }
    }
}

/* Tells the requests whose move was taken its result. Under p->m. */
void dev_moves_done(panel *p, panel_move_wait *w, int r, const char *why)
{
    for (; w != NULL; w = w->next) {
        w->result = r;
        (void)snprintf(w->message, sizeof w->message, "%s", why);
        w->done = true;
    }
    pthread_cond_broadcast(&p->done_cv);
}

/* While the controller is away: the move waiting and a command are
 * answered that it is (503), and it is opened again when due. */
static void away(panel *p, dev_state *st, panel_cmd *c)
{
    pthread_mutex_lock(&p->m);
    char why[PANEL_MSG_MAX];
    (void)snprintf(why, sizeof why, "reconnecting to the controller: %.440s", p->link_why);
    p->move_n = 0;
    dev_moves_done(p, p->move_waiters, LSC_ENODEV, why);
    p->move_waiters = NULL;
    pthread_mutex_unlock(&p->m);
    if (c != NULL) {
        if (c->kind == PANEL_CMD_PLAY) {
            dev_free_action(c->action);
            dev_play_over(p);
        }
        c->result = LSC_ENODEV;
        (void)snprintf(c->message, sizeof c->message, "%s", why);
        dev_finish(p, c);
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
        dev_send_move(p, &st); /* first: a slider waits for nothing */
        if (!st.lost) {
            pump(p, &st);
        }
        if (c != NULL && !st.lost) {
            if (c->kind == PANEL_CMD_PLAY) {
                dev_play(p, c, &st);
            } else {
                pthread_mutex_lock(&p->m);
                p->in_call = true;
                pthread_mutex_unlock(&p->m);
                dev_run_cmd(p, c, &st);
            }
            dev_take_interrupt(p, &st);
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
    dev_moves_done(p, p->move_waiters, LSC_EIO, "lsc-panel is stopping");
    p->move_waiters = NULL;
    p->move_n = 0;
    if (p->cmd != NULL) { /* taken by no one: its caller is told */
        if (p->cmd->kind == PANEL_CMD_PLAY) {
            dev_free_action(p->cmd->action);
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
            dev_free_action(cmd->action); /* handed over: nobody else frees it */
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
    if (cmd->kind == PANEL_CMD_STOP || cmd->kind == PANEL_CMD_HALT) {
        dev_interrupt_call(p, true); /* the play ends at once; then this runs */
    }
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
    dev_play_over(p);
}

/* Drops the move not yet sent (Stop play, Halt): its requests are told.
 * Under p->m. */
static void drop_moves(panel *p, const char *why)
{
    p->move_n = 0;
    dev_moves_done(p, p->move_waiters, LSC_EBUSY, why);
    p->move_waiters = NULL;
}

bool panel_dev_play_stop(panel *p)
{
    pthread_mutex_lock(&p->m);
    bool busy = p->play_busy;
    p->play_stop = busy;
    dev_interrupt_call(p, true);
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
    dev_interrupt_call(p, true);
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
    dev_interrupt_call(p, false);
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
