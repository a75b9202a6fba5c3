/* What lscd costs: prints figures (a benchmark, not a test).
 *
 *  1. A battery exchange (lsc_device_battery) direct and through lscd, on the
 *     virtual controller ("sim" in-process against lscd --port sim) and on
 *     lsc-sim paced at 9600 baud (one lsc-sim opened directly against another
 *     behind lscd, both paced): the calls alternate between the two paths, so
 *     both see the same moments of a busy machine; median and p99 of each, and
 *     what lscd adds.
 *  2. SUBSCRIBERS idle subscribers (default 100: one thread each, blocked in
 *     lsc_lscd_read on its own connection): lscd's CPU time while nothing
 *     happens for IDLE seconds (utime + stime of /proc/PID/stat, in clock
 *     ticks; the nanoseconds on a CPU of /proc/PID/task/x/schedstat; its
 *     threads' context switches, i.e. wake-ups), then the spread of each
 *     notification's arrival across them: a client that does not subscribe
 *     runs a group NOTIFY times, each run sends a start (6) and a completion
 *     (8) to every subscriber, and each subscriber's thread takes
 *     CLOCK_MONOTONIC as its read returns; spread = latest - earliest.
 *  3. Hostile clients: 0, 10 and 100 flooders (connections that send STATUS
 *     requests as fast as lscd takes them and never read a byte) against lscd
 *     on lsc-sim paced at 9600 baud, and meanwhile another client's battery
 *     read as lscctl battery does it (open lscd:PATH, read, close), FLOOD
 *     times each: median, p99 and worst.
 *
 * Usage: bench_lscd [--lscd PATH] [--lsc-sim PATH] [--exchanges-sim N]
 *                   [--exchanges-pty N] [--subscribers N] [--idle S]
 *                   [--notify N]
 *                   [--flood N]
 * (the programs default to those of the build tree this was built in). */
#define _DEFAULT_SOURCE 1
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/device.h"
#include "lsc/lscd.h"
#include "lsc/sim.h"

#ifndef BENCH_LSCD
#define BENCH_LSCD "lscd"
#endif
#ifndef BENCH_LSC_SIM
#define BENCH_LSC_SIM "lsc-sim"
#endif

#define START_DEADLINE_S 30.0 /* for a program to come up */
#define EVENT_DEADLINE_S 30.0 /* for a notification to reach every subscriber */

typedef struct options {
    const char *lscd, *lsc_sim;
    long exchanges_sim, exchanges_pty, subscribers, idle_s, notify, flood;
} options;

static char tmpdir[64];

/* ---- Time, numbers ------------------------------------------------------- */

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec / 1e9;
}

static void sleep_s(double s)
{
    struct timespec t;
    t.tv_sec = (time_t)s;
    t.tv_nsec = (long)((s - (double)t.tv_sec) * 1e9);
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The q-quantile (0..1) of n sorted values: the smallest value with at least
 * q * n values at or below it. */
static double quantile(const double *sorted, size_t n, double q)
{
    size_t k = (size_t)(q * (double)n + 0.999999);
    return sorted[k == 0u ? 0u : (k > n ? n : k) - 1u];
}

/* ---- Programs ------------------------------------------------------------ */

/* Starts argv[0] with stdout to /dev/null and stderr to log (a file in
 * tmpdir); returns its pid or -1. */
static pid_t spawn(char *const argv[], const char *log)
{
    pid_t pid = fork();
    if (pid == 0) {
#ifdef __linux__
        (void)prctl(PR_SET_PDEATHSIG, SIGTERM); /* ends with this program, however it ends */
#endif
        int null = open("/dev/null", O_WRONLY);
        int err = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (null >= 0) {
            (void)dup2(null, 1);
        }
        if (err >= 0) {
            (void)dup2(err, 2);
        }
        execv(argv[0], argv);
        fprintf(stderr, "bench_lscd: cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    return pid;
}

static void stop(pid_t *pid)
{
    if (*pid > 0) {
        (void)kill(*pid, SIGTERM);
        (void)waitpid(*pid, NULL, 0);
        *pid = -1;
    }
}

static bool alive(pid_t pid)
{
    return waitpid(pid, NULL, WNOHANG) == 0;
}

/* lsc-sim on a new pty, linked at tmpdir/NAME (paced at 9600 baud, its
 * default); groups: a group file or NULL. */
static pid_t start_sim(const options *o, const char *name, const char *groups)
{
    char link[128], log[128];
    snprintf(link, sizeof link, "%s/%s", tmpdir, name);
    snprintf(log, sizeof log, "%s/%s.log", tmpdir, name);
    char *argv[] = {(char *)o->lsc_sim, "--link", link, NULL, NULL, NULL};
    if (groups != NULL) {
        argv[3] = "--groups";
        argv[4] = (char *)groups;
    }
    pid_t pid = spawn(argv, log);
    struct stat st;
    for (double end = now_s() + START_DEADLINE_S; pid > 0 && stat(link, &st) != 0;) {
        if (now_s() > end || !alive(pid)) {
            fprintf(stderr, "bench_lscd: lsc-sim did not make %s (see %s)\n", link, log);
            stop(&pid);
            return -1;
        }
        sleep_s(0.005);
    }
    return pid;
}

/* lscd --port PORT --socket tmpdir/SOCK; returns its pid once it answers. */
static pid_t start_lscd(const options *o, const char *port, const char *sock)
{
    char path[128], log[128];
    snprintf(path, sizeof path, "%s/%s", tmpdir, sock);
    snprintf(log, sizeof log, "%s/%s.log", tmpdir, sock);
    char *argv[] = {(char *)o->lscd, "--port", (char *)port, "--socket", path, NULL};
    pid_t pid = spawn(argv, log);
    for (double end = now_s() + START_DEADLINE_S; pid > 0;) {
        lsc_lscd *s;
        int r = lsc_lscd_open(path, NULL, &s);
        lsc_lscd_close(s);
        if (r == 0) {
            break;
        }
        if (now_s() > end || !alive(pid)) {
            fprintf(stderr, "bench_lscd: lscd on %s did not answer at %s (see %s)\n", port, path,
                    log);
            stop(&pid);
            return -1;
        }
        sleep_s(0.005);
    }
    return pid;
}

static lsc_device *open_device(const char *name)
{
    lsc_device *d;
    if (lsc_device_open(name, NULL, &d) != 0) {
        fprintf(stderr, "bench_lscd: %s\n", lsc_device_error(d));
        lsc_device_close(d);
        return NULL;
    }
    return d;
}

/* ---- 1. Battery exchanges -------------------------------------------------- */

static int battery_us(lsc_device *d, double *us)
{
    uint16_t mv = 0;
    double t0 = now_s();
    int r = lsc_device_battery(d, &mv);
    *us = (now_s() - t0) * 1e6;
    if (r != 0 || mv == 0u) {
        fprintf(stderr, "bench_lscd: battery on %s: %s\n", lsc_device_name(d), lsc_device_error(d));
        return -1;
    }
    return 0;
}

/* n exchanges on each of direct and via (alternating which goes first);
 * prints one line of the table. */
static int exchanges(const char *label, const char *direct, const char *via, long n)
{
    lsc_device *a = open_device(direct), *b = a != NULL ? open_device(via) : NULL;
    double *da = calloc((size_t)n, sizeof *da), *db = calloc((size_t)n, sizeof *db);
    int r = a != NULL && b != NULL && da != NULL && db != NULL ? 0 : -1;
    double dummy;
    for (long i = 0; i < 10 && r == 0; i++) { /* warm up both paths */
        r = battery_us(a, &dummy) | battery_us(b, &dummy);
    }
    for (long i = 0; i < n && r == 0; i++) {
        if (i % 2 == 0) {
            r = battery_us(a, &da[i]) | battery_us(b, &db[i]);
        } else {
            r = battery_us(b, &db[i]) | battery_us(a, &da[i]);
        }
    }
    if (r == 0) {
        qsort(da, (size_t)n, sizeof *da, cmp_double);
        qsort(db, (size_t)n, sizeof *db, cmp_double);
        double ma = quantile(da, (size_t)n, 0.5), mb = quantile(db, (size_t)n, 0.5);
        double pa = quantile(da, (size_t)n, 0.99), pb = quantile(db, (size_t)n, 0.99);
        printf("%-22s %6ld %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f  %s\n", label, n, ma, pa, mb,
               pb, mb - ma, pb - pa, mb - ma <= 300.0 ? "met" : "MISSED");
    }
    lsc_device_close(a);
    lsc_device_close(b);
    free(da);
    free(db);
    return r;
}

/* ---- 3. Flooders ---------------------------------------------------------------- */

typedef struct flooders {
    pthread_t thread;
    int *fd;
    long n;
    volatile bool stop; /* (read and written under lock) */
    pthread_mutex_t lock;
    long long requests; /* STATUS requests lscd took in */
} flooders;

static bool flood_stopped(flooders *f)
{
    (void)pthread_mutex_lock(&f->lock);
    bool s = f->stop;
    (void)pthread_mutex_unlock(&f->lock);
    return s;
}

/* Writes STATUS requests on every connection whenever it takes more. */
static void *flood_main(void *arg)
{
    flooders *f = arg;
    static const uint8_t status[5] = {0x55, 0x55, 0x03, LSC_LSCD_CMD, LSC_LSCD_OP_STATUS};
    uint8_t burst[5 * 200];
    for (size_t i = 0; i < sizeof burst; i += sizeof status) {
        memcpy(burst + i, status, sizeof status);
    }
    struct pollfd *pf = calloc((size_t)f->n + 1u, sizeof *pf);
    long long sent = 0;
    while (pf != NULL && !flood_stopped(f)) {
        for (long i = 0; i < f->n; i++) {
            pf[i] = (struct pollfd){f->fd[i], POLLOUT, 0};
        }
        if (poll(pf, (nfds_t)f->n, 20) <= 0) {
            continue;
        }
        for (long i = 0; i < f->n; i++) {
            if ((pf[i].revents & POLLOUT) != 0) {
                ssize_t w = send(f->fd[i], burst, sizeof burst, MSG_DONTWAIT | MSG_NOSIGNAL);
                sent += w > 0 ? w : 0;
            }
        }
    }
    free(pf);
    (void)pthread_mutex_lock(&f->lock);
    f->requests = sent / 5;
    (void)pthread_mutex_unlock(&f->lock);
    return NULL;
}

static int connect_to(const char *path)
{
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    size_t n = strlen(path);
    if (n >= sizeof a.sun_path) {
        return -1;
    }
    memcpy(a.sun_path, path, n + 1u);
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    if (fd >= 0 && connect(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        (void)close(fd);
        fd = -1;
    }
    return fd;
}

/* n flooders on lscd at sock, and meanwhile o->flood battery reads by
 * another client; prints one line of the table. */
static int flood(const options *o, const char *label, const char *sock, long n)
{
    char path[160], via[170];
    snprintf(path, sizeof path, "%s/%s", tmpdir, sock);
    snprintf(via, sizeof via, "lscd:%s", path);
    flooders f;
    memset(&f, 0, sizeof f);
    f.n = n;
    f.fd = calloc((size_t)n + 1u, sizeof *f.fd);
    double *t = calloc((size_t)o->flood, sizeof *t);
    int r = f.fd != NULL && t != NULL ? 0 : -1;
    for (long i = 0; i < n && r == 0; i++) {
        f.fd[i] = connect_to(path);
        r = f.fd[i] >= 0 ? 0 : -1;
    }
    (void)pthread_mutex_init(&f.lock, NULL);
    bool started = r == 0 && pthread_create(&f.thread, NULL, flood_main, &f) == 0;
    r = started ? r : -1;
    long failed = 0;
    for (long i = 0; i < o->flood && r == 0; i++) {
        double t0 = now_s();
        lsc_device *d = NULL;
        uint16_t mv = 0;
        int e = lsc_device_open(via, NULL, &d);
        if (e == 0) {
            e = lsc_device_battery(d, &mv);
        }
        if (e != 0) {
            fprintf(stderr, "bench_lscd: %s\n", lsc_device_error(d));
            failed++;
        }
        lsc_device_close(d);
        t[i] = (now_s() - t0) * 1e3;
    }
    if (started) {
        (void)pthread_mutex_lock(&f.lock);
        f.stop = true;
        (void)pthread_mutex_unlock(&f.lock);
        (void)pthread_join(f.thread, NULL);
    }
    if (r == 0) {
        qsort(t, (size_t)o->flood, sizeof *t, cmp_double);
        double worst = t[o->flood - 1];
        printf("%-22s %9ld %8ld %10.1f %10.1f %10.1f %7ld %12lld  %s\n", label, n, o->flood,
               quantile(t, (size_t)o->flood, 0.5), quantile(t, (size_t)o->flood, 0.99), worst,
               failed, f.requests, failed == 0 && worst < 500.0 ? "met" : "MISSED");
    }
    for (long i = 0; f.fd != NULL && i < n; i++) {
        if (f.fd[i] > 0) {
            (void)close(f.fd[i]);
        }
    }
    (void)pthread_mutex_destroy(&f.lock);
    free(f.fd);
    free(t);
    return r;
}

/* ---- 2. Idle subscribers ----------------------------------------------------- */

typedef struct stamps {
    pthread_mutex_t lock;
    pthread_cond_t changed;
    long nsubs, nevents;
    double *at;    /* at[sub * nevents + event]: when sub read it */
    long *arrived; /* arrived[event]: how many subscribers read it */
    long failed;   /* subscribers whose connection failed */
} stamps;

typedef struct subscriber {
    stamps *st;
    lsc_lscd *conn;
    long index;
    pthread_t thread;
    bool started;
} subscriber;

static void *subscriber_main(void *arg)
{
    subscriber *sub = arg;
    stamps *st = sub->st;
    uint8_t pbuf[LSC_FRAME_MAX], buf[256];
    lsc_parser p;
    lsc_parser_init(&p, pbuf, sizeof pbuf);
    long seen = 0;
    for (;;) {
        int n = lsc_lscd_read(sub->conn, buf, sizeof buf, 60000);
        double t = now_s();
        if (n < 0) {
            pthread_mutex_lock(&st->lock);
            st->failed++;
            pthread_cond_broadcast(&st->changed);
            pthread_mutex_unlock(&st->lock);
            return NULL; /* lscd stopped (or failed): the end */
        }
        const uint8_t *at = buf;
        size_t left = (size_t)n;
        while (left > 0u) {
            lsc_frame f;
            int res = 0;
            size_t used = lsc_parser_feed_buf(&p, at, left, &f, &res);
            at += used;
            left -= used;
            if (res == 1 && (f.cmd == LSC_CMD_GROUP_RUN || f.cmd == LSC_CMD_GROUP_STOP ||
                             f.cmd == LSC_CMD_GROUP_COMPLETE) &&
                seen < st->nevents) {
                pthread_mutex_lock(&st->lock);
                st->at[sub->index * st->nevents + seen] = t;
                if (++st->arrived[seen] == st->nsubs) {
                    pthread_cond_broadcast(&st->changed); /* (only then: no wake-ups meanwhile) */
                }
                pthread_mutex_unlock(&st->lock);
                seen++;
            }
        }
    }
}

/* Waits until every subscriber read event k; false after the deadline. */
static bool all_arrived(stamps *st, long k)
{
    double end = now_s() + EVENT_DEADLINE_S;
    (void)pthread_mutex_lock(&st->lock);
    while (st->arrived[k] != st->nsubs && st->failed == 0 && now_s() < end) {
        struct timespec t;
        clock_gettime(CLOCK_REALTIME, &t);
        t.tv_nsec += 100000000L;
        if (t.tv_nsec >= 1000000000L) {
            t.tv_sec++;
            t.tv_nsec -= 1000000000L;
        }
        (void)pthread_cond_timedwait(&st->changed, &st->lock, &t);
    }
    bool ok = st->arrived[k] == st->nsubs;
    (void)pthread_mutex_unlock(&st->lock);
    return ok;
}

/* lscd's CPU so far: utime + stime (ticks) of /proc/PID/stat; the ns on a CPU
 * and the context switches of all its threads (/proc/PID/task). */
typedef struct cpu {
    unsigned long long ticks, ns, switches;
} cpu;

/* The text of a small file (NUL-terminated; "" if it cannot be read). */
static void slurp(const char *path, char *text, size_t cap)
{
    size_t n = 0;
    FILE *f = fopen(path, "r");
    if (f != NULL) {
        n = fread(text, 1, cap - 1u, f);
        (void)fclose(f);
    }
    text[n] = '\0';
}

/* The number after the first "key" in text (0 if none). */
static unsigned long long number_after(const char *text, const char *key)
{
    const char *p = strstr(text, key);
    return p != NULL ? strtoull(p + strlen(key), NULL, 10) : 0u;
}

static int cpu_of(pid_t pid, cpu *c)
{
    char path[512], text[2048];
    memset(c, 0, sizeof *c);
    snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
    slurp(path, text, sizeof text);
    /* after the command's name ")": state, then ppid pgrp session tty tpgid
     * flags minflt cminflt majflt cmajflt utime stime */
    char *p = strrchr(text, ')');
    if (p == NULL || p[1] != ' ' || p[2] == '\0') {
        return -1;
    }
    p += 3;
    unsigned long long v[12];
    for (int k = 0; k < 12; k++) {
        char *end;
        v[k] = strtoull(p, &end, 10);
        if (end == p) {
            return -1;
        }
        p = end;
    }
    c->ticks = v[10] + v[11];
    snprintf(path, sizeof path, "/proc/%ld/task", (long)pid);
    DIR *dir = opendir(path);
    if (dir == NULL) {
        return -1;
    }
    for (struct dirent *e; (e = readdir(dir)) != NULL;) {
        if (e->d_name[0] == '.') {
            continue;
        }
        snprintf(path, sizeof path, "/proc/%ld/task/%s/schedstat", (long)pid, e->d_name);
        slurp(path, text, sizeof text);
        c->ns += strtoull(text, NULL, 10); /* the first field: ns on a CPU */
        snprintf(path, sizeof path, "/proc/%ld/task/%s/status", (long)pid, e->d_name);
        slurp(path, text, sizeof text);
        c->switches += number_after(text, "\nvoluntary_ctxt_switches:") +
                       number_after(text, "\nnonvoluntary_ctxt_switches:");
    }
    (void)closedir(dir);
    return 0;
}

static int subscribers(const options *o, const char *label, pid_t *lscd, const char *sock)
{
    char path[128];
    snprintf(path, sizeof path, "%s/%s", tmpdir, sock);
    long nsubs = o->subscribers, nevents = 2 * o->notify;
    stamps st;
    memset(&st, 0, sizeof st);
    pthread_mutex_init(&st.lock, NULL);
    pthread_cond_init(&st.changed, NULL);
    st.nsubs = nsubs;
    st.nevents = nevents;
    st.at = calloc((size_t)(nsubs * nevents), sizeof *st.at);
    st.arrived = calloc((size_t)nevents, sizeof *st.arrived);
    subscriber *subs = calloc((size_t)nsubs, sizeof *subs);
    double *spread = calloc((size_t)nevents, sizeof *spread);
    double *first = calloc((size_t)nevents, sizeof *first);
    double *last = calloc((size_t)nevents, sizeof *last);
    int r = st.at != NULL && st.arrived != NULL && subs != NULL && spread != NULL &&
                    first != NULL && last != NULL
                ? 0
                : -1;
    for (long i = 0; i < nsubs && r == 0; i++) {
        subs[i].st = &st;
        subs[i].index = i;
        if (lsc_lscd_open(path, NULL, &subs[i].conn) != 0) {
            fprintf(stderr, "bench_lscd: subscriber %ld: %s\n", i, lsc_lscd_error(subs[i].conn));
            r = -1;
        } else if (pthread_create(&subs[i].thread, NULL, subscriber_main, &subs[i]) != 0) {
            r = -1;
        } else {
            subs[i].started = true;
        }
    }
    /* the trigger: a client that does not subscribe */
    lsc_lscd_options topt = {.size = sizeof topt};
    topt.no_notifications = true;
    topt.timeout_ms = 5000;
    lsc_lscd *trigger = NULL;
    if (r == 0 && lsc_lscd_open(path, &topt, &trigger) != 0) {
        fprintf(stderr, "bench_lscd: trigger: %s\n", lsc_lscd_error(trigger));
        r = -1;
    }

    /* idle: every subscriber blocked in its read, nothing happening */
    cpu c0, c1;
    if (r == 0) {
        sleep_s(1.0); /* let the connections settle */
        r = cpu_of(*lscd, &c0);
    }
    if (r == 0) {
        sleep_s((double)o->idle_s);
        r = cpu_of(*lscd, &c1);
    }
    if (r == 0) {
        printf("%s, %ld subscribers, idle for %ld s: lscd used %llu clock ticks (utime+stime, "
               "1/%ld s), %.3f ms on a CPU (schedstat), %llu context switches: %s\n",
               label, nsubs, o->idle_s, c1.ticks - c0.ticks, sysconf(_SC_CLK_TCK),
               (double)(c1.ns - c0.ns) / 1e6, c1.switches - c0.switches,
               c1.ns == c0.ns && c1.switches == c0.switches ? "no CPU, no wake-up (met)"
                                                            : "MISSED");
    }

    /* notifications: run group 1, NOTIFY times; a start and a completion each */
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_encode_group_run(frame, sizeof frame, 1, 1);
    for (long k = 0; k < o->notify && r == 0; k++) {
        double t0 = now_s();
        if (lsc_lscd_write(trigger, frame, (size_t)len) != len) {
            fprintf(stderr, "bench_lscd: run: %s\n", lsc_lscd_error(trigger));
            r = -1;
            break;
        }
        for (long e = 2 * k; e < 2 * k + 2 && r == 0; e++) {
            if (!all_arrived(&st, e)) {
                fprintf(stderr, "bench_lscd: notification %ld reached %ld of %ld subscribers\n",
                        e, st.arrived[e], nsubs);
                r = -1;
                break;
            }
            double lo = 1e300, hi = -1e300;
            pthread_mutex_lock(&st.lock);
            for (long i = 0; i < nsubs; i++) {
                double t = st.at[i * nevents + e];
                lo = t < lo ? t : lo;
                hi = t > hi ? t : hi;
            }
            pthread_mutex_unlock(&st.lock);
            spread[e] = (hi - lo) * 1e3;
            first[e] = (lo - t0) * 1e3;
            last[e] = (hi - t0) * 1e3;
        }
    }
    if (r == 0) {
        double fs = 0;
        for (long e = 0; e < nevents; e += 2) {
            fs += first[e];
        }
        qsort(spread, (size_t)nevents, sizeof *spread, cmp_double);
        printf("%s, %ld notifications to %ld subscribers: arrival spread (latest - earliest) "
               "median %.3f ms, p90 %.3f ms, max %.3f ms: %s; a group's start reached the first "
               "subscriber %.3f ms after the run was sent (mean)\n",
               label, nevents, nsubs, quantile(spread, (size_t)nevents, 0.5),
               quantile(spread, (size_t)nevents, 0.9), spread[nevents - 1],
               spread[nevents - 1] <= 1.0 ? "all within 1 ms (met)" : "MISSED",
               fs / (double)o->notify);
    }
    lsc_lscd_close(trigger);
    /* the subscribers' reads end when lscd closes their connections */
    stop(lscd);
    for (long i = 0; subs != NULL && i < nsubs; i++) {
        if (subs[i].started) {
            (void)pthread_join(subs[i].thread, NULL);
        }
        lsc_lscd_close(subs[i].conn);
    }
    free(subs);
    free(st.at);
    free(st.arrived);
    free(spread);
    free(first);
    free(last);
    pthread_cond_destroy(&st.changed);
    pthread_mutex_destroy(&st.lock);
    return r;
}

/* The same notifications watched by one thread (epoll) on SUBSCRIBERS plain
 * connections: no thread has to be woken per subscriber, so the spread is
 * about lscd's own sending (its loop over the subscribers), plus at most one
 * turn of this loop. The trigger is a plain connection too (unsubscribed,
 * its run frame sent without waiting), so that this thread is already
 * waiting when lscd sends. */
static int connect_plain(const char *path)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    snprintf(a.sun_path, sizeof a.sun_path, "%s", path);
    if (fd >= 0 && connect(fd, (const struct sockaddr *)&a, sizeof a) != 0) {
        (void)close(fd);
        return -1;
    }
    /* HELLO (55 55 05 CD 80 version present): lscd took the connection */
    uint8_t hello[7];
    size_t got = 0;
    struct timeval tv = {5, 0};
    (void)setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    while (fd >= 0 && got < sizeof hello) {
        ssize_t n = recv(fd, hello + got, sizeof hello - got, 0);
        if (n <= 0) {
            (void)close(fd);
            return -1;
        }
        got += (size_t)n;
    }
    return fd;
}

static int spread_epoll(const options *o, const char *label, const char *sock)
{
    char path[128];
    snprintf(path, sizeof path, "%s/%s", tmpdir, sock);
    long nsubs = o->subscribers, nevents = 2 * o->notify;
    int *fds = calloc((size_t)nsubs, sizeof *fds);
    long *seen = calloc((size_t)nsubs, sizeof *seen);
    lsc_parser *ps = calloc((size_t)nsubs, sizeof *ps);
    uint8_t(*pbuf)[LSC_FRAME_MAX] = calloc((size_t)nsubs, sizeof *pbuf);
    double *spread = calloc((size_t)nevents, sizeof *spread);
    struct epoll_event *evs = calloc((size_t)nsubs, sizeof *evs);
    int ep = epoll_create1(EPOLL_CLOEXEC);
    int r = fds != NULL && seen != NULL && ps != NULL && pbuf != NULL && spread != NULL &&
                    evs != NULL && ep >= 0
                ? 0
                : -1;
    for (long i = 0; fds != NULL && i < nsubs; i++) {
        fds[i] = -1;
    }
    for (long i = 0; i < nsubs && r == 0; i++) {
        fds[i] = connect_plain(path);
        lsc_parser_init(&ps[i], pbuf[i], sizeof pbuf[i]);
        struct epoll_event ev;
        ev.events = EPOLLIN;
        ev.data.u64 = (uint64_t)i;
        if (fds[i] < 0 || fcntl(fds[i], F_SETFL, O_NONBLOCK) != 0 ||
            epoll_ctl(ep, EPOLL_CTL_ADD, fds[i], &ev) != 0) {
            fprintf(stderr, "bench_lscd: plain subscriber %ld: %s\n", i, strerror(errno));
            r = -1;
        }
    }
    int trig = r == 0 ? connect_plain(path) : -1;
    static const uint8_t unsubscribe[] = {0x55, 0x55, 0x04, LSC_LSCD_CMD, LSC_LSCD_OP_SUBSCRIBE, 0};
    uint8_t run[LSC_FRAME_MAX];
    int runlen = lsc_encode_group_run(run, sizeof run, 1, 1);
    if (r == 0 && (trig < 0 || send(trig, unsubscribe, sizeof unsubscribe, MSG_NOSIGNAL) !=
                                      (ssize_t)sizeof unsubscribe)) {
        r = -1;
    }
    for (long k = 0; k < o->notify && r == 0; k++) {
        if (send(trig, run, (size_t)runlen, MSG_NOSIGNAL) != runlen) {
            r = -1;
            break;
        }
        for (long e = 2 * k; e < 2 * k + 2 && r == 0; e++) {
            long done = 0;
            double lo = 0, hi = 0, end = now_s() + EVENT_DEADLINE_S;
            while (done < nsubs && r == 0) {
                int n = epoll_wait(ep, evs, (int)nsubs, 1000);
                double t = now_s();
                if (t > end) {
                    fprintf(stderr, "bench_lscd: notification %ld reached %ld of %ld subscribers\n",
                            e, done, nsubs);
                    r = -1;
                }
                for (int j = 0; j < n; j++) {
                    long i = (long)evs[j].data.u64;
                    uint8_t buf[256];
                    ssize_t got = recv(fds[i], buf, sizeof buf, 0);
                    const uint8_t *at = buf;
                    size_t left = got > 0 ? (size_t)got : 0u;
                    while (left > 0u) {
                        lsc_frame f;
                        int res = 0;
                        size_t used = lsc_parser_feed_buf(&ps[i], at, left, &f, &res);
                        at += used;
                        left -= used;
                        if (res == 1 && f.cmd >= LSC_CMD_GROUP_RUN &&
                            f.cmd <= LSC_CMD_GROUP_COMPLETE && seen[i]++ == e) {
                            lo = done == 0 ? t : lo;
                            hi = t;
                            done++;
                        }
                    }
                }
            }
            spread[e] = (hi - lo) * 1e3;
        }
        /* the trigger's verdict-less run frame: drain what it may get */
        uint8_t junk[256];
        while (recv(trig, junk, sizeof junk, MSG_DONTWAIT) > 0) {
        }
    }
    if (r == 0) {
        qsort(spread, (size_t)nevents, sizeof *spread, cmp_double);
        printf("%s, the same to %ld connections that one thread watches (epoll; lscd's own "
               "sending): spread median %.3f ms, p90 %.3f ms, max %.3f ms\n",
               label, nsubs, quantile(spread, (size_t)nevents, 0.5),
               quantile(spread, (size_t)nevents, 0.9), spread[nevents - 1]);
    }
    if (trig >= 0) {
        (void)close(trig);
    }
    for (long i = 0; fds != NULL && i < nsubs; i++) {
        if (fds[i] >= 0) {
            (void)close(fds[i]);
        }
    }
    if (ep >= 0) {
        (void)close(ep);
    }
    free(fds);
    free(seen);
    free(ps);
    free(pbuf);
    free(spread);
    free(evs);
    return r;
}

/* ---- main ------------------------------------------------------------------------ */

static bool number(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno != 0 || end == s || *end != '\0' || v < lo || v > hi) {
        return false;
    }
    *out = v;
    return true;
}

static int usage(void)
{
    fprintf(stderr, "usage: bench_lscd [--lscd PATH] [--lsc-sim PATH] [--exchanges-sim N] "
                    "[--exchanges-pty N] [--subscribers N] [--idle S] [--notify N] [--flood N]\n");
    return 2;
}

static void remove_tmpdir(void)
{
    DIR *dir = opendir(tmpdir);
    if (dir != NULL) {
        char path[600];
        for (struct dirent *e; (e = readdir(dir)) != NULL;) {
            if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
                snprintf(path, sizeof path, "%s/%s", tmpdir, e->d_name);
                (void)unlink(path);
            }
        }
        closedir(dir);
    }
    (void)rmdir(tmpdir);
}

typedef enum what { EXCHANGES, SUBSCRIBERS, EPOLL, FLOOD } what;

/* lscd on port at tmpdir/sock; then the exchanges against direct (n of
 * each), the subscribers in threads, or the subscribers watched with epoll. */
static int with_lscd(const options *o, const char *label, what w, const char *direct,
                     const char *port, const char *sock, long n)
{
    char via[160];
    snprintf(via, sizeof via, "lscd:%s/%s", tmpdir, sock);
    pid_t lscd = start_lscd(o, port, sock);
    if (lscd < 0) {
        return -1;
    }
    int r = w == EXCHANGES     ? exchanges(label, direct, via, n)
            : w == SUBSCRIBERS ? subscribers(o, label, &lscd, sock)
            : w == FLOOD       ? flood(o, label, sock, n)
                               : spread_epoll(o, label, sock);
    stop(&lscd);
    fflush(stdout);
    return r;
}

int main(int argc, char **argv)
{
    options o = {BENCH_LSCD, BENCH_LSC_SIM, 20000, 500, 100, 5, 10, 50};
    for (int i = 1; i < argc; i += 2) { /* OPTION VALUE pairs */
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        bool ok = v != NULL;
        if (ok && strcmp(a, "--lscd") == 0) {
            o.lscd = v;
        } else if (ok && strcmp(a, "--lsc-sim") == 0) {
            o.lsc_sim = v;
        } else if (ok && strcmp(a, "--exchanges-sim") == 0) {
            ok = number(v, 0, 10000000, &o.exchanges_sim);
        } else if (ok && strcmp(a, "--exchanges-pty") == 0) {
            ok = number(v, 0, 1000000, &o.exchanges_pty);
        } else if (ok && strcmp(a, "--subscribers") == 0) {
            ok = number(v, 0, 900, &o.subscribers);
        } else if (ok && strcmp(a, "--idle") == 0) {
            ok = number(v, 1, 3600, &o.idle_s);
        } else if (ok && strcmp(a, "--notify") == 0) {
            ok = number(v, 1, 10000, &o.notify);
        } else if (ok && strcmp(a, "--flood") == 0) {
            ok = number(v, 0, 100000, &o.flood);
        } else {
            ok = false;
        }
        if (!ok) {
            return usage();
        }
    }
    (void)signal(SIGPIPE, SIG_IGN);
    snprintf(tmpdir, sizeof tmpdir, "/tmp/bench_lscd.XXXXXX");
    if (mkdtemp(tmpdir) == NULL) {
        fprintf(stderr, "bench_lscd: mkdtemp: %s\n", strerror(errno));
        return 1;
    }
    double load[3] = {0, 0, 0};
    char text[256];
    slurp("/proc/loadavg", text, sizeof text);
    char *at = text;
    for (int k = 0; k < 3; k++) {
        load[k] = strtod(at, &at);
    }
    printf("host: %ld cores, load average %.2f %.2f %.2f\nlscd: %s\nlsc-sim: %s\n",
           sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2], o.lscd, o.lsc_sim);
    if (o.exchanges_sim > 0 || o.exchanges_pty > 0) {
        printf("== a battery exchange, direct and through lscd (alternating), microseconds\n");
        printf("%-22s %6s %10s %10s %10s %10s %10s %10s  %s\n", "controller", "calls", "direct",
               "direct", "lscd", "lscd", "lscd adds", "lscd adds", "target: adds <= 300 us");
        printf("%-22s %6s %10s %10s %10s %10s %10s %10s\n", "", "", "median", "p99", "median",
               "p99", "median", "p99");
    }
    fflush(stdout);

    /* a group for lsc-sim: 100 ms */
    char groups[128];
    snprintf(groups, sizeof groups, "%s/groups.txt", tmpdir);
    FILE *f = fopen(groups, "w");
    bool written = f != NULL && fputs("group 1\nstep 100 1:1000\n", f) >= 0;
    if (f != NULL && fclose(f) != 0) {
        written = false;
    }
    if (!written) {
        fprintf(stderr, "bench_lscd: %s: cannot write it\n", groups);
        remove_tmpdir();
        return 1;
    }
    /* the virtual controller, in this process and in lscd; lsc-sim, paced:
     * a opened directly, b through lscd */
    char direct[128], port[128];
    snprintf(direct, sizeof direct, "%s/a", tmpdir);
    snprintf(port, sizeof port, "%s/b", tmpdir);
    pid_t a = start_sim(&o, "a", groups), b = start_sim(&o, "b", groups);
    int r = a > 0 && b > 0 ? 0 : -1;
    if (r == 0 && o.exchanges_sim > 0) {
        r = with_lscd(&o, "sim", EXCHANGES, "sim", "sim", "sim.sock", o.exchanges_sim);
    }
    if (r == 0 && o.exchanges_pty > 0) {
        r = with_lscd(&o, "lsc-sim 9600 baud", EXCHANGES, direct, port, "b.sock", o.exchanges_pty);
    }
    if (r == 0 && o.subscribers > 0) {
        printf("== %ld idle subscribers (targets: no CPU while idle; a notification reaches all "
               "within 1 ms of each other)\n",
               o.subscribers);
        r = with_lscd(&o, "sim", SUBSCRIBERS, NULL, "sim", "sim.sock", 0);
    }
    if (r == 0 && o.subscribers > 0) {
        r = with_lscd(&o, "sim", EPOLL, NULL, "sim", "sim.sock", 0);
    }
    if (r == 0 && o.subscribers > 0) {
        r = with_lscd(&o, "lsc-sim 9600 baud", SUBSCRIBERS, NULL, port, "b.sock", 0);
    }
    if (r == 0 && o.subscribers > 0) {
        r = with_lscd(&o, "lsc-sim 9600 baud", EPOLL, NULL, port, "b.sock", 0);
    }
    if (r == 0 && o.flood > 0) {
        printf("== another client's battery read (open lscd:PATH, read, close) while flooders send "
               "STATUS requests and never read, ms (target: every one answered within 500 ms)\n");
        printf("%-22s %9s %8s %10s %10s %10s %7s %12s\n", "controller", "flooders", "reads",
               "median", "p99", "worst", "failed", "their reqs");
        static const long counts[] = {0, 10, 100};
        for (size_t k = 0; k < sizeof counts / sizeof counts[0] && r == 0; k++) {
            r = with_lscd(&o, "lsc-sim 9600 baud", FLOOD, NULL, port, "b.sock", counts[k]);
        }
    }
    stop(&a);
    stop(&b);
    remove_tmpdir();
    return r == 0 ? 0 : 1;
}
