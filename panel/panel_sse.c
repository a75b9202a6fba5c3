/* lsc-panel: the events as Server-Sent Events (panel_http.h): each page
 * gets the latest battery, positions, pose and link first, then every event
 * from panel_event_add as it comes, a keepalive when nothing does. */
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "panel_http.h"

#define KEEPALIVE_S 15

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

enum MHD_Result api_events(const ctx *x)
{
    sse *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return http_refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, "out of memory");
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
    http_secure(res, false);
    enum MHD_Result ok = MHD_queue_response(x->c, MHD_HTTP_OK, res);
    MHD_destroy_response(res);
    return ok;
}
