/* lscctl record: keyframes posed by hand (Enter) or taken every --every
 * ms, written to an action file. The keyframe reads and the journal are the
 * library's (lsc_device_record, lsc_device_take_keyframe in lsc/device.h;
 * the journal in lsc/files.h): here are the arguments, the terminal, the
 * signals and what is printed. */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/play.h"
#include "lsc/text.h"
#include "lscctl.h"
#include "lscctl_port.h"
#include "lscctl_teach.h"

#define READ_ATTEMPTS 5u   /* a keyframe's position read, before record gives up */
#define DEFAULT_IDS "1-6"  /* the xArm's servos */

const char lscctl_help_record[] =
    "Powers off the servos (after a warning: they go limp) so that you can pose\n"
    "them by hand, then saves a keyframe (their positions and the time since the\n"
    "previous one; the first: 1000 ms, the move to it) each time you press\n"
    "Enter, or every MS ms with --every. With --time MS each keyframe on Enter\n"
    "is MS ms after the one before, however long you took to pose it. q,\n"
    "Ctrl-C, SIGTERM or SIGHUP ends and writes FILE; the extension chooses the\n"
    "format (.txt .csv .rob .d6a .h: docs/action-files.md). FILE is checked\n"
    "before the servos go limp, and each keyframe reaches the disk as it is\n"
    "taken, in FILE.journal.csv beside it (removed once FILE is written; kept,\n"
    "and named, if FILE cannot be). At most 65535 keyframes: record then ends.\n"
    "A read that times out is reported and retried, never saved. Without a\n"
    "terminal, each line of standard input is an Enter, a line 'q' or the end of\n"
    "the input ends (with --every, standard input is read only on a terminal:\n"
    "--count or Ctrl-C ends).\n"
    "\nOptions:\n  --ids LIST   servos to record: 1-6 (default), 1,2,5 or 1-3,8; with\n"
    "               --arm, joint names too: base,shoulder,3-4; all: the arm\n"
    "               profile's joints, else every id of the controller's kind\n"
    "               (HID: 1..6; serial port, lscd, sim: 1..32)\n"
    "  --every MS   a keyframe every MS ms (1..65535) instead of on Enter\n"
    "  --time MS    on Enter: each keyframe's time, MS ms (1..65535)\n"
    "  --count N    end after N keyframes\n"
    "\nExamples:\n  lscctl record wave.csv                  Enter for each pose, q to end\n"
    "  lscctl record arm.rob --every 200 --count 50\n"
    "  lscctl record wave.rob --time 500      Enter for each pose, 500 ms apart\n";

/* The servos of --ids (default 1-6): ids, ranges LO-HI, all and, with --arm,
 * joint names (lsc_device_parse_ids_all). Returns 0 or exit 2 after saying why. */
static int record_ids(const lscctl_opts *o, uint8_t *ids, size_t *n)
{
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    const char *list = o->ids != NULL ? o->ids : DEFAULT_IDS;
    if (o->arm != NULL && lsc_arm_open(o->arm, &arm, why, sizeof why) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    int r = lsc_device_parse_ids_all(arm, o->port, list, ids, LSC_PLAYER_SERVOS_MAX, why,
                                     sizeof why);
    lsc_arm_free(arm);
    if (r == LSC_ENODEV) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "--ids all stands for the controller's servos, which its kind "
                           "tells: name it with --port (or $LSC_PORT), or give --arm FILE");
    }
    if (r < 0) {
        lscctl_shown shown;
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': %s", lscctl_show(&shown, list),
                           why);
    }
    *n = (size_t)r;
    return 0;
}

typedef enum key { KEY_NONE, KEY_FRAME, KEY_QUIT } key;

/* What standard input says within timeout_ms (-1: wait): on a terminal
 * (raw) Enter or q; else a line ('q' quits). End of input quits. */
static key read_key(bool tty, int timeout_ms)
{
    struct pollfd pfd = {STDIN_FILENO, POLLIN, 0};
    int r = poll(&pfd, 1, timeout_ms);
    if (r <= 0) {
        return KEY_NONE; /* timeout, or a signal (Ctrl-C) */
    }
    if (tty) {
        char c;
        ssize_t n = read(STDIN_FILENO, &c, 1);
        if (n <= 0) {
            return n < 0 && errno == EINTR ? KEY_NONE : KEY_QUIT;
        }
        return c == 'q' || c == 'Q' || c == 4 ? KEY_QUIT
               : c == '\n' || c == '\r'       ? KEY_FRAME
                                              : KEY_NONE;
    }
    char line[256];
    if (fgets(line, sizeof line, stdin) == NULL) {
        return KEY_QUIT;
    }
    return line[0] == 'q' ? KEY_QUIT : KEY_FRAME;
}

typedef struct recorder {
    const lscctl_opts *o;
    lscctl_link *l;
    lsc_device *d;
    lsc_journal *j;
    lsc_action a;
    bool tty;
    int code;      /* an exit code that ended the recording (0: none) */
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    size_t n;
    lscctl_shown path;    /* FILE, as messages show it */
    lscctl_shown journal; /* its journal, as messages show it */
} recorder;

static void say_timeout(const recorder *rec, bool retrying)
{
    fprintf(stderr, "lscctl: record: no reply to the position read within %lu ms%s\n",
            rec->o->timeout_ms, retrying ? ": retrying" : "");
}

/* The keyframe just taken (the last of rec->a): printed, and appended to the
 * journal. Returns 0 or the exit code after saying why. */
static int taken(recorder *rec)
{
    const lscctl_opts *o = rec->o;
    const lsc_action *a = &rec->a;
    const uint16_t *row = &a->words[(size_t)(a->count - 1u) * (1u + (size_t)a->nservos)];
    lsc_file_error err = {.size = sizeof err};
    if (o->json) {
        printf("{\"keyframe\":%lu,\"time_ms\":%u,\"servos\":[", (unsigned long)a->count, row[0]);
        for (size_t i = 0; i < a->nservos; i++) {
            printf("%s{\"id\":%u,\"position\":%u}", i ? "," : "", a->ids[i], row[1u + i]);
        }
        printf("]}\n");
    } else {
        printf("keyframe %lu +%u ms:", (unsigned long)a->count, row[0]);
        for (size_t i = 0; i < a->nservos; i++) {
            printf(" %u:%u", a->ids[i], row[1u + i]);
        }
        putchar('\n');
    }
    fflush(stdout);
    if (lsc_journal_append(rec->j, row[0], row + 1, &err) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: %s", rec->journal.text, err.message);
    }
    return 0;
}

/* The journal's rows reach the disk within about a second while waiting. */
static int sync_journal(recorder *rec)
{
    lsc_file_error err = {.size = sizeof err};
    if (lsc_journal_sync(rec->j, &err) != 0) {
        return lscctl_fail(rec->o, LSCCTL_EXIT_FAIL, "%s: %s", rec->journal.text, err.message);
    }
    return 0;
}

/* The host's monotonic clock in ms: Enter is the user's time, not the
 * port's (--port sim's is virtual). */
static uint32_t host_ms(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

/* One keyframe on Enter: the read retried (and said) up to READ_ATTEMPTS
 * times. Returns 0 or an exit code after saying why. */
static int take_on_enter(recorder *rec, uint32_t since_ms)
{
    if (since_ms > 65535u) {
        fprintf(stderr, "lscctl: record: keyframe %lu came %lu ms after the one before; saved "
                        "as 65535 ms, the most a keyframe holds\n",
                (unsigned long)rec->a.count + 1u, (unsigned long)since_ms);
    }
    int r = LSC_ETIMEOUT;
    for (unsigned i = 0; i < READ_ATTEMPTS && r == LSC_ETIMEOUT && lscctl_interrupted == 0; i++) {
        r = lsc_device_take_keyframe(rec->d, &rec->a, since_ms, 1);
        if (r == LSC_ETIMEOUT) {
            say_timeout(rec, i + 1u < READ_ATTEMPTS);
        }
    }
    if (r == LSC_ETIMEOUT) {
        return lscctl_interrupted != 0 ? 0 : LSCCTL_EXIT_TIMEOUT;
    }
    return r != 0 ? lscctl_link_check(rec->l, r) : taken(rec);
}

/* The time of the first keyframe on Enter, when --time does not give it: the
 * move to the first pose (the time spent posing it means nothing). */
#define FIRST_KEYFRAME_MS 1000u

/* Keyframes on Enter, until q, end of input, a signal, --count or the most
 * a file holds. Each keyframe's time: --time, else the time since the one
 * before (the first: FIRST_KEYFRAME_MS). */
static int record_on_enter(recorder *rec)
{
    uint32_t last = host_ms();
    while (lscctl_interrupted == 0 && (rec->o->count == 0 || rec->a.count < rec->o->count) &&
           rec->a.count < LSC_ACTION_KEYFRAMES_MAX) {
        key k = read_key(rec->tty, (int)LSC_JOURNAL_SYNC_MS);
        if (k == KEY_QUIT) {
            break;
        }
        int code = sync_journal(rec);
        if (code == 0 && k == KEY_FRAME) {
            uint32_t now = host_ms();
            uint32_t since = rec->o->time_set ? (uint32_t)rec->o->time_ms
                             : rec->a.count == 0 ? FIRST_KEYFRAME_MS
                                                 : now - last;
            code = take_on_enter(rec, since);
            last = now;
        }
        if (code != 0) {
            return code;
        }
    }
    return 0;
}

/* lsc_device_record's callback: each keyframe printed and journalled, each
 * retry said, q on a terminal and the signals end it. */
static bool on_record(void *user, const lsc_action *a, bool took)
{
    recorder *rec = user;
    (void)a;
    if (took) {
        rec->code = taken(rec);
    } else if (*lsc_device_error(rec->d) != '\0') {
        say_timeout(rec, true); /* a read timed out: it is retried */
    } else {
        rec->code = sync_journal(rec);
        if (rec->tty && read_key(true, 0) == KEY_QUIT) {
            return false;
        }
    }
    return rec->code == 0 && lscctl_interrupted == 0;
}

/* A keyframe every o->every ms on the port's clock, on a fixed schedule. */
static int record_every(recorder *rec)
{
    int r = lsc_device_record(rec->d, &rec->a, (uint32_t)rec->o->every,
                              (uint32_t)rec->o->count, on_record, rec);
    if (rec->code != 0) {
        return rec->code;
    }
    if (r == LSC_ETIMEOUT && lscctl_interrupted == 0) {
        say_timeout(rec, false);
        return LSCCTL_EXIT_TIMEOUT;
    }
    if (r == LSC_ENOSPC && rec->a.count >= LSC_ACTION_KEYFRAMES_MAX) {
        return 0; /* said by the caller */
    }
    return r == 0 || r == LSC_ETIMEOUT ? 0 : lscctl_link_check(rec->l, r);
}

/* Writes what was recorded to path and removes the journal; when path
 * cannot be written, says where the keyframes are. Returns the exit code
 * (code, the recording's own, if it is not 0). */
static int save_recording(recorder *rec, const char *path, int code)
{
    const lscctl_opts *o = rec->o;
    lsc_file_error err = {.size = sizeof err};
    char journal[4096];
    (void)snprintf(journal, sizeof journal, "%s", lsc_journal_path(rec->j));
    if (rec->a.count == 0) { /* nothing: no file, no journal */
        lsc_journal_close(rec->j);
        rec->j = NULL;
        (void)remove(journal);
        return code != 0 ? code
                         : lscctl_fail(o, LSCCTL_EXIT_FAIL, "no keyframe recorded: %s not written",
                                       rec->path.text);
    }
    if (rec->a.count >= LSC_ACTION_KEYFRAMES_MAX) {
        fprintf(stderr, "lscctl: record: stopped at %lu keyframes, the most an action file "
                        "holds\n",
                (unsigned long)rec->a.count);
    }
    int r = lsc_journal_finish(rec->j, &rec->a, &err);
    lsc_journal_close(rec->j);
    rec->j = NULL;
    if (r == 0) {
        fprintf(stderr, "lscctl: record: wrote %lu keyframe%s to %s\n",
                (unsigned long)rec->a.count, rec->a.count == 1u ? "" : "s", rec->path.text);
        return code;
    }
    /* the format cannot hold these keyframes (a .rob and positions past
     * 1000, say: the error names a keyframe): keep them in a CSV beside it;
     * else (the disk, the target's place) they are in the journal */
    bool format = r == LSC_EINVAL && err.at > 0;
    char kept[4096];
    lsc_file_error err2 = {.size = sizeof err2};
    (void)snprintf(kept, sizeof kept, "%s.csv", path);
    bool kept_ok = format && lsc_action_write(kept, &rec->a, &err2) == 0;
    if (kept_ok) {
        (void)remove(journal);
    }
    lscctl_shown shown_kept;
    int fail = lscctl_fail(o, format ? LSCCTL_EXIT_USAGE : LSCCTL_EXIT_FAIL,
                           "%s: %s; the keyframes are saved in %s", rec->path.text, err.message,
                           kept_ok ? lscctl_show(&shown_kept, kept) : rec->journal.text);
    return code != 0 ? code : fail;
}

/* The terminal as record found it and as it records (raw_on: while it
 * records), for the handlers of SIGTSTP and SIGCONT. */
static struct termios tty_saved, tty_raw;
static volatile sig_atomic_t raw_on;

/* Ctrl-Z (SIGTSTP): the terminal as it was, then stop as the default action
 * would; on continuing, raw again. Only async-signal-safe calls. */
static void on_tstp(int sig)
{
    int e = errno;
    struct sigaction sa;
    sigset_t set;
    if (raw_on) {
        (void)tcsetattr(STDIN_FILENO, TCSANOW, &tty_saved);
    }
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_DFL;
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(sig, &sa, NULL);
    (void)kill(getpid(), sig); /* (pending until unblocked below) */
    (void)sigemptyset(&set);
    (void)sigaddset(&set, sig);
    (void)sigprocmask(SIG_UNBLOCK, &set, NULL); /* stops here until SIGCONT */
    sa.sa_handler = on_tstp;
    (void)sigaction(sig, &sa, NULL);
    if (raw_on) {
        (void)tcsetattr(STDIN_FILENO, TCSANOW, &tty_raw);
    }
    errno = e;
}

/* SIGCONT after a stop record did not see (SIGSTOP): raw again, in case the
 * shell restored the terminal meanwhile. */
static void on_cont(int sig)
{
    int e = errno;
    (void)sig;
    if (raw_on) {
        (void)tcsetattr(STDIN_FILENO, TCSANOW, &tty_raw);
    }
    errno = e;
}

static void handle_signal(int sig, void (*fn)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = fn;
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(sig, &sa, NULL);
}

/* The terminal without echo and line buffering, so that Enter and q act at
 * once, until raw_off; Ctrl-Z and fg leave it as it was while stopped. */
static bool raw_terminal(void)
{
    if (tcgetattr(STDIN_FILENO, &tty_saved) != 0) {
        return false;
    }
    tty_raw = tty_saved;
    tty_raw.c_lflag &= ~(tcflag_t)(ICANON | ECHO);
    tty_raw.c_cc[VMIN] = 1;
    tty_raw.c_cc[VTIME] = 0;
    raw_on = 1;
    handle_signal(SIGTSTP, on_tstp);
    handle_signal(SIGCONT, on_cont);
    if (tcsetattr(STDIN_FILENO, TCSANOW, &tty_raw) != 0) {
        raw_on = 0;
        return false;
    }
    return true;
}

/* The terminal as record found it. */
static void raw_off(void)
{
    raw_on = 0;
    handle_signal(SIGTSTP, SIG_DFL);
    handle_signal(SIGCONT, SIG_DFL);
    (void)tcsetattr(STDIN_FILENO, TCSANOW, &tty_saved);
}

int lscctl_cmd_record(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    recorder rec;
    lsc_file_error err = {.size = sizeof err};
    memset(&rec, 0, sizeof rec);
    rec.o = o;
    const char *path = argv[0];
    (void)lscctl_show(&rec.path, path);
    lsc_file_format f = lsc_file_format_of(path);
    if (f == LSC_FILE_UNKNOWN) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s: unknown file type: lsc writes .txt, .csv, .rob, .d6a and .h",
                           rec.path.text);
    }
    int code = record_ids(o, rec.ids, &rec.n);
    if (code != 0) {
        return code;
    }
    if (o->every_set && o->every == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--every 0: give 1..65535 ms");
    }
    if (o->time_set && o->time_ms == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--time 0: give 1..65535 ms");
    }
    if (o->time_set && o->every_set) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "--time is for keyframes on Enter: with --every MS each keyframe's "
                           "time is MS");
    }
    (void)lsc_action_init(&rec.a, rec.ids, rec.n);
    if (o->dry_run) { /* what goes out first: the unload, then each read */
        uint8_t frame[LSC_FRAME_MAX];
        int len = lsc_encode_unload(frame, sizeof frame, rec.ids, rec.n);
        lscctl_dry_run_print(stdout, frame, (size_t)len, o->json);
        len = lsc_encode_pos_request(frame, sizeof frame, rec.ids, rec.n);
        lscctl_dry_run_print(stdout, frame, (size_t)len, o->json);
        return LSCCTL_EXIT_OK;
    }
    /* the destination first: nothing goes limp for a file that cannot be written */
    int r = lsc_journal_open(path, &rec.a, &rec.j, &err);
    if (r != 0) {
        return lscctl_fail(o, r == LSC_EINVAL ? LSCCTL_EXIT_USAGE : LSCCTL_EXIT_FAIL, "%s: %s",
                           rec.path.text, err.message);
    }
    (void)lscctl_show(&rec.journal, lsc_journal_path(rec.j));
    code = lscctl_link_open(o, &rec.l);
    if (code != 0) {
        char journal[4096];
        (void)snprintf(journal, sizeof journal, "%s", lsc_journal_path(rec.j));
        lsc_journal_close(rec.j);
        (void)remove(journal);
        return code;
    }
    rec.d = lscctl_link_device(rec.l);
    rec.tty = isatty(STDIN_FILENO) != 0;
    if (!rec.tty) {
        /* a line at a time from the descriptor: poll then sees what is left */
        (void)setvbuf(stdin, NULL, _IONBF, 0);
    }
    /* every signal that would end the program ends the recording instead,
     * and what was recorded is written */
    lscctl_catch_signal(SIGINT);
    lscctl_catch_signal(SIGTERM);
    lscctl_catch_signal(SIGHUP);
    lscctl_catch_signal(SIGQUIT); /* (Ctrl-\\: no core dump with the terminal left raw) */
    lscctl_shown ids;
    fprintf(stderr, "lscctl: record: %s %s %s limp now (powered off): hold %s\n",
            rec.n == 1u ? "servo" : "servos",
            lscctl_show(&ids, o->ids != NULL ? o->ids : DEFAULT_IDS), rec.n == 1u ? "goes" : "go",
            rec.n == 1u ? "it" : "them");
    code = lscctl_link_unload(rec.l, rec.ids, rec.n);
    bool raw = code == 0 && rec.tty && raw_terminal();
    if (code == 0) {
        if (rec.tty) {
            fprintf(stderr, "lscctl: record: %s; q or Ctrl-C ends and writes %s\n",
                    o->every_set ? "a keyframe every --every ms" : "Enter saves a keyframe",
                    rec.path.text);
        }
        code = o->every_set ? record_every(&rec) : record_on_enter(&rec);
    }
    if (raw) {
        raw_off();
    }
    lscctl_link_close(rec.l);
    /* what was recorded is written even when the controller stopped answering */
    code = save_recording(&rec, path, code);
    lsc_action_free(&rec.a);
    return code;
}
