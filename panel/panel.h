/* lsc-panel: a control panel in the browser for one controller (lsc-panel.1).
 *
 * Three parts:
 *   panel_dev.c   the device thread: the one thread that uses the lsc_device
 *                 (lsc/device.h allows one thread at a time per device); it
 *                 runs the commands the HTTP threads hand it (panel_cmd.c),
 *                 sends the latest slider move, reads positions and the
 *                 battery, turns the controller's notifications into events
 *                 (panel_events.c);
 *   panel_http.c  the HTTP server on libmicrohttpd: requests to their routes,
 *                 the page; beside it (panel_http.h) panel_security.c (the
 *                 checks, the security headers), panel_reply.c (answers),
 *                 panel_api.c (the controller's routes), panel_files.c (the
 *                 files in --dir), panel_sse.c (Server-Sent Events);
 *   lsc-panel.c   the command line, the token, the signals.
 * Everything a controller needs is the library's (lsc/device.h, lsc/arm.h,
 * lsc/files.h): here are only the panel's own rules. */
#ifndef LSC_PANEL_H
#define LSC_PANEL_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/link.h"
#include "lsc/lscd.h"
#include "lsc/lx.h"
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/player.h"

#define PANEL_TOKEN_LEN 32u     /* hex digits of the token (128 bits) */
#define PANEL_EVENTS 128u       /* events kept for the pages that read them */
#define PANEL_EVENT_MAX 2048u   /* bytes of one event's data (JSON) */
#define PANEL_MSG_MAX 512u      /* a refusal's or failure's message */
#define PANEL_NAME_MAX 64u      /* bytes of a file name in --dir, with its NUL */
#define PANEL_PATH_MAX 4200u    /* --dir, a slash and a name */

/* A growing byte buffer (responses, JSON): panel_buf.c. */
typedef struct panel_buf {
    char *data;
    size_t len, cap;
    bool failed; /* out of memory: the contents are cut */
} panel_buf;

void panel_buf_add(panel_buf *b, const char *s, size_t n);
void panel_buf_str(panel_buf *b, const char *s);
void panel_buf_printf(panel_buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* s as a JSON string, quotes included. */
void panel_buf_json(panel_buf *b, const char *s);
void panel_buf_free(panel_buf *b);

/* What the HTTP side asks of the device thread. */
typedef enum panel_cmd_kind {
    PANEL_CMD_NONE = 0,
    PANEL_CMD_RUN,   /* group, value: times */
    PANEL_CMD_STOP,
    PANEL_CMD_SPEED, /* group, value: percent */
    PANEL_CMD_LIMP,
    PANEL_CMD_HOLD,
    PANEL_CMD_POSE,  /* out: "ID,ID,...\nPOS,POS,..." */
    PANEL_CMD_PLAY,  /* action, value: speed percent */
    PANEL_CMD_JOG,   /* axis, step, value: the move's time (ms); out: the target */
    PANEL_CMD_HALT,  /* everything stops where it is */
    PANEL_CMD_CALIBRATE, /* value: a step (lsc_calib_step) or PANEL_CALIBRATE_*; out: the state */
    PANEL_CMD_SERVOS /* a bus's servos: ids[0..nids) (NULL: every id); out: their list */
} panel_cmd_kind;

/* PANEL_CMD_CALIBRATE's values beyond the steps */
#define PANEL_CALIBRATE_SAVE 100u
#define PANEL_CALIBRATE_CANCEL 101u

/* What a jog moves (PANEL_CMD_JOG): the grasp point along x, y or z (mm),
 * or the hand's pitch (degrees). */
typedef enum panel_axis { PANEL_AXIS_X = 0, PANEL_AXIS_Y, PANEL_AXIS_Z, PANEL_AXIS_PITCH } panel_axis;

#define PANEL_JOG_MM_MAX 1000.0   /* the largest jog step, mm */
#define PANEL_JOG_DEG_MAX 180.0   /* ... degrees */

typedef struct panel_cmd {
    panel_cmd_kind kind;
    uint8_t group;
    uint16_t value;
    lsc_action *action; /* PLAY: the device thread's until the play ends */
    panel_axis axis;    /* JOG */
    double step;        /* JOG: mm or degrees, signed */
    const uint8_t *ids; /* SERVOS: the ids to ask (NULL: every id 0..253) */
    size_t nids;
    int result;         /* 0 or an LSC_E... code */
    lsc_device_cause cause;
    char message[PANEL_MSG_MAX];
    panel_buf out;
} panel_cmd;

/* A slider's move waiting to be sent (panel_dev_move): the HTTP thread that
 * handed it waits until the device thread has sent it, or could not. */
typedef struct panel_move_wait {
    struct panel_move_wait *next;
    bool done;
    int result; /* 0 or an LSC_E... code */
    char message[PANEL_MSG_MAX];
} panel_move_wait;

typedef struct panel_event {
    uint64_t seq;
    char type[16];
    char data[PANEL_EVENT_MAX];
} panel_event;

typedef struct panel {
    /* set before the threads start, read-only after */
    lsc_device *dev;                     /* the device thread's only */
    char dev_name[LSC_DEVICE_NAME_MAX];  /* what the page shows of it, taken at the start */
    lsc_device_kind dev_kind;
    uint8_t groups[64];
    size_t ngroups;
    lsc_device_config *cfg;              /* how it was opened (and is opened again) */
    lsc_arm *arm;                        /* NULL without --arm */
    const char *arm_path;                /* its file (NULL without one) */
    const char *arm_given;               /* ... as --arm or $LSC_ARM named it ("xarm") */
    bool arm_calibrated;                 /* ... the controller's calibrated profile */
    char calib_out[PANEL_PATH_MAX];      /* where calibration writes ("": nowhere) */
    bool geometry;                       /* the profile states its geometry (jogs, where) */
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];  /* the servos the page shows */
    size_t nids;
    const char *dir;                     /* --dir */
    char dir_shown[PANEL_PATH_MAX];      /* ... as the page shows it (~/... under $HOME) */
    char host[80];                       /* the listening address as a Host names it */
    bool wildcard;                       /* listening on every address */
    bool loopback;                       /* listening on 127.0.0.1 or ::1 */
    uint16_t port;
    char token[PANEL_TOKEN_LEN + 1];

    /* the device thread's hand-over */
    pthread_mutex_t m;
    pthread_cond_t done_cv;   /* a command is done, a move sent, a play ended */
    pthread_mutex_t cmd_lock; /* one command at a time */
    panel_cmd *cmd;           /* the command waiting or running, or NULL */
    bool cmd_done;
    lsc_servo move[LSC_PLAYER_SERVOS_MAX]; /* the latest move, not yet sent */
    size_t move_n;
    uint16_t move_time;
    panel_move_wait *move_waiters; /* the requests that move is theirs */
    bool play_busy;           /* a play was accepted and has not ended: no other */
    bool playing;             /* ... and it runs */
    bool play_stop;           /* Stop play (or Halt) asked: it ends, or never begins */
    bool in_call;             /* the device thread is in a command's library call
                                 (a play, a pose, ...): lsc_device_interrupt ends it */
    bool interrupted;         /* ... and it was interrupted */
    bool link_up;             /* the controller answers; else the device thread
                                 opens it again (reconnecting) */
    char link_why[PANEL_MSG_MAX]; /* why it is down */
    bool stopping;            /* set under m and ev_m */
    bool exited;              /* the device thread has ended */
    int wake[2];              /* a byte in wake[1] wakes the device thread from its
                                 poll() (beside the device's descriptor); a library
                                 call it is in is ended by lsc_device_interrupt */
    char *calib_text;         /* the calibration in progress (device thread only) */
    size_t calib_len;
    char calib_from[PANEL_PATH_MAX];
    pthread_t thread;

    /* events, for the pages */
    pthread_mutex_t ev_m;
    pthread_cond_t ev_cv;
    panel_event events[PANEL_EVENTS];
    uint64_t next_seq;         /* the next event's number (the first is 1) */
    unsigned clients;          /* pages listening */
    char last_battery[PANEL_EVENT_MAX]; /* the latest of these, for a page that connects */
    char last_positions[PANEL_EVENT_MAX];
    char last_where[PANEL_EVENT_MAX]; /* the grasp point's pose (with geometry) */
    char last_link[PANEL_EVENT_MAX];  /* the link to the controller: up, or reconnecting */

    /* requests under way (not the event streams), for a shutdown that answers them */
    unsigned in_flight;
    int listen_fd;             /* the listening socket once quiesced (-1: none), closed
                                  after the server stops */
} panel;

/* panel_dev.c */
int panel_dev_start(panel *p);
/* Tells every thread to end (the event streams, the device thread). */
void panel_set_stopping(panel *p);
void panel_dev_stop(panel *p);
/* Runs cmd in the device thread and waits until it is done (a play: until it
 * has started or was refused). */
void panel_dev_call(panel *p, panel_cmd *cmd);
/* Hands the device thread a move, merged into one not yet sent (each
 * servo's latest position, this move's time), and waits until it was sent
 * (w: its result). Refused at once (LSC_EBUSY) while a play is accepted or
 * runs, (LSC_ENODEV) while the controller is away. */
void panel_dev_move(panel *p, const lsc_servo *s, size_t n, uint16_t time_ms,
                    panel_move_wait *w);
/* Takes the one play slot (true), or false when a play was accepted or
 * runs: decided under one lock, so of two plays at once one only gets it. */
bool panel_dev_play_reserve(panel *p);
/* Gives the slot back (a play refused before it was handed over). */
void panel_dev_play_release(panel *p);
/* Stops the play (accepted or running) and drops the move not yet sent;
 * returns once the play has ended, so that nothing of it is sent after
 * (false: there was none). */
bool panel_dev_play_stop(panel *p);
bool panel_dev_play_busy(panel *p);
/* Halt's first step, before its command (PANEL_CMD_HALT): the play ends (or
 * never begins), the move not yet sent is dropped. */
void panel_dev_halt_asked(panel *p);
/* Whether the controller answers (else: reconnecting; why in why[cap]). */
bool panel_dev_link(panel *p, char *why, size_t cap);
/* panel_events.c */
/* Adds an event (type, JSON data) for every page. */
void panel_event_add(panel *p, const char *type, const char *data);
/* How many pages listen to the events. */
unsigned panel_event_clients(panel *p);
/* The positions as an event's JSON: {"ids":[..],"pos":[..],"deg":[..]}. */
void panel_positions_json(const panel *p, const lsc_servo *s, size_t n, panel_buf *b);

/* panel_calibrate.c (the device thread): runs a PANEL_CMD_CALIBRATE; 0, or
 * an LSC_E... code with c->message set. */
int panel_calibrate(panel *p, panel_cmd *c);
void panel_calibrate_free(panel *p);

/* panel_http.c */
struct MHD_Daemon;
/* Serves p on its address; NULL and why on failure. */
struct MHD_Daemon *panel_http_start(panel *p, const char *addr, char *why, size_t whylen);
/* Accepts no new connection (at SIGTERM: then panel_http_stop). */
void panel_http_quiesce(panel *p, struct MHD_Daemon *daemon);
/* Stops the server once the requests under way are answered (at most a few
 * seconds); p->stopping is set first. */
void panel_http_stop(panel *p, struct MHD_Daemon *daemon);
/* panel_files.c: whether name is a file name the panel reads and writes in --dir. */
bool panel_file_name_ok(const char *name);

/* page.c (generated from panel/page/ at build time) */
typedef struct panel_asset {
    const char *path; /* "/", "/panel.js", ... */
    const char *type; /* its Content-Type */
    const unsigned char *data;
    size_t len;
} panel_asset;
extern const panel_asset panel_assets[];
extern const size_t panel_assets_count;

#endif /* LSC_PANEL_H */
