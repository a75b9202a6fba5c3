/* lsc-panel: the HTTP side's security (panel_http.h). Every request passes
 * http_check_request before anything else: the Host header (DNS
 * rebinding), the token's cookie, and on state changes (POST) the Origin
 * header; every answer carries the security headers. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>

#include "panel_http.h"

/* The cookie's name holds the port: cookies are not kept apart by port, so
 * two panels on one host would replace each other's. */
#define COOKIE "lsc_panel_"
/* A connection that has shown the token is closed after TOKEN_S idle (one
 * that has not: panel_http.c's PRE_TOKEN_S). */
#define TOKEN_S 120u

static const char security_headers[][2][64] = {
    {"X-Content-Type-Options", "nosniff"},
    {"Referrer-Policy", "no-referrer"},
    {"X-Frame-Options", "DENY"},
    {"Cache-Control", "no-store"},
};
static const char csp[] = "default-src 'self'; img-src 'self' data:; style-src 'self'; "
                          "script-src 'self'; connect-src 'self'; frame-ancestors 'none'; "
                          "base-uri 'none'; form-action 'self'";

void http_secure(struct MHD_Response *res, bool with_csp)
{
    for (size_t i = 0; i < sizeof security_headers / sizeof security_headers[0]; i++) {
        (void)MHD_add_response_header(res, security_headers[i][0], security_headers[i][1]);
    }
    if (with_csp) {
        (void)MHD_add_response_header(res, "Content-Security-Policy", csp);
    }
}

/* Whether a and b are equal, in a time that does not depend on where they differ. */
bool http_same_secret(const char *a, const char *b)
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
bool http_host_ok(const panel *p, const char *host)
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
    if (!http_number(colon + 1, 1, 65535, 0, &port) || (uint16_t)port != p->port) {
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
bool http_check_request(const ctx *x, const char *method, bool *answered)
{
    const char *host = MHD_lookup_connection_value(x->c, MHD_HEADER_KIND, "Host");
    *answered = true;
    if (!http_host_ok(x->p, host)) {
        (void)http_refuse_conn(x->c, MHD_HTTP_MISDIRECTED_REQUEST,
                               "the Host header does not name this server: open the address "
                               "lsc-panel printed",
                               true);
        return false;
    }
    char name[32];
    (void)snprintf(name, sizeof name, COOKIE "%u", (unsigned)x->p->port);
    const char *cookie = MHD_lookup_connection_value(x->c, MHD_COOKIE_KIND, name);
    if (cookie == NULL || !http_same_secret(cookie, x->p->token)) {
        (void)http_refuse_conn(x->c, MHD_HTTP_FORBIDDEN,
                               "no valid token: open the address with ?token= that "
                               "lsc-panel printed",
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
            (void)http_refuse(x->c, MHD_HTTP_FORBIDDEN,
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
bool http_has_nul_arg(struct MHD_Connection *c)
{
    bool nul = false;
    (void)MHD_get_connection_values_n(c, MHD_GET_ARGUMENT_KIND, nul_arg, &nul);
    return nul;
}

/* GET /?token=T: the cookie, and the page without the token in its address. */
enum MHD_Result http_sign_in(const ctx *x, const char *token)
{
    if (!http_same_secret(token, x->p->token)) {
        return http_refuse_conn(x->c, MHD_HTTP_FORBIDDEN,
                                "wrong token: open the address lsc-panel printed", true);
    }
    struct MHD_Response *res = http_response("", 0);
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
