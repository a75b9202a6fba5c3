/* lscctl: what the program's parts share (options, commands, exit codes). */
#ifndef LSCCTL_H
#define LSCCTL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lscctl_out.h"

/* Exit codes (lscctl(1), EXIT STATUS; docs/contributing.md). */
enum {
    LSCCTL_EXIT_OK = 0,      /* done */
    LSCCTL_EXIT_FAIL = 1,    /* failed talking to the controller; decode: invalid bytes */
    LSCCTL_EXIT_USAGE = 2,   /* invalid command line or input: nothing was sent */
    LSCCTL_EXIT_TIMEOUT = 3, /* no reply within the timeout */
    LSCCTL_EXIT_BUSY = 4,    /* the port is busy: another program holds it; nothing sent */
    LSCCTL_EXIT_NEVER_STARTED = 5 /* run --wait: the group never started (the board has none) */
};

/* Everything the command line set. */
typedef struct lscctl_opts {
    /* (ordered by size: pointers and longs, then ints, then the flags) */
    const char *port;       /* --port, else $LSC_PORT, else NULL (auto-detect) */
    const char *arm;        /* --arm, else $LSC_ARM, else NULL: the arm profile's path */
    const char *from_arm, *to_arm; /* convert --from-arm, --to-arm (NULL: not given) */
    const char *ids;        /* record --ids (NULL: 1-6) */
    const char *out;        /* calibrate --out (NULL: the controller's calibrated profile) */
    const char *calib_step; /* calibrate --step (NULL: the whole walk) */
    const char *cmd;        /* the command's name, for messages */
    unsigned long baud;     /* --baud; 0: the port kind's (9600; lx:PATH 115200) */
    unsigned long timeout_ms; /* --timeout, default 1000 */
    unsigned long time_ms;  /* move --time, record --time */
    unsigned long times;    /* run --times */
    unsigned long tolerance; /* move --tolerance (positions), default 10 */
    unsigned long count;    /* monitor --count (0: until interrupted) */
    unsigned long speed;    /* play --speed (percent, default 100) */
    unsigned long lead_ms;  /* play --lead (default 1000) */
    unsigned long every;    /* record --every */
    double deg_speed;       /* move, reach --speed (degrees a second; 0: not given) */
    double pitch, roll;     /* reach --pitch, --roll */
    double step;            /* reach --step (mm; 0: not given) */
    lscctl_dir from;        /* decode --from */
    int group;              /* play/convert --group (0..254), else -1: the file's only one */
    uint16_t hid_vid, hid_pid; /* --hid-id, else 0:0 (then $LSC_HID_ID's, read by the
                                  open): a HID controller's USB ids to accept besides the
                                  known ones (lsc/hid.h) */
    bool timeout_set;       /* --timeout was given */
    bool json, dry_run, verbose;
    bool time_set;          /* --time was given */
    bool strict;            /* move --strict: a servo stopping short is an error */
    bool wait;              /* run --wait, move --wait */
    bool force;             /* send --force */
    bool every_set;         /* --every was given */
    bool pitch_set, roll_set; /* reach --pitch, --roll were given */
    bool line;              /* reach --line */
    bool check;             /* calibrate --check */
    bool save;              /* servo offset --save */
    bool arm_calibrated;    /* arm is the controller's calibrated profile (not given) */
} lscctl_opts;

/* Prints "lscctl: CMD: MESSAGE" (one line) on stderr and returns code. */
int lscctl_fail(const lscctl_opts *o, int code, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The commands (lscctl_cmds.c). Each checks all of argv[0..argc) first and
 * returns LSCCTL_EXIT_USAGE before anything is sent or a port opened. */
int lscctl_cmd_move(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_run(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_stop(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_halt(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_hold(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_speed(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_battery(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_unload(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_read(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_wait(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_monitor(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_send(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_decode(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_ports(const lscctl_opts *o, int argc, char **argv);
/* Teach and play (lscctl_record.c, lscctl_play.c, lscctl_convert.c), with
 * their help texts. */
int lscctl_cmd_record(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_play(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_convert(const lscctl_opts *o, int argc, char **argv);
/* The hand (lscctl_reach.c): where, reach, and move --speed's move. */
int lscctl_cmd_where(const lscctl_opts *o, int argc, char **argv);
int lscctl_cmd_reach(const lscctl_opts *o, int argc, char **argv);
int lscctl_move_at_speed(const lscctl_opts *o, const lsc_servo *servos, size_t n);
extern const char lscctl_help_record[], lscctl_help_play[], lscctl_help_convert[];
int lscctl_cmd_offset(const lscctl_opts *o, int argc, char **argv);
/* Calibration (lscctl_calibrate.c). */
int lscctl_cmd_calibrate(const lscctl_opts *o, int argc, char **argv);
/* lscd's state (lscctl_lscd.c): --port lscd:NAME status. */
int lscctl_cmd_status(const lscctl_opts *o, int argc, char **argv);
/* A bus servo's own settings (lscctl_servo.c): --port lx:PATH servo ..., its help. */
int lscctl_cmd_servo(const lscctl_opts *o, int argc, char **argv);
extern const char lscctl_help_servo[];

/* xArm command 27 writes settings to every servo on the bus at once: send
 * refuses it without --force, like 8. */
#define LSCCTL_CMD_WRITE_ALL 27u

#endif
