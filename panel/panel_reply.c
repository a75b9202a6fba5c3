/* lsc-panel: the HTTP answers (panel_http.h): a copy of the data with the
 * security headers, a refusal as {"error": ...}, a device error's status. */
#include <stdlib.h>
#include <string.h>

#include "panel_http.h"

struct MHD_Response *http_response(const void *data, size_t len)
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
    http_secure(res, true);
    return res;
}

enum MHD_Result http_send(struct MHD_Connection *c, unsigned status, const char *type,
                          const void *data, size_t len)
{
    struct MHD_Response *res = http_response(data, len);
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
enum MHD_Result http_refuse_conn(struct MHD_Connection *c, unsigned status, const char *message,
                                      bool close)
{
    panel_buf b = {0};
    panel_buf_str(&b, "{\"error\":");
    panel_buf_json(&b, message);
    panel_buf_str(&b, "}\n");
    struct MHD_Response *res = b.failed ? NULL : http_response(b.data, b.len);
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

enum MHD_Result http_refuse(struct MHD_Connection *c, unsigned status, const char *message)
{
    return http_refuse_conn(c, status, message, false);
}

enum MHD_Result http_send_json(struct MHD_Connection *c, unsigned status, panel_buf *b)
{
    if (b->failed) {
        panel_buf_free(b);
        return http_refuse(c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
    }
    panel_buf_str(b, "\n");
    enum MHD_Result ok = http_send(c, status, "application/json", b->data, b->len);
    panel_buf_free(b);
    return ok;
}

enum MHD_Result http_send_ok(struct MHD_Connection *c, unsigned status)
{
    return http_send(c, status, "application/json", "{\"ok\":true}\n", 12);
}

/* The HTTP status of a device error. */
unsigned http_device_status(int r)
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
    case LSC_EINTR: /* lsc-panel is stopping */
        return MHD_HTTP_SERVICE_UNAVAILABLE;
    default:
        return MHD_HTTP_BAD_GATEWAY;
    }
}

const char *http_arg(const ctx *x, const char *key)
{
    return MHD_lookup_connection_value(x->c, MHD_GET_ARGUMENT_KIND, key);
}

/* A decimal number lo..hi in s (digits only); def when s is NULL. */
bool http_number(const char *s, long lo, long hi, long def, long *out)
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
