/* lsc-panel: what the device thread's files share (panel.h): its state,
 * and the helpers panel_dev.c (the thread, the link, the reads, the HTTP
 * side's hand-over) and panel_cmd.c (the commands it runs) both use. The
 * device thread's only, but for dev_interrupt_call. */
#ifndef LSC_PANEL_DEV_H
#define LSC_PANEL_DEV_H

#include <stdbool.h>
#include <stdint.h>

#include "panel.h"

#define ACTIVE_MS 3000u /* "something moves" lasts this long after a command */

/* The device thread's state (its own: no lock). */
typedef struct dev_state {
    uint64_t next_read;     /* positions due */
    uint64_t next_battery;  /* battery due */
    uint64_t active_until;  /* read fast until */
    uint64_t last_move;     /* a slider's last move */
    bool limp;              /* the servos are unloaded: they move by hand */
    bool group_running;
    bool lost;               /* the controller went away: open it again */
    uint64_t reopen_at;      /* ... next at */
    uint32_t reopen_ms;      /* ... after this (doubling) */
    uint32_t halts_seen;     /* through lscd: the halts it told of, so far */
    uint8_t run_group;       /* a group run whose start has not been heard ... */
    uint64_t run_deadline;   /* ... by then (0: none awaited) */
    lsc_kin_pose jog_to;     /* the last jog's target ... */
    uint64_t jog_until;      /* ... which the next jog starts from until its move's end */
    bool jog_valid;          /* ... unless something else moved the arm since */
    bool interrupt_left;     /* an interrupt came after the call it was for */
} dev_state;

/* panel_dev.c */

/* The monotonic clock, ms. */
uint64_t dev_now_ms(void);
/* Notes r's verdict on the link (an error that means the controller or
 * lscd went away: st->lost) and returns r. */
int dev_note(dev_state *st, int r);
/* Through lscd: whether another program halted the controller since the
 * last look (then the page is told). */
bool dev_halted_elsewhere(panel *p, dev_state *st);
/* An event that says what failed: {"what":..., "message":...}. */
void dev_event_error(panel *p, const char *what);
/* The grasp point's pose as an event's JSON. */
void dev_pose_json(const lsc_kin_pose *w, panel_buf *b);
/* Tells the requests whose move was taken its result. Under p->m. */
void dev_moves_done(panel *p, panel_move_wait *w, int r, const char *why);

/* panel_cmd.c */

/* Runs c (not PLAY) and answers it. */
void dev_run_cmd(panel *p, panel_cmd *c, dev_state *st);
/* Plays c's action, which is the device thread's: c is answered (and gone)
 * once the play has begun. */
void dev_play(panel *p, panel_cmd *c, dev_state *st);
/* Sends the slider's move waiting, if any, and tells its requests. */
void dev_send_move(panel *p, dev_state *st);
/* c is done: its caller (panel_dev_call) is told. */
void dev_finish(panel *p, const panel_cmd *c);
void dev_free_action(lsc_action *a);
/* The play slot is free again: whoever waits for the play's end is told. */
void dev_play_over(panel *p);
/* Ends the library call the device thread is in (lsc_device_interrupt):
 * only a play (play_only), or any. Under p->m; any thread. */
void dev_interrupt_call(panel *p, bool play_only);
/* Takes an interrupt that came after the call it was for. */
void dev_take_interrupt(panel *p, dev_state *st);

#endif /* LSC_PANEL_DEV_H */
