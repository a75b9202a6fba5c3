/* lscd: what the daemon's parts share: its settings, the device thread
 * (lscd_dev.c), the server loop (lscd_server.c and its parts: lscd_server.h),
 * the log and the clock (lscd_log.c). */
#ifndef LSCD_H
#define LSCD_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"
#include "lsc/link.h"
#include "lsc/lscd.h"
#include "lscd_wire.h"

#define LSCD_PROG "lscd"

/* Exit codes (lscd.8). */
enum {
    LSCD_EXIT_OK = 0,    /* stopped by SIGTERM, SIGINT or SIGHUP */
    LSCD_EXIT_FAIL = 1,  /* the controller could not be opened, or was lost with
                            --exit-on-loss, or the socket failed */
    LSCD_EXIT_USAGE = 2, /* invalid command line */
    LSCD_EXIT_BUSY = 4   /* the port is busy: another program holds it */
};

#define LSCD_TIMEOUT_DEFAULT 1000u   /* ms: a client's frames, unless it says */
#define LSCD_LEASE_MAX_DEFAULT 60000u /* ms: the longest lease */
#define LSCD_QUEUE_DEFAULT 65536u    /* bytes waiting for one client */
#define LSCD_QUEUE_MIN 4096u
#define LSCD_RETRY_DEFAULT 1000u     /* ms between attempts to reopen a lost controller */
#define LSCD_CLIENT_ITEMS 32u        /* frames of one client waiting for the controller */
#define LSCD_CLIENTS_DEFAULT 1000u  /* clients at once (--max-clients) */
#define LSCD_LEASE_BLOCKED_MS 5000u /* a lease ends when its holder has left lscd's
                                       output unread this long (docs/lscd-protocol.md) */

/* The command line. */
typedef struct lscd_config {
    const char *port;
    char socket_path[LSC_LSCD_PATH_MAX];
    uint32_t baud;
    uint32_t timeout_ms;
    uint32_t lease_max_ms;
    uint32_t client_queue;
    uint32_t retry_ms;
    uint32_t max_clients;
    unsigned mode; /* the socket's permissions when lscd makes it */
    bool exit_on_loss;
    bool verbose;
    bool activated; /* the socket came from systemd (LISTEN_FDS) */
} lscd_config;

/* What the device thread tells the server, in the order it happened. */
typedef enum lscd_ev_kind {
    LSCD_EV_BROADCAST = 0, /* a notification frame for every subscriber */
    LSCD_EV_TO,            /* a frame for one client (a reply, an answer lscd routes) */
    LSCD_EV_DONE,          /* the job is over: rc */
    LSCD_EV_GONE,          /* the controller went away: data is the message */
    LSCD_EV_BACK,          /* it is open again */
    LSCD_EV_FATAL          /* lost with --exit-on-loss: data is the message */
} lscd_ev_kind;

typedef struct lscd_ev {
    struct lscd_ev *next;
    lscd_ev_kind kind;
    uint64_t client;
    uint8_t cmd;
    int rc;
    size_t len;
    uint8_t data[]; /* len bytes: a frame, or text and a NUL */
} lscd_ev;

/* The device thread. Fields under `lock` are shared; the rest are its own
 * (d is the same handle from lscd_dev_start to lscd_dev_stop: a lost
 * controller is opened again into it, so the server may interrupt it). */
typedef struct lscd_dev {
    pthread_t thread;
    pthread_mutex_t lock;
    int wake[2];   /* server -> device thread, idle in poll(): a job, or quit */
    int notify[2]; /* device thread -> server */
    const lscd_config *cfg;
    /* shared, under lock */
    bool job_pending;
    lscd_job job;
    uint64_t job_client;
    uint32_t job_timeout_ms;
    bool quit;
    bool running;     /* a job that lscd_dev_interrupt may end is under way */
    bool interrupted; /* ... and lscd_dev_interrupt ended it */
    lscd_ev *head, *tail;
    char name[LSC_DEVICE_NAME_MAX];
    lsc_device_kind kind;
    bool present;
    char error[512];
    uint32_t stray;   /* frames from the controller nobody asked for */
    uint32_t overrun; /* received frames lost: more came during one call than kept */
    lsc_device_counters link; /* the device's, after the last exchange */
    /* the device thread's own */
    lsc_device *d;
    bool gone;            /* the controller was lost: d is opened again (reopen) */
    bool lscd_asked;      /* the port named is lscd's (else lscd on lscd is refused) */
    uint64_t raw_client;  /* who last sent a command lscd does not know */
    uint8_t *frames;      /* frames received during one call: [len][bytes]... */
    size_t frames_len, frames_cap;
    uint64_t next_retry;  /* when to try to open a lost controller again */
} lscd_dev;

/* Starts the thread on the open device d (it owns it from now on). Returns 0
 * or -1 (errno). */
int lscd_dev_start(lscd_dev *dv, const lscd_config *cfg, lsc_device *d);
/* Hands it a job (only when none is pending). */
void lscd_dev_submit(lscd_dev *dv, uint64_t client, const lscd_job *job, uint32_t timeout_ms);
/* Takes everything it told so far, oldest first (free each with free()). */
lscd_ev *lscd_dev_take(lscd_dev *dv);
/* Ends the job under way at once (lsc_device_interrupt), unless it is a
 * halt: it ends as a frame a halt drops (DONE with LSC_EBUSY). Nothing when
 * no job runs. Any thread. */
void lscd_dev_interrupt(lscd_dev *dv);
/* Stops the thread (a job under way is interrupted) and closes the device. */
void lscd_dev_stop(lscd_dev *dv);

/* Opens the controller as lscd does (baud and timeout from cfg); returns
 * lsc_device_open's result and *d. A port that another lscd holds (the
 * device layer would go through it) is LSC_EBUSY, its message
 * lscd_open_error's. */
int lscd_open_device(const lscd_config *cfg, lsc_device **d);
/* Why the open of d failed: lsc_device_error(d), or for a port another lscd
 * holds, saying so. */
const char *lscd_open_error(const lsc_device *d);

/* Serves clients on the listening socket until a signal (its byte arrives on
 * sigfd) or a fatal loss. Returns the exit code. */
int lscd_serve(const lscd_config *cfg, lscd_dev *dv, int listen_fd, int sigfd);

/* One line on stderr: "lscd: ..." (lscd_log.c, as lscd_now_ms) */
void lscd_log(const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* CLOCK_MONOTONIC in ms. */
uint64_t lscd_now_ms(void);

#endif
