/* A program using the installed lsc library's serial transport and client
 * against a controller on a serial port: a real board on /dev/ttyUSB0, or
 * lsc-sim's pseudo-terminal. It reads the battery, moves servo 1 and reads it
 * back, then runs an action group once and prints the notifications the
 * controller sends while it runs (started, then finished or stopped).
 *
 *   lsc-serial PORT [GROUP]      (GROUP 0..255, default 1)
 *
 * Exit status, as lscctl's: 0 done; 1 failed talking to the controller (or
 * the group was stopped before its end); 2 invalid command line, nothing sent;
 * 3 no reply, or no notification, within the timeout; 4 port busy. Every
 * failure is one line on stderr. Built only when the installed lsc has the
 * serial transport (see README.md next to it). */
#include <lsc/lsc.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

enum { EXIT_TALK = 1, EXIT_USAGE = 2, EXIT_NO_REPLY = 3, EXIT_BUSY = 4 };

#define REPLY_MS 2000u        /* a reply takes ~10 ms at 9600 baud: generous */
#define START_MS 2000u        /* a board says "started" as soon as it starts */
#define GROUP_MS 600000u      /* how long a group may run: 10 minutes */
#define SERVO 1u
#define TARGET 2000u
#define MOVE_MS 500u
#define SETTLE_MS 2000u       /* after the move's time, how long it may take to get there */
#define READ_EVERY_MS 50u     /* meanwhile, how often to read where it is */

/* What the notification callback has seen of our group. A stop (7) or an end
 * (8) heard before our group's start (6) belongs to a group that ran before. */
typedef struct progress {
    uint8_t group;
    int started;
    int ended; /* 0, or the command that ended it: 7 stopped, 8 finished */
} progress;

static const char *times_text(uint16_t times)
{
    return times == 1 ? "time" : "times";
}

/* Called from inside lsc_client_poll for every notification, in arrival order. */
static void on_notification(void *user, const lsc_notification *n)
{
    progress *p = user;
    switch (n->cmd) {
    case LSC_CMD_GROUP_RUN:
        printf("group %u: started (%u %s)\n", (unsigned)n->group, (unsigned)n->times,
               times_text(n->times));
        if (n->group == p->group)
            p->started = 1;
        break;
    case LSC_CMD_GROUP_COMPLETE:
        printf("group %u: finished (%u %s)\n", (unsigned)n->group, (unsigned)n->times,
               times_text(n->times));
        if (p->started && n->group == p->group)
            p->ended = n->cmd;
        break;
    default: /* LSC_CMD_GROUP_STOP: the frame names no group */
        printf("group stopped\n");
        if (p->started)
            p->ended = n->cmd;
        break;
    }
    fflush(stdout); /* notifications show as they come, also into a pipe */
}

/* Reads and dispatches notifications until done(p) or ms have passed.
 * Returns 1 when done, 0 on time out, or the transport's error. */
static int poll_until(lsc_client *c, const lsc_io *io, progress *p, int (*done)(const progress *),
                      uint32_t ms)
{
    uint32_t start = io->now_ms(io->ctx);
    while (!done(p)) {
        uint32_t spent = io->now_ms(io->ctx) - start;
        if (spent >= ms)
            return 0;
        int r = lsc_client_poll(c, ms - spent);
        if (r < 0)
            return r;
    }
    return 1;
}

static int never(const progress *p)
{
    (void)p;
    return 0;
}
static int has_started(const progress *p)
{
    return p->started;
}
static int has_ended(const progress *p)
{
    return p->ended != 0;
}

/* Says what went wrong, with what to do about it, and picks the exit status. */
static int fail(const lsc_serial *port, const char *what, int err)
{
    const char *os = lsc_serial_error_message(port);
    switch (err) {
    case LSC_ETIMEOUT:
        fprintf(stderr,
                "lsc-serial: %s: no reply within %u ms: is the controller on, at 9600 baud, "
                "and its TX wired to the adapter's RX?\n",
                what, REPLY_MS);
        return EXIT_NO_REPLY;
    case LSC_EREPLY:
        fprintf(stderr,
                "lsc-serial: %s: what came was not the reply asked for (garbled, or another "
                "command's): check the baud rate and the wiring\n",
                what);
        return EXIT_TALK;
    default: /* the transport's errors: its message names the port and what to do */
        fprintf(stderr, "lsc-serial: %s: %s\n", what, *os ? os : lsc_strerror(err));
        return err == LSC_EBUSY ? EXIT_BUSY : EXIT_TALK;
    }
}

static int usage(const char *why)
{
    fprintf(stderr, "lsc-serial: %s; usage: lsc-serial PORT [GROUP] (GROUP 0..255, default 1)\n",
            why);
    return EXIT_USAGE;
}

static int talk(lsc_serial *port, uint8_t group)
{
    lsc_io io;
    lsc_client client;
    progress p = {group, 0, 0};
    lsc_serial_get_io(port, &io);
    if (lsc_client_init(&client, &io) != 0)
        return fail(port, "client", LSC_EINVAL);
    lsc_client_set_notify(&client, on_notification, &p);

    uint16_t mv = 0;
    int r = lsc_client_get_battery(&client, &mv, REPLY_MS);
    if (r < 0)
        return fail(port, "battery", r);
    printf("battery: %u mV\n", (unsigned)mv);

    r = lsc_client_move_one(&client, SERVO, TARGET, MOVE_MS);
    if (r < 0)
        return fail(port, "move", r);
    printf("servo %u: moving to %u in %u ms\n", SERVO, TARGET, MOVE_MS);
    /* Wait for the move's time, handling notifications meanwhile (a board's
     * handle or another program may start a group at any time), then read
     * the servo until it is there: the board starts the move when the frame
     * has arrived, a little later than it was sent. */
    r = poll_until(&client, &io, &p, never, MOVE_MS);
    if (r < 0)
        return fail(port, "move", r);
    const uint8_t ids[] = {SERVO};
    lsc_servo at;
    uint32_t since = io.now_ms(io.ctx);
    for (;;) {
        r = lsc_client_read_positions(&client, ids, 1, &at, REPLY_MS);
        if (r == LSC_ETIMEOUT)
            break; /* an LSC board's PWM servos do not report: not an error */
        if (r < 0)
            return fail(port, "read", r);
        if (at.position == TARGET || io.now_ms(io.ctx) - since >= SETTLE_MS)
            break;
        r = poll_until(&client, &io, &p, never, READ_EVERY_MS);
        if (r < 0)
            return fail(port, "read", r);
    }
    if (r == LSC_ETIMEOUT)
        printf("servo %u: the controller does not report its position\n", SERVO);
    else if (at.position == TARGET)
        printf("servo %u: at %u\n", (unsigned)at.id, (unsigned)at.position);
    else
        printf("servo %u: at %u, not yet at %u %u ms after the move's time\n", (unsigned)at.id,
               (unsigned)at.position, TARGET, SETTLE_MS);

    /* Only what the controller says after our run frame is about our run. */
    p.started = 0;
    p.ended = 0;
    r = lsc_client_run_group(&client, group, 1);
    if (r < 0)
        return fail(port, "run", r);
    r = poll_until(&client, &io, &p, has_started, START_MS);
    if (r < 0)
        return fail(port, "run", r);
    if (r == 0) {
        fprintf(stderr,
                "lsc-serial: run: the controller did not say group %u started within %u ms: "
                "is there a group %u on it? (lsc-sim: --groups FILE)\n",
                (unsigned)group, START_MS, (unsigned)group);
        return EXIT_NO_REPLY;
    }
    r = poll_until(&client, &io, &p, has_ended, GROUP_MS);
    if (r < 0)
        return fail(port, "run", r);
    if (r == 0) {
        fprintf(stderr, "lsc-serial: run: group %u did not end within %u s\n", (unsigned)group,
                GROUP_MS / 1000u);
        return EXIT_NO_REPLY;
    }
    if (p.ended != LSC_CMD_GROUP_COMPLETE) {
        fprintf(stderr, "lsc-serial: run: group %u was stopped before its end\n", (unsigned)group);
        return EXIT_TALK;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3)
        return usage(argc < 2 ? "no port given" : "too many arguments");
    unsigned long group = 1;
    if (argc == 3) {
        char *end;
        errno = 0;
        group = strtoul(argv[2], &end, 10);
        if (end == argv[2] || *end != '\0' || errno != 0 || group > 255 || argv[2][0] == '-')
            return usage("GROUP must be a number from 0 to 255");
    }

    lsc_serial *port = NULL;
    int r = lsc_serial_open(argv[1], LSC_SERIAL_BAUD_DEFAULT, LSC_SERIAL_AUTO, &port);
    if (r < 0)
        return fail(port, "open", r);
    int status = talk(port, (uint8_t)group);
    lsc_serial_close(port);
    return status;
}
