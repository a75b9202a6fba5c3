/* lscctl: teach and play: record, play and convert action files
 * (include/lsc/files.h) with the keyframe player (include/lsc/player.h). */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "lsc/files.h"
#include "lsc/player.h"
#include "lsc/serial.h" /* lsc_serial_now_ms: CLOCK_MONOTONIC */
#include "lscctl.h"
#include "lscctl_parse.h"
#include "lscctl_port.h"

#define READ_ATTEMPTS 5u   /* a keyframe's position read, before record gives up */
#define IDLE_SLICE_MS 100u /* waits are cut so that Ctrl-C is seen this soon */
#define DEFAULT_IDS "1-6"  /* the xArm's servos */

const char lscctl_help_record[] =
    "Powers off the servos (after a warning: they go limp) so that you can pose\n"
    "them by hand, then saves a keyframe (their positions and the time since the\n"
    "previous one) each time you press Enter, or every MS ms with --every. q or\n"
    "Ctrl-C ends and writes FILE; the extension chooses the format (.txt .csv\n"
    ".rob .d6a .h: docs/action-files.md). A read that times out is reported and\n"
    "retried, never saved. Without a terminal, each line of standard input is an\n"
    "Enter, a line 'q' or the end of the input ends (with --every, standard input\n"
    "is read only on a terminal: --count or Ctrl-C ends).\n"
    "\nOptions:\n  --ids LIST   servos to record: 1-6 (default), 1,2,5 or 1-3,8\n"
    "  --every MS   a keyframe every MS ms (1..65535) instead of on Enter\n"
    "  --count N    end after N keyframes\n"
    "\nExamples:\n  lscctl record wave.csv                  Enter for each pose, q to end\n"
    "  lscctl record arm.rob --every 200 --count 50\n";

const char lscctl_help_play[] =
    "Moves the servos to FILE's first keyframe over --lead ms, then sends each\n"
    "keyframe as one move at its time, on a schedule fixed from one start (no\n"
    "drift). Servos that keep their position are left out of a frame. Keyframes\n"
    "faster than the line carries (at 9600 baud a one-servo move takes 10.4 ms)\n"
    "are dropped, said once, rather than played late. Ctrl-C stops after the\n"
    "frame being sent and leaves the servos where they are. With -n, prints the\n"
    "schedule instead. A bad file is refused whole, before anything is sent.\n"
    "\nOptions:\n  --speed PCT  100 as recorded (default), 200 twice as fast (1..65535)\n"
    "  --times N    play it N times (1..65535, default 1)\n"
    "  --lead MS    the move to the first keyframe (default 1000)\n"
    "\nExamples:\n  lscctl play wave.csv\n  lscctl play arm.rob --speed 50 --times 3\n"
    "  lscctl -n play arm.d6a                print the schedule\n";

const char lscctl_help_convert[] =
    "Converts an action file: the extensions choose the formats (.txt .csv .rob\n"
    ".d6a to read; those and .h to write). The keyframes are the same; a format\n"
    "that cannot hold them (.rob: servos 1..6, positions 0..1000) is refused.\n"
    "The .h is a C header for firmware (examples/arduino/PlayKeyframes).\n"
    "\nExamples:\n  lscctl convert arm.rob arm.csv\n  lscctl convert arm.d6a arm.h\n";

static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig)
{
    (void)sig;
    interrupted = 1;
}

/* Ctrl-C sets `interrupted` instead of ending the program. */
static void catch_interrupt(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt;
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGINT, &sa, NULL);
}

/* Reads path; prints why and returns exit 2 if it cannot be played. */
static int load(const lscctl_opts *o, const char *path, lsc_action *a)
{
    lsc_file_error err;
    int r = lsc_action_read(path, a, &err);
    if (r == LSC_ENOSPC) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: out of memory", path);
    }
    if (r != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s", path, err.message);
    }
    return 0;
}

/* ---- convert ----------------------------------------------------------------- */

int lscctl_cmd_convert(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    lsc_action a;
    lsc_file_error err;
    if (lsc_file_format_of(argv[1]) == LSC_FILE_UNKNOWN) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s: unknown file type: use .txt, .csv, .rob, .d6a or .h", argv[1]);
    }
    int code = load(o, argv[0], &a);
    if (code != 0) {
        return code;
    }
    int r = o->dry_run ? 0 : lsc_action_write(argv[1], &a, &err);
    lsc_action_free(&a);
    if (r == LSC_EINVAL) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s", argv[1], err.message);
    }
    if (r != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: %s", argv[1], err.message);
    }
    return LSCCTL_EXIT_OK;
}

/* ---- play -------------------------------------------------------------------- */

static void print_step(const lscctl_opts *o, const lsc_player_step *s)
{
    if (o->json) {
        printf("{\"at_ms\":%lu,\"keyframe\":%lu,\"time\":%u,\"lead_in\":%s,"
               "\"time_ms\":%u,\"dropped\":%lu,\"servos\":[",
               (unsigned long)s->due_ms, (unsigned long)s->keyframe + 1u, s->repetition + 1u,
               s->lead_in ? "true" : "false", s->time_ms, (unsigned long)s->dropped);
        for (size_t i = 0; i < s->nservos; i++) {
            printf("%s{\"id\":%u,\"position\":%u}", i ? "," : "", s->servos[i].id,
                   s->servos[i].position);
        }
        printf("]}\n");
        return;
    }
    printf("%8lu ms  keyframe %lu", (unsigned long)s->due_ms, (unsigned long)s->keyframe + 1u);
    if (s->repetition > 0) {
        printf(" (time %u)", s->repetition + 1u);
    }
    printf("%s  move %u ms", s->lead_in ? " (lead-in)" : "", s->time_ms);
    for (size_t i = 0; i < s->nservos; i++) {
        printf(" %u:%u", s->servos[i].id, s->servos[i].position);
    }
    if (s->dropped > 0) {
        printf("  (%lu dropped before it)", (unsigned long)s->dropped);
    }
    putchar('\n');
}

/* The schedule on a clock that moves as the player asks (-n). */
static int print_schedule(const lscctl_opts *o, lsc_player *p)
{
    uint32_t now = 0;
    lsc_player_step s;
    int r;
    while ((r = lsc_player_next(p, now, &s)) != LSC_PLAYER_DONE) {
        if (r == LSC_PLAYER_WAIT) {
            now += s.wait_ms;
        } else {
            print_step(o, &s);
        }
    }
    if (!o->json) {
        printf("%8lu ms  end", (unsigned long)lsc_player_total_ms(p));
        if (lsc_player_dropped(p) > 0) {
            printf(" (%lu of %lu keyframes dropped: faster than %lu baud carries)",
                   (unsigned long)lsc_player_dropped(p), (unsigned long)lsc_player_frames(p),
                   o->baud);
        }
        putchar('\n');
    }
    return LSCCTL_EXIT_OK;
}

static void progress(const lsc_player *p, const lsc_player_step *s, uint32_t elapsed,
                     uint32_t count, unsigned long times)
{
    uint32_t total = lsc_player_total_ms(p);
    fprintf(stderr, "\rlscctl: play: keyframe %lu of %lu, time %u of %lu, %lu.%lu of %lu.%lu s ",
            (unsigned long)s->keyframe + 1u, (unsigned long)count, s->repetition + 1u, times, (unsigned long)(elapsed / 1000u),
            (unsigned long)(elapsed % 1000u / 100u), (unsigned long)(total / 1000u),
            (unsigned long)(total % 1000u / 100u));
}

/* Plays on the link until the end or Ctrl-C. */
static int play_on(const lscctl_opts *o, lscctl_link *l, lsc_player *p, uint32_t count)
{
    bool tty = isatty(STDERR_FILENO) && !o->verbose;
    uint32_t start = lscctl_link_now(l);
    lsc_player_step s;
    unsigned long sent = 0; /* the keyframe (1-based) of the last frame sent */
    int code = 0;
    catch_interrupt();
    while (code == 0 && !interrupted) {
        uint32_t now = lscctl_link_now(l);
        int r = lsc_player_next(p, now, &s);
        if (r == LSC_PLAYER_DONE) {
            break;
        }
        if (r == LSC_PLAYER_WAIT) {
            code = lscctl_link_idle(l, s.wait_ms < IDLE_SLICE_MS ? s.wait_ms : IDLE_SLICE_MS);
            continue;
        }
        if (s.dropped > 0 && lsc_player_dropped(p) == s.dropped) {
            fprintf(stderr, "%slscctl: play: keyframes come faster than %lu baud carries: "
                            "dropping those that cannot be sent in time\n",
                    tty ? "\n" : "", o->baud);
        }
        code = lscctl_link_move(l, s.time_ms, s.servos, s.nservos);
        sent = (unsigned long)s.keyframe + 1u;
        if (tty) {
            progress(p, &s, now - start, count, o->times);
        }
    }
    if (tty) {
        fputc('\n', stderr);
    }
    if (code != 0) {
        return code;
    }
    if (interrupted) {
        fprintf(stderr, "lscctl: play: stopped (Ctrl-C) after keyframe %lu; the servos stay "
                        "where they are\n",
                sent);
    }
    if (lsc_player_dropped(p) > 0) {
        fprintf(stderr, "lscctl: play: %lu of %lu keyframes dropped\n",
                (unsigned long)lsc_player_dropped(p), (unsigned long)lsc_player_frames(p));
    }
    return LSCCTL_EXIT_OK;
}

int lscctl_cmd_play(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    lsc_action a;
    lsc_track t;
    lsc_player p;
    if (o->times == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--times 0: play takes 1..65535");
    }
    int code = load(o, argv[0], &a);
    if (code != 0) {
        return code;
    }
    lsc_action_track(&a, &t);
    lsc_player_config c = {(uint16_t)o->speed, (uint16_t)o->times, (uint16_t)o->lead_ms,
                           (uint32_t)o->baud};
    if (a.count == 0) {
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: no keyframes to play", argv[0]);
    } else if (lsc_player_init(&p, &t, &c) != 0) {
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s: too long to play (more than 49 days at this speed and --times)",
                           argv[0]);
    } else if (o->dry_run) {
        code = print_schedule(o, &p);
    } else {
        lscctl_link *l;
        code = lscctl_link_open(o, &l);
        if (code == 0) {
            code = play_on(o, l, &p, a.count);
            lscctl_link_close(l);
        }
    }
    lsc_action_free(&a);
    return code;
}

/* ---- record ------------------------------------------------------------------ */

/* "1-6", "1,2,5", "1-3,8": distinct ids 0..255, at most LSC_PLAYER_SERVOS_MAX. */
static int parse_ids(const lscctl_opts *o, const char *list, uint8_t *ids, size_t *n)
{
    char buf[256], why[96];
    *n = 0;
    if (strlen(list) >= sizeof buf || *list == '\0') {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': give ids like 1-6 or 1,2,5", list);
    }
    memcpy(buf, list, strlen(list) + 1u);
    for (char *save = NULL, *part = strtok_r(buf, ",", &save); part != NULL;
         part = strtok_r(NULL, ",", &save)) {
        char *dash = strchr(part, '-');
        unsigned long lo, hi;
        if (dash != NULL) {
            *dash = '\0';
        }
        if (lscctl_parse_uint(part, 255, "id", &lo, why, sizeof why) != 0 ||
            (dash != NULL && lscctl_parse_uint(dash + 1, 255, "id", &hi, why, sizeof why) != 0)) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': %s", list, why);
        }
        if (dash == NULL) {
            hi = lo;
        }
        if (hi < lo) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': the range %lu-%lu is empty",
                               list, lo, hi);
        }
        for (unsigned long id = lo; id <= hi; id++) {
            if (memchr(ids, (int)id, *n) != NULL) {
                return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': servo %lu listed twice",
                                   list, id);
            }
            if (*n == LSC_PLAYER_SERVOS_MAX) {
                return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': more than %u servos",
                                   list, LSC_PLAYER_SERVOS_MAX);
            }
            ids[(*n)++] = (uint8_t)id;
        }
    }
    if (*n == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--ids '%s': give ids like 1-6 or 1,2,5", list);
    }
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
    lsc_action a;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    size_t n;
} recorder;

/* Reads the positions and appends a keyframe; timeouts are retried. */
static int take_keyframe(recorder *rec, uint32_t since_ms)
{
    lsc_servo got[LSC_PLAYER_SERVOS_MAX];
    uint16_t pos[LSC_PLAYER_SERVOS_MAX];
    int r = LSC_ETIMEOUT;
    for (unsigned i = 0; i < READ_ATTEMPTS && r == LSC_ETIMEOUT && !interrupted; i++) {
        r = lscctl_link_try_read(rec->l, rec->ids, rec->n, got);
        if (r == LSC_ETIMEOUT) {
            fprintf(stderr, "lscctl: record: no reply to the position read within %lu ms%s\n",
                    rec->o->timeout_ms, i + 1u < READ_ATTEMPTS ? ": retrying" : "");
        }
    }
    if (r == LSC_ETIMEOUT) {
        return interrupted ? 0 : LSCCTL_EXIT_TIMEOUT;
    }
    if (r != 0) {
        return r;
    }
    if (since_ms > 65535u) {
        fprintf(stderr, "lscctl: record: keyframe %lu came %lu ms after the one before; saved "
                        "as 65535 ms, the most a keyframe holds\n",
                (unsigned long)rec->a.count + 1u, (unsigned long)since_ms);
        since_ms = 65535u;
    }
    for (size_t i = 0; i < rec->n; i++) {
        pos[i] = got[i].position;
    }
    if (since_ms == 0) {
        since_ms = 1; /* a move needs time; and lsc's text format has no 0 ms step */
    }
    if (lsc_action_append(&rec->a, (uint16_t)since_ms, pos) != 0) {
        return lscctl_fail(rec->o, LSCCTL_EXIT_FAIL, "out of memory");
    }
    if (rec->o->json) {
        printf("{\"keyframe\":%lu,\"time_ms\":%lu,\"servos\":[", (unsigned long)rec->a.count,
               (unsigned long)since_ms);
        for (size_t i = 0; i < rec->n; i++) {
            printf("%s{\"id\":%u,\"position\":%u}", i ? "," : "", got[i].id, got[i].position);
        }
        printf("]}\n");
    } else {
        printf("keyframe %lu +%lu ms:", (unsigned long)rec->a.count, (unsigned long)since_ms);
        for (size_t i = 0; i < rec->n; i++) {
            printf(" %u:%u", got[i].id, got[i].position);
        }
        putchar('\n');
    }
    fflush(stdout);
    return 0;
}

/* Keyframes on Enter, until q, end of input or Ctrl-C. Timed by the host's
 * monotonic clock (the user's time), not the link's: --port sim's is virtual. */
static int record_on_enter(recorder *rec, bool tty)
{
    uint32_t last = lsc_serial_now_ms(NULL);
    while (!interrupted && (rec->o->count == 0 || rec->a.count < rec->o->count)) {
        key k = read_key(tty, -1);
        if (k == KEY_QUIT) {
            break;
        }
        if (k == KEY_FRAME) {
            uint32_t now = lsc_serial_now_ms(NULL);
            int code = take_keyframe(rec, now - last);
            if (code != 0) {
                return code;
            }
            last = now;
        }
    }
    return 0;
}

/* A keyframe every o->every ms on the link's clock, on a fixed schedule. */
static int record_every(recorder *rec, bool tty)
{
    uint32_t start = lscctl_link_now(rec->l), last = start - (uint32_t)rec->o->every;
    uint32_t due = start;
    while (!interrupted && (rec->o->count == 0 || rec->a.count < rec->o->count)) {
        uint32_t now = lscctl_link_now(rec->l);
        if ((int32_t)(due - now) > 0) {
            uint32_t wait = due - now;
            int code = lscctl_link_idle(rec->l, wait < IDLE_SLICE_MS ? wait : IDLE_SLICE_MS);
            if (code != 0) {
                return code;
            }
            if (tty && read_key(true, 0) == KEY_QUIT) {
                break;
            }
            continue;
        }
        int code = take_keyframe(rec, now - last);
        if (code != 0) {
            return code;
        }
        last = now;
        due += (uint32_t)rec->o->every;
    }
    return 0;
}

int lscctl_cmd_record(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    recorder rec;
    lsc_file_error err;
    memset(&rec, 0, sizeof rec);
    rec.o = o;
    const char *path = argv[0];
    lsc_file_format f = lsc_file_format_of(path);
    if (f == LSC_FILE_UNKNOWN) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s: unknown file type: use .txt, .csv, .rob, .d6a or .h", path);
    }
    int code = parse_ids(o, o->ids != NULL ? o->ids : DEFAULT_IDS, rec.ids, &rec.n);
    if (code != 0) {
        return code;
    }
    if (o->every_set && o->every == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--every 0: give 1..65535 ms");
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
    code = lscctl_link_open(o, &rec.l);
    if (code != 0) {
        return code;
    }
    bool tty = isatty(STDIN_FILENO) != 0;
    fprintf(stderr, "lscctl: record: servos %s go limp now (powered off): hold them\n",
            o->ids != NULL ? o->ids : DEFAULT_IDS);
    code = lscctl_link_unload(rec.l, rec.ids, rec.n);
    struct termios saved;
    bool raw = false;
    if (code == 0 && tty && tcgetattr(STDIN_FILENO, &saved) == 0) {
        struct termios t = saved;
        t.c_lflag &= ~(tcflag_t)(ICANON | ECHO);
        t.c_cc[VMIN] = 1;
        t.c_cc[VTIME] = 0;
        raw = tcsetattr(STDIN_FILENO, TCSANOW, &t) == 0;
    }
    if (code == 0) {
        if (tty) {
            fprintf(stderr, "lscctl: record: %s; q or Ctrl-C ends and writes %s\n",
                    o->every_set ? "a keyframe every --every ms" : "Enter saves a keyframe",
                    path);
        }
        catch_interrupt();
        code = o->every_set ? record_every(&rec, tty) : record_on_enter(&rec, tty);
    }
    if (raw) {
        (void)tcsetattr(STDIN_FILENO, TCSANOW, &saved);
    }
    lscctl_link_close(rec.l);
    /* what was recorded is written even when the controller stopped answering */
    if (rec.a.count == 0) {
        if (code == 0) {
            code = lscctl_fail(o, LSCCTL_EXIT_FAIL, "no keyframe recorded: %s not written", path);
        }
    } else {
        int r = lsc_action_write(path, &rec.a, &err);
        if (r != 0) {
            /* the format cannot hold these keyframes (a .rob and positions past
             * 1000, say): keep them in a CSV beside it rather than lose them */
            char kept[4096];
            lsc_file_error err2;
            (void)snprintf(kept, sizeof kept, "%s.csv", path);
            bool kept_ok = r == LSC_EINVAL && lsc_action_write(kept, &rec.a, &err2) == 0;
            code = lscctl_fail(o, r == LSC_EINVAL ? LSCCTL_EXIT_USAGE : LSCCTL_EXIT_FAIL,
                               "%s: %s%s%s", path, err.message,
                               kept_ok ? "; the keyframes are saved in " : "", kept_ok ? kept : "");
        } else {
            fprintf(stderr, "lscctl: record: wrote %lu keyframes to %s\n",
                    (unsigned long)rec.a.count, path);
        }
    }
    lsc_action_free(&rec.a);
    return code;
}
