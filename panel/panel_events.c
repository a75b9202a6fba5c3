/* lsc-panel: the events for the pages (panel.h): a ring of the latest
 * PANEL_EVENTS, and the latest of each state (battery, positions, pose,
 * link) for a page that connects; panel_sse.c sends them. */
#include <stdio.h>
#include <string.h>

#include "panel.h"

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

unsigned panel_event_clients(panel *p)
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
