/* lscd: one process owns a controller and any number of programs share it
 * over a Unix socket (lscd.8, docs/lscd-protocol.md). This file: the command
 * line, the listening socket (made here, or passed by systemd: LISTEN_FDS),
 * signals; the work is in lscd_server.c (and its parts) and lscd_dev.c. */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "lscctl_parse.h"
#include "lscd.h"
#include "signal_pipe.h"
#include "lsc/env.h"
#include "lsc/lscd.h"

#define LISTEN_FDS_START 3 /* sd_listen_fds(3): the first passed descriptor */

static const char usage_text[] =
    "Usage: " LSCD_PROG " --port PORT [OPTION]...\n"
    "       " LSCD_PROG " --instance NAME [OPTION]...\n"
    "Own one LSC servo controller and share it with any number of programs over a\n"
    "Unix socket: their frames go to the controller one at a time, each reply to\n"
    "the program that asked, notifications to every program that listens.\n"
    "Clients name it lscd:NAME (the socket DIR/NAME.sock) or lscd:PATH.\n"
    "\n"
    "Options:\n"
    "  --port PORT        the controller: a serial port (/dev/ttyUSB0), hid,\n"
    "                     hid:SERIAL, a hidraw node, or sim (the built-in virtual\n"
    "                     controller); or a bus of servos: lx:PATH, lx:sim\n"
    "  --instance NAME    the port NAME stands for (systemd's lscd@NAME): sim, hid,\n"
    "                     hid-SERIAL (hid:SERIAL), lx-sim (lx:sim), lx-NAME\n"
    "                     (lx:/dev/NAME), else /dev/NAME\n"
    "  --socket PATH      listen on PATH (default: DIR/NAME.sock, DIR $LSC_LSCD_DIR\n"
    "                     or /run/lsc, NAME from the port: ttyUSB0, hid-SERIAL, sim);\n"
    "                     ignored when systemd passes the socket (LISTEN_FDS)\n"
    "  --mode OCTAL       permissions of the socket lscd makes (default 0660)\n"
    "  --baud N           serial ports: baud rate (default 9600)\n"
    "  --timeout MS       how long a client's frame may take, from its arrival to\n"
    "                     its reply, unless the client says (default 1000)\n"
    "  --lease-max MS     the longest lease a client gets (default 60000)\n"
    "  --client-queue N   bytes kept for a client that does not read, beyond what\n"
    "                     its socket holds (default 65536, at least 4096); more is\n"
    "                     dropped, counted and told\n"
    "  --max-clients N    clients served at once (default 1000); one more is told\n"
    "                     lscd is full and disconnected (the open file limit,\n"
    "                     ulimit -n or LimitNOFILE=, must allow N + 16)\n"
    "  --retry MS         after the controller is lost, try to open it again every\n"
    "                     MS ms (default 1000)\n"
    "  --exit-on-loss     exit 1 when the controller is lost instead (for a service\n"
    "                     manager that restarts lscd)\n"
    "  -v, --verbose      log every client, lease and controller event\n"
    "  -h, --help         show this help and exit\n"
    "  -V, --version      show the version and exit\n"
    "\n"
    "Runs in the foreground; stops on SIGTERM, SIGINT or SIGHUP. No TCP: for a\n"
    "remote machine, forward the socket with ssh -L (lscd(8)).\n"
    "\n"
    "Exit status: 0 stopped by a signal; 1 the controller could not be opened or\n"
    "was lost with --exit-on-loss, or the socket failed; 2 invalid command line;\n"
    "4 the port is busy (another program holds it).\n";

static int usage_error(const char *fmt, const char *arg)
{
    (void)fprintf(stderr, LSCD_PROG ": ");
    (void)fprintf(stderr, fmt, arg);
    (void)fprintf(stderr, " (see " LSCD_PROG " --help)\n");
    return LSCD_EXIT_USAGE;
}

static int number(const char *opt, const char *s, unsigned long min, unsigned long max,
                  uint32_t *out)
{
    char why[128];
    unsigned long v;
    if (lscctl_parse_range(s, min, max, opt, &v, why, sizeof why) != 0) {
        return usage_error("%s", why);
    }
    *out = (uint32_t)v;
    return 0;
}

static int mode_of(const char *s, unsigned *out)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(s, &end, 8);
    if (*s == '\0' || *end != '\0' || errno != 0 || v > 0777u || s[0] == '-' || s[0] == '+') {
        return usage_error("--mode: '%s' is not an octal mode 0..0777", s);
    }
    *out = (unsigned)v;
    return 0;
}

enum { OPT_PORT = 256, OPT_INSTANCE, OPT_SOCKET, OPT_MODE, OPT_BAUD, OPT_TIMEOUT, OPT_LEASE_MAX,
       OPT_QUEUE, OPT_RETRY, OPT_EXIT_ON_LOSS, OPT_MAX_CLIENTS };

static const struct option options[] = {
    {"port", required_argument, NULL, OPT_PORT},
    {"instance", required_argument, NULL, OPT_INSTANCE},
    {"socket", required_argument, NULL, OPT_SOCKET},
    {"mode", required_argument, NULL, OPT_MODE},
    {"baud", required_argument, NULL, OPT_BAUD},
    {"timeout", required_argument, NULL, OPT_TIMEOUT},
    {"lease-max", required_argument, NULL, OPT_LEASE_MAX},
    {"client-queue", required_argument, NULL, OPT_QUEUE},
    {"retry", required_argument, NULL, OPT_RETRY},
    {"max-clients", required_argument, NULL, OPT_MAX_CLIENTS},
    {"exit-on-loss", no_argument, NULL, OPT_EXIT_ON_LOSS},
    {"verbose", no_argument, NULL, 'v'},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, 'V'},
    {NULL, 0, NULL, 0},
};

/* Parses the command line into cfg; returns -1 to go on, else an exit code. */
static int parse_args(int argc, char **argv, lscd_config *cfg, char *port_buf, size_t port_cap,
                      const char **socket_opt, const char **instance)
{
    int c;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":vhV", options, NULL)) != -1) {
        int r = 0;
        switch (c) {
        case OPT_PORT: cfg->port = optarg; break;
        case OPT_INSTANCE: *instance = optarg; break;
        case OPT_SOCKET: *socket_opt = optarg; break;
        case OPT_MODE: r = mode_of(optarg, &cfg->mode); break;
        case OPT_BAUD: r = number("--baud", optarg, 1, 4000000, &cfg->baud); break;
        case OPT_TIMEOUT: r = number("--timeout", optarg, 1, LSCD_TIMEOUT_MAX, &cfg->timeout_ms); break;
        case OPT_LEASE_MAX: r = number("--lease-max", optarg, 1, 86400000, &cfg->lease_max_ms); break;
        case OPT_QUEUE:
            r = number("--client-queue", optarg, LSCD_QUEUE_MIN, 64ul * 1024 * 1024, &cfg->client_queue);
            break;
        case OPT_RETRY: r = number("--retry", optarg, 1, 3600000, &cfg->retry_ms); break;
        case OPT_MAX_CLIENTS: r = number("--max-clients", optarg, 1, 100000, &cfg->max_clients); break;
        case OPT_EXIT_ON_LOSS: cfg->exit_on_loss = true; break;
        case 'v': cfg->verbose = true; break;
        case 'h': (void)fputs(usage_text, stdout); return LSCD_EXIT_OK;
        case 'V': (void)printf(LSCD_PROG " %s\n", LSCD_VERSION); return LSCD_EXIT_OK;
        case ':': return usage_error("%s needs a value", argv[optind - 1]);
        default:
            return usage_error("unknown option '%s'", argv[optind - 1]);
        }
        if (r != 0) {
            return r;
        }
    }
    if (optind < argc) {
        return usage_error("unexpected argument '%s'", argv[optind]);
    }
    if (*instance != NULL) {
        if (cfg->port != NULL) {
            return usage_error("%s", "--port and --instance: give one of them");
        }
        if (lsc_lscd_port_of_name(*instance, port_buf, port_cap) < 0) {
            return usage_error("--instance: '%s' is not a port name (sim, hid, hid-SERIAL, "
                               "ttyUSB0, ...)", *instance);
        }
        cfg->port = port_buf;
    }
    if (cfg->port == NULL || cfg->port[0] == '\0') {
        return usage_error("%s", "which controller? give --port PORT");
    }
    return -1;
}

/* ---- The socket -------------------------------------------------------------------- */

/* systemd's socket (sd_listen_fds semantics, without libsystemd): -1 if none
 * was passed, -2 after an error message. */
static int passed_socket(void)
{
    const char *pid = getenv("LISTEN_PID"), *fds = getenv("LISTEN_FDS");
    if (pid == NULL || fds == NULL) {
        return -1;
    }
    char *end;
    unsigned long p = strtoul(pid, &end, 10);
    if (*end != '\0' || p != (unsigned long)getpid()) {
        return -1; /* meant for another process */
    }
    unsigned long n = strtoul(fds, &end, 10);
    (void)unsetenv("LISTEN_PID");
    (void)unsetenv("LISTEN_FDS");
    (void)unsetenv("LISTEN_FDNAMES");
    if (*end != '\0' || n == 0u) {
        return -1;
    }
    if (n != 1u) {
        lscd_log("systemd passed %lu sockets: lscd serves one (a single ListenStream=)", n);
        return -2;
    }
    int fd = LISTEN_FDS_START, type = 0;
    socklen_t len = sizeof type;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_STREAM) {
        lscd_log("the socket systemd passed is not a stream socket (ListenStream=)");
        return -2;
    }
#ifdef SO_ACCEPTCONN
    int listening = 0;
    len = sizeof listening;
    if (getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &len) == 0 && !listening) {
        lscd_log("the socket systemd passed is not listening (Accept=no is needed)");
        return -2;
    }
#endif
    (void)fcntl(fd, F_SETFD, FD_CLOEXEC);
    return fd;
}

/* Makes the directory of the default socket (only its last component). */
static void make_dir_of(const char *path)
{
    char dir[LSC_LSCD_PATH_MAX];
    const char *slash = strrchr(path, '/');
    if (slash == NULL || slash == path || (size_t)(slash - path) >= sizeof dir) {
        return;
    }
    memcpy(dir, path, (size_t)(slash - path));
    dir[slash - path] = '\0';
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        lscd_log("cannot make %s: %s", dir, strerror(errno));
    }
}

static int listen_on(const char *path, unsigned mode)
{
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    if (strlen(path) >= sizeof addr.sun_path) {
        lscd_log("%s: a socket path has at most %u bytes", path,
                 (unsigned)sizeof addr.sun_path - 1u);
        return -1;
    }
    memcpy(addr.sun_path, path, strlen(path) + 1u);
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    if (fd < 0) {
        lscd_log("socket: %s", strerror(errno));
        return -1;
    }
    (void)fcntl(fd, F_SETFD, FD_CLOEXEC);
    if (bind(fd, (const struct sockaddr *)&addr, sizeof addr) != 0 && errno == EADDRINUSE) {
        /* a socket file is there: a running lscd's, or one left by a killed one */
        int probe = socket(AF_UNIX, SOCK_STREAM, 0);
        bool alive = probe >= 0 && connect(probe, (const struct sockaddr *)&addr, sizeof addr) == 0;
        if (probe >= 0) {
            (void)close(probe);
        }
        if (alive) {
            lscd_log("%s: another lscd serves this socket", path);
            (void)close(fd);
            return -1;
        }
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISSOCK(st.st_mode)) {
            (void)unlink(path);
        }
        errno = EADDRINUSE;
        if (bind(fd, (const struct sockaddr *)&addr, sizeof addr) == 0) {
            errno = 0;
        }
    } else {
        errno = 0;
    }
    if (errno != 0) {
        lscd_log("cannot listen on %s: %s%s", path, strerror(errno),
                 errno == EACCES ? " (run lscd as root for /run/lsc, or give --socket PATH)" : "");
        (void)close(fd);
        return -1;
    }
    if (chmod(path, (mode_t)mode) != 0 || listen(fd, SOMAXCONN) != 0) {
        lscd_log("%s: %s", path, strerror(errno));
        (void)unlink(path);
        (void)close(fd);
        return -1;
    }
    return fd;
}

/* A serial port's record (lsc/lscd.h): programs that open the port are sent
 * to this socket wherever it is. Returns whether it was written (record[cap]
 * its path, removed at the end). */
static bool record_socket(const lscd_config *cfg, const lsc_device *d, char *record, size_t cap)
{
    char name[LSC_LSCD_NAME_MAX], usual[LSC_LSCD_PATH_MAX];
    if (lsc_device_kind_of(d) != LSC_DEVICE_SERIAL) {
        return false; /* sim is each program's own; HID is not looked up */
    }
    if (lsc_lscd_name(cfg->port, name, sizeof name) >= 0 &&
        lsc_lscd_socket_path(name, usual, sizeof usual) >= 0 &&
        strcmp(usual, cfg->socket_path) == 0) {
        return false; /* the socket where programs look first: no record needed */
    }
    int r = lsc_lscd_record_write(cfg->port, cfg->socket_path, record, cap);
    if (r != 0) {
        lscd_log("cannot record in %s which socket serves %s (%s): programs that open the "
                 "port will find it busy; they name lscd:%s instead",
                 r == LSC_EINVAL || r == LSC_ENOSPC ? "the run directory" : record, cfg->port,
                 lsc_strerror(r), cfg->socket_path);
        return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    lscd_config cfg;
    char port_buf[LSC_LSCD_PATH_MAX + 8u];
    const char *socket_opt = NULL, *instance = NULL;
    memset(&cfg, 0, sizeof cfg);
    cfg.timeout_ms = LSCD_TIMEOUT_DEFAULT;
    cfg.lease_max_ms = LSCD_LEASE_MAX_DEFAULT;
    cfg.client_queue = LSCD_QUEUE_DEFAULT;
    cfg.retry_ms = LSCD_RETRY_DEFAULT;
    cfg.max_clients = LSCD_CLIENTS_DEFAULT;
    cfg.mode = 0660;
    int r = parse_args(argc, argv, &cfg, port_buf, sizeof port_buf, &socket_opt, &instance);
    if (r >= 0) {
        return r;
    }
    /* the environment as every front end reads it: $LSC_HID_ID for the open */
    char env_why[160];
    lsc_device_config *env = lsc_device_config_new();
    r = env == NULL ? 0 : lsc_device_config_from_env(env, env_why, sizeof env_why);
    lsc_device_config_free(env);
    if (r != 0) {
        return usage_error("%s", env_why);
    }
    int listen_fd = passed_socket();
    if (listen_fd == -2) {
        return LSCD_EXIT_FAIL;
    }
    cfg.activated = listen_fd >= 0;
    if (cfg.activated) {
        struct sockaddr_un addr;
        socklen_t len = sizeof addr;
        memset(&addr, 0, sizeof addr);
        if (getsockname(listen_fd, (struct sockaddr *)&addr, &len) == 0 && addr.sun_family == AF_UNIX) {
            (void)snprintf(cfg.socket_path, sizeof cfg.socket_path, "%.*s",
                           (int)sizeof addr.sun_path, addr.sun_path);
        }
    } else if (socket_opt != NULL) {
        if (strlen(socket_opt) >= sizeof cfg.socket_path || socket_opt[0] == '\0') {
            return usage_error("--socket: '%s' is empty or longer than 107 bytes", socket_opt);
        }
        memcpy(cfg.socket_path, socket_opt, strlen(socket_opt) + 1u);
    } else {
        char name[LSC_LSCD_NAME_MAX];
        if (lsc_lscd_name(instance != NULL ? instance : cfg.port, name, sizeof name) < 0 ||
            lsc_lscd_socket_path(name, cfg.socket_path, sizeof cfg.socket_path) < 0) {
            return usage_error("no socket name comes from the port '%s': give --socket PATH",
                               cfg.port);
        }
        make_dir_of(cfg.socket_path);
    }
    /* each of these stops lscd: its read end wakes the server's poll */
    static const int stops[] = {SIGINT, SIGTERM, SIGHUP};
    int sig_fd = signal_pipe_open(stops, sizeof stops / sizeof stops[0]);
    if (sig_fd < 0) {
        lscd_log("pipe: %s", strerror(errno));
        return LSCD_EXIT_FAIL;
    }
    /* the controller first: a port that cannot be opened makes no socket */
    lsc_device *d = NULL;
    r = lscd_open_device(&cfg, &d);
    if (r != 0) {
        lscd_log("%s", lscd_open_error(d));
        lsc_device_close(d);
        return r == LSC_EBUSY ? LSCD_EXIT_BUSY : r == LSC_EINVAL ? LSCD_EXIT_USAGE : LSCD_EXIT_FAIL;
    }
    if (!cfg.activated) {
        listen_fd = listen_on(cfg.socket_path, cfg.mode);
        if (listen_fd < 0) {
            lsc_device_close(d);
            return LSCD_EXIT_FAIL;
        }
    }
    (void)fcntl(listen_fd, F_SETFL, fcntl(listen_fd, F_GETFL) | O_NONBLOCK);
    lscd_dev dv;
    if (lscd_dev_start(&dv, &cfg, d) != 0) {
        lscd_log("cannot start: %s", strerror(errno));
        lsc_device_close(d);
        if (!cfg.activated) {
            (void)unlink(cfg.socket_path);
        }
        return LSCD_EXIT_FAIL;
    }
    lscd_log("serving %s (%s) on %s%s", cfg.port, dv.name, cfg.socket_path,
             cfg.activated ? " (socket from systemd)" : "");
    char record[LSC_LSCD_PATH_MAX + 16u];
    bool recorded = record_socket(&cfg, d, record, sizeof record);
    r = lscd_serve(&cfg, &dv, listen_fd, sig_fd);
    if (recorded) {
        (void)unlink(record);
    }
    lscd_dev_stop(&dv);
    if (!cfg.activated) {
        (void)unlink(cfg.socket_path);
    }
    (void)close(listen_fd);
    lscd_log("stopped");
    return r;
}
