/* lsc-panel: the HTTP side (panel.h) on libmicrohttpd, one thread per
 * connection. Every request passes the checks in check_request before
 * anything else: the Host header (DNS rebinding), the token's cookie, and on
 * state changes (POST) the Origin header. */
#include <arpa/inet.h>
#include <dirent.h>
#include <errno.h>
#include <microhttpd.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "lsc/calibrate.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/player.h"
#include "lsc/kinematics.h"
#include "panel.h"

/* The cookie's name holds the port: cookies are not kept apart by port, so
 * two panels on one host would replace each other's. */
#define COOKIE "lsc_panel_"
#define KEEPALIVE_S 15
/* Connections: a connection that has not shown the token is closed after
 * PRE_TOKEN_S idle (and after any refusal); one that has, after TOKEN_S.
 * At most CONNECTIONS_MAX at once, PER_IP_MAX from one address (so one
 * machine on the network cannot take every slot), each thread's stack
 * STACK_BYTES. */
#define PRE_TOKEN_S 10u
#define TOKEN_S 120u
#define CONNECTIONS_MAX 256u
#define PER_IP_MAX 100u
#define STACK_BYTES (512u * 1024u)
#define SHUTDOWN_GRACE_S 10 /* at most this long for the requests under way to be answered */
#define FILES_MAX 1000u /* files listed from --dir */
#define BROADCAST_MIN 254u /* 254 (bus servos) and 255 (every group): every servo at once */

static const char security_headers[][2][64] = {
    {"X-Content-Type-Options", "nosniff"},
    {"Referrer-Policy", "no-referrer"},
    {"X-Frame-Options", "DENY"},
    {"Cache-Control", "no-store"},
};
static const char csp[] = "default-src 'self'; img-src 'self' data:; style-src 'self'; "
                          "script-src 'self'; connect-src 'self'; frame-ancestors 'none'; "
                          "base-uri 'none'; form-action 'self'";

/* ---- a request --------------------------------------------------------------------- */

typedef struct route route;

typedef struct req {
    const route *route;
    panel_buf body;
    bool too_big;
    bool no_body;   /* a body where none is taken */
    bool counted;   /* in p->in_flight (every request but the event streams) */
} req;

typedef struct ctx {
    panel *p;
    struct MHD_Connection *c;
    req *r;
} ctx;

/* A response holding a copy of data[0..len), with the security headers. */
static struct MHD_Response *new_response(const void *data, size_t len)
{
    void *copy = malloc(len ? len : 1u);
    if (copy == NULL) {
        return NULL;
    }
    if (len) {
        memcpy(copy, data, len);
    }
    struct MHD_Response *res = MHD_create_response_from_buffer(len, copy, MHD_RESPMEM_MUST_FREE);
    if (res == NULL) {
        free(copy);
        return NULL;
    }
    for (size_t i = 0; i < sizeof security_headers / sizeof security_headers[0]; i++) {
        (void)MHD_add_response_header(res, security_headers[i][0], security_headers[i][1]);
    }
    (void)MHD_add_response_header(res, "Content-Security-Policy", csp);
    return res;
}

static enum MHD_Result send_response(struct MHD_Connection *c, unsigned status, const char *type,
                                     const void *data, size_t len)
{
    struct MHD_Response *res = new_response(data, len);
    if (res == NULL) {
        return MHD_NO;
    }
    if (type != NULL) {
        (void)MHD_add_response_header(res, MHD_HTTP_HEADER_CONTENT_TYPE, type);
    }
    enum MHD_Result ok = MHD_queue_response(c, status, res);
    MHD_destroy_response(res);
    return ok;
}

/* {"error": message} with status; close: the connection is closed after it
 * (a request without the token keeps no connection). */
static enum MHD_Result refuse_conn(struct MHD_Connection *c, unsigned status, const char *message,
                                   bool close)
{
    panel_buf b = {0};
    panel_buf_str(&b, "{\"error\":");
    panel_buf_json(&b, message);
    panel_buf_str(&b, "}\n");
    struct MHD_Response *res = b.failed ? NULL : new_response(b.data, b.len);
    panel_buf_free(&b);
    if (res == NULL) {
        return MHD_NO;
    }
    (void)MHD_add_response_header(res, MHD_HTTP_HEADER_CONTENT_TYPE, "application/json");
    if (close) {
        (void)MHD_add_response_header(res, MHD_HTTP_HEADER_CONNECTION, "close");
    }
    enum MHD_Result ok = MHD_queue_response(c, status, res);
    MHD_destroy_response(res);
    return ok;
}

static enum MHD_Result refuse(struct MHD_Connection *c, unsigned status, const char *message)
{
    return refuse_conn(c, status, message, false);
}

static enum MHD_Result send_json(struct MHD_Connection *c, unsigned status, panel_buf *b)
{
    if (b->failed) {
        panel_buf_free(b);
        return refuse(c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
    }
    panel_buf_str(b, "\n");
    enum MHD_Result ok = send_response(c, status, "application/json", b->data, b->len);
    panel_buf_free(b);
    return ok;
}

static enum MHD_Result send_ok(struct MHD_Connection *c, unsigned status)
{
    return send_response(c, status, "application/json", "{\"ok\":true}\n", 12);
}

/* The HTTP status of a device error. */
static unsigned device_status(int r)
{
    switch (r) {
    case LSC_EINVAL:
        return MHD_HTTP_BAD_REQUEST;
    case LSC_EBUSY:
        return MHD_HTTP_CONFLICT;
    case LSC_ETIMEOUT:
        return MHD_HTTP_GATEWAY_TIMEOUT;
    case LSC_ENODEV: /* away: the panel opens it again */
    case LSC_EIO:
        return MHD_HTTP_SERVICE_UNAVAILABLE;
    default:
        return MHD_HTTP_BAD_GATEWAY;
    }
}

static const char *arg(const ctx *x, const char *key)
{
    return MHD_lookup_connection_value(x->c, MHD_GET_ARGUMENT_KIND, key);
}

/* A decimal number lo..hi in s (digits only); def when s is NULL. */
static bool number(const char *s, long lo, long hi, long def, long *out)
{
    if (s == NULL) {
        *out = def;
        return def >= lo;
    }
    long v = 0;
    if (*s == '\0' || strlen(s) > 9u) { /* 9 digits: a 16 MiB body's length fits */
        return false;
    }
    for (const char *c = s; *c; c++) {
        if (*c < '0' || *c > '9') {
            return false;
        }
        v = v * 10 + (*c - '0');
    }
    *out = v;
    return v >= lo && v <= hi;
}

/* ---- the checks ----------------------------------------------------------------- */

/* Whether a and b are equal, in a time that does not depend on where they differ. */
static bool same_secret(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    unsigned d = na == nb ? 0u : 1u;
    for (size_t i = 0; i < na && i < nb; i++) {
        d |= (unsigned)((unsigned char)a[i] ^ (unsigned char)b[i]);
    }
    return d == 0u;
}

/* Whether a Host header names this server: its own address (the address it
 * listens on; "localhost" too when that is a loopback address; any address
 * literal when it listens on every address: never a DNS name, which is what
 * DNS rebinding needs) with its port. */
static bool host_ok(const panel *p, const char *host)
{
    char name[80];
    if (host == NULL) {
        return false;
    }
    const char *colon = strrchr(host, ':');
    if (colon == NULL || (host[0] == '[' && colon < strchr(host, ']'))) {
        return false; /* no port */
    }
    long port;
    if (!number(colon + 1, 1, 65535, 0, &port) || (uint16_t)port != p->port) {
        return false;
    }
    size_t n = (size_t)(colon - host);
    if (n == 0u || n >= sizeof name) {
        return false;
    }
    memcpy(name, host, n);
    name[n] = '\0';
    if (strcmp(name, p->host) == 0 || (p->loopback && strcmp(name, "localhost") == 0)) {
        return true;
    }
    if (!p->wildcard) {
        return false;
    }
    unsigned char a[16];
    if (name[0] == '[' && name[n - 1u] == ']') {
        name[n - 1u] = '\0';
        return inet_pton(AF_INET6, name + 1, a) == 1;
    }
    return inet_pton(AF_INET, name, a) == 1;
}

/* Refuses a request that may not go on (and says why); true when it may. */
static bool check_request(const ctx *x, const char *method, bool *answered)
{
    const char *host = MHD_lookup_connection_value(x->c, MHD_HEADER_KIND, "Host");
    *answered = true;
    if (!host_ok(x->p, host)) {
        (void)refuse_conn(x->c, MHD_HTTP_MISDIRECTED_REQUEST,
                          "the Host header does not name this server: open the address "
                          "lsc-panel printed",
                          true);
        return false;
    }
    char name[32];
    (void)snprintf(name, sizeof name, COOKIE "%u", (unsigned)x->p->port);
    const char *cookie = MHD_lookup_connection_value(x->c, MHD_COOKIE_KIND, name);
    if (cookie == NULL || !same_secret(cookie, x->p->token)) {
        (void)refuse_conn(x->c, MHD_HTTP_FORBIDDEN,
                          "no valid token: open the address with ?token= that lsc-panel printed",
                          true);
        return false;
    }
    /* the owner's connection: kept open longer than one without the token */
    (void)MHD_set_connection_option(x->c, MHD_CONNECTION_OPTION_TIMEOUT, TOKEN_S);
    if (strcmp(method, MHD_HTTP_METHOD_POST) == 0) {
        const char *origin = MHD_lookup_connection_value(x->c, MHD_HEADER_KIND, "Origin");
        char want[96];
        (void)snprintf(want, sizeof want, "http://%s", host);
        if (origin == NULL || strcmp(origin, want) != 0) {
            (void)refuse(x->c, MHD_HTTP_FORBIDDEN,
                         "a change must come from the panel's own page (the Origin header "
                         "is missing or names another site)");
            return false;
        }
    }
    *answered = false;
    return true;
}

static enum MHD_Result nul_arg(void *cls, enum MHD_ValueKind kind, const char *key,
                               size_t key_size, const char *value, size_t value_size)
{
    bool *nul = cls;
    (void)kind;
    if (strlen(key) != key_size || (value != NULL && strlen(value) != value_size)) {
        *nul = true;
        return MHD_NO;
    }
    return MHD_YES;
}

/* Whether an argument holds a NUL byte (%00): C would see it cut there. */
static bool has_nul_arg(struct MHD_Connection *c)
{
    bool nul = false;
    (void)MHD_get_connection_values_n(c, MHD_GET_ARGUMENT_KIND, nul_arg, &nul);
    return nul;
}

/* ---- the routes ------------------------------------------------------------------ */

typedef enum MHD_Result (*handler_fn)(const ctx *x);

struct route {
    const char *method;
    const char *path;
    handler_fn fn;
    bool body; /* takes a body (an action as CSV) */
};

static enum MHD_Result h_config(const ctx *x)
{
    const panel *p = x->p;
    static const char *const kinds[] = {"serial", "hid", "sim", "lscd"};
    panel_buf b = {0};
    panel_buf_str(&b, "{\"name\":");
    panel_buf_json(&b, p->dev_name);
    panel_buf_printf(&b, ",\"kind\":\"%s\",\"arm\":%s,\"geometry\":%s,\"joints\":[",
                     kinds[p->dev_kind & 3], p->arm ? "true" : "false",
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
    return send_json(x->c, MHD_HTTP_OK, &b);
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

static enum MHD_Result h_move(const ctx *x)
{
    long t;
    if (!number(arg(x, "time"), 0, 65535, 500, &t)) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "time= must be 0..65535 (ms)");
    }
    move_args m;
    memset(&m, 0, sizeof m);
    m.p = x->p;
    (void)MHD_get_connection_values(x->c, MHD_GET_ARGUMENT_KIND, move_arg, &m);
    if (m.why[0] != '\0') {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, m.why);
    }
    if (m.n == 0u) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "a move needs s=JOINT:VALUE");
    }
    panel_move_wait w;
    panel_dev_move(x->p, m.s, m.n, (uint16_t)t, &w); /* returns once it was sent, or not */
    if (w.result < 0) {
        return refuse(x->c, w.result == LSC_EBUSY ? MHD_HTTP_CONFLICT : device_status(w.result),
                      w.message);
    }
    return send_ok(x->c, MHD_HTTP_ACCEPTED);
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
        return refuse(x->c, MHD_HTTP_SERVICE_UNAVAILABLE, why);
    }
    if (cmd->kind != PANEL_CMD_STOP && cmd->kind != PANEL_CMD_PLAY &&
        cmd->kind != PANEL_CMD_HALT && panel_dev_play_busy(x->p)) {
        return refuse(x->c, MHD_HTTP_CONFLICT, "a play is running: stop it first");
    }
    panel_dev_call(x->p, cmd);
    enum MHD_Result ok;
    if (cmd->result < 0) {
        ok = refuse(x->c,
                    cmd->kind == PANEL_CMD_PLAY && cmd->result == LSC_EBUSY
                        ? MHD_HTTP_CONFLICT
                        : device_status(cmd->result),
                    cmd->message);
    } else if (cmd->out.len > 0u || cmd->out.failed) {
        ok = send_json(x->c, MHD_HTTP_OK, &cmd->out);
    } else {
        ok = send_ok(x->c, MHD_HTTP_OK);
    }
    panel_buf_free(&cmd->out);
    return ok;
}

static enum MHD_Result h_run(const ctx *x)
{
    long g, t;
    if (!number(arg(x, "group"), 0, 255, -1, &g) || !number(arg(x, "times"), 0, 65535, 1, &t)) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST,
                      "run needs group=0..255 and times=0..65535 (0: for ever)");
    }
    panel_cmd c = {.kind = PANEL_CMD_RUN, .group = (uint8_t)g, .value = (uint16_t)t};
    return call(x, &c);
}

static enum MHD_Result h_speed(const ctx *x)
{
    long g, s;
    if (!number(arg(x, "group"), 0, 255, -1, &g) ||
        !number(arg(x, "percent"), 1, 65535, -1, &s)) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST,
                      "speed needs group=0..255 (255: all) and percent=1..65535");
    }
    panel_cmd c = {.kind = PANEL_CMD_SPEED, .group = (uint8_t)g, .value = (uint16_t)s};
    return call(x, &c);
}

static enum MHD_Result h_simple(const ctx *x, panel_cmd_kind kind)
{
    panel_cmd c = {.kind = kind};
    return call(x, &c);
}

static enum MHD_Result h_stop(const ctx *x)
{
    return h_simple(x, PANEL_CMD_STOP);
}

static enum MHD_Result h_limp(const ctx *x)
{
    return h_simple(x, PANEL_CMD_LIMP);
}

static enum MHD_Result h_hold(const ctx *x)
{
    return h_simple(x, PANEL_CMD_HOLD);
}

static enum MHD_Result h_pose(const ctx *x)
{
    return h_simple(x, PANEL_CMD_POSE);
}

/* Halt: the play ends (or never begins), the move not yet sent is dropped,
 * then the device stops everything where it is (lsc_device_halt). */
static enum MHD_Result h_halt(const ctx *x)
{
    panel_dev_halt_asked(x->p);
    return h_simple(x, PANEL_CMD_HALT);
}

/* The request's body, an action as CSV, into a; refuses it (answered) when
 * it is not one. */
static bool body_action(const ctx *x, lsc_action *a, enum MHD_Result *ok)
{
    lsc_file_error err;
    int r = lsc_action_parse(LSC_FILE_CSV, x->r->body.data ? x->r->body.data : "",
                             x->r->body.len, a, &err);
    if (r == 0) {
        return true;
    }
    char msg[PANEL_MSG_MAX];
    (void)snprintf(msg, sizeof msg, "the keyframes: %s", err.message);
    *ok = refuse(x->c, r == LSC_ENOSPC ? MHD_HTTP_INTERNAL_SERVER_ERROR : MHD_HTTP_BAD_REQUEST,
                 r == LSC_ENOSPC ? "out of memory" : msg);
    return false;
}

static enum MHD_Result h_play(const ctx *x)
{
    long speed;
    enum MHD_Result ok = MHD_NO;
    if (!number(arg(x, "speed"), 1, 65535, 100, &speed)) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "speed= must be 1..65535 (%)");
    }
    /* the one play slot, taken under one lock: of two plays at once, one only */
    if (!panel_dev_play_reserve(x->p)) {
        return refuse(x->c, MHD_HTTP_CONFLICT, "a play is running: stop it first");
    }
    lsc_action *a = malloc(sizeof *a);
    if (a == NULL) {
        panel_dev_play_release(x->p);
        return refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
    }
    if (!body_action(x, a, &ok)) {
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
            return refuse(x->c, MHD_HTTP_BAD_REQUEST, why);
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

static enum MHD_Result h_jog(const ctx *x)
{
    static const char *const axes[] = {"x", "y", "z", "pitch"};
    const char *a = arg(x, "axis");
    size_t axis = 0;
    while (axis < 4u && (a == NULL || strcmp(a, axes[axis]) != 0)) {
        axis++;
    }
    if (!x->p->geometry) {
        return refuse(x->c, MHD_HTTP_CONFLICT,
                      x->p->arm ? "the arm profile states no geometry (its chain: and links: "
                                  "lines): there is nothing to jog"
                                : "no arm profile (--arm) with geometry: there is nothing to jog");
    }
    if (axis == 4u) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "a jog needs axis=x, y, z or pitch");
    }
    double step;
    double max = axis == PANEL_AXIS_PITCH ? PANEL_JOG_DEG_MAX : PANEL_JOG_MM_MAX;
    if (!step_number(arg(x, "step"), max, &step)) {
        char msg[128];
        (void)snprintf(msg, sizeof msg, "step= must be a number, not 0, within -%g..%g (%s)", max,
                       max, axis == PANEL_AXIS_PITCH ? "degrees" : "mm");
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, msg);
    }
    long t;
    if (!number(arg(x, "time"), 0, 65535, 500, &t)) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "time= must be 0..65535 (ms)");
    }
    panel_cmd c = {.kind = PANEL_CMD_JOG, .axis = (panel_axis)axis, .step = step,
                   .value = (uint16_t)t};
    return call(x, &c);
}

/* POST /api/calibrate?step=STEP|save|cancel (lsc/calibrate.h's steps) */
static enum MHD_Result h_calibrate(const ctx *x)
{
    const char *s = arg(x, "step");
    lsc_calib_step step = LSC_CALIB_HOME;
    unsigned value;
    if (s != NULL && lsc_calib_step_parse(s, &step) == 0) {
        value = (unsigned)step;
    } else if (s != NULL && strcmp(s, "save") == 0) {
        value = PANEL_CALIBRATE_SAVE;
    } else if (s != NULL && strcmp(s, "cancel") == 0) {
        value = PANEL_CALIBRATE_CANCEL;
    } else {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST,
                      "calibrate needs step=home, lean, gripper-closed, gripper-open, save or "
                      "cancel");
    }
    if (!x->p->geometry) {
        return refuse(x->c, MHD_HTTP_CONFLICT,
                      "calibration needs an arm profile with geometry (--arm, with its chain: "
                      "and links: lines)");
    }
    panel_cmd c = {.kind = PANEL_CMD_CALIBRATE, .value = (uint16_t)value};
    return call(x, &c);
}

/* Stop play: answered once the play has ended (nothing of it is sent after). */
static enum MHD_Result h_play_stop(const ctx *x)
{
    bool was = panel_dev_play_stop(x->p);
    return send_response(x->c, MHD_HTTP_OK, "application/json",
                         was ? "{\"stopped\":true}\n" : "{\"stopped\":false}\n",
                         was ? 16u : 17u);
}

bool panel_file_name_ok(const char *name)
{
    size_t n = name ? strlen(name) : 0u;
    if (n == 0u || n >= PANEL_NAME_MAX || name[0] == '.') {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '.' || c == '_' || c == '-')) {
            return false;
        }
    }
    lsc_file_format f = lsc_file_format_of(name);
    return f == LSC_FILE_TEXT || f == LSC_FILE_CSV || f == LSC_FILE_ROB || f == LSC_FILE_D6A;
}

/* name= as a path in --dir; refuses (answered) a name that is not allowed. */
static bool file_path(const ctx *x, char *path, size_t cap, enum MHD_Result *ok)
{
    const char *name = arg(x, "name");
    if (!panel_file_name_ok(name)) {
        *ok = refuse(x->c, MHD_HTTP_BAD_REQUEST,
                     "name= must be a file name in the panel's directory: letters, digits, "
                     "'.', '_' and '-', not starting with '.', at most 63 bytes, ending in "
                     ".rob, .d6a, .csv or .txt");
        return false;
    }
    (void)snprintf(path, cap, "%s/%s", x->p->dir, name);
    struct stat st;
    if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* a link (or a directory...) would reach outside --dir */
        *ok = refuse(x->c, MHD_HTTP_BAD_REQUEST,
                     "name= is not a regular file in the panel's directory (a link, a "
                     "directory or a device): lsc-panel reads and writes only its own files");
        return false;
    }
    return true;
}

static enum MHD_Result h_save(const ctx *x)
{
    char path[PANEL_PATH_MAX];
    enum MHD_Result ok = MHD_NO;
    lsc_action a;
    lsc_file_error err;
    if (!file_path(x, path, sizeof path, &ok) || !body_action(x, &a, &ok)) {
        return ok;
    }
    int r = lsc_action_write(path, &a, &err);
    lsc_action_free(&a);
    if (r != 0) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "%s: %s", arg(x, "name"), err.message);
        return refuse(x->c, r == LSC_EINVAL ? MHD_HTTP_BAD_REQUEST : MHD_HTTP_INTERNAL_SERVER_ERROR,
                      msg);
    }
    return send_ok(x->c, MHD_HTTP_OK);
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static enum MHD_Result h_files(const ctx *x)
{
    DIR *d = opendir(x->p->dir);
    if (d == NULL) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "cannot list the directory: %s", strerror(errno));
        return refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, msg);
    }
    char *names[FILES_MAX] = {NULL};
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < FILES_MAX) {
        if (panel_file_name_ok(e->d_name) && (names[n] = strdup(e->d_name)) != NULL) {
            n++;
        }
    }
    (void)closedir(d);
    qsort(names, n, sizeof names[0], by_name);
    panel_buf b = {0};
    panel_buf_str(&b, "{\"files\":[");
    bool first = true;
    for (size_t i = 0; i < n; i++) {
        char path[PANEL_PATH_MAX];
        struct stat st;
        (void)snprintf(path, sizeof path, "%s/%s", x->p->dir, names[i]);
        if (lstat(path, &st) == 0 && S_ISREG(st.st_mode)) { /* no links: see file_path */
            panel_buf_str(&b, first ? "{\"name\":" : ",{\"name\":");
            first = false;
            panel_buf_json(&b, names[i]);
            panel_buf_printf(&b, ",\"bytes\":%lld}", (long long)st.st_size);
        }
        free(names[i]);
    }
    panel_buf_str(&b, "]}");
    return send_json(x->c, MHD_HTTP_OK, &b);
}

/* An action as the page's teach list takes it: {"keyframes":[{"time":T,
 * "ids":[..],"pos":[..],"deg":[..]}, ...]} (deg: the joints' angles with
 * --arm, else null). */
static void action_json(const panel *p, const lsc_action *a, panel_buf *b)
{
    size_t w = 1u + a->nservos;
    panel_buf_str(b, "{\"keyframes\":[");
    for (uint32_t k = 0; k < a->count && !b->failed; k++) {
        lsc_servo s[LSC_PLAYER_SERVOS_MAX];
        for (size_t i = 0; i < a->nservos; i++) {
            s[i].id = a->ids[i];
            s[i].position = a->words[k * w + 1u + i];
        }
        panel_buf_printf(b, "%s{\"time\":%u,\"servos\":", k ? "," : "",
                         (unsigned)a->words[k * w]);
        panel_positions_json(p, s, a->nservos, b);
        panel_buf_str(b, "}");
    }
    panel_buf_str(b, "]}");
}

static enum MHD_Result h_file(const ctx *x)
{
    char path[PANEL_PATH_MAX];
    enum MHD_Result ok = MHD_NO;
    lsc_action a;
    lsc_file_error err;
    if (!file_path(x, path, sizeof path, &ok)) {
        return ok;
    }
    const char *as = arg(x, "as");
    if (as != NULL && strcmp(as, "json") != 0 && strcmp(as, "csv") != 0) {
        return refuse(x->c, MHD_HTTP_BAD_REQUEST, "as= must be csv (the default) or json");
    }
    int r = lsc_action_read(path, &a, &err);
    uint8_t *csv = NULL;
    size_t len = 0;
    if (r == 0 && as != NULL && strcmp(as, "json") == 0) {
        panel_buf b = {0};
        action_json(x->p, &a, &b);
        lsc_action_free(&a);
        return send_json(x->c, MHD_HTTP_OK, &b);
    }
    if (r == 0) {
        r = lsc_action_format(LSC_FILE_CSV, &a, path, &csv, &len, &err);
        lsc_action_free(&a);
    }
    if (r != 0) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "%s: %s", arg(x, "name"), err.message);
        return refuse(x->c,
                      r == LSC_EINVAL  ? MHD_HTTP_UNPROCESSABLE_CONTENT
                      : r == LSC_EIO   ? MHD_HTTP_NOT_FOUND
                                       : MHD_HTTP_INTERNAL_SERVER_ERROR,
                      msg);
    }
    ok = send_response(x->c, MHD_HTTP_OK, "text/csv; charset=utf-8", csv, len);
    free(csv);
    return ok;
}

/* ---- Server-Sent Events ------------------------------------------------------------ */

typedef struct sse {
    panel *p;
    uint64_t next; /* the next event to send */
    bool began;
    panel_buf out;
    size_t sent;
} sse;

static void sse_add(sse *s, uint64_t seq, const char *type, const char *data)
{
    if (seq) {
        panel_buf_printf(&s->out, "id: %llu\n", (unsigned long long)seq);
    }
    panel_buf_printf(&s->out, "event: %s\ndata: ", type);
    panel_buf_str(&s->out, data);
    panel_buf_str(&s->out, "\n\n");
}

static ssize_t sse_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    sse *s = cls;
    panel *p = s->p;
    (void)pos;
    if (s->sent == s->out.len) {
        s->out.len = 0;
        s->sent = 0;
        pthread_mutex_lock(&p->ev_m);
        while (s->out.len == 0u && !s->out.failed) {
            if (p->stopping) {
                pthread_mutex_unlock(&p->ev_m);
                return MHD_CONTENT_READER_END_OF_STREAM;
            }
            if (!s->began) {
                s->began = true;
                s->next = p->next_seq;
                panel_buf_str(&s->out, "retry: 1000\n\n");
                if (p->last_battery[0]) {
                    sse_add(s, 0, "battery", p->last_battery);
                }
                if (p->last_positions[0]) {
                    sse_add(s, 0, "positions", p->last_positions);
                }
                if (p->last_where[0]) {
                    sse_add(s, 0, "where", p->last_where);
                }
                if (p->last_link[0]) {
                    sse_add(s, 0, "link", p->last_link);
                }
                break;
            }
            if (s->next < p->next_seq) {
                if (p->next_seq - s->next > PANEL_EVENTS) {
                    s->next = p->next_seq - PANEL_EVENTS; /* fell behind: the oldest kept */
                }
                for (; s->next < p->next_seq; s->next++) {
                    const panel_event *e = &p->events[s->next % PANEL_EVENTS];
                    sse_add(s, e->seq, e->type, e->data);
                }
                break;
            }
            struct timespec until;
            (void)clock_gettime(CLOCK_REALTIME, &until);
            until.tv_sec += KEEPALIVE_S;
            if (pthread_cond_timedwait(&p->ev_cv, &p->ev_m, &until) == ETIMEDOUT) {
                panel_buf_str(&s->out, ": keepalive\n\n");
            }
        }
        pthread_mutex_unlock(&p->ev_m);
        if (s->out.failed) {
            return MHD_CONTENT_READER_END_WITH_ERROR;
        }
    }
    size_t n = s->out.len - s->sent < max ? s->out.len - s->sent : max;
    memcpy(buf, s->out.data + s->sent, n);
    s->sent += n;
    return (ssize_t)n;
}

static void sse_free(void *cls)
{
    sse *s = cls;
    pthread_mutex_lock(&s->p->ev_m);
    s->p->clients--;
    pthread_mutex_unlock(&s->p->ev_m);
    panel_buf_free(&s->out);
    free(s);
}

static enum MHD_Result h_events(const ctx *x)
{
    sse *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
    }
    s->p = x->p;
    struct MHD_Response *res =
        MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 4096, sse_read, s, sse_free);
    if (res == NULL) {
        free(s);
        return MHD_NO;
    }
    pthread_mutex_lock(&x->p->ev_m);
    x->p->clients++;
    pthread_mutex_unlock(&x->p->ev_m);
    (void)MHD_add_response_header(res, MHD_HTTP_HEADER_CONTENT_TYPE, "text/event-stream");
    for (size_t i = 0; i < sizeof security_headers / sizeof security_headers[0]; i++) {
        (void)MHD_add_response_header(res, security_headers[i][0], security_headers[i][1]);
    }
    enum MHD_Result ok = MHD_queue_response(x->c, MHD_HTTP_OK, res);
    MHD_destroy_response(res);
    return ok;
}

static const char NO_BODY[] = "this request takes no body";
static const char TOO_BIG[] = "the body is larger than an action file may be (16 MiB)";

static const route routes[] = {
    {"GET", "/api/config", h_config, false},   {"GET", "/api/events", h_events, false},
    {"GET", "/api/files", h_files, false},     {"GET", "/api/file", h_file, false},
    {"POST", "/api/move", h_move, false},      {"POST", "/api/run", h_run, false},
    {"POST", "/api/stop", h_stop, false},      {"POST", "/api/speed", h_speed, false},
    {"POST", "/api/limp", h_limp, false},      {"POST", "/api/hold", h_hold, false},
    {"POST", "/api/pose", h_pose, false},      {"POST", "/api/play", h_play, true},
    {"POST", "/api/play-stop", h_play_stop, false}, {"POST", "/api/save", h_save, true},
    {"POST", "/api/jog", h_jog, false},        {"POST", "/api/halt", h_halt, false},
    {"POST", "/api/calibrate", h_calibrate, false},
};

/* ---- the page ------------------------------------------------------------------------ */

static const panel_asset *asset(const char *url)
{
    for (size_t i = 0; i < panel_assets_count; i++) {
        if (strcmp(panel_assets[i].path, url) == 0) {
            return &panel_assets[i];
        }
    }
    return NULL;
}

/* GET /?token=T: the cookie, and the page without the token in its address. */
static enum MHD_Result sign_in(const ctx *x, const char *token)
{
    if (!same_secret(token, x->p->token)) {
        return refuse_conn(x->c, MHD_HTTP_FORBIDDEN,
                           "wrong token: open the address lsc-panel printed", true);
    }
    struct MHD_Response *res = new_response("", 0);
    if (res == NULL) {
        return MHD_NO;
    }
    char cookie[128];
    (void)snprintf(cookie, sizeof cookie, COOKIE "%u=%s; Path=/; HttpOnly; SameSite=Strict",
                   (unsigned)x->p->port, x->p->token);
    (void)MHD_add_response_header(res, MHD_HTTP_HEADER_SET_COOKIE, cookie);
    (void)MHD_add_response_header(res, MHD_HTTP_HEADER_LOCATION, "/");
    enum MHD_Result ok = MHD_queue_response(x->c, MHD_HTTP_SEE_OTHER, res);
    MHD_destroy_response(res);
    return ok;
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url,
                                  const char *method, const char *version,
                                  const char *upload_data, size_t *upload_data_size,
                                  void **con_cls)
{
    panel *p = cls;
    ctx x = {.p = p, .c = c, .r = *con_cls};
    (void)version;
    if (x.r == NULL) { /* the headers: every check, before any body is read */
        bool get = strcmp(method, MHD_HTTP_METHOD_GET) == 0 ||
                   strcmp(method, MHD_HTTP_METHOD_HEAD) == 0;
        const char *host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host");
        if (get && strcmp(url, "/favicon.ico") == 0 && host_ok(p, host)) {
            return send_response(c, MHD_HTTP_NO_CONTENT, NULL, "", 0);
        }
        const char *token = get && strcmp(url, "/") == 0 ? arg(&x, "token") : NULL;
        if (token != NULL) {
            if (!host_ok(p, host)) {
                return refuse_conn(c, MHD_HTTP_MISDIRECTED_REQUEST,
                                   "the Host header does not name this server: open the "
                                   "address lsc-panel printed",
                                   true);
            }
            return sign_in(&x, token);
        }
        bool answered;
        if (!check_request(&x, method, &answered)) {
            return answered ? MHD_YES : MHD_NO;
        }
        if (has_nul_arg(c)) {
            return refuse(c, MHD_HTTP_BAD_REQUEST, "an argument holds a NUL byte (%00)");
        }
        const route *rt = NULL;
        bool path_known = asset(url) != NULL;
        for (size_t i = 0; i < sizeof routes / sizeof routes[0]; i++) {
            if (strcmp(routes[i].path, url) == 0) {
                path_known = true;
                if (strcmp(routes[i].method, method) == 0) {
                    rt = &routes[i];
                }
            }
        }
        if (rt == NULL && !(get && asset(url) != NULL)) {
            return path_known ? refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed")
                              : refuse(c, MHD_HTTP_NOT_FOUND, "no such page");
        }
        const char *len = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Content-Length");
        bool takes_body = rt != NULL && rt->body;
        long n = 0;
        if (len != NULL && number(len, 1, (long)LSC_FILE_MAX_BYTES, 0, &n) && !takes_body) {
            return refuse(c, MHD_HTTP_BAD_REQUEST, NO_BODY);
        }
        if (len != NULL && !number(len, 0, (long)LSC_FILE_MAX_BYTES, 0, &n)) {
            return refuse(c, MHD_HTTP_CONTENT_TOO_LARGE, TOO_BIG);
        }
        req *r = calloc(1, sizeof *r);
        if (r == NULL) {
            return MHD_NO;
        }
        r->route = rt;
        r->counted = rt == NULL || rt->fn != h_events;
        if (r->counted) {
            pthread_mutex_lock(&p->m);
            p->in_flight++;
            pthread_mutex_unlock(&p->m);
        }
        *con_cls = r;
        return MHD_YES;
    }
    if (*upload_data_size > 0u) { /* a body, with a length or chunked */
        if (x.r->route == NULL || !x.r->route->body) {
            x.r->no_body = true;
        } else if (x.r->body.len + *upload_data_size > LSC_FILE_MAX_BYTES) {
            x.r->too_big = true;
        } else if (!x.r->too_big) {
            panel_buf_add(&x.r->body, upload_data, *upload_data_size);
        }
        *upload_data_size = 0;
        return MHD_YES;
    }
    if (x.r->no_body) {
        return refuse(c, MHD_HTTP_BAD_REQUEST, NO_BODY);
    }
    if (x.r->too_big || x.r->body.failed) {
        return refuse(c, x.r->body.failed ? MHD_HTTP_INTERNAL_SERVER_ERROR
                                          : MHD_HTTP_CONTENT_TOO_LARGE,
                      x.r->body.failed ? "out of memory" : TOO_BIG);
    }
    if (x.r->route != NULL) {
        return x.r->route->fn(&x);
    }
    const panel_asset *a = asset(url);
    return send_response(c, MHD_HTTP_OK, a->type, a->data, a->len);
}

static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    panel *p = cls;
    req *r = *con_cls;
    (void)c;
    (void)toe;
    if (r != NULL) {
        if (r->counted) { /* answered (or given up): a shutdown may go on */
            pthread_mutex_lock(&p->m);
            p->in_flight--;
            pthread_cond_broadcast(&p->done_cv);
            pthread_mutex_unlock(&p->m);
        }
        panel_buf_free(&r->body);
        free(r);
        *con_cls = NULL;
    }
}

/* ---- the server -------------------------------------------------------------------- */

struct MHD_Daemon *panel_http_start(panel *p, const char *addr, char *why, size_t whylen)
{
    char host[80];
    const char *colon = strrchr(addr, ':');
    long port;
    size_t n = colon ? (size_t)(colon - addr) : 0u;
    if (colon == NULL || n == 0u || n >= sizeof host || !number(colon + 1, 0, 65535, 0, &port)) {
        (void)snprintf(why, whylen, "--listen wants ADDRESS:PORT (127.0.0.1:8480, [::1]:8480)");
        return NULL;
    }
    memcpy(host, addr, n);
    host[n] = '\0';
    struct sockaddr_in v4;
    struct sockaddr_in6 v6;
    memset(&v4, 0, sizeof v4);
    memset(&v6, 0, sizeof v6);
    const struct sockaddr *sa;
    unsigned flags = MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_ITC;
    if (host[0] == '[' && host[n - 1u] == ']') {
        char bare[80];
        (void)snprintf(bare, sizeof bare, "%.*s", (int)(n - 2u), host + 1);
        if (inet_pton(AF_INET6, bare, &v6.sin6_addr) != 1) {
            (void)snprintf(why, whylen, "--listen: %s is no IPv6 address", bare);
            return NULL;
        }
        v6.sin6_family = AF_INET6;
        v6.sin6_port = htons((uint16_t)port);
        sa = (const struct sockaddr *)&v6;
        p->wildcard = IN6_IS_ADDR_UNSPECIFIED(&v6.sin6_addr);
        p->loopback = IN6_IS_ADDR_LOOPBACK(&v6.sin6_addr);
    } else if (inet_pton(AF_INET, host, &v4.sin_addr) == 1) {
        v4.sin_family = AF_INET;
        v4.sin_port = htons((uint16_t)port);
        sa = (const struct sockaddr *)&v4;
        uint32_t a = ntohl(v4.sin_addr.s_addr);
        p->wildcard = a == 0u;
        p->loopback = (a >> 24) == 127u;
    } else {
        (void)snprintf(why, whylen,
                       "--listen: %s is no IP address (an IPv6 one goes in brackets: [::1]:8480)",
                       host);
        return NULL;
    }
    (void)snprintf(p->host, sizeof p->host, "%s", host);
    /* bound here, so that the port is known before a request can come */
    socklen_t salen = sa->sa_family == AF_INET6 ? sizeof v6 : sizeof v4;
    int one = 1;
    int fd = socket(sa->sa_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(fd, sa, salen) != 0 || listen(fd, 32) != 0 ||
        getsockname(fd, (struct sockaddr *)(sa->sa_family == AF_INET6 ? (void *)&v6 : (void *)&v4),
                    &salen) != 0) {
        (void)snprintf(why, whylen, "cannot listen on %s: %s", addr, strerror(errno));
        if (fd >= 0) {
            (void)close(fd);
        }
        return NULL;
    }
    p->port = ntohs(sa->sa_family == AF_INET6 ? v6.sin6_port : v4.sin_port);
    struct MHD_Daemon *d = MHD_start_daemon(
        flags, 0, NULL, NULL, on_request, p, MHD_OPTION_LISTEN_SOCKET, fd,
        MHD_OPTION_NOTIFY_COMPLETED, on_completed, p, MHD_OPTION_CONNECTION_LIMIT, CONNECTIONS_MAX,
        MHD_OPTION_PER_IP_CONNECTION_LIMIT, PER_IP_MAX, MHD_OPTION_CONNECTION_TIMEOUT, PRE_TOKEN_S,
        MHD_OPTION_THREAD_STACK_SIZE, (size_t)STACK_BYTES, MHD_OPTION_END);
    if (d == NULL) {
        (void)snprintf(why, whylen, "cannot serve on %s: libmicrohttpd refused", addr);
        (void)close(fd);
        return NULL;
    }
    return d;
}

void panel_http_quiesce(panel *p, struct MHD_Daemon *daemon)
{
    p->listen_fd = MHD_quiesce_daemon(daemon); /* closed after MHD_stop_daemon: ours now */
}

void panel_http_stop(panel *p, struct MHD_Daemon *daemon)
{
    pthread_mutex_lock(&p->ev_m);
    pthread_cond_broadcast(&p->ev_cv); /* the event streams end (p->stopping is set) */
    pthread_mutex_unlock(&p->ev_m);
    /* the requests under way are answered first (a save: the client learns
     * it was saved), for at most SHUTDOWN_GRACE_S */
    struct timespec until;
    (void)clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += SHUTDOWN_GRACE_S;
    pthread_mutex_lock(&p->m);
    while (p->in_flight > 0u &&
           pthread_cond_timedwait(&p->done_cv, &p->m, &until) != ETIMEDOUT) {
    }
    pthread_mutex_unlock(&p->m);
    MHD_stop_daemon(daemon);
    if (p->listen_fd >= 0) {
        (void)close(p->listen_fd);
        p->listen_fd = -1;
    }
}
