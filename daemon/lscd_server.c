/* lscd: the server loop. It waits on the signal pipe, the device thread's
 * pipe, the listening socket and the clients (lscd_clients.c), tells clients
 * what the device thread told (replies, notifications, the controller gone
 * and back), and runs the schedule (lscd_queue.c) after each turn. The
 * server's parts share lscd_server.h: writing to clients (lscd_out.c), the
 * lease and the halt (lscd_lease.c), control requests (lscd_control.c), the
 * status (lscd_status.c) (docs/lscd-protocol.md, lscd.8). */
#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>

#include "lscd_server.h"

static void controller_event(server *s, bool present, const char *text)
{
    uint8_t state = present ? 1u : 0u;
    for (client *c = s->clients; c != NULL; c = c->next) {
        lscd_put_text(s, c, LSC_LSCD_EV_CONTROLLER, &state, 1, text);
    }
}

static void on_device(server *s)
{
    lscd_ev *e = lscd_dev_take(s->dv);
    while (e != NULL) {
        lscd_ev *next = e->next;
        client *c;
        switch (e->kind) {
        case LSCD_EV_BROADCAST:
            s->n_notifications++;
            for (c = s->clients; c != NULL; c = c->next) {
                if (c->subscribed) {
                    lscd_put(s, c, e->data, e->len);
                }
            }
            break;
        case LSCD_EV_TO:
            c = lscd_find_client(s, e->client);
            if (c != NULL) {
                lscd_put(s, c, e->data, e->len);
            }
            break;
        case LSCD_EV_DONE:
            s->busy = false;
            if (e->cmd == LSC_LSCD_CMD) { /* a halt */
                c = lscd_find_client(s, e->client);
                if (c != NULL) {
                    c->queued--;
                }
                lscd_halted(s, e->rc, (const char *)e->data);
                break;
            }
            if (e->rc == 0) {
                s->n_done++;
            } else if (e->rc == LSC_ETIMEOUT) {
                s->n_timeouts++;
            } else if (e->rc == LSC_EBUSY) { /* a halt ended it (lscd_dev_interrupt) */
                s->n_refused++;
            } else {
                s->n_failed++;
            }
            c = lscd_find_client(s, e->client);
            if (c != NULL) {
                c->queued--;
                lscd_verdict_why(s, c, e->cmd, e->rc, (const char *)e->data);
            }
            break;
        case LSCD_EV_GONE:
        case LSCD_EV_FATAL:
            s->present = false;
            s->n_losses++;
            lscd_log("controller lost: %s", (const char *)e->data);
            controller_event(s, false, (const char *)e->data);
            if (e->kind == LSCD_EV_FATAL) {
                lscd_log("exiting (--exit-on-loss)");
                s->stop = true;
                s->exit_code = LSCD_EXIT_FAIL;
            } else {
                lscd_log("opening %s again every %lu ms until it is back", s->cfg->port,
                         (unsigned long)s->cfg->retry_ms);
            }
            break;
        default: /* BACK */
            s->present = true;
            lscd_log("controller back: %s", (const char *)e->data);
            controller_event(s, true, (const char *)e->data);
            break;
        }
        free(e);
        e = next;
    }
}

/* ---- The loop ------------------------------------------------------------------------------ */

int lscd_serve(const lscd_config *cfg, lscd_dev *dv, int listen_fd, int sigfd)
{
    server srv;
    server *s = &srv;
    struct pollfd *pfd = NULL;
    size_t pfd_cap = 0;
    memset(s, 0, sizeof *s);
    s->cfg = cfg;
    s->dv = dv;
    s->listen_fd = listen_fd;
    s->sigfd = sigfd;
    s->present = true;
    s->started = lscd_now_ms();
    while (!s->stop) {
        size_t need = 3u + s->nclients;
        if (need > pfd_cap) {
            struct pollfd *p = realloc(pfd, need * sizeof *p);
            if (p == NULL) {
                lscd_log("out of memory");
                s->exit_code = LSCD_EXIT_FAIL;
                break;
            }
            pfd = p;
            pfd_cap = need;
        }
        pfd[0] = (struct pollfd){sigfd, POLLIN, 0};
        pfd[1] = (struct pollfd){dv->notify[0], POLLIN, 0};
        pfd[2] = (struct pollfd){s->accept_paused ? -1 : listen_fd, POLLIN, 0};
        size_t n = 3;
        for (client *c = s->clients; c != NULL; c = c->next) {
            short ev = 0;
            if (!c->eof && c->in_len == 0u && c->out_len == 0u) {
                ev |= POLLIN;
            }
            if (!c->shut) {
                ev |= POLLRDHUP; /* a half-close ends its lease even while lscd does not read */
            }
            if (c->out_len > 0u) {
                ev |= POLLOUT;
            }
            pfd[n++] = (struct pollfd){c->fd, ev, 0};
        }
        int r = poll(pfd, (nfds_t)n, lscd_next_timer(s));
        s->more_input = false;
        for (client *c = s->clients; c != NULL; c = c->next) {
            c->taken = 0;
        }
        if (r < 0 && errno != EINTR) {
            lscd_log("poll: %s", strerror(errno));
            s->exit_code = LSCD_EXIT_FAIL;
            break;
        }
        if (r > 0 && pfd[0].revents != 0) {
            s->stop = true;
            s->exit_code = LSCD_EXIT_OK;
        }
        if (r > 0 && pfd[1].revents != 0) {
            on_device(s);
        }
        /* clients, in the order of the poll set (it was built from the list) */
        n = 3;
        for (client *c = s->clients; c != NULL && r > 0; c = c->next) {
            short rev = pfd[n++].revents;
            if ((rev & POLLRDHUP) != 0 && !c->shut) {
                lscd_on_shut(s, c);
            }
            if ((rev & POLLOUT) != 0) {
                lscd_flush_out(s, c);
            }
            if ((rev & POLLIN) != 0) {
                lscd_read_client(s, c);
            }
            if ((rev & (POLLHUP | POLLERR | POLLNVAL)) != 0 && (rev & POLLIN) == 0) {
                c->dead = true; /* closed both ways: nobody reads what it asked for */
            }
        }
        if (r > 0 && pfd[2].revents != 0) {
            lscd_accept_clients(s);
        }
        lscd_schedule(s);
        /* what waits in clients' buffers, now that their queues may have room */
        for (client *c = s->clients, *next; c != NULL; c = next) {
            next = c->next;
            lscd_take_input(s, c);
            if (c->eof && c->queued == 0u && c->out_len == 0u && c->in_len == 0u) {
                c->dead = true;
            }
            if (c->dead) {
                lscd_remove_client(s, c);
            }
        }
        lscd_schedule(s);
    }
    for (client *c = s->clients, *next; c != NULL; c = next) {
        next = c->next;
        lscd_flush_out(s, c);
        lscd_remove_client(s, c);
    }
    for (item *it = s->qhead, *next; it != NULL; it = next) {
        next = it->next; /* (only frames of clients that left remain) */
        free(it);
    }
    free(pfd);
    return s->exit_code;
}
