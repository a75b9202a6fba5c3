/* The serial transport and the client end to end over real pseudo-terminals
 * (openpty), against a peer thread that plays the controller on the master
 * side. Built twice: with LSC_TEST_SP (test_serial_sp) the port is opened by
 * the libserialport backend, made able to open a pty by the test-only shim
 * linked in (sp_pty_shim.c); without it by termios, and AUTO is checked to
 * fall back to termios for a pty that plain libserialport refuses. */
#define _GNU_SOURCE 1 /* RTLD_NEXT */
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "lsc/client.h"
#include "lsc/serial.h"
#include "../src/serial/serial_internal.h" /* white box: the write timeout */
#include "test_hex.h"
#include "test_time.h"

#ifdef LSC_TEST_SP
#include "sp_pty_shim.h"
#define BACKEND LSC_SERIAL_LIBSERIALPORT
#define HAVE_PTY_SHIM 1 /* libserialport can open ptys in this build */
#else
#define BACKEND LSC_SERIAL_TERMIOS
#define HAVE_PTY_SHIM 0
#endif

/* ---- Time ------------------------------------------------------------------- */

static void sleep_ms(unsigned ms)
{
    struct timespec ts = {(time_t)(ms / 1000u), (long)(ms % 1000u) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

static uint32_t now_ms(void)
{
    return lsc_serial_now_ms(NULL);
}

/* ---- Fault injection ------------------------------------------------------------ */

/* While set, tcsetattr fails with EIO (this definition takes precedence over
 * libc's for the library linked in; otherwise it calls libc's). */
static bool fail_tcsetattr;

int tcsetattr(int fd, int actions, const struct termios *t)
{
    if (fail_tcsetattr) {
        errno = EIO;
        return -1;
    }
    int (*real)(int, int, const struct termios *);
    void *sym = dlsym(RTLD_NEXT, "tcsetattr");
    memcpy(&real, &sym, sizeof real); /* ISO C: no object-to-function cast */
    return real(fd, actions, t);
}

/* ---- The peer: a controller played on the pty's master side ------------------ */

#define CLOSE "close"       /* step: close the master (the device goes away) */
#define SIGNAL "signal"     /* step: interrupt the test thread with SIGUSR1 */
#define BYTEWISE "bytewise:" /* step prefix: write the bytes one by one, 1 ms apart */

typedef struct step {
    unsigned delay_ms; /* before this step */
    const char *what;  /* hex bytes, CLOSE, SIGNAL or BYTEWISE hex */
} step;

typedef struct peer {
    int master;
    char path[128];
    size_t expect; /* bytes to receive before running the steps */
    step steps[16];
    size_t nsteps;
    uint8_t got[65536];
    size_t ngot;
    size_t drain; /* after the steps, read this many more bytes (slowly) */
    pthread_t thread, victim;
} peer;

static peer P;

static size_t parse_hex(const char *hex, uint8_t *out)
{
    return test_hex(hex, out, 1024);
}

static void peer_write(const uint8_t *b, size_t n)
{
    while (n > 0) {
        ssize_t w = write(P.master, b, n);
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w <= 0) {
            return;
        }
        b += w;
        n -= (size_t)w;
    }
}

static void peer_receive(size_t want, unsigned pause_ms)
{
    while (P.ngot < want) {
        struct pollfd p = {P.master, POLLIN, 0};
        if (poll(&p, 1, (int)test_ms(3000)) <= 0) {
            return;
        }
        size_t room = want - P.ngot < 512 ? want - P.ngot : 512;
        ssize_t r = read(P.master, P.got + P.ngot, room);
        if (r <= 0) {
            return;
        }
        P.ngot += (size_t)r;
        if (pause_ms) {
            sleep_ms(pause_ms);
        }
    }
}

static void *peer_main(void *arg)
{
    (void)arg;
    peer_receive(P.expect, 0);
    for (size_t i = 0; i < P.nsteps; i++) {
        sleep_ms(P.steps[i].delay_ms);
        const char *w = P.steps[i].what;
        uint8_t bytes[1024];
        if (strcmp(w, CLOSE) == 0) {
            (void)close(P.master);
            P.master = -1;
        } else if (strcmp(w, SIGNAL) == 0) {
            (void)pthread_kill(P.victim, SIGUSR1);
        } else if (strncmp(w, BYTEWISE, strlen(BYTEWISE)) == 0) {
            size_t n = parse_hex(w + strlen(BYTEWISE), bytes);
            for (size_t k = 0; k < n; k++) {
                peer_write(&bytes[k], 1);
                sleep_ms(1);
            }
        } else {
            peer_write(bytes, parse_hex(w, bytes));
        }
    }
    if (P.drain && P.master >= 0) {
        peer_receive(P.ngot + P.drain, 2);
    }
    return NULL;
}

static void start_peer(size_t expect)
{
    P.expect = expect;
    P.victim = pthread_self();
    assert_int_equal(pthread_create(&P.thread, NULL, peer_main, NULL), 0);
}

static void join_peer(void)
{
    assert_int_equal(pthread_join(P.thread, NULL), 0);
}

static void add_step(unsigned delay_ms, const char *what)
{
    P.steps[P.nsteps].delay_ms = delay_ms;
    P.steps[P.nsteps++].what = what;
}

/* ---- Fixture: a pty pair, the slave opened by the transport ------------------------- */

static lsc_serial *S;
static lsc_client C;
static lsc_io IO;
static lsc_notification notes[64];
static size_t nnotes;

static void record(void *user, const lsc_notification *n)
{
    (void)user;
    notes[nnotes++] = *n;
}

static void on_signal(int sig)
{
    (void)sig;
}

static int setup(void **state)
{
    (void)state;
    memset(&P, 0, sizeof P);
    nnotes = 0;
    int slave;
    if (openpty(&P.master, &slave, P.path, NULL, NULL) != 0) {
        return -1;
    }
    (void)close(slave);
    S = NULL;
    int r = lsc_serial_open(P.path, 9600, BACKEND, &S);
    if (r != 0) {
        fprintf(stderr, "open %s: %s (%s)\n", P.path, lsc_strerror(r), lsc_serial_error_message(S));
        return -1;
    }
    if (lsc_serial_backend_in_use(S) != BACKEND) {
        return -1;
    }
    lsc_serial_get_io(S, &IO);
    if (lsc_client_init(&C, &IO) != 0) {
        return -1;
    }
    lsc_client_set_notify(&C, record, NULL);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: poll() and read() see EINTR */
    (void)sigaction(SIGUSR1, &sa, NULL);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    lsc_serial_close(S);
    if (P.master >= 0) {
        (void)close(P.master);
    }
    return 0;
}

#define BATTERY_REQ_LEN 4u
#define BATTERY_7500 "55 55 04 0F 4C 1D"
#define STARTED_8 "55 55 05 06 08 01 00"
#define COMPLETE_8 "55 55 05 08 08 01 00"
#define STOPPED "55 55 02 07"

/* ---- Opening ------------------------------------------------------------------------ */

static void opened_raw_8n1_9600(void **state)
{
    (void)state;
    struct termios t;
    assert_int_equal(tcgetattr(lsc_serial_fileno(S), &t), 0);
    assert_int_equal(t.c_cflag & CSIZE, CS8);
    assert_int_equal(t.c_cflag & (PARENB | CSTOPB | CRTSCTS), 0);
    assert_int_equal(t.c_iflag & (IXON | IXOFF | ICRNL | ISTRIP), 0);
    assert_int_equal(t.c_lflag & (ICANON | ECHO | ISIG), 0);
    assert_int_equal(t.c_oflag & OPOST, 0);
    assert_int_equal(cfgetospeed(&t), B9600);
    assert_int_equal(cfgetispeed(&t), B9600);
    assert_string_equal(lsc_serial_error_message(S), "");
#ifdef LSC_TEST_SP
    assert_true(lsc_test_shim_hits > 0); /* libserialport really opened it */
#endif
}

static void second_opener_is_refused(void **state)
{
    (void)state;
    lsc_serial *other = NULL;
    for (int b = LSC_SERIAL_AUTO; b <= LSC_SERIAL_LIBSERIALPORT; b++) {
        if (b == LSC_SERIAL_LIBSERIALPORT && !lsc_serial_have_libserialport()) {
            continue;
        }
        int r = lsc_serial_open(P.path, 9600, (lsc_serial_backend)b, &other);
        /* libserialport without the shim cannot open a pty at all */
        if (b == LSC_SERIAL_LIBSERIALPORT && !HAVE_PTY_SHIM) {
            assert_int_equal(r, LSC_ENODEV);
            continue;
        }
        assert_int_equal(r, LSC_EBUSY);
        assert_non_null(strstr(lsc_serial_error_message(other), P.path));
        assert_non_null(strstr(lsc_serial_error_message(other), "busy"));
        /* this process holds it: the message says so, not "another program" */
        assert_non_null(strstr(lsc_serial_error_message(other),
                               "port busy: this program has it open already"));
        assert_int_equal(lsc_serial_backend_in_use(other), LSC_SERIAL_AUTO);
    }
    /* from another process too (we may be root: flock stops it, not TIOCEXCL);
     * the child closes the copy of the port it inherited first (the lock
     * stays the opener's): then another program holds it */
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_serial_close(S);
        S = NULL;
        other = NULL;
        _exit(lsc_serial_open(P.path, 9600, BACKEND, &other) == LSC_EBUSY &&
                      strstr(lsc_serial_error_message(other),
                             "port busy: another program has it open") != NULL
                  ? 0
                  : 1);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    if (geteuid() == 0) {
        print_message("running as root: the second opener was refused by flock\n");
    }
    /* a child that inherited the port (fork) and closes it leaves the opener's
     * lock alone: the port stays busy for others while the opener has it */
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_serial_close(S);
        S = NULL;
        _exit(0);
    }
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    assert_int_equal(lsc_serial_open(P.path, 9600, LSC_SERIAL_TERMIOS, &other), LSC_EBUSY);
    /* and the port's descriptor does not survive an exec */
    assert_true((fcntl(lsc_serial_fileno(S), F_GETFD) & FD_CLOEXEC) != 0);
    /* after close, the port can be opened again */
    lsc_serial_close(S);
    S = NULL;
    lsc_serial_close(NULL); /* NULL is harmless */
    assert_int_equal(lsc_serial_open(P.path, 0, BACKEND, &other), 0);
    lsc_serial_close(other);
}

static void not_root_refused_by_flock_and_eacces(void **state)
{
    (void)state;
    if (geteuid() != 0) {
        skip(); /* needs root to become another user */
    }
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_serial *other = NULL;
        if (chown(P.path, 65534, 65534) != 0 || chmod(P.path, 0600) != 0 ||
            setgid(65534) != 0 || setuid(65534) != 0) {
            _exit(2);
        }
        /* the flock stops a non-root user as it stops root */
        if (lsc_serial_open(P.path, 9600, LSC_SERIAL_TERMIOS, &other) != LSC_EBUSY ||
            lsc_serial_os_errno(other) != EWOULDBLOCK) {
            _exit(3);
        }
        _exit(0);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    /* permission denied: the message says how to get access */
    lsc_serial_close(S);
    S = NULL;
    assert_int_equal(chown(P.path, 0, 0), 0);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_serial *other = NULL;
        if (setgid(65534) != 0 || setuid(65534) != 0) {
            _exit(2);
        }
        int r = lsc_serial_open(P.path, 9600, LSC_SERIAL_AUTO, &other);
        const char *m = lsc_serial_error_message(other);
        _exit(r == LSC_EACCES && strstr(m, P.path) && strstr(m, "Permission denied") &&
                      strstr(m, "dialout") && strstr(m, "udev")
                  ? 0
                  : 3);
    }
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
}

/* Closes the port and opens the slave again plainly, keeping the tty open the
 * way lsc-sim does; returns that descriptor. */
static int hold_the_tty_open(void)
{
    lsc_serial_close(S);
    S = NULL;
    int keeper = open(P.path, O_RDWR | O_NOCTTY);
    assert_true(keeper >= 0);
    return keeper;
}

/* The tty's exclusive flag (TIOCGEXCL) through keeper, one of its descriptors. */
static int exclusive_flag(int keeper)
{
    int excl = -1;
    assert_int_equal(ioctl(keeper, TIOCGEXCL, &excl), 0);
    return excl;
}

/* Checks the tty's exclusive flag is clear, then closes keeper. */
static void assert_not_exclusive(int keeper)
{
    assert_int_equal(exclusive_flag(keeper), 0);
    (void)close(keeper);
}

/* The port opens (and is closed again). */
static void assert_opens(void)
{
    lsc_serial *s = NULL;
    assert_int_equal(lsc_serial_open(P.path, 9600, BACKEND, &s), 0);
    lsc_serial_close(s);
}

/* The exclusive flag (TIOCEXCL) is the tty's, not the descriptor's: when
 * another descriptor keeps the slave open (as lsc-sim does), a close that left
 * it set would make every later non-root open fail with "port busy". Opens
 * and closes twice as uid 65534 (a forked child when we are root), then
 * checks the flag is clear (TIOCGEXCL). */
static void close_clears_the_exclusive_flag(void **state)
{
    (void)state;
    int keeper = hold_the_tty_open();
    assert_int_equal(chmod(P.path, 0666), 0);
    bool root = geteuid() == 0;
    if (!root) {
        print_message("not root: opening as the current user, not as uid 65534\n");
    }
    pid_t pid = root ? fork() : 0;
    assert_true(pid >= 0);
    if (pid == 0) {
        int code = 0;
        if (root && (setgroups(0, NULL) != 0 || setgid(65534) != 0 || setuid(65534) != 0)) {
            code = 2;
        }
        for (int i = 0; code == 0 && i < 2; i++) {
            lsc_serial *s = NULL;
            int r = lsc_serial_open(P.path, 9600, BACKEND, &s);
            if (r != 0) {
                fprintf(stderr, "open %d as uid %d: %s\n", i + 1, (int)getuid(),
                        lsc_serial_error_message(s));
                code = 3 + i;
            }
            lsc_serial_close(s);
        }
        if (root) {
            _exit(code);
        }
        assert_int_equal(code, 0);
    } else {
        int status;
        assert_int_equal(waitpid(pid, &status, 0), pid);
        assert_true(WIFEXITED(status));
        assert_int_equal(WEXITSTATUS(status), 0);
    }
    assert_not_exclusive(keeper);
}

/* A holder killed with SIGKILL (nothing of it runs: no close, no cleanup)
 * while another descriptor keeps the tty open leaves neither an exclusive flag
 * nor a lock behind: the next open works, for root and every other user. */
static void killed_holder_leaves_the_port_free(void **state)
{
    (void)state;
    int keeper = hold_the_tty_open();
    int ready[2];
    assert_int_equal(pipe(ready), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_serial *s = NULL;
        char r = lsc_serial_open(P.path, 9600, BACKEND, &s) == 0 ? 'y' : 'n';
        (void)write(ready[1], &r, 1);
        for (;;) {
            pause(); /* holds the port until killed */
        }
    }
    char r = 0;
    assert_int_equal(read(ready[0], &r, 1), 1);
    (void)close(ready[0]);
    (void)close(ready[1]);
    assert_int_equal(kill(pid, SIGKILL), 0);
    assert_int_equal(waitpid(pid, NULL, 0), pid);
    assert_int_equal(r, 'y');
    /* checked before anything of ours opens (and closes) it again */
    assert_int_equal(exclusive_flag(keeper), 0);
    assert_opens();
    assert_not_exclusive(keeper);
}

/* A program that holds the tty with TIOCEXCL only (no flock) keeps it: the
 * open is refused as busy, also for root (whom TIOCEXCL does not stop), and
 * its flag is left as it was. */
static void foreign_exclusive_flag_means_busy(void **state)
{
    (void)state;
    int keeper = hold_the_tty_open();
    assert_int_equal(ioctl(keeper, TIOCEXCL), 0);
    lsc_serial *s = NULL;
    assert_int_equal(lsc_serial_open(P.path, 9600, BACKEND, &s), LSC_EBUSY);
    const char *m = lsc_serial_error_message(s);
    assert_non_null(strstr(m, P.path));
    assert_non_null(strstr(m, "busy"));
    if (geteuid() == 0) { /* root's open() passed TIOCEXCL: our check refused it */
        assert_non_null(strstr(m, "TIOCEXCL"));
    }
    assert_int_equal(exclusive_flag(keeper), 1); /* not cleared by the refused open */
    assert_int_equal(ioctl(keeper, TIOCNXCL), 0);
    assert_opens(); /* the flag gone, the port opens */
    assert_not_exclusive(keeper);
}

/* An open that fails after claiming the port leaves no exclusive flag behind. */
static void failed_open_clears_the_exclusive_flag(void **state)
{
    (void)state;
    int keeper = hold_the_tty_open();
    lsc_serial *s = NULL;
    fail_tcsetattr = true;
    int r = lsc_serial_open(P.path, 9600, LSC_SERIAL_TERMIOS, &s);
    fail_tcsetattr = false;
    assert_int_equal(r, LSC_EIO);
    assert_non_null(strstr(lsc_serial_error_message(s), "8N1"));
    assert_not_exclusive(keeper);
}

static void open_errors(void **state)
{
    (void)state;
    lsc_serial *s = NULL;
    char longpath[LSC_SERIAL_PATH_MAX + 8];
    memset(longpath, 'a', sizeof longpath - 1);
    longpath[sizeof longpath - 1] = '\0';
    assert_int_equal(lsc_serial_open(P.path, 9600, BACKEND, NULL), LSC_EINVAL);
    assert_non_null(strstr(lsc_serial_error_message(NULL), "invalid argument"));
    assert_int_equal(lsc_serial_open(NULL, 9600, BACKEND, &s), LSC_EINVAL);
    assert_int_equal(lsc_serial_open("", 9600, BACKEND, &s), LSC_EINVAL);
    assert_int_equal(lsc_serial_open(longpath, 9600, BACKEND, &s), LSC_EINVAL);
    assert_int_equal(lsc_serial_open(P.path, 9600, (lsc_serial_backend)7, &s), LSC_EINVAL);
    assert_int_equal(lsc_serial_open("/dev/lsc-no-such-port", 9600, LSC_SERIAL_AUTO, &s),
                     LSC_ENODEV);
    assert_non_null(strstr(lsc_serial_error_message(s), "/dev/lsc-no-such-port"));
    assert_non_null(strstr(lsc_serial_error_message(s), "No such file or directory"));
    assert_int_equal(lsc_serial_os_errno(s), ENOENT);
    assert_int_equal(lsc_serial_open("/dev/null", 9600, LSC_SERIAL_TERMIOS, &s), LSC_ENODEV);
    assert_non_null(strstr(lsc_serial_error_message(s), "/dev/null: not a serial port"));
    assert_int_equal(lsc_serial_os_errno(s), ENOTTY);
    /* not a device at all: said so, not only "Is a directory" */
    assert_int_equal(lsc_serial_open("/", 9600, LSC_SERIAL_AUTO, &s), LSC_ENODEV);
    assert_string_equal(lsc_serial_error_message(s), "/: a directory, not a device");
    assert_int_equal(lsc_serial_os_errno(s), EISDIR);
    assert_int_equal(lsc_serial_open("", 9600, BACKEND, &s), LSC_EINVAL);
    assert_string_equal(lsc_serial_error_message(s),
                        "serial port: invalid device path (empty or too long)");
    assert_int_equal(lsc_serial_open(P.path, 12345, LSC_SERIAL_TERMIOS, &s), LSC_EINVAL);
    assert_non_null(strstr(lsc_serial_error_message(s), "baud"));
    /* closed ports refuse I/O; NULL is harmless */
    uint8_t b;
    assert_int_equal(lsc_serial_read(s, &b, 1, 0), LSC_EINVAL);
    assert_int_equal(lsc_serial_write(s, &b, 1), LSC_EINVAL);
    assert_null(s); /* a failed open leaves no handle: NULL says the last one's */
    assert_non_null(strstr(lsc_serial_error_message(NULL), "baud"));
    assert_int_equal(lsc_serial_os_errno(NULL), 0);
    assert_int_equal(lsc_serial_backend_in_use(NULL), LSC_SERIAL_AUTO);
    assert_int_equal(lsc_serial_fileno(NULL), -1);
    lsc_serial_close(NULL);
    lsc_serial_get_io(s, NULL);
    /* an open that succeeds clears the thread's last error */
    assert_int_equal(lsc_serial_open(P.path, 9600, LSC_SERIAL_TERMIOS, &s), LSC_EBUSY);
    assert_non_null(strstr(lsc_serial_error_message(NULL), "busy"));
    lsc_serial_close(S);
    S = NULL;
    assert_int_equal(lsc_serial_open(P.path, 9600, BACKEND, &s), 0);
    assert_non_null(s);
    assert_string_equal(lsc_serial_error_message(NULL), "");
    assert_string_equal(lsc_serial_error_message(s), "");
    lsc_serial_close(s);
}

static void auto_backend(void **state)
{
    (void)state;
    lsc_serial_close(S);
    S = NULL;
    lsc_serial *s = NULL;
    assert_int_equal(lsc_serial_open(P.path, 115200, LSC_SERIAL_AUTO, &s), 0);
#ifdef LSC_TEST_SP
    assert_int_equal(lsc_serial_backend_in_use(s), LSC_SERIAL_LIBSERIALPORT);
#else
    /* plain libserialport refuses a pty: AUTO fell back to termios */
    assert_int_equal(lsc_serial_backend_in_use(s), LSC_SERIAL_TERMIOS);
    lsc_serial *t = NULL;
    if (lsc_serial_have_libserialport()) {
        lsc_serial_close(s);
        assert_int_equal(lsc_serial_open(P.path, 9600, LSC_SERIAL_LIBSERIALPORT, &t), LSC_ENODEV);
        assert_non_null(strstr(lsc_serial_error_message(t), "libserialport"));
        assert_int_equal(lsc_serial_open(P.path, 115200, LSC_SERIAL_AUTO, &s), 0);
    } else {
        assert_int_equal(lsc_serial_open(P.path, 9600, LSC_SERIAL_LIBSERIALPORT, &t), LSC_EINVAL);
    }
#endif
    struct termios t2;
    assert_int_equal(tcgetattr(lsc_serial_fileno(s), &t2), 0);
    assert_int_equal(cfgetospeed(&t2), B115200);
    lsc_serial_close(s);
}

/* ---- End to end ------------------------------------------------------------------------ */

static void battery_with_notifications_around(void **state)
{
    (void)state;
    add_step(2, STARTED_8);
    add_step(2, "00 13 55 AA"); /* garbage */
    add_step(2, "55 55 02 0F"); /* wrong shape (an echo of the request) */
    add_step(2, "bytewise:" BATTERY_7500 " " COMPLETE_8);
    start_peer(BATTERY_REQ_LEN);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 2000), 0);
    assert_int_equal(mv, 7500);
    join_peer();
    assert_int_equal(P.ngot, 4);
    assert_memory_equal(P.got, ((uint8_t[]){0x55, 0x55, 0x02, 0x0F}), 4);
    for (int i = 0; i < 20 && nnotes < 2; i++) {
        assert_true(lsc_client_poll(&C, 100) >= 0);
    }
    assert_int_equal(nnotes, 2);
    assert_int_equal(notes[0].cmd, 6);
    assert_int_equal(notes[1].cmd, 8);
    assert_int_equal(C.unexpected, 1);
}

static void positions_and_wait_group(void **state)
{
    (void)state;
    add_step(1, "55 55 09 15 02 01 F4 01 03 F4 01"); /* wrong ids: discarded */
    add_step(1, "55 55 09 15 02 01 F4 01 02 DC 05 " STARTED_8);
    add_step(30, STOPPED);
    start_peer(7);
    uint8_t ids[2] = {1, 2};
    lsc_servo out[2];
    assert_int_equal(lsc_client_read_positions(&C, ids, 2, out, 2000), 2);
    assert_int_equal(out[0].position, 500);
    assert_int_equal(out[1].position, 1500);
    lsc_notification end;
    assert_int_equal(lsc_client_wait_group(&C, 2000, &end), 0);
    assert_int_equal(end.cmd, 7);
    join_peer();
    assert_memory_equal(P.got, ((uint8_t[]){0x55, 0x55, 0x05, 0x15, 0x02, 0x01, 0x02}), 7);
    assert_int_equal(nnotes, 2);
}

static void sending_commands(void **state)
{
    (void)state;
    start_peer(10 + 7 + 4);
    assert_int_equal(lsc_client_move_one(&C, 1, 2000, 1000), 0);
    assert_int_equal(lsc_client_run_group(&C, 8, 1), 0);
    assert_int_equal(lsc_client_stop_group(&C), 0);
    join_peer();
    uint8_t want[21];
    assert_int_equal(test_hex("55 55 08 03 01 E8 03 01 D0 07 55 55 05 06 08 01 00 55 55 02 07",
                              want, sizeof want),
                     21);
    assert_int_equal(P.ngot, 21);
    assert_memory_equal(P.got, want, 21);
}

/* How late a loaded machine may wake us on a real clock (LSC_TEST_TIME_SCALE
 * raises it): generous, it only catches a wait that ignores its timeout. */
#define SCHEDULING_SLACK_MS ((uint32_t)test_ms(1000))

static void silence_times_out_on_time(void **state)
{
    (void)state;
    static const uint32_t timeouts[] = {50, 200};
    for (size_t i = 0; i < 2; i++) {
        uint16_t mv;
        uint32_t start = now_ms();
        assert_int_equal(lsc_client_get_battery(&C, &mv, timeouts[i]), LSC_ETIMEOUT);
        uint32_t took = now_ms() - start;
        /* Never early. The 20% bound is proven on the fake clock in test_client;
         * on a real clock a loaded CI machine can schedule us late, so the upper
         * bound here only catches a wait that ignores its timeout. */
        assert_true(took >= timeouts[i]);
        assert_true(took <= timeouts[i] + SCHEDULING_SLACK_MS);
    }
}

static void eintr_resumes_the_wait(void **state)
{
    (void)state;
    add_step(20, SIGNAL);
    add_step(20, SIGNAL);
    add_step(20, BATTERY_7500);
    start_peer(BATTERY_REQ_LEN);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 2000), 0);
    assert_int_equal(mv, 7500);
    join_peer();
    /* and a signal during a timeout wait does not cut it short */
    memset(&P.steps, 0, sizeof P.steps);
    P.nsteps = 0;
    P.ngot = 0;
    add_step(30, SIGNAL);
    start_peer(BATTERY_REQ_LEN);
    uint32_t start = now_ms();
    assert_int_equal(lsc_client_get_battery(&C, &mv, 150), LSC_ETIMEOUT);
    uint32_t took = now_ms() - start;
    assert_true(took >= 150 && took <= 150 + SCHEDULING_SLACK_MS);
    join_peer();
}

static void peer_closes_mid_request(void **state)
{
    (void)state;
    add_step(5, "55 55 04");
    add_step(5, CLOSE);
    start_peer(BATTERY_REQ_LEN);
    uint16_t mv = 0;
    uint32_t start = now_ms();
    assert_int_equal(lsc_client_get_battery(&C, &mv, (uint32_t)test_ms(5000)), LSC_ENODEV);
    assert_true(now_ms() - start < test_ms(1000)); /* at once, not at the timeout */
    join_peer();
    const char *m = lsc_serial_error_message(S);
    assert_non_null(strstr(m, P.path));
    const char *said = strstr(m, "went away");
    assert_non_null(said);
    assert_null(strstr(said + 1, "went away")); /* said once, not twice */
    /* every later call fails the same way at once: no busy loop, no hang */
    start = now_ms();
    assert_int_equal(lsc_client_poll(&C, (uint32_t)test_ms(3000)), LSC_ENODEV);
    assert_int_equal(lsc_client_wait_group(&C, (uint32_t)test_ms(3000), NULL), LSC_ENODEV);
    assert_int_equal(lsc_client_stop_group(&C), LSC_ENODEV);
    assert_true(now_ms() - start < test_ms(1000));
}

static void short_writes_and_slow_reader(void **state)
{
    (void)state;
    /* 64 KiB is more than the pty buffers: write() must be resumed many times */
    static uint8_t big[65536];
    for (size_t i = 0; i < sizeof big; i++) {
        big[i] = (uint8_t)(i * 7u);
    }
    P.drain = sizeof big;
    start_peer(0);
    assert_int_equal(lsc_serial_write(S, big, sizeof big), (int)sizeof big);
    join_peer();
    assert_int_equal(P.ngot, sizeof big);
    assert_memory_equal(P.got, big, sizeof big);
}

/* Fills the pty's buffers until they take no more: nobody reads the master,
 * and the pty frees room lazily (a kernel work item moves bytes on), so
 * rounds go on until one writes nothing (finite: the buffers are). */
static void fill_until_full(void)
{
    static uint8_t fill[4096];
    size_t wrote;
    do {
        wrote = 0;
        for (size_t chunk = sizeof fill; chunk > 0; chunk /= 2) {
            ssize_t w;
            while ((w = write(lsc_serial_fileno(S), fill, chunk)) > 0) {
                wrote += (size_t)w;
            }
            assert_true(errno == EAGAIN || errno == EWOULDBLOCK);
        }
        sleep_ms(5);
    } while (wrote > 0);
}

static void write_that_cannot_drain_times_out(void **state)
{
    (void)state;
    const uint8_t ten[10] = {0};
    S->write_timeout_ms = 100; /* white box (serial_internal.h): keep the test short */
    int r;
    uint32_t took;
    /* room the pty freed after the fill (a busy machine runs its work item
     * late) lets the write through: then fill again */
    for (int attempt = 0;; attempt++) {
        fill_until_full();
        uint32_t start = now_ms();
        r = lsc_serial_write(S, ten, sizeof ten);
        took = now_ms() - start;
        if (r != (int)sizeof ten || attempt == 50) {
            break;
        }
    }
    assert_int_equal(r, LSC_EIO);
    assert_true(took >= 100 && took <= 100 + SCHEDULING_SLACK_MS);
    assert_non_null(strstr(lsc_serial_error_message(S), "timed out"));
    assert_non_null(strstr(lsc_serial_error_message(S), "(0 of 10 bytes went out"));
}

static void list_ports(void **state)
{
    (void)state;
    char msg[128];
    int n = lsc_serial_list_ports(NULL, 0, msg, sizeof msg);
    if (!lsc_serial_have_libserialport()) {
        assert_int_equal(n, LSC_ENODEV);
        assert_non_null(strstr(msg, "libserialport"));
        return;
    }
    assert_true(n >= 0);
    assert_int_equal(lsc_serial_list_ports(NULL, 1, msg, sizeof msg), LSC_EINVAL);
    lsc_port_info ports[16];
    ports[0].size = sizeof ports[0];
    int m = lsc_serial_list_ports(ports, 16, NULL, 0);
    assert_int_equal(m, n);
    for (int i = 0; i < m && i < 16; i++) {
        assert_true(strncmp(ports[i].path, "/dev/", 5) == 0);
        print_message("port %s (%s)%s\n", ports[i].path, ports[i].description,
                      ports[i].usb ? " usb" : "");
    }
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, setup, teardown)
    const struct CMUnitTest tests[] = {
        T(opened_raw_8n1_9600),
        T(second_opener_is_refused),
        T(not_root_refused_by_flock_and_eacces),
        T(close_clears_the_exclusive_flag),
        T(failed_open_clears_the_exclusive_flag),
        T(open_errors),
        T(auto_backend),
        T(battery_with_notifications_around),
        T(positions_and_wait_group),
        T(sending_commands),
        T(silence_times_out_on_time),
        T(eintr_resumes_the_wait),
        T(peer_closes_mid_request),
        T(short_writes_and_slow_reader),
        T(write_that_cannot_drain_times_out),
        T(killed_holder_leaves_the_port_free),
        T(foreign_exclusive_flag_means_busy),
        T(list_ports),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
