/* lsc-sim: serves the virtual LSC controller (lsc/sim.h), or with --lx a
 * virtual bus of serial bus servos (lsc/lxbus.h, lsc_sim_lx.c), on a new
 * pseudo-terminal, in real time, until SIGINT, SIGTERM, SIGHUP or SIGQUIT. */
/* _DEFAULT_SOURCE (openpty, cfmakeraw) comes from cli/CMakeLists.txt */

#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <limits.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "lsc/lsc.h"
#include "lsc_sim_lx.h"
#include "lscctl_parse.h"
#include "signal_pipe.h"

#define PROG "lsc-sim"
#define EXIT_USAGE 2
#define GROUP_FILE_MAX (16L * 1024 * 1024)

static const char usage_text[] =
    "Usage: " PROG " [OPTION]...\n"
    "   or: " PROG " --lx IDS [--state FILE] [--echo] [OPTION]...\n"
    "Serve a virtual LSC servo controller on a new pseudo-terminal; with --lx, a\n"
    "virtual bus of serial bus servos (LX-16A, LX-15D, LX-224...).\n"
    "\n"
    "Prints the pseudo-terminal's path on stdout, then answers the LSC protocol on it\n"
    "in real time until SIGINT, SIGTERM, SIGHUP or SIGQUIT (then exits 0, removing\n"
    "the --link).\n"
    "Servos 0..255 start at position 1500, powered (with --arm: that arm's joints\n"
    "at 0 degrees); the battery reads 7500 mV.\n"
    "\n"
    "Options:\n"
    "  --lx IDS           serve a bus of bus servos with these ids (0..253, at most\n"
    "                     32: \"1-6\", \"1,3,5\"), speaking the bus-servo protocol\n"
    "                     at 115200 baud (docs/protocol.md): each starts at\n"
    "                     position 500, torque off; SIGUSR2 power-cycles the bus.\n"
    "                     With --lx, --baud, --fast, --battery (the servos' supply),\n"
    "                     --log, --link and the reply faults apply\n"
    "  --state FILE       (--lx) keep what the servos keep at power-off (ids, saved\n"
    "                     offsets, limits, LED) in FILE across runs: read at start\n"
    "                     when it exists (it must hold as many servos as IDS names),\n"
    "                     written whenever that changes and at exit (atomically)\n"
    "  --echo             (--lx) send every byte received back first, as a one-wire\n"
    "                     bus heard from the host's own pin\n";
/* the rest (one string would pass the 4095 characters C99 promises) */
static const char usage_text_more[] =
    "  --link PATH        also make a symlink to the pseudo-terminal at PATH\n"
    "                     (an existing symlink there is replaced; removed on exit)\n"
    "  --baud N           pace output at N baud, 10 bits a byte (default 9600:\n"
    "                     about 1.04 ms a byte; with --lx 115200), 1..4000000\n"
    "  --fast             send replies at once (no pacing)\n"
    "  --battery MV       battery voltage reported, 0..65535 millivolts (default 7500)\n"
    "  --arm NAME|FILE    stand in for the arm of this profile (docs/arm-profile.md;\n"
    "                     a NAME such as xarm as lscctl --arm takes it):\n"
    "                     each joint's servo starts at the joint's 0 degrees (an\n"
    "                     xArm's at 500), and a move beyond its servo's range\n"
    "                     (bus servos 0..1000, PWM 500..2500) stops at the end\n"
    "  --groups FILE...   load action groups from each FILE (format:\n"
    "                     docs/action-groups.md, lsc-sim(1)); the files after\n"
    "                     --groups up to the next option, and those of every other\n"
    "                     --groups, are served together. A .csv, .rob or .d6a\n"
    "                     action file is one group, numbered as the vendors'\n"
    "                     software numbers them: by the number its name starts with\n"
    "                     (10.rob: group 10; 7-wave.rob: group 7), else group 1.\n"
    "                     A group number two files define is an error naming both\n"
    "  --button GROUP     SIGUSR1 runs GROUP once, as the board's button or a handset\n"
    "                     would (its notifications go to whoever has the port open)\n"
    "  --log              log to stderr every frame in (rx) and out (tx) as hex with\n"
    "                     the time in seconds, every beep (malformed frame; with\n"
    "                     --lx: discarded, such as a bad checksum), every ignored\n"
    "                     command, dropped reply and noise byte\n"
    "  --block ID:POS[:below]\n"
    "                     hold servo ID at position POS, as an object in a gripper's\n"
    "                     way would: it cannot go above POS (with :below, below\n"
    "                     POS); a move beyond stops there (repeat for more servos)\n"
    "  --drop-replies N   do not send the next N replies (battery, position)\n"
    "  --delay-ms N       send every frame N ms later than due (0..3600000)\n"
    "  --corrupt N[:OFFSET[:XOR]]\n"
    "                     XOR byte OFFSET (default 2, the LEN byte; past the end:\n"
    "                     the last byte) of the next N replies with XOR (default\n"
    "                     0xFF)\n"
    "  -h, --help         show this help and exit\n"
    "  -V, --version      show the version and exit\n"
    "\n"
    "Numbers are decimal or 0x-hex (a leading 0 does not make a number octal).\n"
    "\n"
    "Exit status: 0 after one of those signals (or --help); 1 if the pseudo-terminal or\n"
    "the link cannot be made; 2 for invalid options, an invalid group file or arm\n"
    "profile.\n";

static int usage_error(const char *fmt, const char *arg)
{
    (void)fprintf(stderr, PROG ": ");
    (void)fprintf(stderr, fmt, arg);
    (void)fprintf(stderr, "\nTry '" PROG " --help' for more information.\n");
    return EXIT_USAGE;
}

/* Parses s, the value (or, in --corrupt, a part of the value `value`) of
 * option opt, with lscctl's number parser (decimal or 0x-hex; a leading 0
 * does not make it octal) into *out, in min..max. Returns 0, or EXIT_USAGE
 * after printing why. */
static int parse_number(const char *opt, const char *value, const char *s, const char *what,
                        unsigned long min, unsigned long max, unsigned long *out)
{
    char why[160], other[160], msg[400];
    unsigned long v;
    if (lscctl_parse_uint(s, max, what, &v, why, sizeof why) == 0) {
        if (v >= min) {
            *out = v;
            return 0;
        }
        (void)snprintf(why, sizeof why, "%s %s is out of range: use %lu..%lu", what, s, min, max);
    } else if (min > 0 && *s == '-') {
        (void)snprintf(why, sizeof why, "%s '%s' is negative: use %lu..%lu", what, s, min, max);
    } else if (min > 0 && lscctl_parse_uint(s, ULONG_MAX, what, &v, other, sizeof other) == 0) {
        (void)snprintf(why, sizeof why, "%s %s is out of range: use %lu..%lu", what, s, min, max);
    }
    (void)snprintf(msg, sizeof msg, "invalid %s '%s': %s", opt, value, why);
    return usage_error("%s", msg);
}

/* ---- Options ---------------------------------------------------------------- */

typedef struct options {
    const char *link;
    const char **groups; /* the --groups files, in the order given */
    size_t ngroups;
    unsigned long baud;
    bool baud_given;
    bool fast;
    bool log;
    unsigned long battery;
    unsigned long drop;
    unsigned long delay_ms;
    unsigned long corrupt_n;
    unsigned long corrupt_offset;
    unsigned long corrupt_xor;
    long button; /* the group SIGUSR1 runs, or -1 */
    uint8_t block[LSC_SIM_SERVOS]; /* --block: lsc_sim_block_side of each servo */
    uint16_t block_at[LSC_SIM_SERVOS];
    const char *arm; /* --arm FILE, or NULL */
    const char *lx;    /* --lx IDS, or NULL */
    const char *state; /* --state FILE, or NULL */
    bool echo;         /* --echo */
    bool block_given;
} options;

enum { OPT_LINK = 256, OPT_BAUD, OPT_FAST, OPT_BATTERY, OPT_GROUPS, OPT_LOG, OPT_DROP,
       OPT_DELAY, OPT_CORRUPT, OPT_BUTTON, OPT_BLOCK, OPT_ARM, OPT_LX, OPT_STATE, OPT_ECHO };

/* --block ID:POS[:below]; returns 0 or EXIT_USAGE (message printed). */
static int parse_block(const char *arg, options *o)
{
    char id_text[16], pos_text[16];
    unsigned long id, pos;
    const char *colon = strchr(arg, ':');
    const char *side = colon != NULL ? strchr(colon + 1, ':') : NULL;
    size_t id_len = colon != NULL ? (size_t)(colon - arg) : 0;
    size_t pos_len = colon == NULL ? 0 : side != NULL ? (size_t)(side - colon - 1) : strlen(colon + 1);
    if (colon == NULL || id_len >= sizeof id_text || pos_len >= sizeof pos_text ||
        (side != NULL && strcmp(side, ":below") != 0 && strcmp(side, ":above") != 0)) {
        return usage_error("invalid --block '%s': use ID:POS, ID:POS:above or ID:POS:below", arg);
    }
    memcpy(id_text, arg, id_len);
    id_text[id_len] = '\0';
    memcpy(pos_text, colon + 1, pos_len);
    pos_text[pos_len] = '\0';
    if (parse_number("--block", arg, id_text, "servo id", 0, LSC_SIM_SERVOS - 1u, &id) != 0 ||
        parse_number("--block", arg, pos_text, "position", 0, 65535, &pos) != 0) {
        return EXIT_USAGE;
    }
    o->block[id] = (uint8_t)(side != NULL && strcmp(side, ":below") == 0 ? LSC_SIM_BLOCK_BELOW
                                                                          : LSC_SIM_BLOCK_ABOVE);
    o->block_at[id] = (uint16_t)pos;
    return 0;
}

/* N[:OFFSET[:XOR]]; returns 0 or an exit status (message printed). */
static int parse_corrupt(const char *arg, options *o)
{
    static const char *const what[] = {"count", "offset", "XOR mask"};
    static const unsigned long max[] = {UINT32_MAX, 255, 255};
    unsigned long *field[] = {&o->corrupt_n, &o->corrupt_offset, &o->corrupt_xor};
    char *copy = strdup(arg);
    char *p = copy;
    int r = 0;
    if (copy == NULL) {
        (void)fprintf(stderr, PROG ": out of memory\n");
        return 1;
    }
    for (size_t i = 0; p != NULL && r == 0; i++) {
        char *colon = strchr(p, ':');
        if (i == 2 && colon != NULL) {
            r = usage_error("invalid --corrupt '%s': N[:OFFSET[:XOR]] has at most two ':'", arg);
            break;
        }
        if (colon != NULL) {
            *colon = '\0';
        }
        r = parse_number("--corrupt", arg, p, what[i], 0, max[i], field[i]);
        p = colon != NULL ? colon + 1 : NULL;
    }
    free(copy);
    return r;
}

/* Returns -1 to go on, or an exit status. o->groups is allocated (free it)
 * when this returns -1. */
static int parse_options(int argc, char **argv, options *o)
{
    static const struct option longopts[] = {
        {"link", required_argument, NULL, OPT_LINK},
        {"baud", required_argument, NULL, OPT_BAUD},
        {"fast", no_argument, NULL, OPT_FAST},
        {"battery", required_argument, NULL, OPT_BATTERY},
        {"groups", required_argument, NULL, OPT_GROUPS},
        {"log", no_argument, NULL, OPT_LOG},
        {"drop-replies", required_argument, NULL, OPT_DROP},
        {"delay-ms", required_argument, NULL, OPT_DELAY},
        {"corrupt", required_argument, NULL, OPT_CORRUPT},
        {"button", required_argument, NULL, OPT_BUTTON},
        {"block", required_argument, NULL, OPT_BLOCK},
        {"arm", required_argument, NULL, OPT_ARM},
        {"lx", required_argument, NULL, OPT_LX},
        {"state", required_argument, NULL, OPT_STATE},
        {"echo", no_argument, NULL, OPT_ECHO},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    memset(o, 0, sizeof *o);
    o->baud = 9600;
    o->battery = LSC_SIM_BATTERY_DEFAULT;
    o->corrupt_offset = 2;
    o->corrupt_xor = 0xFF;
    o->button = -1;
    o->groups = calloc((size_t)argc, sizeof *o->groups);
    if (o->groups == NULL) {
        (void)fprintf(stderr, PROG ": out of memory\n");
        return 1;
    }
    opterr = 0;
    bool in_groups = false; /* the last option was --groups: a word is one more file */
    for (;;) {
        /* "-": the words that are not options come in order, as 1 */
        int c = getopt_long(argc, argv, "-:hV", longopts, NULL);
        if (c == -1) {
            break;
        }
        /* the value of an option that takes one (getopt never gives it as NULL) */
        const char *arg = optarg != NULL ? optarg : "";
        if (c == 1 && in_groups) {
            o->groups[o->ngroups++] = arg;
            continue;
        }
        in_groups = c == OPT_GROUPS;
        switch (c) {
        case OPT_LINK:
            if (arg[0] == '\0') {
                return usage_error("--link needs a path%s", "");
            }
            o->link = arg;
            break;
        case OPT_BAUD:
            if (parse_number("--baud", arg, arg, "baud rate", 1, 4000000, &o->baud) != 0) {
                return EXIT_USAGE;
            }
            o->baud_given = true;
            break;
        case OPT_FAST:
            o->fast = true;
            break;
        case OPT_BATTERY:
            if (parse_number("--battery", arg, arg, "millivolts", 0, 65535,
                             &o->battery) != 0) {
                return EXIT_USAGE;
            }
            break;
        case OPT_GROUPS:
            o->groups[o->ngroups++] = arg;
            break;
        case OPT_LOG:
            o->log = true;
            break;
        case OPT_DROP:
            if (parse_number("--drop-replies", arg, arg, "count", 0, UINT32_MAX,
                             &o->drop) != 0) {
                return EXIT_USAGE;
            }
            break;
        case OPT_DELAY:
            if (parse_number("--delay-ms", arg, arg, "delay", 0, 3600000,
                             &o->delay_ms) != 0) {
                return EXIT_USAGE;
            }
            break;
        case OPT_CORRUPT:
            if (parse_corrupt(arg, o) != 0) {
                return EXIT_USAGE;
            }
            break;
        case OPT_BLOCK:
            if (parse_block(arg, o) != 0) {
                return EXIT_USAGE;
            }
            o->block_given = true;
            break;
        case OPT_BUTTON: {
            unsigned long g;
            if (parse_number("--button", arg, arg, "group", 0, LSC_SIM_GROUPS - 1u,
                             &g) != 0) {
                return EXIT_USAGE;
            }
            o->button = (long)g;
            break;
        }
        case OPT_ARM:
            o->arm = arg;
            break;
        case OPT_LX:
            o->lx = arg;
            break;
        case OPT_STATE:
            if (arg[0] == '\0') {
                return usage_error("--state needs a path%s", "");
            }
            o->state = arg;
            break;
        case OPT_ECHO:
            o->echo = true;
            break;
        case 'h':
            (void)fputs(usage_text, stdout);
            (void)fputs(usage_text_more, stdout);
            return 0;
        case 'V': /* as lscctl -V prints it */
            (void)printf(PROG " %s\n", LSC_SIM_VERSION);
            return 0;
        case 1:
            return usage_error("unexpected argument '%s' (group files follow --groups)",
                               arg);
        case ':':
            return usage_error("option '%s' needs an argument", argv[optind - 1]);
        default:
            return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    if (o->fast && o->baud_given) {
        return usage_error("--fast and --baud exclude each other%s", "");
    }
    if (o->lx == NULL && (o->state != NULL || o->echo)) {
        return usage_error("%s is for a bus of servos: give --lx IDS",
                           o->state != NULL ? "--state" : "--echo");
    }
    if (o->lx != NULL) {
        const char *other = o->ngroups > 0   ? "--groups"
                            : o->button >= 0 ? "--button"
                            : o->block_given ? "--block"
                            : o->arm != NULL ? "--arm"
                                             : NULL;
        if (other != NULL) {
            return usage_error("%s is for the virtual controller, not a bus of servos (--lx)",
                               other);
        }
        if (!o->baud_given) {
            o->baud = 115200;
        }
    }
    return -1;
}

/* ---- Group files ----------------------------------------------------------------- */

/* The groups served: the text of every --groups file, one after the other,
 * parsed into one set. */
typedef struct group_file {
    char *text;
    size_t len;
    lsc_sim_step *steps;
    lsc_servo *targets;
    lsc_sim_groups groups;
} group_file;

static void group_file_free(group_file *gf)
{
    free(gf->text);
    free(gf->steps);
    free(gf->targets);
    memset(gf, 0, sizeof *gf);
}

/* Reads group text from path into *text, *lenp bytes; 0 or an exit status.
 * A regular file only: a FIFO, directory or device is refused at once. */
static int read_text(const char *path, char **text, size_t *lenp)
{
    uint8_t *data = NULL;
    lsc_file_error err = {.size = sizeof err};
    int r = lsc_file_load(path, (size_t)GROUP_FILE_MAX, &data, lenp, &err);
    if (r != 0) {
        (void)fprintf(stderr, PROG ": %s: %s\n", path, err.message);
        return r == LSC_ENOSPC ? 1 : EXIT_USAGE;
    }
    *text = (char *)data;
    return 0;
}

/* An action file (.csv, .rob, .d6a: include/lsc/files.h) as the text of one
 * group, numbered as the vendors' software numbers its files: by the number
 * its name starts with (10.rob is group 10, 7-wave.rob group 7), else 1. */
static int action_text(const char *path, char **text, size_t *lenp)
{
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    int group = lsc_file_group_number(path);
    if (group < 0 && *base >= '0' && *base <= '9') {
        (void)fprintf(stderr, PROG ": %s: the number the name starts with is not a group "
                              "(0..254)\n", path);
        return EXIT_USAGE;
    }
    lsc_action a;
    lsc_file_error err = {.size = sizeof err};
    uint8_t *out = NULL;
    int r = lsc_action_read(path, &a, &err);
    if (r == 0) {
        r = lsc_action_format(LSC_FILE_TEXT, &a, path, &out, lenp, &err);
        lsc_action_free(&a);
    }
    if (r != 0) {
        (void)fprintf(stderr, PROG ": %s: %s\n", path, err.message);
        return r == LSC_ENOSPC ? 1 : EXIT_USAGE;
    }
    *text = (char *)out;
    (void)fprintf(stderr, PROG ": %s: group %d\n", path, group >= 0 ? group : 1);
    return 0;
}

/* Parses len bytes of text into gf->groups, with storage sized from the
 * text. Returns 0, LSC_ENOSPC (out of memory: said) or the parser's code
 * (*perr says why). */
static int parse_text(const char *path, const char *text, size_t len, group_file *gf,
                      lsc_sim_parse_error *perr)
{
    /* every step needs a line, every target at least 4 characters */
    size_t lines = 1;
    for (size_t i = 0; i < len; i++) {
        lines += text[i] == '\n';
    }
    gf->steps = calloc(lines, sizeof *gf->steps);
    gf->targets = calloc(len / 4 + 1, sizeof *gf->targets);
    if (gf->steps == NULL || gf->targets == NULL) {
        (void)fprintf(stderr, PROG ": %s: out of memory\n", path);
        return LSC_ENOSPC;
    }
    (void)lsc_sim_groups_init(&gf->groups, gf->steps, lines, gf->targets, len / 4 + 1);
    return lsc_sim_groups_parse(&gf->groups, text, len, perr);
}

/* Reads, checks and parses one file into one (its text kept in one->text).
 * Returns 0 or an exit status (message printed). */
static int load_one(const char *path, group_file *one)
{
    lsc_file_format kind = lsc_file_format_of(path);
    int status = kind == LSC_FILE_CSV || kind == LSC_FILE_ROB || kind == LSC_FILE_D6A
                     ? action_text(path, &one->text, &one->len)
                     : read_text(path, &one->text, &one->len);
    if (status != 0) {
        return status;
    }
    lsc_sim_parse_error err = {0, 0, NULL};
    int r = parse_text(path, one->text, one->len, one, &err);
    if (r == LSC_ENOSPC && err.message == NULL) {
        return 1;
    }
    if (r < 0) {
        (void)fprintf(stderr, PROG ": %s:%u:%u: %s\n", path, (unsigned)err.line,
                (unsigned)err.column, err.message);
        return EXIT_USAGE;
    }
    return 0;
}

/* Loads every file of paths[0..n) into gf: each file read and parsed alone
 * (its errors name it), a group number two files define refused naming
 * both, then all the texts parsed together. Returns 0 or an exit status
 * (message printed). */
static int load_groups(const char *const *paths, size_t n, group_file *gf)
{
    size_t owner[LSC_SIM_GROUPS]; /* the file that defines each group, + 1 (0: none) */
    memset(owner, 0, sizeof owner);
    memset(gf, 0, sizeof *gf);
    for (size_t f = 0; f < n; f++) {
        group_file one;
        memset(&one, 0, sizeof one);
        int status = load_one(paths[f], &one);
        for (size_t g = 0; status == 0 && g < LSC_SIM_GROUPS; g++) {
            if (one.groups.group_steps[g] == 0u) {
                continue;
            }
            if (owner[g] != 0u) {
                (void)fprintf(stderr, PROG ": group %zu is in both %s and %s: give each group "
                                      "one file\n",
                        g, paths[owner[g] - 1u], paths[f]);
                status = EXIT_USAGE;
            }
            owner[g] = f + 1u;
        }
        char *all = status == 0 ? realloc(gf->text, gf->len + one.len + 1u) : NULL;
        if (status == 0 && all == NULL) {
            (void)fprintf(stderr, PROG ": %s: out of memory\n", paths[f]);
            status = 1;
        }
        if (status == 0) { /* one text after the other, each on lines of its own */
            memcpy(all + gf->len, one.text, one.len);
            all[gf->len + one.len] = '\n';
            gf->text = all;
            gf->len += one.len + 1u;
        }
        group_file_free(&one);
        if (status != 0) {
            return status;
        }
    }
    lsc_sim_parse_error err = {0, 0, NULL};
    int r = parse_text(n > 0 ? paths[0] : "--groups", gf->text, gf->len, gf, &err);
    if (r == LSC_ENOSPC && err.message == NULL) {
        return 1;
    }
    if (r < 0) { /* each file parsed alone: only the sum can be too large */
        (void)fprintf(stderr, PROG ": the --groups files together: %s\n", err.message);
        return EXIT_USAGE;
    }
    return 0;
}

/* ---- Logging ------------------------------------------------------------------- */

/* One event of the virtual controller or (bus) of the bus of servos, which
 * does not beep: it discards a bad frame silently. */
static void log_line(const lsc_sim_event *ev, bool bus)
{
    static const char *const names[] = {"?", "rx", "tx", "beep", "ignored", "dropped", "noise"};
    const char *name = (unsigned)ev->kind < sizeof names / sizeof names[0] ? names[ev->kind] : "?";
    if (bus && ev->kind == LSC_SIM_EV_BEEP) {
        name = "discarded";
    }
    (void)fprintf(stderr, PROG ": %llu.%06llu %s", (unsigned long long)(ev->time_us / 1000000u),
            (unsigned long long)(ev->time_us % 1000000u), name);
    if (!bus && ev->kind == LSC_SIM_EV_BEEP) {
        (void)fputs(" (two beeps)", stderr);
    }
    if (ev->text != NULL) {
        (void)fprintf(stderr, " %s%s", ev->text, ev->len > 0 ? ":" : "");
    }
    for (size_t i = 0; i < ev->len; i++) {
        (void)fprintf(stderr, " %02X", ev->bytes[i]);
    }
    (void)fputc('\n', stderr);
}

static void log_event(void *ctx, const lsc_sim_event *ev)
{
    (void)ctx;
    log_line(ev, false);
}

static void log_bus_event(void *ctx, const lsc_sim_event *ev)
{
    (void)ctx;
    log_line(ev, true);
}

/* ---- Serving --------------------------------------------------------------------- */

static uint64_t mono_us(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

static int make_link(const char *target, const char *path)
{
    struct stat st;
    if (lstat(path, &st) == 0) {
        if (!S_ISLNK(st.st_mode)) {
            (void)fprintf(stderr, PROG ": --link %s: exists and is not a symlink\n", path);
            return -1;
        }
        if (unlink(path) < 0) {
            (void)fprintf(stderr, PROG ": --link %s: %s\n", path, strerror(errno));
            return -1;
        }
    }
    if (symlink(target, path) < 0) {
        (void)fprintf(stderr, PROG ": --link %s: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

/* Removes the link if it still points at target. */
static void remove_link(const char *target, const char *path)
{
    char buf[PATH_MAX];
    ssize_t n = readlink(path, buf, sizeof buf - 1);
    if (n >= 0) {
        buf[n] = '\0';
        if (strcmp(buf, target) == 0) {
            (void)unlink(path);
        }
    }
}

/* The read end of the pipe the signals write to (signal_pipe.h), or -1. */
static int setup_signals(bool button, bool bus)
{
    /* each of these ends serving cleanly (the --link is removed); --button:
     * SIGUSR1 presses it (serve tells it from the stops); --lx: SIGUSR2
     * power-cycles the bus */
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1};
    static const int bus_sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR2};
    const size_t stops = 4;
    if (bus) {
        return signal_pipe_open(bus_sigs, stops + 1u);
    }
    return signal_pipe_open(sigs, button ? stops + 1u : stops);
}

/* Runs the model on master until a signal, read from sig_fd, that stops it
 * (SIGUSR1 runs group button instead, when button >= 0); returns the exit
 * status. */
static int serve(lsc_sim *sim, int master, int sig_fd, long button)
{
    uint8_t out[LSC_SIM_OUT_BYTES];
    size_t out_len = 0;
    size_t out_off = 0;
    uint64_t start = mono_us();

    for (;;) {
        uint64_t now = mono_us() - start;
        if (now > lsc_sim_now_us(sim)) {
            lsc_sim_advance_us(sim, now - lsc_sim_now_us(sim));
        }
        if (out_off == out_len) {
            out_off = 0;
            out_len = lsc_sim_read(sim, out, sizeof out);
        }
        while (out_off < out_len) {
            ssize_t n = write(master, out + out_off, out_len - out_off);
            if (n < 0) {
                if (errno == EINTR) {
                    continue;
                }
                if (errno != EAGAIN && errno != EIO) {
                    (void)fprintf(stderr, PROG ": write to the pseudo-terminal: %s\n",
                            strerror(errno));
                    return 1;
                }
                break; /* nobody reads: try again later */
            }
            out_off += (size_t)n;
        }

        int timeout = -1;
        uint64_t next = lsc_sim_next_event_us(sim);
        if (out_off < out_len) {
            timeout = 10; /* output is stuck: retry soon */
        } else if (next != LSC_SIM_TIME_NEVER) {
            uint64_t ms = (next + 999u) / 1000u;
            timeout = ms > 60000u ? 60000 : (int)ms;
        }
        struct pollfd fds[2] = {{master, POLLIN, 0}, {sig_fd, POLLIN, 0}};
        int r = poll(fds, 2, timeout);
        if (r < 0 && errno != EINTR) {
            (void)fprintf(stderr, PROG ": poll: %s\n", strerror(errno));
            return 1;
        }
        if (r > 0 && (fds[1].revents & POLLIN) != 0) {
            unsigned char sig = 0;
            if (read(sig_fd, &sig, 1) == 1 && sig == SIGUSR1 && button >= 0) {
                /* the same rules as a host's run frame */
                (void)lsc_sim_group_run(sim, (uint8_t)button, 1);
                continue;
            }
            return 0;
        }
        if (r > 0 && (fds[0].revents & POLLIN) != 0) {
            uint8_t in[512];
            ssize_t n = read(master, in, sizeof in);
            if (n > 0) {
                now = mono_us() - start;
                if (now > lsc_sim_now_us(sim)) {
                    lsc_sim_advance_us(sim, now - lsc_sim_now_us(sim));
                }
                (void)lsc_sim_feed(sim, in, (size_t)n);
            }
        }
    }
}

int main(int argc, char **argv)
{
    static lsc_sim sim;
    static lsc_lxbus bus;
    static group_file gf;
    options o;
    int status = parse_options(argc, argv, &o);
    if (status >= 0) {
        free(o.groups);
        return status;
    }
    if (o.lx != NULL) {
        (void)lsc_lxbus_init(&bus);
        status = lsc_sim_lx_setup(&bus, PROG, o.lx, o.state);
        if (status >= 0) {
            free(o.groups);
            return status;
        }
        (void)lsc_lxbus_set_vin(&bus, (uint16_t)o.battery);
        lsc_lxbus_set_baud(&bus, o.fast ? 0u : (uint32_t)o.baud);
        lsc_lxbus_set_echo(&bus, o.echo);
        lsc_lxbus_fault_drop(&bus, (uint32_t)o.drop);
        lsc_lxbus_fault_delay(&bus, (uint32_t)o.delay_ms);
        lsc_lxbus_fault_corrupt(&bus, (uint32_t)o.corrupt_n, (uint8_t)o.corrupt_offset,
                                (uint8_t)o.corrupt_xor);
        if (o.log) {
            lsc_lxbus_set_log(&bus, log_bus_event, NULL);
        }
    }
    (void)lsc_sim_init(&sim);
    lsc_sim_set_battery(&sim, (uint16_t)o.battery);
    lsc_sim_set_baud(&sim, o.fast ? 0u : (uint32_t)o.baud);
    lsc_sim_fault_drop(&sim, (uint32_t)o.drop);
    lsc_sim_fault_delay(&sim, (uint32_t)o.delay_ms);
    lsc_sim_fault_corrupt(&sim, (uint32_t)o.corrupt_n, (uint8_t)o.corrupt_offset,
                          (uint8_t)o.corrupt_xor);
    if (o.log) {
        lsc_sim_set_log(&sim, log_event, NULL);
    }
    if (o.arm != NULL) {
        char why[LSC_ARM_MESSAGE_MAX];
        lsc_arm *arm = NULL;
        int r = lsc_arm_open(o.arm, &arm, why, sizeof why);
        if (r != 0) {
            (void)fprintf(stderr, PROG ": --arm: %s\n", why);
            free(o.groups);
            return r == LSC_ENOSPC ? 1 : EXIT_USAGE;
        }
        (void)lsc_arm_stand_in(arm, &sim);
        lsc_arm_free(arm);
    }
    /* after --arm: a block narrows where the arm's servo can go */
    for (size_t id = 0; id < LSC_SIM_SERVOS; id++) {
        if (o.block[id] != LSC_SIM_BLOCK_NONE) {
            (void)lsc_sim_block(&sim, (uint8_t)id, o.block_at[id], (lsc_sim_block_side)o.block[id]);
        }
    }
    if (o.ngroups > 0) {
        status = load_groups(o.groups, o.ngroups, &gf);
        if (status != 0) {
            free(o.groups);
            group_file_free(&gf);
            return status;
        }
        lsc_sim_set_groups(&sim, &gf.groups);
    }
    free(o.groups);
    if (o.button >= 0 && (o.ngroups == 0 || gf.groups.group_steps[o.button] == 0u)) {
        (void)fprintf(stderr,
                PROG ": --button %ld: no group %ld is loaded (load it with --groups FILE)\n",
                o.button, o.button);
        group_file_free(&gf);
        return EXIT_USAGE;
    }

    int master;
    int slave;
    char name[PATH_MAX];
    if (openpty(&master, &slave, name, NULL, NULL) < 0) {
        (void)fprintf(stderr, PROG ": openpty: %s\n", strerror(errno));
        return 1;
    }
    struct termios tio;
    if (tcgetattr(slave, &tio) == 0) {
        cfmakeraw(&tio);
        (void)cfsetispeed(&tio, o.lx != NULL ? B115200 : B9600);
        (void)cfsetospeed(&tio, o.lx != NULL ? B115200 : B9600);
        (void)tcsetattr(slave, TCSANOW, &tio);
    }
    (void)fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
    (void)fcntl(master, F_SETFD, FD_CLOEXEC);
    (void)fcntl(slave, F_SETFD, FD_CLOEXEC);
    int sig_fd = setup_signals(o.button >= 0, o.lx != NULL);
    if (sig_fd < 0) {
        (void)fprintf(stderr, PROG ": signals: %s\n", strerror(errno));
        return 1;
    }
    if (o.link != NULL && make_link(name, o.link) < 0) {
        return 1;
    }
    (void)printf("%s\n", name);
    (void)fflush(stdout);

    /* the slave stays open here so the line never hangs up between clients */
    status = o.lx != NULL ? lsc_sim_lx_serve(&bus, PROG, master, sig_fd, o.state)
                          : serve(&sim, master, sig_fd, o.button);
    if (o.link != NULL) {
        remove_link(name, o.link);
    }
    (void)close(master);
    (void)close(slave);
    group_file_free(&gf);
    return status;
}
