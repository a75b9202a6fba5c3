/* lsc-panel: the HTTP server (panel.h) on libmicrohttpd, one thread per
 * connection: every request passes panel_security.c's checks, then goes to
 * its route (the table below) or to the page (panel/page/, built in). */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "panel_http.h"

/* Connections: a connection that has not shown the token is closed after
 * PRE_TOKEN_S idle (and after any refusal); one that has, after
 * panel_security.c's TOKEN_S. At most CONNECTIONS_MAX at once, PER_IP_MAX
 * from one address (so one machine on the network cannot take every slot),
 * each thread's stack STACK_BYTES. */
#define PRE_TOKEN_S 10u
#define CONNECTIONS_MAX 256u
#define PER_IP_MAX 100u
#define STACK_BYTES (512u * 1024u)
#define SHUTDOWN_GRACE_S 10 /* at most this long for the requests under way to be answered */

typedef enum MHD_Result (*handler_fn)(const ctx *x);

struct route {
    const char *method;
    const char *path;
    handler_fn fn;
    bool body; /* takes a body (an action as CSV) */
};

static const char NO_BODY[] = "this request takes no body";
static const char TOO_BIG[] = "the body is larger than an action file may be (16 MiB)";

static const route routes[] = {
    {"GET", "/api/config", api_config, false},   {"GET", "/api/events", api_events, false},
    {"GET", "/api/files", api_files, false},     {"GET", "/api/file", api_file, false},
    {"POST", "/api/move", api_move, false},      {"POST", "/api/run", api_run, false},
    {"POST", "/api/stop", api_stop, false},      {"POST", "/api/speed", api_speed, false},
    {"POST", "/api/limp", api_limp, false},      {"POST", "/api/hold", api_hold, false},
    {"POST", "/api/pose", api_pose, false},      {"POST", "/api/play", api_play, true},
    {"POST", "/api/play-stop", api_play_stop, false}, {"POST", "/api/save", api_save, true},
    {"POST", "/api/jog", api_jog, false},        {"POST", "/api/halt", api_halt, false},
    {"POST", "/api/calibrate", api_calibrate, false},
    {"GET", "/api/servos", api_servos, false},
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
        if (get && strcmp(url, "/favicon.ico") == 0 && http_host_ok(p, host)) {
            return http_send(c, MHD_HTTP_NO_CONTENT, NULL, "", 0);
        }
        const char *token = get && strcmp(url, "/") == 0 ? http_arg(&x, "token") : NULL;
        if (token != NULL) {
            if (!http_host_ok(p, host)) {
                return http_refuse_conn(c, MHD_HTTP_MISDIRECTED_REQUEST,
                                        "the Host header does not name this server: open the "
                                        "address lsc-panel printed",
                                        true);
            }
            return http_sign_in(&x, token);
        }
        bool answered;
        if (!http_check_request(&x, method, &answered)) {
            return answered ? MHD_YES : MHD_NO;
        }
        if (http_has_nul_arg(c)) {
            return http_refuse(c, MHD_HTTP_BAD_REQUEST, "an argument holds a NUL byte (%00)");
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
            return path_known ? http_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed")
                              : http_refuse(c, MHD_HTTP_NOT_FOUND, "no such page");
        }
        const char *len = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Content-Length");
        bool takes_body = rt != NULL && rt->body;
        long n = 0;
        if (len != NULL && http_number(len, 1, (long)LSC_FILE_MAX_BYTES, 0, &n) && !takes_body) {
            return http_refuse(c, MHD_HTTP_BAD_REQUEST, NO_BODY);
        }
        if (len != NULL && !http_number(len, 0, (long)LSC_FILE_MAX_BYTES, 0, &n)) {
            return http_refuse(c, MHD_HTTP_CONTENT_TOO_LARGE, TOO_BIG);
        }
        req *r = calloc(1, sizeof *r);
        if (r == NULL) {
            return MHD_NO;
        }
        r->route = rt;
        r->counted = rt == NULL || rt->fn != api_events;
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
        return http_refuse(c, MHD_HTTP_BAD_REQUEST, NO_BODY);
    }
    if (x.r->too_big || x.r->body.failed) {
        return http_refuse(c, x.r->body.failed ? MHD_HTTP_INTERNAL_SERVER_ERROR
                                               : MHD_HTTP_CONTENT_TOO_LARGE,
                           x.r->body.failed ? "out of memory" : TOO_BIG);
    }
    if (x.r->route != NULL) {
        return x.r->route->fn(&x);
    }
    const panel_asset *a = asset(url);
    return http_send(c, MHD_HTTP_OK, a->type, a->data, a->len);
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
    if (colon == NULL || n == 0u || n >= sizeof host ||
        !http_number(colon + 1, 0, 65535, 0, &port)) {
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
