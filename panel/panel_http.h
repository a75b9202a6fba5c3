/* lsc-panel: what the HTTP side's files share (panel.h). A request passes
 * panel_security.c's checks before anything else, then goes to its route
 * (panel_http.c's table): the controller's API (panel_api.c), the files in
 * --dir (panel_files.c) or the event stream (panel_sse.c); every answer is
 * made by panel_reply.c. */
#ifndef LSC_PANEL_HTTP_H
#define LSC_PANEL_HTTP_H

#include <microhttpd.h>
#include <stdbool.h>
#include <stddef.h>

#include "panel.h"

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

/* panel_reply.c: the answers, each with the security headers */

/* A response holding a copy of data[0..len). */
struct MHD_Response *http_response(const void *data, size_t len);
enum MHD_Result http_send(struct MHD_Connection *c, unsigned status, const char *type,
                          const void *data, size_t len);
/* {"error": message} with status; close: the connection is closed after it
 * (a request without the token keeps no connection). */
enum MHD_Result http_refuse_conn(struct MHD_Connection *c, unsigned status, const char *message,
                                 bool close);
enum MHD_Result http_refuse(struct MHD_Connection *c, unsigned status, const char *message);
/* b and a newline as application/json (b is freed). */
enum MHD_Result http_send_json(struct MHD_Connection *c, unsigned status, panel_buf *b);
/* {"ok":true} */
enum MHD_Result http_send_ok(struct MHD_Connection *c, unsigned status);
/* The HTTP status of a device error. */
unsigned http_device_status(int r);
/* The request's argument key (NULL: none). */
const char *http_arg(const ctx *x, const char *key);
/* A decimal number lo..hi in s (digits only); def when s is NULL. */
bool http_number(const char *s, long lo, long hi, long def, long *out);

/* panel_security.c: the checks */

/* Adds the security headers to res (with csp: the Content-Security-Policy,
 * which an event stream does not need). */
void http_secure(struct MHD_Response *res, bool csp);
/* Whether a and b are equal, in a time that does not depend on where they differ. */
bool http_same_secret(const char *a, const char *b);
/* Whether a Host header names this server. */
bool http_host_ok(const panel *p, const char *host);
/* Refuses a request that may not go on (and says why: *answered); true
 * when it may: the Host header, the token's cookie, a POST's Origin. */
bool http_check_request(const ctx *x, const char *method, bool *answered);
/* Whether an argument holds a NUL byte (%00): C would see it cut there. */
bool http_has_nul_arg(struct MHD_Connection *c);
/* GET /?token=T: the cookie, and the page without the token in its address. */
enum MHD_Result http_sign_in(const ctx *x, const char *token);

/* The routes: each answers its request. */

/* panel_api.c: the controller, through the device thread */
enum MHD_Result api_config(const ctx *x);
enum MHD_Result api_move(const ctx *x);
enum MHD_Result api_run(const ctx *x);
enum MHD_Result api_speed(const ctx *x);
enum MHD_Result api_stop(const ctx *x);
enum MHD_Result api_limp(const ctx *x);
enum MHD_Result api_hold(const ctx *x);
enum MHD_Result api_pose(const ctx *x);
enum MHD_Result api_halt(const ctx *x);
enum MHD_Result api_play(const ctx *x);
enum MHD_Result api_play_stop(const ctx *x);
enum MHD_Result api_jog(const ctx *x);
enum MHD_Result api_calibrate(const ctx *x);
enum MHD_Result api_servos(const ctx *x);
/* The request's body, an action as CSV, into a; refuses it (answered:
 * *ok) when it is not one. */
bool api_body_action(const ctx *x, lsc_action *a, enum MHD_Result *ok);

/* panel_files.c: the action files in --dir */
enum MHD_Result api_files(const ctx *x);
enum MHD_Result api_file(const ctx *x);
enum MHD_Result api_save(const ctx *x);

/* panel_sse.c: the events, as Server-Sent Events */
enum MHD_Result api_events(const ctx *x);

#endif /* LSC_PANEL_HTTP_H */
