/* lscd: the status a client asks for (OP_STATUS): one STATUS event per
 * item, then STATUS_END (lscd.8 lists the items). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "lsc/text.h"
#include "lscd_server.h"

static void status_item(server *s, client *c, const char *key, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void status_item(server *s, client *c, const char *key, const char *fmt, ...)
{
    char text[LSCD_ARGS_MAX + 1u];
    int n = snprintf(text, sizeof text, "%s=", key);
    if (n > 0 && (size_t)n < sizeof text) {
        va_list ap;
        va_start(ap, fmt);
        (void)vsnprintf(text + n, sizeof text - (size_t)n, fmt, ap);
        va_end(ap);
    }
    lscd_put_text(s, c, LSC_LSCD_EV_STATUS, NULL, 0, text);
}

void lscd_send_status(server *s, client *asker)
{
    char name[LSC_DEVICE_NAME_MAX], error[512];
    lsc_device_kind kind;
    uint32_t stray, overrun;
    lsc_device_counters link;
    lscd_dev *dv = s->dv;
    (void)pthread_mutex_lock(&dv->lock);
    memcpy(name, dv->name, sizeof name);
    memcpy(error, dv->error, sizeof error);
    kind = dv->kind;
    stray = dv->stray;
    overrun = dv->overrun;
    link = dv->link;
    (void)pthread_mutex_unlock(&dv->lock);
    uint64_t now = lscd_now_ms();
    status_item(s, asker, "version", "%s", LSCD_VERSION);
    status_item(s, asker, "protocol", "%u", (unsigned)LSC_LSCD_PROTOCOL);
    status_item(s, asker, "port", "%s", s->cfg->port);
    status_item(s, asker, "device", "%s", name);
    status_item(s, asker, "kind", "%s", lsc_device_kind_name(kind));
    status_item(s, asker, "controller", "%s", s->present ? "present" : "gone");
    if (!s->present) {
        status_item(s, asker, "error", "%s", error);
    }
    status_item(s, asker, "socket", "%s%s", s->cfg->socket_path,
                s->cfg->activated ? " (systemd)" : "");
    status_item(s, asker, "uptime_ms", "%llu", (unsigned long long)(now - s->started));
    status_item(s, asker, "clients", "%u", s->nclients);
    status_item(s, asker, "subscribers", "%u", s->nsubscribers);
    if (s->holder != NULL) {
        status_item(s, asker, "lease", "client %llu (pid %ld), %llu ms left",
                    (unsigned long long)s->holder->id, s->holder->pid,
                    (unsigned long long)(s->lease_until > now ? s->lease_until - now : 0u));
    } else {
        status_item(s, asker, "lease", "none");
    }
    status_item(s, asker, "queue", "%u", s->qlen + (s->busy ? 1u : 0u));
    status_item(s, asker, "frames", "%lu", (unsigned long)s->n_frames);
    status_item(s, asker, "done", "%lu", (unsigned long)s->n_done);
    status_item(s, asker, "timeouts", "%lu", (unsigned long)s->n_timeouts);
    status_item(s, asker, "failed", "%lu", (unsigned long)s->n_failed);
    status_item(s, asker, "expired", "%lu", (unsigned long)s->n_expired);
    status_item(s, asker, "refused", "%lu", (unsigned long)s->n_refused);
    status_item(s, asker, "notifications", "%lu", (unsigned long)s->n_notifications);
    status_item(s, asker, "dropped", "%lu", (unsigned long)s->n_dropped);
    status_item(s, asker, "stray", "%lu", (unsigned long)stray);
    status_item(s, asker, "overrun", "%lu", (unsigned long)overrun);
    status_item(s, asker, "losses", "%lu", (unsigned long)s->n_losses);
    status_item(s, asker, "link_sent", "%llu", (unsigned long long)link.frames_sent);
    status_item(s, asker, "link_received", "%llu", (unsigned long long)link.frames_received);
    status_item(s, asker, "link_bad", "%llu", (unsigned long long)link.bad_frames);
    status_item(s, asker, "link_discarded", "%llu", (unsigned long long)link.bytes_discarded);
    status_item(s, asker, "link_timeouts", "%llu", (unsigned long long)link.timeouts);
    status_item(s, asker, "connections", "%lu", (unsigned long)s->n_clients_total);
    status_item(s, asker, "max_clients", "%lu", (unsigned long)s->cfg->max_clients);
    status_item(s, asker, "full", "%lu", (unsigned long)s->n_full);
    uint64_t malformed = s->gone_malformed, discarded = s->gone_discarded;
    for (const client *c = s->clients; c != NULL; c = c->next) {
        malformed += c->wire.parser.errors;
        discarded += c->wire.parser.discarded;
    }
    status_item(s, asker, "malformed", "%llu", (unsigned long long)malformed);
    status_item(s, asker, "discarded", "%llu", (unsigned long long)discarded);
    unsigned listed = 0;
    for (client *c = s->clients; c != NULL; c = c->next) {
        if (listed++ == STATUS_CLIENTS_MAX) {
            status_item(s, asker, "client", "... and %u more", s->nclients - STATUS_CLIENTS_MAX);
            break;
        }
        status_item(s, asker, "client",
                    "%llu pid=%ld uid=%ld%s%s%s%s%s frames=%lu queue=%u dropped=%lu%s",
                    (unsigned long long)c->id, c->pid, c->uid, c->subscribed ? " subscribed" : "",
                    c->ack ? " ack" : "", c->refuse ? " refuse" : "", c->shut ? " shut" : "",
                    c->out_len > 0u ? " unread" : "", (unsigned long)c->frames,
                    c->queued, (unsigned long)c->dropped, c == asker ? " (this one)" : "");
    }
    lscd_put_ctl(s, asker, LSC_LSCD_EV_STATUS_END, NULL, 0);
}
