/* lscd end to end: the daemon (argv[1]) on "sim", on lsc-sim's pseudo-terminal
 * (argv[2], groups argv[3]) and on a scripted controller of the test's own
 * (a pty), started directly and through systemd-socket-activate when it is
 * installed; its clients through the library's transport (lsc/lscd.h) and
 * lsc_client, and raw sockets.
 *
 * Every wait derives from the work: a condition polled until a deadline
 * (test_ms, scaled by LSC_TEST_TIME_SCALE), a process's exit, a thread's
 * end. Durations are only ever checked as upper bounds. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "lsc/lsc.h"
#include "lsc/lscd.h"
#include "../test_time.h"
#include "../test_open.h"

static const char *g_lscd, *g_sim, *g_groups;
static char g_activate[512]; /* systemd-socket-activate, or "" */
static char g_dir[256];
static unsigned g_seq;

/* ---- Time, paths, processes ---------------------------------------------------------- */

static long now_ms(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

/* A pause between two looks at a condition (never synchronisation itself). */
static void pause_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

static void path_in_dir(char *out, size_t cap, const char *what)
{
    int w = snprintf(out, cap, "%s/%s%u", g_dir, what, ++g_seq);
    assert_true(w > 0 && (size_t)w < cap);
}

/* Every process a test started, so that a failed test leaves none behind. */
#define SPAWNED_MAX 64u
static pid_t g_spawned[SPAWNED_MAX];
static size_t g_nspawned;

/* Starts argv with stdout to /dev/null and stderr appended to log. */
static pid_t spawn(char *const argv[], const char *log)
{
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid > 0 && g_nspawned < SPAWNED_MAX) {
        g_spawned[g_nspawned++] = pid;
    }
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        int err = open(log, O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (null >= 0) {
            (void)dup2(null, 0);
            (void)dup2(null, 1);
        }
        if (err >= 0) {
            (void)dup2(err, 2);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    return pid;
}

/* The process's exit status (or 128 + signal), waiting up to ms; -1 if it
 * did not end (then it is killed). */
static int wait_exit(pid_t pid, long ms)
{
    long deadline = now_ms() + test_ms(ms);
    for (;;) {
        int st;
        pid_t r = waitpid(pid, &st, WNOHANG);
        if (r == pid) {
            return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        }
        if (now_ms() > deadline) {
            (void)kill(pid, SIGKILL);
            (void)waitpid(pid, &st, 0);
            return -1;
        }
        pause_ms(2);
    }
}

static bool exited(pid_t pid)
{
    int st;
    return waitpid(pid, &st, WNOHANG) == pid;
}

static void print_log(const char *log)
{
    char buf[4096];
    FILE *f = fopen(log, "r");
    if (f == NULL) {
        return;
    }
    size_t n = fread(buf, 1, sizeof buf - 1u, f);
    buf[n] = '\0';
    (void)fclose(f);
    print_message("--- %s ---\n%s\n", log, buf);
}

typedef struct lscd_proc {
    pid_t pid;
    char sock[108];
    char log[256];
} lscd_proc;

/* Waits until the lscd_proc at sock answers (or its process ended: fails). */
static void wait_answers(lscd_proc *dm)
{
    long deadline = now_ms() + test_ms(30000);
    lsc_lscd_options opt = {sizeof opt, 0, (uint32_t)test_ms(5000), false, true};
    for (;;) {
        lsc_lscd *s = NULL;
        int r = lsc_lscd_open(dm->sock, &opt, &s);
        lsc_lscd_close(s);
        if (r == 0) {
            return;
        }
        if (exited(dm->pid) || now_ms() > deadline) {
            print_log(dm->log);
            fail_msg("lscd at %s did not answer: %s", dm->sock, lsc_strerror(r));
        }
        pause_ms(5);
    }
}

/* lscd --port port [extra...] on a new socket (through systemd-socket-activate
 * when activate is true: it starts lscd at the first connection). */
static void start_lscd(lscd_proc *dm, const char *port, bool activate, const char *const *extra)
{
    char *argv[32];
    size_t n = 0;
    path_in_dir(dm->sock, sizeof dm->sock, "lscd.sock.");
    path_in_dir(dm->log, sizeof dm->log, "lscd.log.");
    if (activate) {
        argv[n++] = g_activate;
        argv[n++] = (char *)"-l";
        argv[n++] = dm->sock;
    }
    argv[n++] = (char *)g_lscd;
    argv[n++] = (char *)"--port";
    argv[n++] = (char *)port;
    if (!activate) {
        argv[n++] = (char *)"--socket";
        argv[n++] = dm->sock;
    }
    for (size_t i = 0; extra != NULL && extra[i] != NULL && n < 31u; i++) {
        argv[n++] = (char *)extra[i];
    }
    argv[n] = NULL;
    dm->pid = spawn(argv, dm->log);
    if (activate) {
        /* systemd-socket-activate listens first: wait for its socket */
        long deadline = now_ms() + test_ms(30000);
        struct stat st;
        while (stat(dm->sock, &st) != 0) {
            assert_false(exited(dm->pid));
            assert_true(now_ms() < deadline);
            pause_ms(2);
        }
    }
    wait_answers(dm);
}

/* SIGTERM: lscd stops, exits 0 and removes its socket (unless activated). */
static void stop_lscd(lscd_proc *dm)
{
    assert_int_equal(kill(dm->pid, SIGTERM), 0);
    int st = wait_exit(dm->pid, 30000);
    if (st != 0) {
        print_log(dm->log);
    }
    assert_int_equal(st, 0);
}

typedef struct sim_proc {
    pid_t pid;
    char link[256];
    char log[256];
} sim_proc;

/* lsc-sim --link link --fast --groups on the link it had (after stop_sim);
 * waits for the link. */
static void restart_sim(sim_proc *sp)
{
    char *argv[] = {(char *)g_sim, (char *)"--link", sp->link, (char *)"--fast",
                    (char *)"--groups", (char *)g_groups, NULL};
    sp->pid = spawn(argv, sp->log);
    long deadline = now_ms() + test_ms(30000);
    struct stat st;
    while (lstat(sp->link, &st) != 0) {
        assert_false(exited(sp->pid));
        assert_true(now_ms() < deadline);
        pause_ms(2);
    }
}

/* lsc-sim as restart_sim, on a new link and log. */
static void start_sim(sim_proc *sp)
{
    path_in_dir(sp->link, sizeof sp->link, "pty.");
    path_in_dir(sp->log, sizeof sp->log, "sim.log.");
    restart_sim(sp);
}

/* SIGTERM: lsc-sim exits 0. */
static void stop_sim(sim_proc *sp)
{
    (void)kill(sp->pid, SIGTERM);
    assert_int_equal(wait_exit(sp->pid, 30000), 0);
}

/* ---- Clients ---------------------------------------------------------------------------- */

#define NOTES_MAX 8192u

typedef struct client {
    lsc_lscd *s;
    lsc_io io;
    lsc_client c;
    lsc_notification notes[NOTES_MAX];
    size_t nnotes;
} client;

static void on_note(void *user, const lsc_notification *n)
{
    client *k = user;
    if (k->nnotes < NOTES_MAX) {
        k->notes[k->nnotes++] = *n;
    }
}

static int client_try_opt(client **out, const char *sock, uint32_t timeout_ms, bool refuse,
                          bool quiet)
{
    client *k = calloc(1, sizeof *k);
    assert_non_null(k);
    lsc_lscd_options opt = {sizeof opt, timeout_ms, (uint32_t)test_ms(10000), refuse, quiet};
    int r = lsc_lscd_open(sock, &opt, &k->s);
    if (r != 0) {
        print_message("open %s: %s\n", sock, lsc_lscd_error(k->s));
        lsc_lscd_close(k->s);
        free(k);
        *out = NULL;
        return r;
    }
    lsc_lscd_get_io(k->s, &k->io);
    assert_int_equal(lsc_client_init(&k->c, &k->io), 0);
    lsc_client_set_notify(&k->c, on_note, k);
    *out = k;
    return 0;
}

static int client_try(client **out, const char *sock, uint32_t timeout_ms, bool refuse)
{
    return client_try_opt(out, sock, timeout_ms, refuse, false);
}

/* A client that hears no notifications. */
static client *client_open_quiet(const char *sock, uint32_t timeout_ms)
{
    client *k = NULL;
    assert_int_equal(client_try_opt(&k, sock, timeout_ms, false, true), 0);
    return k;
}

static client *client_open(const char *sock, uint32_t timeout_ms, bool refuse)
{
    client *k = NULL;
    assert_int_equal(client_try(&k, sock, timeout_ms, refuse), 0);
    return k;
}

static void client_close(client *k)
{
    if (k != NULL) {
        lsc_lscd_close(k->s);
        free(k);
    }
}

/* Reads until k has n notifications (fails after the deadline). */
static void wait_notes(client *k, size_t n)
{
    long deadline = now_ms() + test_ms(30000);
    while (k->nnotes < n) {
        int r = lsc_client_poll(&k->c, 100);
        assert_true(r >= 0);
        if (now_ms() > deadline) {
            fail_msg("%zu notifications of %zu arrived", k->nnotes, n);
        }
    }
}

/* ---- Status ------------------------------------------------------------------------------ */

typedef struct status {
    char text[8192];
    size_t len;
} status;

static void on_item(void *user, const char *key, const char *value)
{
    status *st = user;
    int w = snprintf(st->text + st->len, sizeof st->text - st->len, "%s=%s\n", key, value);
    if (w > 0 && (size_t)w < sizeof st->text - st->len) {
        st->len += (size_t)w;
    }
}

static void get_status(lsc_lscd *s, status *st)
{
    st->len = 0;
    st->text[0] = '\0';
    int r = lsc_lscd_status(s, on_item, st, (uint32_t)test_ms(10000));
    assert_true(r > 10);
}

/* The value of key (the first line "key=..."), or "" . */
static const char *status_value(const status *st, const char *key, char *out, size_t cap)
{
    size_t klen = strlen(key);
    const char *p = st->text;
    out[0] = '\0';
    while (*p != '\0') {
        const char *eol = strchr(p, '\n');
        if (strncmp(p, key, klen) == 0 && p[klen] == '=') {
            size_t n = (size_t)(eol - p) - klen - 1u;
            n = n < cap - 1u ? n : cap - 1u;
            memcpy(out, p + klen + 1, n);
            out[n] = '\0';
            return out;
        }
        p = eol + 1;
    }
    return out;
}

static long status_num(lsc_lscd *s, const char *key)
{
    status st;
    char v[64];
    get_status(s, &st);
    return strtol(status_value(&st, key, v, sizeof v), NULL, 10);
}

static bool status_is(lsc_lscd *s, const char *key, const char *want)
{
    status st;
    char v[256];
    get_status(s, &st);
    return strcmp(status_value(&st, key, v, sizeof v), want) == 0;
}

/* Waits until lscd's status says key=want. */
static void wait_status(lsc_lscd *s, const char *key, const char *want)
{
    long deadline = now_ms() + test_ms(30000);
    while (!status_is(s, key, want)) {
        if (now_ms() > deadline) {
            fail_msg("lscd's status never said %s=%s", key, want);
        }
        pause_ms(5);
    }
}

/* Waits until lscd has at least n frames queued (or running). */
static void wait_queued(lsc_lscd *s, long n)
{
    long deadline = now_ms() + test_ms(30000);
    while (status_num(s, "queue") < n) {
        if (now_ms() > deadline) {
            fail_msg("lscd never had %ld queued", n);
        }
        pause_ms(2);
    }
}

/* ---- Basics on "sim" ----------------------------------------------------------------------- */

static void test_sim_basics(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *k = client_open(dm.sock, 2000, false);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&k->c, &mv, 2000), 0);
    assert_int_equal(mv, 7500);
    lsc_servo to = {100, 1234}, got[2];
    assert_int_equal(lsc_client_move(&k->c, 0, &to, 1), 0);
    uint8_t ids[2] = {100, 101};
    int r = lsc_client_read_positions(&k->c, ids, 2, got, 2000);
    if (r != 2) {
        print_message("read: %s\n", lsc_lscd_error(k->s));
        print_log(dm.log);
    }
    assert_int_equal(r, 2);
    assert_int_equal(got[0].position, 1234);
    assert_int_equal(got[1].position, 1500);
    lsc_servo_offset off[1];
    assert_int_equal(lsc_client_adjust_offset(&k->c, 100, -7), 0);
    assert_int_equal(lsc_client_read_offsets(&k->c, ids, 1, off, 2000), 1);
    assert_int_equal(off[0].offset, -7);
    /* lscd's own command cannot be written through the io */
    uint8_t ctl[] = {0x55, 0x55, 0x03, LSC_LSCD_CMD, LSC_LSCD_OP_STATUS};
    assert_int_equal(k->io.write(k->io.ctx, ctl, sizeof ctl), LSC_EINVAL);
    /* status: the device, this client */
    status st;
    char v[256];
    get_status(k->s, &st);
    assert_string_equal(status_value(&st, "port", v, sizeof v), "sim");
    assert_string_equal(status_value(&st, "kind", v, sizeof v), "sim");
    assert_string_equal(status_value(&st, "controller", v, sizeof v), "present");
    assert_string_equal(status_value(&st, "lease", v, sizeof v), "none");
    assert_non_null(strstr(st.text, "(this one)"));
    assert_true(lsc_lscd_controller_present(k->s));
    assert_int_equal(lsc_lscd_dropped(k->s), 0);
    /* a control frame lscd does not know: it says so, and serves on */
    client_close(k);
    stop_lscd(&dm);
    struct stat sb;
    assert_int_not_equal(stat(dm.sock, &sb), 0); /* its socket is gone */
}

static void test_open_errors(void **state)
{
    (void)state;
    lsc_lscd *s = NULL;
    char path[256];
    path_in_dir(path, sizeof path, "none.sock.");
    assert_int_equal(lsc_lscd_open(path, NULL, &s), LSC_ENODEV);
    assert_non_null(strstr(lsc_lscd_error(s), path));
    /* a failed handle refuses every call with the open's error */
    uint8_t b[4];
    assert_int_equal(lsc_lscd_read(s, b, sizeof b, 0), LSC_ENODEV);
    assert_int_equal(lsc_lscd_write(s, b, 0), LSC_ENODEV);
    assert_int_equal(lsc_lscd_lease(s, 1, 0), LSC_ENODEV);
    lsc_lscd_close(s);
    assert_int_equal(lsc_lscd_open("", NULL, &s), LSC_EINVAL);
    lsc_lscd_close(s);
    assert_int_equal(lsc_lscd_open("lscd:", NULL, &s), LSC_EINVAL);
    lsc_lscd_close(s);
    /* something else listening: not lscd */
    path_in_dir(path, sizeof path, "other.sock.");
    int lfd = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    assert_true(strlen(path) < sizeof a.sun_path);
    memcpy(a.sun_path, path, strlen(path) + 1u);
    assert_int_equal(bind(lfd, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(lfd, 4), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) { /* answers anything with a battery reply */
        int c = accept(lfd, NULL, NULL);
        static const uint8_t reply[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
        char buf[256];
        (void)!read(c, buf, sizeof buf);
        (void)!write(c, reply, sizeof reply);
        while (read(c, buf, sizeof buf) > 0) {
        }
        _exit(0);
    }
    assert_int_equal(lsc_lscd_open(path, NULL, &s), LSC_EREPLY);
    lsc_lscd_close(s);
    (void)close(lfd);
    assert_int_equal(wait_exit(pid, 30000), 0);
}

static void test_names(void **state)
{
    (void)state;
    char out[128];
    assert_int_equal(lsc_lscd_name("/dev/ttyUSB0", out, sizeof out), 7);
    assert_string_equal(out, "ttyUSB0");
    assert_int_equal(lsc_lscd_name("hid:1A2B", out, sizeof out), 8);
    assert_string_equal(out, "hid-1A2B");
    assert_int_equal(lsc_lscd_name("sim", out, sizeof out), 3);
    assert_int_equal(lsc_lscd_name("/dev/serial/by-id/usb-a b:c", out, sizeof out), 9);
    assert_string_equal(out, "usb-a_b_c");
    assert_int_equal(lsc_lscd_name("/dev/", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_name("..", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_name("hid:", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_name("sim", out, 3), LSC_ENOSPC);
    assert_int_equal(lsc_lscd_port_of_name("ttyUSB0", out, sizeof out), 12);
    assert_string_equal(out, "/dev/ttyUSB0");
    assert_int_equal(lsc_lscd_port_of_name("hid-1A2B", out, sizeof out), 8);
    assert_string_equal(out, "hid:1A2B");
    assert_int_equal(lsc_lscd_port_of_name("sim", out, sizeof out), 3);
    /* a bus: "lx-" and its port's name, both ways */
    assert_int_equal(lsc_lscd_name("lx:/dev/ttyUSB0", out, sizeof out), 10);
    assert_string_equal(out, "lx-ttyUSB0");
    assert_int_equal(lsc_lscd_name("lx:sim", out, sizeof out), 6);
    assert_string_equal(out, "lx-sim");
    assert_int_equal(lsc_lscd_name("lx:sim:1-3", out, sizeof out), 10);
    assert_string_equal(out, "lx-sim_1-3");
    /* no port's name after "lx:" (or a path's last '/'): none */
    assert_int_equal(lsc_lscd_name("lx:", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_name("lx:/dev/", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_name("/dev/", out, sizeof out), LSC_EINVAL);
    assert_int_equal(lsc_lscd_port_of_name("lx-ttyUSB0", out, sizeof out), 15);
    assert_string_equal(out, "lx:/dev/ttyUSB0");
    assert_int_equal(lsc_lscd_port_of_name("lx-sim", out, sizeof out), 6);
    assert_string_equal(out, "lx:sim");
    assert_int_equal(lsc_lscd_port_of_name("lx-", out, sizeof out), 8);
    assert_string_equal(out, "/dev/lx-");
    assert_int_equal(lsc_lscd_port_of_name("a/b", out, sizeof out), LSC_EINVAL);
    assert_int_equal(setenv("LSC_LSCD_DIR", "/tmp/x/", 1), 0);
    assert_int_equal(lsc_lscd_socket_path("lscd:arm", out, sizeof out), 15);
    assert_string_equal(out, "/tmp/x/arm.sock");
    assert_int_equal(unsetenv("LSC_LSCD_DIR"), 0);
    assert_int_equal(lsc_lscd_socket_path("lscd:ttyUSB0", out, sizeof out), 21);
    assert_string_equal(out, "/run/lsc/ttyUSB0.sock");
    assert_int_equal(lsc_lscd_socket_path("lscd:/x/y.sock", out, sizeof out), 9);
    assert_string_equal(out, "/x/y.sock");
    assert_int_equal(lsc_lscd_socket_path("lscd:", out, sizeof out), LSC_EINVAL);
}

/* ---- Notifications ----------------------------------------------------------------------- */

static void test_notifications(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *w = client_open(dm.sock, 2000, false);
    client *r = client_open(dm.sock, 2000, false);
    /* a client that subscribed and then runs a group sees its start */
    assert_int_equal(lsc_client_run_group(&r->c, 2, 1), 0);
    lsc_notification end;
    assert_int_equal(lsc_client_wait_group(&r->c, (uint32_t)test_ms(30000), &end), 0);
    assert_int_equal(end.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(end.group, 2);
    assert_int_equal(r->nnotes, 2);
    assert_int_equal(r->notes[0].cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(r->notes[0].group, 2);
    /* another client heard both */
    wait_notes(w, 2);
    assert_int_equal(w->notes[0].cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(w->notes[1].cmd, LSC_CMD_GROUP_COMPLETE);
    client_close(w);
    client_close(r);
    stop_lscd(&dm);
}

/* Context switches of every thread of process pid, so far: each time one of
 * them woke up (or was preempted). */
static long ctx_switches(pid_t pid)
{
    char dirpath[64];
    (void)snprintf(dirpath, sizeof dirpath, "/proc/%ld/task", (long)pid);
    DIR *dir = opendir(dirpath);
    assert_non_null(dir);
    long total = 0;
    struct dirent *e;
    while ((e = readdir(dir)) != NULL) {
        if (e->d_name[0] == '.') {
            continue;
        }
        char path[sizeof dirpath + sizeof e->d_name + 8], line[128];
        (void)snprintf(path, sizeof path, "%s/%s/status", dirpath, e->d_name);
        FILE *f = fopen(path, "r");
        if (f == NULL) {
            continue; /* a thread that ended meanwhile */
        }
        while (fgets(line, sizeof line, f) != NULL) {
            /* "voluntary_ctxt_switches:\tN" and "nonvoluntary_ctxt_switches:\tN" */
            const char *colon = strchr(line, ':');
            if (colon != NULL && strstr(line, "ctxt_switches:") != NULL) {
                total += strtol(colon + 1, NULL, 10);
            }
        }
        (void)fclose(f);
    }
    (void)closedir(dir);
    return total;
}

/* On "sim" with clients connected and nothing running, lscd sleeps: none of
 * its threads wakes up (it did every 10 ms while it moved the virtual
 * clock on), and a group still ends on time. */
static void test_sim_idle_sleeps(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *k = client_open(dm.sock, 2000, false);
    assert_int_equal(lsc_client_run_group(&k->c, 2, 1), 0);
    lsc_notification end;
    assert_int_equal(lsc_client_wait_group(&k->c, (uint32_t)test_ms(30000), &end), 0);
    assert_int_equal(end.cmd, LSC_CMD_GROUP_COMPLETE);
    long before = ctx_switches(dm.pid);
    pause_ms(500); /* the window watched, not a wait for anything */
    long woke = ctx_switches(dm.pid) - before;
    if (woke > 2) {
        fail_msg("lscd's threads woke %ld times in 500 ms with nothing to do", woke);
    }
    client_close(k);
    stop_lscd(&dm);
}

/* ---- 50 clients at once: 20 watching, 30 commanding ------------------------------------ */

#define WATCHERS 20
#define COMMANDERS 30
#define RUNS ((size_t)3)
#define ROUNDS 10

typedef struct many {
    const char *sock;
    uint8_t group;
    pthread_barrier_t ready;
    int failures;
    pthread_mutex_t lock;
    char why[256];
    size_t expected; /* notifications every watcher must get (set by the conductor) */
    bool done;
} many;

typedef struct worker {
    many *m;
    int index;
    pthread_t t;
} worker;

static void many_fail(many *m, const char *fmt, ...)
{
    (void)pthread_mutex_lock(&m->lock);
    if (m->failures++ == 0) {
        va_list ap;
        va_start(ap, fmt);
        (void)vsnprintf(m->why, sizeof m->why, fmt, ap);
        va_end(ap);
    }
    (void)pthread_mutex_unlock(&m->lock);
}

static client *worker_open(many *m)
{
    client *k = NULL;
    int r = client_try(&k, m->sock, (uint32_t)test_ms(10000), false);
    if (r != 0) {
        many_fail(m, "open: %s", lsc_strerror(r));
    }
    (void)pthread_barrier_wait(&m->ready);
    return k;
}

static void *watcher(void *arg)
{
    worker *wk = arg;
    many *m = wk->m;
    client *k = worker_open(m);
    if (k == NULL) {
        return NULL;
    }
    long deadline = now_ms() + test_ms(120000);
    for (;;) {
        (void)pthread_mutex_lock(&m->lock);
        bool done = m->done;
        size_t expected = m->expected;
        (void)pthread_mutex_unlock(&m->lock);
        if (done && k->nnotes >= expected) {
            break;
        }
        if (now_ms() > deadline) {
            many_fail(m, "watcher %d: %zu notifications, want %zu", wk->index, k->nnotes, expected);
            break;
        }
        int r = lsc_client_poll(&k->c, 50);
        if (r < 0) {
            many_fail(m, "watcher %d: poll: %s", wk->index, lsc_strerror(r));
            break;
        }
    }
    /* exactly start, end for each run, in order */
    if (k->nnotes != 2u * RUNS) {
        many_fail(m, "watcher %d: %zu notifications, want %zu", wk->index, k->nnotes, 2u * RUNS);
    }
    for (size_t i = 0; i < k->nnotes && i < 2u * RUNS; i++) {
        uint8_t want = i % 2u == 0u ? LSC_CMD_GROUP_RUN : LSC_CMD_GROUP_COMPLETE;
        if (k->notes[i].cmd != want || k->notes[i].group != m->group) {
            many_fail(m, "watcher %d: notification %zu is %u/%u", wk->index, i, k->notes[i].cmd,
                      k->notes[i].group);
        }
    }
    if (lsc_lscd_dropped(k->s) != 0u) {
        many_fail(m, "watcher %d: %u dropped", wk->index, lsc_lscd_dropped(k->s));
    }
    client_close(k);
    return NULL;
}

static void *commander(void *arg)
{
    worker *wk = arg;
    many *m = wk->m;
    client *k = worker_open(m);
    if (k == NULL) {
        return NULL;
    }
    uint8_t id = (uint8_t)(100 + wk->index);
    uint32_t t = (uint32_t)test_ms(10000);
    for (int round = 0; round < ROUNDS; round++) {
        lsc_servo to = {id, (uint16_t)(1000 + wk->index * 20 + round)}, got = {0, 0};
        int r = lsc_client_move(&k->c, 0, &to, 1);
        if (r == 0) {
            r = lsc_client_read_positions(&k->c, &id, 1, &got, t);
        }
        if (r == 1 && got.position != to.position) {
            many_fail(m, "commander %d: servo %u read %u, want %u", wk->index, id, got.position,
                      to.position);
        } else if (r != 1) {
            many_fail(m, "commander %d: %s", wk->index, lsc_lscd_error(k->s));
        }
        uint16_t mv;
        r = lsc_client_get_battery(&k->c, &mv, t);
        if (r != 0) {
            many_fail(m, "commander %d: battery: %s", wk->index, lsc_lscd_error(k->s));
        }
        lsc_client_counts counts;
        lsc_client_get_counts(&k->c, &counts);
        if (counts.unexpected != 0u || counts.discarded != 0u) {
            many_fail(m, "commander %d: %u frames not its own, %u bytes discarded", wk->index,
                      counts.unexpected, counts.discarded);
        }
    }
    client_close(k);
    return NULL;
}

static void *conductor(void *arg)
{
    worker *wk = arg;
    many *m = wk->m;
    client *k = worker_open(m);
    if (k != NULL) {
        for (size_t i = 0; i < RUNS; i++) {
            lsc_notification end;
            int r = lsc_client_run_group(&k->c, m->group, 1);
            if (r == 0) {
                r = lsc_client_wait_group(&k->c, (uint32_t)test_ms(30000), &end);
            }
            if (r != 0) {
                many_fail(m, "conductor: run %zu: %s", i, lsc_strerror(r));
                break;
            }
        }
        client_close(k);
    }
    (void)pthread_mutex_lock(&m->lock);
    m->expected = 2u * RUNS;
    m->done = true;
    (void)pthread_mutex_unlock(&m->lock);
    return NULL;
}

static void run_many(const char *sock, uint8_t group)
{
    many m;
    memset(&m, 0, sizeof m);
    m.sock = sock;
    m.group = group;
    m.expected = (size_t)-1;
    assert_int_equal(pthread_mutex_init(&m.lock, NULL), 0);
    assert_int_equal(pthread_barrier_init(&m.ready, NULL, WATCHERS + COMMANDERS + 1), 0);
    worker w[WATCHERS + COMMANDERS + 1];
    for (int i = 0; i < WATCHERS + COMMANDERS + 1; i++) {
        w[i].m = &m;
        w[i].index = i < WATCHERS ? i : i - WATCHERS;
        void *(*fn)(void *) = i < WATCHERS                ? watcher
                              : i < WATCHERS + COMMANDERS ? commander
                                                          : conductor;
        assert_int_equal(pthread_create(&w[i].t, NULL, fn, &w[i]), 0);
    }
    for (int i = 0; i < WATCHERS + COMMANDERS + 1; i++) {
        (void)pthread_join(w[i].t, NULL);
    }
    (void)pthread_barrier_destroy(&m.ready);
    (void)pthread_mutex_destroy(&m.lock);
    if (m.failures != 0) {
        client *k = NULL;
        if (client_try(&k, sock, 2000, false) == 0) {
            status st;
            get_status(k->s, &st);
            print_message("lscd's status:\n%s", st.text);
            client_close(k);
        }
        fail_msg("%d failures; the first: %s", m.failures, m.why);
    }
}

static void test_many_sim(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    run_many(dm.sock, 2);
    client *k = client_open(dm.sock, 2000, false);
    assert_int_equal(status_num(k->s, "notifications"), 2u * RUNS);
    assert_int_equal(status_num(k->s, "dropped"), 0);
    assert_int_equal(status_num(k->s, "stray"), 0);
    client_close(k);
    stop_lscd(&dm);
}

static void test_many_pty(void **state)
{
    (void)state;
    sim_proc sim;
    start_sim(&sim);
    lscd_proc dm;
    start_lscd(&dm, sim.link, false, NULL);
    run_many(dm.sock, 2);
    stop_lscd(&dm);
    stop_sim(&sim);
}

static void test_many_activated(void **state)
{
    (void)state;
    if (g_activate[0] == '\0') {
        print_message("SKIP: systemd-socket-activate is not installed (package systemd)\n");
        skip();
    }
    lscd_proc dm;
    start_lscd(&dm, "sim", true, NULL);
    client *k = client_open(dm.sock, 2000, false);
    status st;
    char v[256];
    get_status(k->s, &st);
    assert_non_null(strstr(status_value(&st, "socket", v, sizeof v), "(systemd)"));
    client_close(k);
    run_many(dm.sock, 2);
    stop_lscd(&dm);
}

/* ---- The lease --------------------------------------------------------------------------- */

typedef struct bg_battery {
    client *k;
    uint32_t timeout;
    int r;
    long took;
    pthread_t t;
} bg_battery;

static void *battery_thread(void *arg)
{
    bg_battery *b = arg;
    uint16_t mv;
    long start = now_ms();
    b->r = lsc_client_get_battery(&b->k->c, &mv, b->timeout);
    b->took = now_ms() - start;
    return NULL;
}

static void bg_start(bg_battery *b, client *k, uint32_t timeout)
{
    b->k = k;
    b->timeout = timeout;
    assert_int_equal(pthread_create(&b->t, NULL, battery_thread, b), 0);
}

typedef struct bg_lease {
    client *k;
    int r;
    pthread_t t;
} bg_lease;

static void *lease_thread(void *arg)
{
    bg_lease *b = arg;
    b->r = lsc_lscd_lease(b->k->s, 60000, (uint32_t)test_ms(30000));
    return NULL;
}

static void test_lease(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *a = client_open(dm.sock, 2000, false);
    client *refuser = client_open(dm.sock, 2000, true);
    client *waiter = client_open(dm.sock, 300, false);
    uint16_t mv;
    assert_int_equal(lsc_lscd_lease(a->s, 60000, 0), 0);
    assert_int_equal(lsc_lscd_lease_ms(a->s), 60000);
    status st;
    char v[256];
    get_status(a->s, &st);
    assert_int_equal(strncmp(status_value(&st, "lease", v, sizeof v), "client ", 7), 0);
    /* the holder's frames go; the others' are refused at once, or wait and then are refused */
    assert_int_equal(lsc_client_get_battery(&a->c, &mv, 2000), 0);
    long start = now_ms();
    assert_int_equal(lsc_client_get_battery(&refuser->c, &mv, 2000), LSC_EBUSY);
    assert_true(now_ms() - start < test_ms(1000));
    assert_int_equal(lsc_client_get_battery(&waiter->c, &mv, 300), LSC_EBUSY);
    /* a lease wanted without waiting: busy */
    assert_int_equal(lsc_lscd_lease(refuser->s, 1000, 0), LSC_EBUSY);
    /* one who waits for the lease gets it when the holder lets go */
    bg_lease bl = {refuser, 0, 0};
    assert_int_equal(pthread_create(&bl.t, NULL, lease_thread, &bl), 0);
    wait_queued(a->s, 1);
    assert_int_equal(lsc_lscd_release(a->s), 0);
    assert_int_equal(pthread_join(bl.t, NULL), 0);
    assert_int_equal(bl.r, 0);
    assert_int_equal(lsc_lscd_set_timeout(a->s, 300), 0);
    assert_int_equal(lsc_client_get_battery(&a->c, &mv, 300), LSC_EBUSY);
    assert_int_equal(lsc_lscd_set_timeout(a->s, 2000), 0);
    assert_int_equal(lsc_lscd_release(refuser->s), 0);
    assert_int_equal(lsc_lscd_release(refuser->s), LSC_EINVAL);
    assert_int_equal(lsc_client_get_battery(&refuser->c, &mv, 2000), 0);
    /* a lease ends when its time runs out: a waiting frame then goes */
    client *patient = client_open(dm.sock, (uint32_t)test_ms(30000), false);
    assert_int_equal(lsc_lscd_lease(a->s, 300, 0), 0);
    bg_battery bb;
    bg_start(&bb, patient, (uint32_t)test_ms(30000));
    assert_int_equal(pthread_join(bb.t, NULL), 0);
    assert_int_equal(bb.r, 0);
    assert_int_equal(lsc_lscd_release(a->s), LSC_EINVAL); /* expired */
    /* longer than --lease-max is cut to it */
    assert_int_equal(lsc_lscd_lease(a->s, 0, 0), 0);
    assert_int_equal(lsc_lscd_lease_ms(a->s), 60000);
    assert_int_equal(lsc_lscd_release(a->s), 0);
    client_close(patient);
    client_close(waiter);
    client_close(refuser);
    client_close(a);
    stop_lscd(&dm);
}

/* lsc_lscd_options grows: a caller's shorter struct (up to
 * connect_timeout_ms), garbage beyond it, opens with the defaults of the rest
 * (a frame waits for a lease another holds, it is not refused); a size below
 * the size field and timeout_ms is refused before anything connects. */
static void test_options_size(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *a = client_open(dm.sock, 2000, false);
    lsc_lscd_options opt;
    memset(&opt, 0xA5, sizeof opt);
    lsc_lscd *s = NULL;
    opt.size = sizeof opt.size;
    assert_int_equal(lsc_lscd_open(dm.sock, &opt, &s), LSC_EINVAL);
    assert_non_null(strstr(lsc_lscd_error(s), "lsc_lscd_options.size is"));
    assert_non_null(strstr(lsc_lscd_error(s),
                           "set it to sizeof(lsc_lscd_options); nothing was sent"));
    uint8_t b[1];
    assert_int_equal(lsc_lscd_write(s, b, 0), LSC_EINVAL); /* a failed handle */
    assert_int_equal(status_num(a->s, "clients"), 1); /* a alone: it never connected */
    lsc_lscd_close(s);
    client *k = calloc(1, sizeof *k);
    assert_non_null(k);
    opt.size = offsetof(lsc_lscd_options, refuse_busy);
    opt.timeout_ms = (uint32_t)test_ms(30000);
    opt.connect_timeout_ms = (uint32_t)test_ms(10000);
    assert_int_equal(lsc_lscd_open(dm.sock, &opt, &k->s), 0);
    lsc_lscd_get_io(k->s, &k->io);
    assert_int_equal(lsc_client_init(&k->c, &k->io), 0);
    assert_int_equal(lsc_lscd_lease(a->s, 60000, 0), 0);
    bg_battery bb;
    bg_start(&bb, k, (uint32_t)test_ms(30000));
    wait_queued(a->s, 1);
    assert_int_equal(lsc_lscd_release(a->s), 0);
    assert_int_equal(pthread_join(bb.t, NULL), 0);
    assert_int_equal(bb.r, 0);
    client_close(k);
    client_close(a);
    stop_lscd(&dm);
}

/* A halt outranks a lease: another client's halt is not refused; the
 * holder's lease ends (LEASE HALTED) and its frames still waiting are
 * dropped; lscd stops a move under way where the servo is (two reads 0.6 s
 * apart agree, between start and target); every client hears HALTED. The
 * device layer's lsc_device_halt on "lscd:PATH" goes this way. */
static void test_halt(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *holder = client_open(dm.sock, 2000, false);
    client *other = client_open(dm.sock, 2000, false);
    assert_int_equal(lsc_lscd_lease(holder->s, 60000, 0), 0);
    lsc_servo to = {1, 2500};
    assert_int_equal(lsc_client_move(&holder->c, 6000, &to, 1), 0);
    pause_ms(300); /* (the move is under way: 6 s) */
    assert_int_equal(lsc_lscd_halts(other->s), 0);
    assert_int_equal(lsc_lscd_halt(other->s), 0);
    assert_string_equal(lsc_lscd_error(other->s), "");
    assert_int_equal(lsc_lscd_halts(other->s), 1);
    /* the holder's lease is over: it was told */
    assert_int_equal(lsc_lscd_release(holder->s), LSC_EINVAL);
    assert_int_equal(lsc_lscd_halts(holder->s), 1);
    /* the servo holds where it was */
    const uint8_t id = 1;
    lsc_servo first, second;
    assert_int_equal(lsc_client_read_positions(&other->c, &id, 1, &first, 2000), 1);
    pause_ms(600);
    assert_int_equal(lsc_client_read_positions(&other->c, &id, 1, &second, 2000), 1);
    assert_int_equal(first.position, second.position);
    assert_true(first.position > 1500 && first.position < 2500);
    /* through the device layer */
    char name[sizeof dm.sock + 8];
    snprintf(name, sizeof name, "lscd:%s", dm.sock);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open(name, NULL, &d), 0);
    assert_int_equal(lsc_lscd_lease(holder->s, 60000, 0), 0);
    assert_int_equal(lsc_device_halt(d), 0);
    assert_int_equal(lsc_lscd_release(holder->s), LSC_EINVAL);
    /* its connection closed, nothing goes to lscd; opened again, the same */
    lsc_device_close_port(d);
    assert_int_equal(lsc_device_fileno(d), -1);
    assert_int_equal(lsc_device_halt(d), LSC_ENODEV);
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_true(lsc_device_fileno(d) >= 0);
    assert_int_equal(lsc_device_halt(d), 0);
    client_close(holder);
    client_close(other);
    stop_lscd(&dm);
    /* lscd gone: its error */
    assert_true(lsc_device_halt(d) < 0);
    assert_true(strlen(lsc_device_error(d)) > 0);
    lsc_device_close(d);
}

/* A play through lscd (another thread's device) ends at once when a halt
 * comes: LSC_EBUSY, cause LSC_DEVICE_CAUSE_HALTED, after its first frame. */
typedef struct bg_play {
    lsc_device *d;
    lsc_action a;
    lsc_play_result res;
    int r;
    volatile int frames; /* set by the callback: the play has begun */
    pthread_t t;
} bg_play;

static bool play_step(void *user, const lsc_player_step *step, uint32_t elapsed_ms)
{
    bg_play *b = user;
    (void)elapsed_ms;
    if (step != NULL) {
        __atomic_store_n(&b->frames, b->frames + 1, __ATOMIC_SEQ_CST);
    }
    return true;
}

static void *play_thread(void *arg)
{
    bg_play *b = arg;
    lsc_player_config cfg = {100, 1, 100, 0};
    b->r = lsc_device_play(b->d, &b->a, &cfg, play_step, b, &b->res);
    return NULL;
}

static void test_halt_stops_a_play(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    char name[sizeof dm.sock + 8];
    snprintf(name, sizeof name, "lscd:%s", dm.sock);
    bg_play b;
    memset(&b, 0, sizeof b);
    b.res.size = sizeof b.res;
    assert_int_equal(lsc_device_open(name, NULL, &b.d), 0);
    static const uint8_t ids[] = {1};
    static const uint16_t row1[] = {1000}, row2[] = {2000};
    assert_int_equal(lsc_action_init(&b.a, ids, 1), 0);
    assert_int_equal(lsc_action_append(&b.a, 100, row1), 0);
    assert_int_equal(lsc_action_append(&b.a, 60000, row2), 0);
    assert_int_equal(pthread_create(&b.t, NULL, play_thread, &b), 0);
    long deadline = now_ms() + test_ms(30000);
    while (__atomic_load_n(&b.frames, __ATOMIC_SEQ_CST) == 0 && now_ms() < deadline) {
        pause_ms(5);
    }
    client *other = client_open(dm.sock, 2000, false);
    assert_int_equal(lsc_lscd_halt(other->s), 0);
    assert_int_equal(pthread_join(b.t, NULL), 0);
    assert_int_equal(b.r, LSC_EBUSY);
    assert_int_equal(lsc_device_error_cause(b.d), LSC_DEVICE_CAUSE_HALTED);
    assert_non_null(strstr(lsc_device_error(b.d), "the controller was halted through lscd"));
    assert_true(b.res.frames >= 1u && b.res.frames < 3u);
    lsc_action_free(&b.a);
    lsc_device_close(b.d);
    client_close(other);
    stop_lscd(&dm);
}

/* A client SIGKILLed while it holds the lease: the lease ends, the others go on. */
static void test_lease_holder_killed(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    int p[2];
    assert_int_equal(pipe(p), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_lscd *s = NULL;
        char c = lsc_lscd_open(dm.sock, NULL, &s) == 0 && lsc_lscd_lease(s, 600000, 0) == 0 ? 'y'
                                                                                            : 'n';
        (void)!write(p[1], &c, 1);
        for (;;) {
            (void)pause();
        }
    }
    char c = 0;
    assert_int_equal(read(p[0], &c, 1), 1);
    assert_int_equal(c, 'y');
    client *b = client_open(dm.sock, (uint32_t)test_ms(60000), false);
    bg_battery bb;
    bg_start(&bb, b, (uint32_t)test_ms(60000));
    client *watch = client_open(dm.sock, 2000, false);
    wait_queued(watch->s, 1);
    assert_int_equal(kill(pid, SIGKILL), 0);
    assert_int_equal(wait_exit(pid, 30000), 128 + SIGKILL);
    assert_int_equal(pthread_join(bb.t, NULL), 0);
    assert_int_equal(bb.r, 0);
    assert_true(bb.took < test_ms(30000));
    assert_true(status_is(watch->s, "lease", "none"));
    client_close(watch);
    client_close(b);
    (void)close(p[0]);
    (void)close(p[1]);
    stop_lscd(&dm);
}

/* lscd SIGKILLed while clients wait: each gets an error at once; a new lscd
 * on the same socket serves new connections. */
typedef struct bg_poll {
    client *k;
    int r;
    pthread_t t;
} bg_poll;

static void *poll_thread(void *arg)
{
    bg_poll *b = arg;
    long deadline = now_ms() + test_ms(60000);
    do {
        b->r = lsc_client_poll(&b->k->c, 1000);
    } while (b->r >= 0 && now_ms() < deadline);
    return NULL;
}

static void test_lscd_killed(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *a = client_open(dm.sock, 2000, false);
    client *b = client_open(dm.sock, (uint32_t)test_ms(60000), false);
    client *w = client_open(dm.sock, 2000, false);
    assert_int_equal(lsc_lscd_lease(a->s, 600000, 0), 0);
    bg_battery bb;
    bg_start(&bb, b, (uint32_t)test_ms(60000));
    bg_poll bp = {w, 0, 0};
    assert_int_equal(pthread_create(&bp.t, NULL, poll_thread, &bp), 0);
    wait_queued(a->s, 1);
    long start = now_ms();
    assert_int_equal(kill(dm.pid, SIGKILL), 0);
    assert_int_equal(wait_exit(dm.pid, 30000), 128 + SIGKILL);
    assert_int_equal(pthread_join(bb.t, NULL), 0);
    assert_int_equal(pthread_join(bp.t, NULL), 0);
    assert_int_equal(bb.r, LSC_ENODEV);
    assert_int_equal(bp.r, LSC_ENODEV);
    assert_true(now_ms() - start < test_ms(30000));
    assert_non_null(strstr(lsc_lscd_error(b->s), "closed the connection"));
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&a->c, &mv, 1000), LSC_ENODEV);
    client_close(a);
    client_close(b);
    client_close(w);
    /* the socket file is left behind: a new lscd takes its place */
    struct stat sb;
    assert_int_equal(stat(dm.sock, &sb), 0);
    char *argv[] = {(char *)g_lscd, (char *)"--port", (char *)"sim", (char *)"--socket", dm.sock,
                    NULL};
    dm.pid = spawn(argv, dm.log);
    wait_answers(&dm);
    client *k = client_open(dm.sock, 2000, false);
    assert_int_equal(lsc_client_get_battery(&k->c, &mv, 2000), 0);
    client_close(k);
    /* and a second lscd on a served socket refuses to start */
    pid_t second = spawn(argv, dm.log);
    assert_int_equal(wait_exit(second, 30000), 1);
    stop_lscd(&dm);
}

/* ---- The controller gone and back: lsc-sim's pty closed and made again ----------------- */

static void test_controller_gone_and_back(void **state)
{
    (void)state;
    sim_proc sim;
    start_sim(&sim);
    lscd_proc dm;
    const char *extra[] = {"--retry", "20", NULL};
    start_lscd(&dm, sim.link, false, extra);
    client *k = client_open(dm.sock, 2000, false);
    client *w = client_open(dm.sock, 2000, false);
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&k->c, &mv, 2000), 0);
    stop_sim(&sim);
    /* a client that only listens is told */
    long deadline = now_ms() + test_ms(30000);
    int r;
    while ((r = lsc_client_poll(&w->c, 100)) >= 0 && now_ms() < deadline) {
    }
    assert_int_equal(r, LSC_ENODEV);
    assert_non_null(strstr(lsc_lscd_error(w->s), "went away"));
    assert_false(lsc_lscd_controller_present(w->s));
    /* requests fail at once while it is gone */
    assert_int_equal(lsc_client_get_battery(&k->c, &mv, 2000), LSC_ENODEV);
    assert_true(status_is(k->s, "controller", "gone"));
    assert_true(status_num(k->s, "losses") == 1);
    /* back: the same path again */
    restart_sim(&sim);
    wait_status(k->s, "controller", "present");
    assert_int_equal(lsc_client_get_battery(&k->c, &mv, 2000), 0);
    assert_int_equal(mv, 7500);
    client_close(k);
    client_close(w);
    stop_lscd(&dm);
    /* --exit-on-loss: lscd exits 1 instead */
    const char *exiting[] = {"--exit-on-loss", NULL};
    start_lscd(&dm, sim.link, false, exiting);
    k = client_open(dm.sock, 2000, false);
    stop_sim(&sim);
    assert_int_equal(wait_exit(dm.pid, 30000), 1);
    deadline = now_ms() + test_ms(30000);
    while ((r = lsc_client_poll(&k->c, 100)) >= 0 && now_ms() < deadline) {
    }
    assert_int_equal(r, LSC_ENODEV);
    client_close(k);
}

/* ---- A client that never reads ------------------------------------------------------------- */

static int raw_connect(const char *path)
{
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    assert_true(strlen(path) < sizeof a.sun_path);
    memcpy(a.sun_path, path, strlen(path) + 1u);
    assert_int_equal(connect(fd, (struct sockaddr *)&a, sizeof a), 0);
    return fd;
}

/* A raw client's frames, one at a time, as lscd sent them. */
typedef struct raw_reader {
    int fd;
    lsc_parser p;
    uint8_t pbuf[LSC_FRAME_MAX];
    uint8_t buf[4096];
    size_t n, at; /* bytes read into buf, bytes of them fed */
    long deadline;
} raw_reader;

static void raw_reader_init(raw_reader *rd, int fd)
{
    rd->fd = fd;
    assert_int_equal(lsc_parser_init(&rd->p, rd->pbuf, sizeof rd->pbuf), 0);
    rd->n = 0;
    rd->at = 0;
    rd->deadline = now_ms() + test_ms(30000);
}

/* The next whole frame from the socket; fails after the reader's deadline,
 * at the end of the connection, or on bytes that are not a frame. */
static void raw_next(raw_reader *rd, lsc_frame *f)
{
    for (;;) {
        while (rd->at < rd->n) {
            int r = lsc_parser_feed(&rd->p, rd->buf[rd->at++], f);
            assert_true(r >= 0);
            if (r == 1) {
                return;
            }
        }
        struct pollfd pf = {rd->fd, POLLIN, 0};
        assert_true(now_ms() < rd->deadline);
        if (poll(&pf, 1, 100) <= 0) {
            continue;
        }
        ssize_t n = read(rd->fd, rd->buf, sizeof rd->buf);
        assert_true(n > 0);
        rd->n = (size_t)n;
        rd->at = 0;
    }
}

#define FLOOD_RUNS 2000

static void test_client_never_reads(void **state)
{
    (void)state;
    lscd_proc dm;
    const char *extra[] = {"--client-queue", "4096", NULL};
    start_lscd(&dm, "sim", false, extra);
    int lazy = raw_connect(dm.sock);
    client *c = client_open_quiet(dm.sock, 5000);
    client *w = client_open(dm.sock, 5000, false);
    /* each run while the last runs: 7 (stopped) and 6 (started); then a stop */
    for (int i = 0; i < FLOOD_RUNS; i++) {
        int rr = lsc_client_run_group(&c->c, 2, 0);
        if (rr != 0) {
            print_message("run %d: %s\n", i, lsc_lscd_error(c->s));
            print_log(dm.log);
        }
        assert_int_equal(rr, 0);
        if (i % 16 == 0) {
            while (lsc_client_poll(&w->c, 0) > 0) {
            }
        }
    }
    assert_int_equal(lsc_client_stop_group(&c->c), 0);
    wait_notes(w, (size_t)2 * FLOOD_RUNS);
    size_t sixes = 0;
    for (size_t i = 0; i < w->nnotes; i++) {
        sixes += w->notes[i].cmd == LSC_CMD_GROUP_RUN;
    }
    assert_int_equal(sixes, FLOOD_RUNS);
    assert_int_equal(lsc_lscd_dropped(w->s), 0);
    /* the one that never read lost some, and lscd says so; the others did not wait */
    long total = status_num(c->s, "notifications");
    assert_int_equal(total, (long)w->nnotes);
    assert_true(status_num(c->s, "dropped") > 0);
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&c->c, &mv, 5000), 0);
    /* now it reads: whole frames, the DROPPED event, and frames + dropped = all */
    uint8_t ping[] = {0x55, 0x55, 0x07, LSC_LSCD_CMD, LSC_LSCD_OP_PING, 1, 2, 3, 4};
    raw_reader rd;
    raw_reader_init(&rd, lazy);
    long notes = 0, dropped = -1;
    bool pinged = false, ponged = false;
    while (!ponged) {
        lsc_frame f;
        raw_next(&rd, &f);
        if (f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_DROPPED) {
            dropped = (long)f.params[1] | ((long)f.params[2] << 8) | ((long)f.params[3] << 16);
        } else if (f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_PONG) {
            ponged = true;
        } else if (f.cmd != LSC_LSCD_CMD) {
            notes++;
        }
        if (dropped >= 0 && !pinged) {
            assert_int_equal(write(lazy, ping, sizeof ping), (ssize_t)sizeof ping);
            pinged = true;
        }
    }
    assert_true(dropped > 0);
    assert_int_equal(notes + dropped, total);
    assert_int_equal(rd.p.discarded, 0);
    (void)close(lazy);
    client_close(c);
    client_close(w);
    stop_lscd(&dm);
}

/* ---- Hostile clients -------------------------------------------------------------------------- */

static const uint8_t k_status_req[5] = {0x55, 0x55, 0x03, LSC_LSCD_CMD, LSC_LSCD_OP_STATUS};

/* Writes STATUS requests on fd until its socket takes no more now; returns
 * how many whole requests went. */
static long stuff_status(int fd, long most)
{
    long n = 0;
    while (n < most) {
        ssize_t w = send(fd, k_status_req, sizeof k_status_req, MSG_DONTWAIT | MSG_NOSIGNAL);
        if (w != (ssize_t)sizeof k_status_req) {
            assert_true(w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK));
            break;
        }
        n++;
    }
    return n;
}

/* Clients that send STATUS requests as fast as lscd takes them and never read. */
typedef struct flood {
    int fd[100];
    size_t n;
    pthread_t t;
    pthread_mutex_t lock;
    bool stop;
    long sent;
} flood;

static bool flood_stopped(flood *f)
{
    (void)pthread_mutex_lock(&f->lock);
    bool stop = f->stop;
    (void)pthread_mutex_unlock(&f->lock);
    return stop;
}

static void *flood_thread(void *arg)
{
    flood *f = arg;
    struct pollfd pf[100];
    long sent = 0;
    while (!flood_stopped(f)) {
        for (size_t i = 0; i < f->n; i++) {
            pf[i] = (struct pollfd){f->fd[i], POLLOUT, 0};
        }
        if (poll(pf, (nfds_t)f->n, 20) <= 0) {
            continue;
        }
        for (size_t i = 0; i < f->n; i++) {
            if ((pf[i].revents & POLLOUT) != 0) {
                sent += stuff_status(f->fd[i], 64);
            }
        }
    }
    (void)pthread_mutex_lock(&f->lock);
    f->sent = sent;
    (void)pthread_mutex_unlock(&f->lock);
    return NULL;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return x < y ? -1 : x > y;
}

/* 100 clients flood lscd (on lsc-sim's pty) with STATUS requests and never
 * read: another client's battery read, as lscctl battery does it (open,
 * read, close), is answered every time, typically within 0.5 s (the median of
 * 20: a loaded machine's scheduler may delay any one read; before the
 * backpressure rule the median was over 5 s, bench_lscd). */
static void test_hostile_flooders(void **state)
{
    (void)state;
    sim_proc sp;
    start_sim(&sp);
    lscd_proc dm;
    start_lscd(&dm, sp.link, false, NULL);
    char via[160];
    (void)snprintf(via, sizeof via, "lscd:%s", dm.sock);
    flood f;
    memset(&f, 0, sizeof f);
    f.n = sizeof f.fd / sizeof f.fd[0];
    for (size_t i = 0; i < f.n; i++) {
        f.fd[i] = raw_connect(dm.sock);
    }
    assert_int_equal(pthread_mutex_init(&f.lock, NULL), 0);
    assert_int_equal(pthread_create(&f.t, NULL, flood_thread, &f), 0);
    long took[20];
    test_options opt;
    memset(&opt, 0, sizeof opt);
    opt.timeout_ms = (uint32_t)test_ms(10000);
    for (int i = 0; i < 20; i++) {
        long start = now_ms();
        lsc_device *d = NULL;
        uint16_t mv = 0;
        int r = test_open(via, &opt, &d);
        if (r == 0) {
            r = lsc_device_battery(d, &mv);
        }
        if (r != 0) {
            print_message("battery %d: %s\n", i, lsc_device_error(d));
        }
        lsc_device_close(d);
        assert_int_equal(r, 0);
        took[i] = now_ms() - start;
    }
    qsort(took, 20, sizeof took[0], cmp_long);
    (void)pthread_mutex_lock(&f.lock);
    f.stop = true;
    (void)pthread_mutex_unlock(&f.lock);
    assert_int_equal(pthread_join(f.t, NULL), 0);
    print_message("100 flooders (%ld requests): battery read median %ld ms, worst %ld ms\n",
                  f.sent, took[10], took[19]);
    assert_true(f.sent > 0);
    assert_true(took[10] < test_ms(500));
    /* the flooders are each held back by their own unread output, not served */
    client *k = client_open_quiet(dm.sock, 5000);
    assert_true(status_num(k->s, "clients") == 101);
    for (size_t i = 0; i < f.n; i++) {
        (void)close(f.fd[i]);
    }
    (void)pthread_mutex_destroy(&f.lock);
    client_close(k);
    stop_lscd(&dm);
    stop_sim(&sp);
}

/* Waits until lscd lists a client that shut its sending side. */
static void wait_shut(lsc_lscd *s)
{
    long deadline = now_ms() + test_ms(30000);
    for (;;) {
        status st;
        get_status(s, &st);
        if (strstr(st.text, " shut ") != NULL) {
            return;
        }
        assert_true(now_ms() < deadline);
        pause_ms(2);
    }
}

/* A raw client that holds the lease (60 s). */
static int raw_lease_holder(const char *sock)
{
    int fd = raw_connect(sock);
    uint8_t lease[] = {0x55, 0x55, 0x0B, LSC_LSCD_CMD, LSC_LSCD_OP_LEASE, 0x60, 0xEA, 0, 0, 0, 0, 0, 0};
    assert_int_equal(send(fd, lease, sizeof lease, MSG_NOSIGNAL), (ssize_t)sizeof lease);
    raw_reader rd;
    raw_reader_init(&rd, fd);
    for (;;) {
        lsc_frame f;
        raw_next(&rd, &f);
        if (f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_LEASE) {
            assert_int_equal(f.params[1], LSC_LSCD_LEASE_GRANTED);
            return fd;
        }
    }
}

/* A lease asked for behind queued output and then a half-close: never
 * granted; a lease whose holder half-closes or leaves its output unread ends. */
static void test_hostile_leases(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    client *b = client_open_quiet(dm.sock, 5000);
    /* 3000 STATUS requests (as many as the socket takes), a LEASE, a half-close */
    int a = raw_connect(dm.sock);
    static const uint8_t lease[] = {0x55, 0x55, 0x0B, LSC_LSCD_CMD, LSC_LSCD_OP_LEASE,
                                    0x60, 0xEA, 0, 0, 0, 0, 0, 0};
    static uint8_t burst[3000u * sizeof k_status_req + sizeof lease];
    for (size_t i = 0; i < 3000u; i++) {
        memcpy(burst + i * sizeof k_status_req, k_status_req, sizeof k_status_req);
    }
    memcpy(burst + 3000u * sizeof k_status_req, lease, sizeof lease);
    assert_int_equal(send(a, burst, sizeof burst, MSG_NOSIGNAL), (ssize_t)sizeof burst);
    assert_int_equal(shutdown(a, SHUT_WR), 0);
    /* whatever lscd did with a, b gets the lease at once once lscd has seen the half-close */
    long deadline = now_ms() + test_ms(30000);
    int r;
    while ((r = lsc_lscd_lease(b->s, 1000, 0)) == LSC_EBUSY && now_ms() < deadline) {
        pause_ms(5);
    }
    assert_int_equal(r, 0);
    assert_int_equal(lsc_lscd_release(b->s), 0);
    /* a PING b sends after the half-close was seen: a's lease is never granted later */
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&b->c, &mv, 5000), 0);
    assert_true(status_is(b->s, "lease", "none"));
    (void)close(a);

    /* a lease waited for, then a half-close: not granted when the holder lets go */
    assert_int_equal(lsc_lscd_lease(b->s, 60000, 0), 0);
    a = raw_connect(dm.sock);
    uint8_t wait_lease[] = {0x55, 0x55, 0x0B, LSC_LSCD_CMD, LSC_LSCD_OP_LEASE, 0x60, 0xEA, 0, 0,
                            0x30, 0x75, 0, 0}; /* 60 s, waiting up to 30 s */
    assert_int_equal(send(a, wait_lease, sizeof wait_lease, MSG_NOSIGNAL), (ssize_t)sizeof wait_lease);
    wait_queued(b->s, 1);
    assert_int_equal(shutdown(a, SHUT_WR), 0);
    wait_shut(b->s);
    client *probe = client_open_quiet(dm.sock, 5000);
    assert_int_equal(lsc_lscd_release(b->s), 0);
    assert_int_equal(lsc_lscd_lease(probe->s, 1000, 0), 0);
    assert_int_equal(lsc_lscd_release(probe->s), 0);
    client_close(probe);
    (void)close(a);
    /* a holder that half-closes while its output waits unread: its lease ends at once */
    a = raw_lease_holder(dm.sock);
    assert_true(stuff_status(a, 100000) > 0);
    assert_int_equal(shutdown(a, SHUT_WR), 0);
    assert_int_equal(lsc_lscd_lease(b->s, 1000, (uint32_t)test_ms(30000)), 0);
    assert_int_equal(lsc_lscd_release(b->s), 0);
    (void)close(a);
    /* a holder that leaves its output unread: its lease ends after LSCD_LEASE_BLOCKED_MS */
    a = raw_lease_holder(dm.sock);
    long start = now_ms();
    assert_true(stuff_status(a, 100000) > 0);
    assert_int_equal(lsc_lscd_lease(b->s, 1000, (uint32_t)test_ms(60000)), 0);
    assert_true(now_ms() - start >= 4000); /* (5 s, less what the ms clocks round away) */
    assert_int_equal(lsc_lscd_release(b->s), 0);
    (void)close(a);
    client_close(b);
    stop_lscd(&dm);
}

/* lscd's log escapes what it repeats: a socket path with ESC and a newline
 * forges no line and colours nothing; the protocol keeps the exact bytes. */
static void test_hostile_log_escapes(void **state)
{
    (void)state;
    lscd_proc dm;
    int w = snprintf(dm.sock, sizeof dm.sock, "%s/e\033[31m\nlscd: forged%u", g_dir, ++g_seq);
    assert_true(w > 0 && (size_t)w < sizeof dm.sock);
    path_in_dir(dm.log, sizeof dm.log, "lscd.log.");
    char *argv[] = {(char *)g_lscd, (char *)"--port", (char *)"sim", (char *)"--socket", dm.sock,
                    (char *)"-v", NULL};
    dm.pid = spawn(argv, dm.log);
    wait_answers(&dm);
    client *k = client_open_quiet(dm.sock, 5000);
    status st;
    get_status(k->s, &st);
    char want[300];
    (void)snprintf(want, sizeof want, "socket=%s\n", dm.sock);
    assert_non_null(strstr(st.text, want));
    client_close(k);
    stop_lscd(&dm);
    char buf[8192];
    FILE *f = fopen(dm.log, "r");
    assert_non_null(f);
    size_t n = fread(buf, 1, sizeof buf - 1u, f);
    (void)fclose(f);
    buf[n] = '\0';
    assert_null(strchr(buf, '\033'));
    assert_non_null(strstr(buf, "e\\x1B[31m\\x0Alscd: forged"));
    for (const char *line = buf; *line != '\0'; line = strchr(line, '\n') + 1) {
        assert_int_equal(strncmp(line, "lscd: ", 6), 0);
        assert_non_null(strchr(line, '\n'));
    }
}

/* lscd at its client limit tells the one too many why (its limit, how to
 * raise it), as a busy port; malformed frames are counted in its status. */
static void test_hostile_full_and_malformed(void **state)
{
    (void)state;
    lscd_proc dm;
    const char *extra[] = {"--max-clients", "2", NULL};
    start_lscd(&dm, "sim", false, extra);
    client *a = client_open_quiet(dm.sock, 5000);
    client *b = client_open_quiet(dm.sock, 5000);
    lsc_lscd *s = NULL;
    lsc_lscd_options opt = {sizeof opt, 0, (uint32_t)test_ms(10000), false, true};
    assert_int_equal(lsc_lscd_open(dm.sock, &opt, &s), LSC_EBUSY);
    assert_non_null(strstr(lsc_lscd_error(s), "at most 2 clients"));
    assert_non_null(strstr(lsc_lscd_error(s), "--max-clients"));
    lsc_lscd_close(s);
    assert_int_equal(status_num(a->s, "full"), 1);
    assert_int_equal(status_num(a->s, "max_clients"), 2);
    /* a battery request with a parameter is malformed (and garbage is discarded) */
    static const uint8_t bad[] = {0x55, 0x55, 0x03, 0x0F, 0x00, 0x01, 0x02};
    long before = status_num(a->s, "malformed");
    assert_int_equal(lsc_lscd_write(b->s, bad, sizeof bad), (int)sizeof bad);
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&b->c, &mv, 5000), 0); /* (after the bad bytes) */
    assert_true(status_num(a->s, "malformed") > before);
    assert_true(status_num(a->s, "discarded") > 0);
    client_close(b);
    client_close(a);
    stop_lscd(&dm);
}

/* ---- A controller of the test's own: order, timeouts, frames lscd does not know ---------- */

typedef struct fake {
    int master;
    pthread_t t;
    int stop[2];
    pthread_mutex_t lock;
    bool mute_battery; /* leave battery requests unanswered */
    unsigned got[256]; /* frames received, by command */
} fake;

static void fake_send(fake *f, uint8_t cmd, const uint8_t *params, size_t n)
{
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_encode_frame(frame, sizeof frame, cmd, params, n);
    if (len > 0) {
        (void)!write(f->master, frame, (size_t)len);
    }
}

static void *fake_main(void *arg)
{
    fake *f = arg;
    lsc_parser p;
    uint8_t pbuf[LSC_FRAME_MAX];
    (void)lsc_parser_init(&p, pbuf, sizeof pbuf);
    for (;;) {
        struct pollfd pf[2] = {{f->master, POLLIN, 0}, {f->stop[0], POLLIN, 0}};
        if (poll(pf, 2, -1) < 0 || pf[1].revents != 0) {
            return NULL;
        }
        uint8_t buf[256];
        ssize_t n = read(f->master, buf, sizeof buf);
        if (n <= 0) {
            continue;
        }
        for (ssize_t i = 0; i < n; i++) {
            lsc_frame fr;
            if (lsc_parser_feed(&p, buf[i], &fr) != 1) {
                continue;
            }
            (void)pthread_mutex_lock(&f->lock);
            f->got[fr.cmd]++;
            bool mute = f->mute_battery;
            (void)pthread_mutex_unlock(&f->lock);
            uint8_t out[LSC_PARAMS_MAX];
            if (fr.cmd == LSC_CMD_BATTERY && !mute) {
                const uint8_t mv[2] = {0x38, 0x1C}; /* 7224 */
                fake_send(f, LSC_CMD_BATTERY, mv, 2);
            } else if (fr.cmd == LSC_CMD_POS_READ && fr.nparams >= 2u) {
                lsc_servo s[LSC_READ_MAX];
                size_t k = fr.params[0];
                for (size_t j = 0; j < k && j < LSC_READ_MAX; j++) {
                    s[j].id = fr.params[1 + j];
                    s[j].position = (uint16_t)(s[j].id * 10u);
                }
                uint8_t frame[LSC_FRAME_MAX];
                int len = lsc_encode_pos_reply(frame, sizeof frame, s, k);
                if (len > 0) {
                    (void)!write(f->master, frame, (size_t)len);
                }
            } else if (fr.cmd == 0x1A) { /* a command lscd does not know, with an answer */
                for (size_t j = 0; j < fr.nparams; j++) {
                    out[j] = fr.params[fr.nparams - 1u - j];
                }
                fake_send(f, 0x1A, out, fr.nparams);
            } else if (fr.cmd == LSC_CMD_GROUP_RUN) {
                /* notifications around an answer to something else */
                fake_send(f, LSC_CMD_GROUP_RUN, fr.params, fr.nparams);
                fake_send(f, LSC_CMD_GROUP_COMPLETE, fr.params, fr.nparams);
            }
        }
    }
}

static void fake_start(fake *f, char *link, size_t cap)
{
    int slave;
    char name[128];
    memset(f, 0, sizeof *f);
    assert_int_equal(openpty(&f->master, &slave, name, NULL, NULL), 0);
    struct termios t;
    assert_int_equal(tcgetattr(slave, &t), 0);
    cfmakeraw(&t);
    assert_int_equal(tcsetattr(slave, TCSANOW, &t), 0);
    (void)close(slave);
    path_in_dir(link, cap, "fake.");
    assert_int_equal(symlink(name, link), 0);
    assert_int_equal(pipe(f->stop), 0);
    assert_int_equal(pthread_mutex_init(&f->lock, NULL), 0);
    assert_int_equal(pthread_create(&f->t, NULL, fake_main, f), 0);
}

static void fake_stop(fake *f)
{
    (void)!write(f->stop[1], "x", 1);
    (void)pthread_join(f->t, NULL);
    (void)close(f->master);
    (void)close(f->stop[0]);
    (void)close(f->stop[1]);
    (void)pthread_mutex_destroy(&f->lock);
}

static unsigned fake_got(fake *f, uint8_t cmd)
{
    (void)pthread_mutex_lock(&f->lock);
    unsigned n = f->got[cmd];
    (void)pthread_mutex_unlock(&f->lock);
    return n;
}

typedef struct bg_read {
    client *k;
    int r;
    long took;
    lsc_servo got;
    pthread_t t;
} bg_read;

static void *read_thread(void *arg)
{
    bg_read *b = arg;
    uint8_t id = 7;
    long start = now_ms();
    b->r = lsc_client_read_positions(&b->k->c, &id, 1, &b->got, (uint32_t)test_ms(30000));
    b->took = now_ms() - start;
    return NULL;
}

static void test_routing_and_timeouts(void **state)
{
    (void)state;
    fake f;
    char link[256];
    fake_start(&f, link, sizeof link);
    lscd_proc dm;
    start_lscd(&dm, link, false, NULL);
    client *a = client_open(dm.sock, 2000, false);
    client *b = client_open(dm.sock, 2000, false);
    /* a command lscd does not know: its answer goes to whoever sent it */
    uint8_t params[3] = {1, 2, 3}, reply[8];
    assert_int_equal(lsc_client_request_raw(&a->c, 0x1A, params, 3, 0x1A, reply, sizeof reply, 2000),
                     3);
    assert_int_equal(reply[0], 3);
    assert_int_equal(reply[2], 1);
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&b->c, &mv, 2000), 0);
    assert_int_equal(mv, 7224);
    lsc_client_counts counts;
    lsc_client_get_counts(&b->c, &counts);
    assert_int_equal(counts.unexpected, 0);
    /* notifications the controller sends between replies reach every client */
    int rr = lsc_client_run_group(&a->c, 4, 1);
    if (rr != 0) {
        print_message("run: %s\n", lsc_lscd_error(a->s));
        print_log(dm.log);
    }
    assert_int_equal(rr, 0);
    wait_notes(b, 2);
    assert_int_equal(b->notes[1].cmd, LSC_CMD_GROUP_COMPLETE);
    /* a request that gets no reply holds the next one back for its own
     * timeout at most; one whose timeout passes while it waits is never sent */
    (void)pthread_mutex_lock(&f.lock);
    f.mute_battery = true;
    (void)pthread_mutex_unlock(&f.lock);
    client *slow = client_open(dm.sock, 500, false);
    client *hasty = client_open(dm.sock, 100, false);
    client *reader = client_open(dm.sock, (uint32_t)test_ms(30000), false);
    unsigned batteries = fake_got(&f, LSC_CMD_BATTERY);
    bg_battery bs;
    bg_start(&bs, slow, 500);
    wait_queued(a->s, 1);
    bg_read br = {reader, 0, 0, {0, 0}, 0};
    assert_int_equal(pthread_create(&br.t, NULL, read_thread, &br), 0);
    assert_int_equal(lsc_client_get_battery(&hasty->c, &mv, 100), LSC_ETIMEOUT);
    assert_int_equal(pthread_join(bs.t, NULL), 0);
    assert_int_equal(pthread_join(br.t, NULL), 0);
    assert_int_equal(bs.r, LSC_ETIMEOUT);
    assert_int_equal(br.r, 1);
    assert_int_equal(br.got.position, 70);
    assert_true(br.took < 500 + test_ms(2000));
    /* the slow one's battery went out; the hasty one's expired unsent */
    assert_int_equal(fake_got(&f, LSC_CMD_BATTERY), batteries + 1u);
    assert_true(status_num(a->s, "expired") >= 1);
    /* the link's counters: every frame lscd wrote and read, the battery
     * request left unanswered */
    assert_true(status_num(a->s, "link_timeouts") == 1);
    assert_true(status_num(a->s, "link_sent") >= 5);
    assert_true(status_num(a->s, "link_received") >= 4);
    assert_true(status_num(a->s, "link_bad") == 0);
    assert_true(status_num(a->s, "link_discarded") == 0);
    client_close(slow);
    client_close(hasty);
    client_close(reader);
    client_close(a);
    client_close(b);
    stop_lscd(&dm);
    fake_stop(&f);
}

/* A halt does not wait for the request under way: the request stops waiting
 * for its reply (LSC_EBUSY, as the frames the halt drops), the halt goes at
 * once, and the next request is answered as usual. */
static void test_halt_cuts_a_request(void **state)
{
    (void)state;
    fake f;
    char link[256];
    fake_start(&f, link, sizeof link);
    (void)pthread_mutex_lock(&f.lock);
    f.mute_battery = true;
    (void)pthread_mutex_unlock(&f.lock);
    lscd_proc dm;
    start_lscd(&dm, link, false, NULL);
    client *slow = client_open(dm.sock, (uint32_t)test_ms(60000), false);
    client *halter = client_open(dm.sock, 2000, false);
    unsigned batteries = fake_got(&f, LSC_CMD_BATTERY);
    bg_battery bs;
    bg_start(&bs, slow, (uint32_t)test_ms(60000));
    long deadline = now_ms() + test_ms(30000);
    while (fake_got(&f, LSC_CMD_BATTERY) == batteries) { /* the request is out */
        assert_true(now_ms() < deadline);
        pause_ms(2);
    }
    assert_int_equal(lsc_lscd_halt(halter->s), 0);
    assert_int_equal(pthread_join(bs.t, NULL), 0);
    assert_int_equal(bs.r, LSC_EBUSY);
    assert_true(bs.took < test_ms(30000)); /* (its own timeout: 60 s) */
    assert_int_equal(fake_got(&f, LSC_CMD_GROUP_STOP), 1);
    assert_true(fake_got(&f, LSC_CMD_POS_READ) >= 1);
    /* nothing of the interrupt is left for the next request */
    (void)pthread_mutex_lock(&f.lock);
    f.mute_battery = false;
    (void)pthread_mutex_unlock(&f.lock);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&slow->c, &mv, 2000), 0);
    assert_int_equal(mv, 7224);
    client_close(slow);
    client_close(halter);
    stop_lscd(&dm);
    fake_stop(&f);
}

/* Clients that speak the protocol themselves, badly. */
static void test_raw_clients(void **state)
{
    (void)state;
    lscd_proc dm;
    start_lscd(&dm, "sim", false, NULL);
    int fd = raw_connect(dm.sock);
    /* noise, an unknown op, a bad length, then a battery request without ack */
    static const uint8_t junk[] = {0x00, 0x55, 0x13, 0x55, 0x55, 0x03, LSC_LSCD_CMD, 0x7F,
                                   0x55, 0x55, 0x05, LSC_LSCD_CMD, LSC_LSCD_OP_MODE, 1, 2,
                                   0x55, 0x55, 0x02, 0x0F};
    assert_int_equal(write(fd, junk, sizeof junk), (ssize_t)sizeof junk);
    raw_reader rd;
    raw_reader_init(&rd, fd);
    int errors = 0;
    bool battery = false, hello = false;
    while (!battery) {
        lsc_frame f;
        raw_next(&rd, &f);
        if (f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_HELLO) {
            hello = true;
            assert_int_equal(f.params[1], LSC_LSCD_PROTOCOL);
        } else if (f.cmd == LSC_LSCD_CMD && f.params[0] == LSC_LSCD_EV_ERROR) {
            errors++;
        } else if (f.cmd == LSC_CMD_BATTERY) {
            battery = true;
        } else {
            assert_int_not_equal(f.params[0], LSC_LSCD_EV_VERDICT); /* no ack asked */
        }
    }
    assert_true(hello);
    assert_int_equal(errors, 2);
    (void)close(fd);
    stop_lscd(&dm);
}

/* After each test: whatever it started and did not stop is killed. */
static int reap(void **state)
{
    (void)state;
    for (size_t i = 0; i < g_nspawned; i++) {
        int st;
        if (waitpid(g_spawned[i], &st, WNOHANG) == 0) {
            (void)kill(g_spawned[i], SIGKILL);
            (void)waitpid(g_spawned[i], &st, 0);
        }
    }
    g_nspawned = 0;
    return 0;
}

static int setup(void **state)
{
    (void)state;
    (void)snprintf(g_dir, sizeof g_dir, "%s/lscd-test-XXXXXX",
                   getenv("TMPDIR") != NULL ? getenv("TMPDIR") : "/tmp");
    if (mkdtemp(g_dir) == NULL) {
        return -1;
    }
    (void)signal(SIGPIPE, SIG_IGN);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    pid_t pid = fork();
    if (pid == 0) {
        execlp("rm", "rm", "-rf", g_dir, (char *)NULL);
        _exit(127);
    }
    int st = 0;
    return pid > 0 && waitpid(pid, &st, 0) == pid && WIFEXITED(st) && WEXITSTATUS(st) == 0 ? 0
                                                                                         : -1;
}

static void find_activate(void)
{
    const char *path = getenv("PATH");
    g_activate[0] = '\0';
    if (path == NULL) {
        return;
    }
    char copy[4096];
    (void)snprintf(copy, sizeof copy, "%s", path);
    for (char *dir = strtok(copy, ":"); dir != NULL; dir = strtok(NULL, ":")) {
        char candidate[512];
        (void)snprintf(candidate, sizeof candidate, "%s/systemd-socket-activate", dir);
        if (access(candidate, X_OK) == 0) {
            (void)snprintf(g_activate, sizeof g_activate, "%s", candidate);
            return;
        }
    }
}

/* Writes text to path. */
static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
}

/* lscd's records (DIR/NAME.record): written atomically with absolute paths;
 * read back for the same port (through a link too); ignored for another
 * port of the same NAME, a process that is gone, a file that is no record. */
static void test_records(void **state)
{
    (void)state;
    char dir[] = "/tmp/lsc-test-record-XXXXXX", run[96], port[96], link_[96], other[96];
    char record[160], out[LSC_LSCD_PATH_MAX], cwd[512], want[700], text[600];
    long pid = 0;
    assert_non_null(mkdtemp(dir));
    snprintf(run, sizeof run, "%s/run", dir);
    snprintf(port, sizeof port, "%s/arm", dir);
    snprintf(link_, sizeof link_, "%s/link", dir);
    snprintf(other, sizeof other, "%s/other", dir);
    assert_int_equal(mkdir(other, 0755), 0);
    snprintf(other, sizeof other, "%s/other/arm", dir);
    put_file(port, "");
    put_file(other, "");
    assert_int_equal(symlink(port, link_), 0);
    assert_int_equal(setenv("LSC_LSCD_DIR", run, 1), 0);
    assert_int_equal(lsc_lscd_recorded_socket(port, out, sizeof out, &pid), LSC_ENODEV);
    /* the run directory is made; the socket's relative path made absolute */
    assert_int_equal(lsc_lscd_record_write(port, "s.sock", record, sizeof record), 0);
    assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(want, sizeof want, "%s/s.sock", cwd);
    int n = lsc_lscd_recorded_socket(port, out, sizeof out, &pid);
    if (strlen(want) < sizeof out) {
        assert_int_equal(n, (int)strlen(want));
        assert_string_equal(out, want);
        assert_int_equal(pid, (long)getpid());
    }
    assert_int_equal(lsc_lscd_record_write(port, "/x/s.sock", record, sizeof record), 0);
    snprintf(want, sizeof want, "%s/arm.record", run);
    assert_string_equal(record, want);
    assert_int_equal(lsc_lscd_recorded_socket(port, out, sizeof out, NULL), 9);
    assert_string_equal(out, "/x/s.sock");
    assert_int_equal(lsc_lscd_recorded_socket(port, out, 9, NULL), LSC_ENOSPC);
    /* the same file through a link of another name has no record; a port of
     * the same NAME that is another file is not the recorded one */
    assert_int_equal(lsc_lscd_recorded_socket(link_, out, sizeof out, NULL), LSC_ENODEV);
    assert_int_equal(lsc_lscd_recorded_socket(other, out, sizeof out, NULL), LSC_ENODEV);
    /* the process is gone */
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        _exit(0);
    }
    assert_int_equal(waitpid(child, NULL, 0), child);
    snprintf(text, sizeof text, "pid %ld\nport %s\nsocket /x/s.sock\n", (long)child, port);
    put_file(record, text);
    assert_int_equal(lsc_lscd_recorded_socket(port, out, sizeof out, NULL), LSC_ENODEV);
    /* not records: a key missing, a line cut short, a relative path, a bad pid */
    static const char *const bad[] = {"pid 1\nport %s\n", "pid 1\nport %s\nsocket /x",
                                      "pid 1\nport %s\nsocket x.sock\n",
                                      "pid 0\nport %s\nsocket /x\n",
                                      "pid 1x\nport %s\nsocket /x\n"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(text, sizeof text, bad[i], port);
        put_file(record, text);
        assert_int_equal(lsc_lscd_recorded_socket(port, out, sizeof out, NULL), LSC_EINVAL);
    }
    assert_int_equal(unlink(record), 0);
    assert_int_equal(mkdir(record, 0755), 0); /* not a regular file */
    assert_int_equal(lsc_lscd_recorded_socket(port, out, sizeof out, NULL), LSC_EINVAL);
    assert_int_equal(rmdir(record), 0);
    /* refused: NULLs, a port without a NAME, a path with a newline */
    assert_int_equal(lsc_lscd_recorded_socket(NULL, out, sizeof out, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lscd_recorded_socket(port, NULL, 0, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lscd_recorded_socket("/dev/", out, sizeof out, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lscd_record_write(port, "/x/a\nb", record, sizeof record), LSC_EINVAL);
    assert_int_equal(lsc_lscd_record_write(port, "/x", record, 8), LSC_ENOSPC);
    (void)unsetenv("LSC_LSCD_DIR");
    (void)rmdir(run);
    (void)unlink(link_);
    (void)unlink(port);
    (void)unlink(other);
    snprintf(other, sizeof other, "%s/other", dir);
    (void)rmdir(other);
    (void)rmdir(dir);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        (void)fprintf(stderr, "usage: %s LSCD LSC-SIM GROUPS\n", argv[0]);
        return 2;
    }
    g_lscd = argv[1];
    g_sim = argv[2];
    g_groups = argv[3];
    find_activate();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_names, reap),
        cmocka_unit_test_teardown(test_records, reap),
        cmocka_unit_test_teardown(test_open_errors, reap),
        cmocka_unit_test_teardown(test_sim_basics, reap),
        cmocka_unit_test_teardown(test_raw_clients, reap),
        cmocka_unit_test_teardown(test_notifications, reap),
        cmocka_unit_test_teardown(test_sim_idle_sleeps, reap),
        cmocka_unit_test_teardown(test_lease, reap),
        cmocka_unit_test_teardown(test_options_size, reap),
        cmocka_unit_test_teardown(test_halt, reap),
        cmocka_unit_test_teardown(test_halt_stops_a_play, reap),
        cmocka_unit_test_teardown(test_lease_holder_killed, reap),
        cmocka_unit_test_teardown(test_lscd_killed, reap),
        cmocka_unit_test_teardown(test_routing_and_timeouts, reap),
        cmocka_unit_test_teardown(test_halt_cuts_a_request, reap),
        cmocka_unit_test_teardown(test_controller_gone_and_back, reap),
        cmocka_unit_test_teardown(test_client_never_reads, reap),
        cmocka_unit_test_teardown(test_hostile_flooders, reap),
        cmocka_unit_test_teardown(test_hostile_leases, reap),
        cmocka_unit_test_teardown(test_hostile_log_escapes, reap),
        cmocka_unit_test_teardown(test_hostile_full_and_malformed, reap),
        cmocka_unit_test_teardown(test_many_sim, reap),
        cmocka_unit_test_teardown(test_many_pty, reap),
        cmocka_unit_test_teardown(test_many_activated, reap),
    };
    if (argc > 4) {
        cmocka_set_test_filter(argv[4]); /* one test, or a pattern (while debugging) */
    }
    return cmocka_run_group_tests(tests, setup, teardown);
}
