/* lsc-panel: the controller's API (panel_http.h): each route checks its
 * arguments, hands the device thread a command (panel_dev_call) or a move
 * (panel_dev_move) and answers with the result. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/calibrate.h"
#include "lsc/text.h"

#include "panel_http.h"

#define BROADCAST_MIN 254u /* 254 (bus servos) and 255 (every group): every servo at once */

enum MHD_Result api_config(const ctx *x)
{
    const panel *p = x->p;
    panel_buf b = {0};
    panel_buf_str(&b, "{\"name\":");
    panel_buf_json(&b, p->dev_name);
    panel_buf_printf(&b, ",\"kind\":\"%s\",\"arm\":%s,\"geometry\":%s,\"joints\":[",
                     lsc_device_kind_name(p->dev_kind), p->arm ? "true" : "false",
                     p->geometry ? "true" : "false");
    for (size_t i = 0; i < p->nids; i++) {
        int j = lsc_arm_by_id(p->arm, p->ids[i]);
        panel_buf_str(&b, i ? ",{\"name\":" : "{\"name\":");
        if (j >= 0) {
            const lsc_joint *jt = lsc_arm_joint(p->arm, (size_t)j);
            panel_buf_json(&b, lsc_arm_name(p->arm, (size_t)j));
            /* whole degrees inside the limits */
            long lo = jt->min_cdeg >= 0 ? (jt->min_cdeg + 99) / 100 : -((-jt->min_cdeg) / 100);
            long hi = jt->max_cdeg >= 0 ? jt->max_cdeg / 100 : -((-jt->max_cdeg + 99) / 100);
            panel_buf_printf(&b, ",\"id\":%u,\"unit\":\"deg\",\"min\":%ld,\"max\":%ld}",
                             p->ids[i], lo, hi);
        } else {
            panel_buf_printf(&b, "\"%u\",\"id\":%u,\"unit\":\"pos\",\"min\":0,\"max\":1000}",
                             p->ids[i], p->ids[i]);
        }
    }
    panel_buf_str(&b, "],\"profile\":");
    panel_buf_json(&b, p->arm_given != NULL ? p->arm_given : "");
    panel_buf_printf(&b, ",\"calibrated\":%s,\"calibrate_out\":",
                     p->arm_calibrated ? "true" : "false");
    panel_buf_json(&b, p->calib_out);
    lsc_kin_chain chain;
    int joints[LSC_ARM_CHAIN_MAX];
    if (p->geometry && lsc_arm_chain(p->arm, &chain, joints, NULL, 0) == 0) {
        /* for the drawing: the chain's servos and its lengths */
        panel_buf_str(&b, ",\"chain\":[");
        for (size_t q = 0; q < LSC_ARM_CHAIN_MAX && joints[q] >= 0; q++) {
            panel_buf_printf(&b, "%s%u", q ? "," : "",
                             lsc_arm_joint(p->arm, (size_t)joints[q])->id);
        }
        panel_buf_printf(&b, "],\"links\":{\"height\":%.2f,\"upper\":%.2f,\"fore\":%.2f,"
                             "\"tool\":%.2f}",
                         (double)chain.base_mm, (double)chain.upper_mm, (double)chain.fore_mm,
                         (double)chain.tool_mm);
    }
    panel_buf_str(&b, ",\"groups\":[");
    for (size_t i = 0; i < p->ngroups; i++) {
        panel_buf_printf(&b, "%s%u", i ? "," : "", p->groups[i]);
    }
    panel_buf_str(&b, "],\"dir\":");
    panel_buf_json(&b, p->dir_shown);
    panel_buf_str(&b, "}");
    return http_send_json(x->c, MHD_HTTP_OK, &b);
}

/* Whether servo id is one the panel shows (the arm profile's joints, or
 * --ids): the only ones it moves; never the broadcast ids. */
static bool servo_shown(const panel *p, unsigned id, char *why, size_t cap)
{
    for (size_t i = 0; i < p->nids; i++) {
        if (p->ids[i] == id && id < BROADCAST_MIN) {
            return true;
        }
    }
    (void)snprintf(why, cap,
                   id >= 254u ? "servo %u is a broadcast id (every servo): the panel moves "
                                "its servos one by one"
                   : p->arm   ? "servo %u is no joint of the arm profile: the panel moves its "
                                "joints only"
                              : "servo %u is not one of the panel's servos (--ids)",
                   id);
    return false;
}

typedef struct move_args {
    const panel *p;
    lsc_servo s[LSC_PLAYER_SERVOS_MAX];
    size_t n;
    char why[LSC_ARM_MESSAGE_MAX];
} move_args;

static enum MHD_Result move_arg(void *cls, enum MHD_ValueKind kind, const char *key,
                                const char *value)
{
    move_args *m = cls;
    (void)kind;
    if (strcmp(key, "s") != 0) {
        return MHD_YES;
    }
    if (m->n == LSC_PLAYER_SERVOS_MAX) {
        (void)snprintf(m->why, sizeof m->why, "more than %u servos in one move",
                       LSC_PLAYER_SERVOS_MAX);
        return MHD_NO;
    }
    if (value == NULL ||
        lsc_arm_target(m->p->arm, value, &m->s[m->n], m->why, sizeof m->why) != 0) {
        if (value == NULL) {
            (void)snprintf(m->why, sizeof m->why, "s= needs JOINT:VALUE");
        }
        return MHD_NO;
    }
    if (!servo_shown(m->p, m->s[m->n].id, m->why, sizeof m->why)) {
        return MHD_NO;
    }
    for (size_t i = 0; i < m->n; i++) {
        if (m->s[i].id == m->s[m->n].id) {
            (void)snprintf(m->why, sizeof m->why, "servo %u listed twice", m->s[i].id);
            return MHD_NO;
        }
    }
    m->n++;
    return MHD_YES;
}

enum MHD_Result api_move(const ctx *x)
{
    long t;
    if (!http_number(http_arg(x, "time"), 0, 65535, 500, &t)) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "time= must be 0..65535 (ms)");
    }
    move_args m;
    memset(&m, 0, sizeof m);
    m.p = x->p;
    (void)MHD_get_connection_values(x->c, MHD_GET_ARGUMENT_KIND, move_arg, &m);
    if (m.why[0] != '\0') {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, m.why);
    }
    if (m.n == 0u) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "a move needs s=JOINT:VALUE");
    }
    panel_move_wait w;
    panel_dev_move(x->p, m.s, m.n, (uint16_t)t, &w); /* returns once it was sent, or not */
    if (w.result < 0) {
        return http_refuse(x->c,
                           w.result == LSC_EBUSY ? MHD_HTTP_CONFLICT
                                                 : http_device_status(w.result),
                           w.message);
    }
    return http_send_ok(x->c, MHD_HTTP_ACCEPTED);
}

/* Runs cmd in the device thread and answers with its result. */
static enum MHD_Result call(const ctx *x, panel_cmd *cmd)
{
    char why[PANEL_MSG_MAX + 64];
    if (!panel_dev_link(x->p, why, sizeof why)) { /* nothing can be delivered */
        if (cmd->kind == PANEL_CMD_PLAY) {
            lsc_action_free(cmd->action);
            free(cmd->action);
            panel_dev_play_release(x->p);
        }
        return http_refuse(x->c, MHD_HTTP_SERVICE_UNAVAILABLE, why);
    }
    if (cmd->kind != PANEL_CMD_STOP && cmd->kind != PANEL_CMD_PLAY &&
        cmd->kind != PANEL_CMD_HALT && panel_dev_play_busy(x->p)) {
        return http_refuse(x->c, MHD_HTTP_CONFLICT, "a play is running: stop it first");
    }
    panel_dev_call(x->p, cmd);
    enum MHD_Result ok;
    if (cmd->result < 0) {
        ok = http_refuse(x->c,
                         cmd->kind == PANEL_CMD_PLAY && cmd->result == LSC_EBUSY
                             ? MHD_HTTP_CONFLICT
                             : http_device_status(cmd->result),
                         cmd->message);
    } else if (cmd->out.len > 0u || cmd->out.failed) {
        ok = http_send_json(x->c, MHD_HTTP_OK, &cmd->out);
    } else {
        ok = http_send_ok(x->c, MHD_HTTP_OK);
    }
    panel_buf_free(&cmd->out);
    return ok;
}

enum MHD_Result api_run(const ctx *x)
{
    long g, t;
    if (!http_number(http_arg(x, "group"), 0, 255, -1, &g) ||
        !http_number(http_arg(x, "times"), 0, 65535, 1, &t)) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST,
                           "run needs group=0..255 and times=0..65535 (0: for ever)");
    }
    panel_cmd c = {.kind = PANEL_CMD_RUN, .group = (uint8_t)g, .value = (uint16_t)t};
    return call(x, &c);
}

enum MHD_Result api_speed(const ctx *x)
{
    long g, s;
    if (!http_number(http_arg(x, "group"), 0, 255, -1, &g) ||
        !http_number(http_arg(x, "percent"), 1, 65535, -1, &s)) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST,
                           "speed needs group=0..255 (255: all) and percent=1..65535");
    }
    panel_cmd c = {.kind = PANEL_CMD_SPEED, .group = (uint8_t)g, .value = (uint16_t)s};
    return call(x, &c);
}

static enum MHD_Result api_simple(const ctx *x, panel_cmd_kind kind)
{
    panel_cmd c = {.kind = kind};
    return call(x, &c);
}

enum MHD_Result api_stop(const ctx *x)
{
    return api_simple(x, PANEL_CMD_STOP);
}

enum MHD_Result api_limp(const ctx *x)
{
    return api_simple(x, PANEL_CMD_LIMP);
}

enum MHD_Result api_hold(const ctx *x)
{
    return api_simple(x, PANEL_CMD_HOLD);
}

enum MHD_Result api_pose(const ctx *x)
{
    return api_simple(x, PANEL_CMD_POSE);
}

/* GET /api/servos[?ids=LIST]: the servos of a bus (lx:PATH) that answer,
 * each with its position, temperature, supply voltage and alarms; 404 on a
 * controller that is no bus opened directly (a board, lscd). */
enum MHD_Result api_servos(const ctx *x)
{
    const panel *p = x->p;
    char why[PANEL_MSG_MAX];
    if (p->dev_kind != LSC_DEVICE_LX) {
        (void)snprintf(why, sizeof why,
                       "%s (%s) is no bus of servos opened directly (lx:PATH): only a bus's "
                       "servos are asked for their ids, temperature and voltage",
                       p->dev_name, lsc_device_kind_name(p->dev_kind));
        return http_refuse(x->c, MHD_HTTP_NOT_FOUND, why);
    }
    uint8_t ids[LSC_LX_ID_MAX + 1u];
    const char *list = http_arg(x, "ids");
    int n = 0;
    if (list != NULL) {
        char bad[256];
        n = lsc_device_parse_ids(NULL, list, ids, sizeof ids, bad, sizeof bad);
        for (int i = 0; i < n; i++) {
            if (ids[i] > LSC_LX_ID_MAX) {
                (void)snprintf(bad, sizeof bad, "id %u is not a servo's: use 0..253",
                               ids[i]);
                n = LSC_EINVAL;
            }
        }
        if (n < 0) {
            (void)snprintf(why, sizeof why, "ids=: %s", bad);
            return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, why);
        }
    }
    panel_cmd c = {.kind = PANEL_CMD_SERVOS, .ids = list != NULL ? ids : NULL,
                   .nids = (size_t)n};
    return call(x, &c);
}

/* Halt: the play ends (or never begins), the move not yet sent is dropped,
 * then the device stops everything where it is (lsc_device_halt). */
enum MHD_Result api_halt(const ctx *x)
{
    panel_dev_halt_asked(x->p);
    return api_simple(x, PANEL_CMD_HALT);
}

/* The request's body, an action as CSV, into a; refuses it (answered) when
 * it is not one. */
bool api_body_action(const ctx *x, lsc_action *a, enum MHD_Result *ok)
{
    lsc_file_error err = {.size = sizeof err};
    int r = lsc_action_parse(LSC_FILE_CSV, x->r->body.data ? x->r->body.data : "",
                             x->r->body.len, a, &err);
    if (r == 0) {
        return true;
    }
    char msg[PANEL_MSG_MAX];
    (void)snprintf(msg, sizeof msg, "the keyframes: %s", err.message);
    *ok = http_refuse(x->c, r == LSC_ENOSPC ? MHD_HTTP_INTERNAL_SERVER_ERROR : MHD_HTTP_BAD_REQUEST,
                      r == LSC_ENOSPC ? "out of memory" : msg);
    return false;
}

enum MHD_Result api_play(const ctx *x)
{
    long speed;
    enum MHD_Result ok = MHD_NO;
    if (!http_number(http_arg(x, "speed"), 1, 65535, 100, &speed)) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "speed= must be 1..65535 (%)");
    }
    /* the one play slot, taken under one lock: of two plays at once, one only */
    if (!panel_dev_play_reserve(x->p)) {
        return http_refuse(x->c, MHD_HTTP_CONFLICT, "a play is running: stop it first");
    }
    lsc_action *a = malloc(sizeof *a);
    if (a == NULL) {
        panel_dev_play_release(x->p);
        return http_refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
    }
    if (!api_body_action(x, a, &ok)) {
        free(a);
        panel_dev_play_release(x->p);
        return ok;
    }
    char why[LSC_ARM_MESSAGE_MAX];
    for (size_t i = 0; i < a->nservos; i++) {
        if (!servo_shown(x->p, a->ids[i], why, sizeof why)) {
            lsc_action_free(a);
            free(a);
            panel_dev_play_release(x->p);
            return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, why);
        }
    }
    panel_cmd c = {.kind = PANEL_CMD_PLAY, .value = (uint16_t)speed, .action = a};
    return call(x, &c); /* a is the device thread's now; the slot too */
}

/* A signed decimal number (digits, at most one point, a sign first) in s,
 * |value| within 0 < |v| <= max. */
static bool step_number(const char *s, double max, double *out)
{
    if (s == NULL || *s == '\0' || strlen(s) > 12u) {
        return false;
    }
    size_t digits = 0, points = 0;
    for (const char *c = s; *c; c++) {
        if (*c >= '0' && *c <= '9') {
            digits++;
        } else if (*c == '.') {
            points++;
        } else if (!((*c == '-' || *c == '+') && c == s)) {
            return false;
        }
    }
    if (digits == 0u || points > 1u) {
        return false;
    }
    double v = strtod(s, NULL);
    *out = v;
    return v != 0.0 && v <= max && v >= -max;
}

enum MHD_Result api_jog(const ctx *x)
{
    static const char *const axes[] = {"x", "y", "z", "pitch"};
    const char *a = http_arg(x, "axis");
    size_t axis = 0;
    while (axis < 4u && (a == NULL || strcmp(a, axes[axis]) != 0)) {
        axis++;
    }
    if (!x->p->geometry) {
        return http_refuse(x->c, MHD_HTTP_CONFLICT,
                           x->p->arm
                               ? "the arm profile states no geometry (its chain: and links: "
                                 "lines): there is nothing to jog"
                               : "no arm profile (--arm) with geometry: there is nothing to jog");
    }
    if (axis == 4u) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "a jog needs axis=x, y, z or pitch");
    }
    double step;
    double max = axis == PANEL_AXIS_PITCH ? PANEL_JOG_DEG_MAX : PANEL_JOG_MM_MAX;
    if (!step_number(http_arg(x, "step"), max, &step)) {
        char msg[128];
        (void)snprintf(msg, sizeof msg, "step= must be a number, not 0, within -%g..%g (%s)", max,
                       max, axis == PANEL_AXIS_PITCH ? "degrees" : "mm");
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, msg);
    }
    long t;
    if (!http_number(http_arg(x, "time"), 0, 65535, 500, &t)) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "time= must be 0..65535 (ms)");
    }
    panel_cmd c = {.kind = PANEL_CMD_JOG, .axis = (panel_axis)axis, .step = step,
                   .value = (uint16_t)t};
    return call(x, &c);
}

/* POST /api/calibrate?step=STEP|save|cancel (lsc/calibrate.h's steps) */
enum MHD_Result api_calibrate(const ctx *x)
{
    const char *s = http_arg(x, "step");
    lsc_calib_step step = LSC_CALIB_HOME;
    unsigned value;
    if (s != NULL && lsc_calib_step_parse(s, &step) == 0) {
        value = (unsigned)step;
    } else if (s != NULL && strcmp(s, "save") == 0) {
        value = PANEL_CALIBRATE_SAVE;
    } else if (s != NULL && strcmp(s, "cancel") == 0) {
        value = PANEL_CALIBRATE_CANCEL;
    } else {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST,
                           "calibrate needs step=home, lean, gripper-closed, gripper-open, save or "
                           "cancel");
    }
    if (!x->p->geometry) {
        return http_refuse(x->c, MHD_HTTP_CONFLICT,
                           "calibration needs an arm profile with geometry (--arm, with its chain: "
                           "and links: lines)");
    }
    panel_cmd c = {.kind = PANEL_CMD_CALIBRATE, .value = (uint16_t)value};
    return call(x, &c);
}

/* Stop play: answered once the play has ended (nothing of it is sent after). */
enum MHD_Result api_play_stop(const ctx *x)
{
    bool was = panel_dev_play_stop(x->p);
    return http_send(x->c, MHD_HTTP_OK, "application/json",
                     was ? "{\"stopped\":true}\n" : "{\"stopped\":false}\n",
                     was ? 16u : 17u);
}
