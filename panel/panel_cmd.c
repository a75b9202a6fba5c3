/* lsc-panel: the commands the device thread runs (panel_dev.h): a play,
 * a jog, a hold or halt, a group's run, stop and speed, a pose, a
 * calibration's step, a slider's move. Each is the library's call; here
 * are what the panel answers and the events it sends. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/bus.h"
#include "lsc/lxclient.h"

#include "panel_dev.h"

/* The command failed with r: its message the device's line, unless the
 * command said why itself. */
static void fail(panel *p, panel_cmd *c, int r)
{
    c->result = r;
    c->cause = lsc_device_error_cause(p->dev);
    if (c->message[0] != '\0') {
        return;
    }
    pthread_mutex_lock(&p->m);
    bool stopping = p->stopping;
    pthread_mutex_unlock(&p->m);
    (void)snprintf(c->message, sizeof c->message, "%s",
                   r != LSC_EINTR ? lsc_device_error(p->dev)
                   : stopping     ? "lsc-panel is stopping: the command was cut short"
                                  : "Halt: the command was cut short");
}

void dev_finish(panel *p, const panel_cmd *c)
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
                     (unsigned long)res->frames, (unsigned long)(dev_now_ms() - x->last_event),
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

/* Whether a play must not begin: Stop play, Halt or a group's Stop (which
 * then runs) was asked, or lsc-panel stops. Once it runs, these interrupt
 * it (dev_interrupt_call). Under p->m. */
static bool play_must_end(const panel *p)
{
    bool stop_asked = p->cmd != NULL &&
                      (p->cmd->kind == PANEL_CMD_STOP || p->cmd->kind == PANEL_CMD_HALT);
    return p->play_stop || p->stopping || stop_asked;
}

/* Ends the library call the device thread is in (lsc_device_interrupt: it
 * returns LSC_EINTR within the library's slice): only a play or a bus's
 * scan (play_only: Stop play, Halt, a group's Stop), or any (lsc-panel
 * stopping: a pose's read, a calibration's wait). Under p->m, which keeps
 * p->dev open while p->in_call: the device thread changes p->dev only
 * between calls. */
void dev_interrupt_call(panel *p, bool play_only)
{
    /* a bus's scan takes seconds: the servos must not wait that for a Halt */
    bool scanning = p->cmd != NULL && p->cmd->kind == PANEL_CMD_SERVOS;
    if (p->in_call && (p->playing || scanning || !play_only)) {
        lsc_device_interrupt(p->dev);
        p->interrupted = true;
    }
}

/* The device thread's call has returned: no interrupt is aimed at it any
 * more. One that came after the call stopped waiting would end the
 * device's next wait (a battery read, say): dev_take_interrupt takes it. */
static void call_over(panel *p, dev_state *st)
{
    pthread_mutex_lock(&p->m);
    st->interrupt_left = p->interrupted;
    p->in_call = false;
    p->interrupted = false;
    pthread_mutex_unlock(&p->m);
}

/* After the command's result was taken (its message: this sets the
 * device's), a wait of 1 ms takes an interrupt left over, if any. */
void dev_take_interrupt(panel *p, dev_state *st)
{
    if (st->interrupt_left) {
        st->interrupt_left = false;
        int r = lsc_device_poll(p->dev, 1);
        (void)dev_note(st, r == LSC_EINTR ? 0 : r);
    }
}

static bool on_play(void *user, const lsc_player_step *step, uint32_t elapsed_ms)
{
    (void)elapsed_ms;
    play_ctx *x = user;
    panel *p = x->p;
    if (x->cmd != NULL) {
        dev_finish(p, x->cmd); /* the play has begun: its request is answered */
        x->cmd = NULL;
    }
    if (step != NULL) {
        play_event(x, false, 0);
    }
    return !dev_halted_elsewhere(p, x->st); /* another program's halt ends it */
}

void dev_free_action(lsc_action *a)
{
    lsc_action_free(a);
    free(a);
}

/* The play slot is free again: whoever waits for the play's end is told. */
void dev_play_over(panel *p)
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
void dev_play(panel *p, panel_cmd *c, dev_state *st)
{
    lsc_action *a = c->action;
    lsc_play_result res = {.size = sizeof res};
    play_ctx x = {.p = p,
                  .st = st,
                  .cmd = c,
                  .result = &res,
                  .count = a->count,
                  .last_event = dev_now_ms()};
    lsc_player_config cfg = {.speed_pct = c->value, .times = 1, .lead_ms = 1000, .baud = 0};
    pthread_mutex_lock(&p->m);
    bool refused = play_must_end(p);
    p->playing = !refused;
    p->in_call = !refused;
    pthread_mutex_unlock(&p->m);
    if (refused) {
        c->result = LSC_EBUSY;
        (void)snprintf(c->message, sizeof c->message,
                       "the play was stopped before it began: nothing was sent");
        dev_free_action(a);
        dev_play_over(p);
        dev_finish(p, c);
        return;
    }
    int r = dev_note(st, lsc_device_play(p->dev, a, &cfg, on_play, &x, &res));
    call_over(p, st);
    if (r == LSC_EINTR) { /* Stop play, Halt, a group's Stop or lsc-panel stopping */
        r = 0;
        res.stopped = true;
    }
    if (x.cmd != NULL) { /* refused before anything was sent */
        if (r < 0) {
            fail(p, c, r);
        }
        dev_finish(p, c);
    }
    dev_free_action(a);
    play_event(&x, true, r);
    dev_play_over(p);
    st->jog_valid = false;
    st->active_until = dev_now_ms() + ACTIVE_MS;
    st->next_read = 0;
}

/* A jog: the grasp point from where it is (or, while the last jog's move
 * runs, from that jog's target) by c->step along c->axis, the pitch kept
 * (or turned by c->step), through lsc_device_reach. Refused by the library
 * (nothing sent) when the target is out of reach or beyond a limit. */
static int jog(panel *p, const panel_cmd *c, dev_state *st, panel_buf *out)
{
    lsc_kin_pose from;
    uint64_t now = dev_now_ms();
    if (st->jog_valid && now < st->jog_until) {
        from = st->jog_to;
    } else {
        int r = lsc_device_where(p->dev, NULL, &from);
        if (r < 0) {
            return r;
        }
    }
    lsc_reach rq = {.size = sizeof rq};
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
    st->jog_until = dev_now_ms() + rq.time_ms;
    st->jog_valid = true;
    dev_pose_json(&st->jog_to, out);
    return 0;
}

/* Holds the page's servos where they are (lsc_device_hold: even one beyond
 * its limits, which it names), or with halt stops everything first
 * (lsc_device_halt: a group, a move under way). out: {"held":N} and, when
 * some joint is beyond its limits, "beyond":[ids] and the library's
 * "message". */
static int hold(panel *p, bool halt, panel_buf *out)
{
    lsc_hold_result res = {.size = sizeof res};
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

/* A bus's servos (PANEL_CMD_SERVOS): a scan of c's ids, then each found
 * one's info, into out as {"asked":N,"servos":[{"id":..,"position":..,
 * "temperature_c":..,"vin_mv":..,"alarms":..,"torque":..,"mode":..},...]};
 * a servo that does not answer its info, or whose answers collide, is
 * {"id":..,"error":...}. 0, or the scan's error (or a lost port's) after
 * the device's line. */
static int servos(panel *p, panel_cmd *c, panel_buf *out)
{
    lsc_lxclient *bus = lsc_device_lxclient(p->dev);
    lsc_lx_scan found;
    if (bus == NULL) { /* (reopened through an lscd that took the bus meanwhile) */
        (void)snprintf(c->message, sizeof c->message, "%s",
                       "the bus is now reached through lscd, which lists no servos");
        return LSC_ENODEV;
    }
    int r = lsc_lxclient_scan(bus, c->ids, c->nids, 0, &found);
    if (r < 0) {
        return lsc_device_lx_result(p->dev, r, "the scan of the bus", 0, LSC_LX_DONE);
    }
    panel_buf_printf(out, "{\"asked\":%u,\"servos\":[", found.asked);
    const char *sep = "";
    for (unsigned id = 0; id <= LSC_LX_ID_MAX; id++) {
        lsc_lx_info info;
        if (lsc_lx_scan_garbled(&found, (uint8_t)id) && !lsc_lx_scan_found(&found, (uint8_t)id)) {
            panel_buf_printf(out, "%s{\"id\":%u,\"error\":", sep, id);
            panel_buf_json(out, "its answers collide: two servos may share this id (connect "
                                "one at a time to give it another)");
            panel_buf_str(out, "}");
            sep = ",";
            continue;
        }
        if (!lsc_lx_scan_found(&found, (uint8_t)id)) {
            continue;
        }
        r = lsc_lxclient_info(bus, (uint8_t)id, &info);
        if (r < 0) {
            r = lsc_device_lx_result(p->dev, r, "its info", (uint8_t)id, LSC_LX_DONE);
            if (r == LSC_ENODEV || r == LSC_EIO || r == LSC_EINTR) {
                return r; /* the port went away, or lsc-panel stops */
            }
            panel_buf_printf(out, "%s{\"id\":%u,\"error\":", sep, id);
            panel_buf_json(out, lsc_device_error(p->dev));
            panel_buf_str(out, "}");
        } else {
            panel_buf_printf(out,
                             "%s{\"id\":%u,\"position\":%d,\"temperature_c\":%u,"
                             "\"vin_mv\":%u,\"alarms\":%u,\"torque\":%s,\"mode\":\"%s\"}",
                             sep, id, info.position, info.temp_c, info.vin_mv, info.alarms,
                             info.torque ? "true" : "false",
                             info.mode == LSC_LX_MODE_MOTOR ? "motor" : "servo");
        }
        sep = ",";
    }
    panel_buf_str(out, "]}");
    return 0;
}

/* The time a board takes at most to announce a group's start after a run
 * (lsc_device_start_ms): a start not heard by then never came. */
static uint32_t start_ms(panel *p)
{
    return lsc_device_start_ms(p->dev);
}

/* Runs c (not PLAY, which answers itself). */
void dev_run_cmd(panel *p, panel_cmd *c, dev_state *st)
{
    int r = 0;
    switch (c->kind) {
    case PANEL_CMD_RUN:
        r = lsc_device_run(p->dev, c->group, c->value);
        if (r == 0) { /* its start is awaited (pump says when it never came) */
            st->run_group = c->group;
            st->run_deadline = dev_now_ms() + start_ms(p);
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
    case PANEL_CMD_SERVOS:
        r = servos(p, c, &c->out);
        break;
    default:
        break;
    }
    call_over(p, st);
    if (c->kind != PANEL_CMD_JOG) {
        st->jog_valid = false; /* the arm moved otherwise, or may have */
    }
    if (dev_note(st, r) < 0 && c->kind == PANEL_CMD_CALIBRATE) {
        c->result = r; /* panel_calibrate said why */
    } else if (r < 0) {
        fail(p, c, r);
    } else {
        c->result = 0;
    }
    st->active_until = dev_now_ms() + ACTIVE_MS;
    st->next_read = 0;
    dev_finish(p, c);
}

void dev_send_move(panel *p, dev_state *st)
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
    int r = dev_note(st, lsc_device_move(p->dev, t, s, n));
    if (r < 0) {
        dev_event_error(p, "move");
    }
    pthread_mutex_lock(&p->m);
    dev_moves_done(p, w, r, r < 0 ? lsc_device_error(p->dev) : "");
    pthread_mutex_unlock(&p->m);
    st->last_move = dev_now_ms();
    st->active_until = st->last_move + ACTIVE_MS + t;
    st->limp = false;
    st->jog_valid = false;
}
