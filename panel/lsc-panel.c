/* lsc-panel: a control panel in the browser for one controller (lsc-panel.1):
 * the command line, the token, the signals. */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>

#include <microhttpd.h>

#include "lsc/calibrated.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/player.h"
#include "lsc/kinematics.h"
#include "panel.h"

enum { EXIT_OK = 0, EXIT_FAIL = 1, EXIT_USAGE = 2, EXIT_TIMEOUT = 3, EXIT_BUSY = 4 };

static const char usage[] =
    "Usage: lsc-panel [--port NAME] [--arm NAME|FILE] [--ids LIST] [--listen ADDR:PORT] [--dir DIR]\n"
    "Serves a control panel for one controller to a browser and prints the address\n"
    "to open (with its token) on standard output.\n"
    "\n"
    "  --port NAME         the controller: a serial port, hid, hid:SERIAL, sim, lscd:NAME\n"
    "                      or lscd:PATH (default: $LSC_PORT, else the one present)\n"
    "  --arm NAME|FILE     an arm profile: joints by name, in degrees, checked against\n"
    "                      its limits (a NAME such as xarm as lscctl --arm takes it)\n"
    "                      (default: $LSC_ARM unless --ids is given, else the\n"
    "                      profile calibrated for the arm: lscctl calibrate)\n"
    "  --ids LIST          without --arm, the servos shown (default 1-6)\n"
    "  --listen ADDR:PORT  where to listen (default 127.0.0.1:8480; port 0: any free)\n"
    "  --dir DIR           where action files are saved and opened (default:\n"
    "                      $XDG_DATA_HOME/lsc/panel, else ~/.local/share/lsc/panel)\n"
    "  --timeout MS        a request's reply timeout (default 1000)\n"
    "  --help, --version\n";

static int fail(int code, const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "lsc-panel: ");
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    return code;
}

static int exit_code(int r)
{
    switch (r) {
    case LSC_EINVAL:
        return EXIT_USAGE;
    case LSC_ETIMEOUT:
        return EXIT_TIMEOUT;
    case LSC_EBUSY:
        return EXIT_BUSY;
    default:
        return EXIT_FAIL;
    }
}

static bool make_token(char *out)
{
    unsigned char raw[PANEL_TOKEN_LEN / 2u];
    size_t got = 0;
    while (got < sizeof raw) {
        ssize_t n = getrandom(raw + got, sizeof raw - got, 0);
        if (n < 0 && errno != EINTR) {
            return false;
        }
        got += n > 0 ? (size_t)n : 0u;
    }
    for (size_t i = 0; i < sizeof raw; i++) {
        (void)snprintf(out + 2u * i, 3, "%02x", raw[i]);
    }
    return true;
}

/* Creates path's missing directories (mode 0700, as the XDG base
 * directories are); false with errno on failure. */
static bool make_dirs(char *path)
{
    for (char *s = strchr(path + 1, '/');; s = strchr(s + 1, '/')) {
        if (s != NULL) {
            *s = '\0';
        }
        int r = mkdir(path, 0700);
        int e = errno;
        if (s != NULL) {
            *s = '/';
        }
        if (r != 0 && e != EEXIST) {
            errno = e;
            return false;
        }
        if (s == NULL) {
            return true;
        }
    }
}

/* The default --dir: $XDG_DATA_HOME/lsc/panel (an absolute $XDG_DATA_HOME;
 * the XDG base directory rule), else $HOME/.local/share/lsc/panel, created
 * when missing; never the working directory. */
static bool default_dir(char *out, size_t cap, char *why, size_t whylen)
{
    const char *xdg = getenv("XDG_DATA_HOME");
    const char *home = getenv("HOME");
    int n;
    if (xdg != NULL && xdg[0] == '/') {
        n = snprintf(out, cap, "%s/lsc/panel", xdg);
    } else if (home != NULL && home[0] == '/') {
        n = snprintf(out, cap, "%s/.local/share/lsc/panel", home);
    } else {
        (void)snprintf(why, whylen, "no --dir, and neither $XDG_DATA_HOME nor $HOME names a "
                                    "directory: give --dir DIR for the action files");
        return false;
    }
    if (n < 0 || (size_t)n >= cap) {
        (void)snprintf(why, whylen, "the default directory for the action files is too long: "
                                    "give --dir DIR");
        return false;
    }
    if (!make_dirs(out)) {
        (void)snprintf(why, whylen, "cannot create %s for the action files: %s (give --dir DIR)",
                       out, strerror(errno));
        return false;
    }
    return true;
}

/* The directory as the page shows it: ~/... under $HOME. */
static void shown_dir(panel *p)
{
    const char *home = getenv("HOME");
    size_t n = home ? strlen(home) : 0u;
    while (n > 1u && home[n - 1u] == '/') {
        n--;
    }
    if (n > 1u && home[0] == '/' && strncmp(p->dir, home, n) == 0 && p->dir[n] == '/') {
        (void)snprintf(p->dir_shown, sizeof p->dir_shown, "~%s", p->dir + n);
    } else {
        (void)snprintf(p->dir_shown, sizeof p->dir_shown, "%s", p->dir);
    }
}

typedef struct args {
    const char *port, *arm, *ids, *listen, *dir;
    unsigned long timeout;
} args;

/* Returns -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, args *a)
{
    static const struct option longs[] = {
        {"port", required_argument, NULL, 'p'},   {"arm", required_argument, NULL, 'a'},
        {"ids", required_argument, NULL, 'i'},    {"listen", required_argument, NULL, 'l'},
        {"dir", required_argument, NULL, 'd'},    {"timeout", required_argument, NULL, 't'},
        {"help", no_argument, NULL, 'h'},         {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0}};
    int o;
    opterr = 0;
    while ((o = getopt_long(argc, argv, "", longs, NULL)) != -1) {
        char *end;
        switch (o) {
        case 'p': a->port = optarg; break;
        case 'a': a->arm = optarg; break;
        case 'i': a->ids = optarg; break;
        case 'l': a->listen = optarg; break;
        case 'd': a->dir = optarg; break;
        case 't':
            errno = 0;
            a->timeout = strtoul(optarg, &end, 10);
            if (errno || *end || optarg[0] < '0' || optarg[0] > '9' || a->timeout == 0 ||
                a->timeout > 600000u) {
                return fail(EXIT_USAGE, "--timeout: '%s' is not 1..600000 (ms)%s", optarg, "");
            }
            break;
        case 'h': fputs(usage, stdout); return EXIT_OK;
        case 'V': printf("lsc-panel %s\n", LSC_PANEL_VERSION); return EXIT_OK;
        default:
            return fail(EXIT_USAGE, "unknown or incomplete option '%s' (lsc-panel --help)%s",
                        argv[optind - 1], "");
        }
    }
    if (optind < argc) {
        return fail(EXIT_USAGE, "unexpected argument '%s' (lsc-panel --help)%s", argv[optind], "");
    }
    if (a->arm != NULL && a->ids != NULL) {
        return fail(EXIT_USAGE, "--ids and --arm go apart: the profile lists the joints%s%s", "",
                    "");
    }
    if (a->arm == NULL && a->ids == NULL) {
        a->arm = lsc_device_env_arm(); /* $LSC_ARM, as lscctl takes it (NULL: none) */
    }
    return -1;
}

/* The servos shown: the profile's joints (--arm, else the calibrated
 * profile of the controller when it has one), or --ids. */
static int servos(panel *p, args *a)
{
    static char calibrated[PANEL_PATH_MAX];
    char why[LSC_ARM_MESSAGE_MAX];
    if (a->arm == NULL && a->ids == NULL &&
        lsc_calibrated_find(a->port, calibrated, sizeof calibrated) == 0) {
        a->arm = calibrated;
        p->arm_calibrated = true;
    }
    /* the file, for calibration to start from */
    static char file[PANEL_PATH_MAX];
    p->arm_given = a->arm;
    p->arm_path = a->arm != NULL && lsc_arm_path(a->arm, file, sizeof file, NULL, 0) == 0 ? file
                                                                                       : NULL;
    if (a->arm != NULL) {
        int r = lsc_arm_open(a->arm, &p->arm, why, sizeof why);
        if (r != 0) {
            return fail(r == LSC_ENOSPC ? EXIT_FAIL : EXIT_USAGE, "%s%s", why, "");
        }
        p->nids = lsc_arm_count(p->arm);
        for (size_t i = 0; i < p->nids && i < LSC_PLAYER_SERVOS_MAX; i++) {
            p->ids[i] = lsc_arm_joint(p->arm, i)->id;
        }
        return -1;
    }
    int n = lsc_device_parse_ids(NULL, a->ids ? a->ids : "1-6", p->ids, LSC_PLAYER_SERVOS_MAX,
                                 why, sizeof why);
    if (n < 0) {
        return fail(EXIT_USAGE, "--ids: %s%s", why, "");
    }
    p->nids = (size_t)n;
    return -1;
}

static int serve(panel *p, const args *a)
{
    char why[256];
    p->cfg = lsc_device_config_new();
    if (p->cfg == NULL) {
        return fail(EXIT_FAIL, "out of memory%s%s", "", "");
    }
    (void)lsc_device_config_set_timeout_ms(p->cfg, (uint32_t)a->timeout); /* (1..600000) */
    int r = lsc_device_open(a->port, p->cfg, &p->dev);
    if (r != 0) {
        /* no handle: lsc_device_error(NULL) is this thread's failed open */
        int code = fail(exit_code(r), "%s%s", lsc_device_error(NULL), "");
        return code;
    }
    if (p->arm != NULL && lsc_device_set_arm(p->dev, p->arm) != 0) {
        return fail(EXIT_FAIL, "out of memory%s%s", "", "");
    }
    if (p->arm != NULL) { /* a profile with chain: and links: lines: the hand's section */
        lsc_kin_chain chain;
        char no[LSC_ARM_MESSAGE_MAX];
        p->geometry = lsc_arm_chain(p->arm, &chain, NULL, no, sizeof no) == 0;
    }
    /* what the HTTP threads show of the device, which only the device thread uses */
    (void)snprintf(p->dev_name, sizeof p->dev_name, "%s", lsc_device_name(p->dev));
    /* where a calibration goes: the calibrated profile of this controller */
    char key[LSC_CALIBRATED_KEY_MAX];
    if (lsc_calibrated_key(a->port, key, sizeof key) != 0 ||
        lsc_calibrated_path(key, p->calib_out, sizeof p->calib_out) != 0) {
        p->calib_out[0] = '\0';
    }
    p->dev_kind = lsc_device_kind_of(p->dev);
    p->ngroups = lsc_device_groups(p->dev, p->groups, sizeof p->groups);
    p->ngroups = p->ngroups < sizeof p->groups ? p->ngroups : sizeof p->groups;
    /* the device thread first: a request may come as soon as the server listens */
    if (panel_dev_start(p) != 0) {
        return fail(EXIT_FAIL, "cannot start the device thread%s%s", "", "");
    }
    struct MHD_Daemon *d = panel_http_start(p, a->listen ? a->listen : "127.0.0.1:8480", why,
                                            sizeof why);
    if (d == NULL) {
        panel_dev_stop(p);
        return fail(a->listen && strncmp(why, "--listen", 8) == 0 ? EXIT_USAGE : EXIT_FAIL,
                    "%s%s", why, "");
    }
    const char *shown = p->wildcard ? (strchr(p->host, ':') ? "[::1]" : "127.0.0.1") : p->host;
    printf("http://%s:%u/?token=%s\n", shown, (unsigned)p->port, p->token);
    fflush(stdout);

    sigset_t set;
    (void)sigemptyset(&set);
    (void)sigaddset(&set, SIGINT);
    (void)sigaddset(&set, SIGTERM);
    (void)sigaddset(&set, SIGHUP);
    int sig = 0;
    (void)sigwait(&set, &sig);

    /* no new connection; the event streams and the device thread end (a play
     * stops, a command waiting is answered); the requests under way (a save)
     * are answered; then the server stops */
    panel_http_quiesce(p, d);
    panel_set_stopping(p);
    panel_http_stop(p, d);
    panel_dev_stop(p);
    return EXIT_OK;
}

int main(int argc, char **argv)
{
    args a = {0};
    int code = parse_args(argc, argv, &a);
    if (code >= 0) {
        return code;
    }
    /* every thread leaves these signals to sigwait in serve() */
    sigset_t set;
    (void)sigemptyset(&set);
    (void)sigaddset(&set, SIGINT);
    (void)sigaddset(&set, SIGTERM);
    (void)sigaddset(&set, SIGHUP);
    (void)pthread_sigmask(SIG_BLOCK, &set, NULL);
    (void)signal(SIGPIPE, SIG_IGN);

    panel *p = calloc(1, sizeof *p);
    if (p == NULL) {
        return fail(EXIT_FAIL, "out of memory%s%s", "", "");
    }
    static char dir[PANEL_PATH_MAX];
    if (a.dir == NULL) { /* the default: created */
        char why[PANEL_PATH_MAX + 128];
        if (!default_dir(dir, sizeof dir, why, sizeof why)) {
            free(p);
            return fail(EXIT_USAGE, "%s%s", why, "");
        }
        p->dir = dir;
    } else {
        p->dir = a.dir;
    }
    struct stat st;
    errno = 0;
    if (stat(p->dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        int e = errno;
        code = fail(EXIT_USAGE, "--dir %s: %s", p->dir, e ? strerror(e) : "not a directory");
        free(p);
        return code;
    }
    shown_dir(p);
    if (!make_token(p->token)) {
        free(p);
        return fail(EXIT_FAIL, "cannot make a token: %s%s", strerror(errno), "");
    }
    pthread_mutex_init(&p->m, NULL);
    pthread_mutex_init(&p->cmd_lock, NULL);
    pthread_mutex_init(&p->ev_m, NULL);
    pthread_cond_init(&p->done_cv, NULL);
    pthread_cond_init(&p->ev_cv, NULL);
    p->next_seq = 1;
    p->listen_fd = -1;
    code = servos(p, &a);
    if (code < 0) {
        code = serve(p, &a);
    }
    lsc_device_close(p->dev);
    lsc_device_config_free(p->cfg);
    lsc_arm_free(p->arm);
    pthread_mutex_destroy(&p->m);
    pthread_mutex_destroy(&p->cmd_lock);
    pthread_mutex_destroy(&p->ev_m);
    pthread_cond_destroy(&p->done_cv);
    pthread_cond_destroy(&p->ev_cv);
    free(p);
    return code;
}
