/* The device layer (src/device, lsc/device.h) on a serial port played by a
 * peer on a pseudo-terminal: requests, every timeout message, waits and
 * settling, the port going away, the torn-write rule, the last word before
 * a signal (write wrapped), a poll whose clock stands still (the transports'
 * clock wrapped), a program's own event loop. */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "device_test.h"
#include "lsc/device.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "lsc/serial.h"
#include "test_hex.h"
#include "test_time.h"

/* ---- Linker wraps: write, and the transports' clock (src/port) -------------------- */

ssize_t __real_write(int fd, const void *buf, size_t n);
ssize_t __wrap_write(int fd, const void *buf, size_t n);
uint32_t __real_lsc_port_now_ms(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
uint32_t __wrap_lsc_port_now_ms(void); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static int write_raises;    /* a signal: the next write raises it, then fails (LSC_EIO) */
static bool clock_stands_still; /* the transports' clock stays at still_at */
static uint32_t still_at;

uint32_t __wrap_lsc_port_now_ms(void) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    return clock_stands_still ? still_at : __real_lsc_port_now_ms();
}

ssize_t __wrap_write(int fd, const void *buf, size_t n)
{
    if (write_raises != 0) {
        (void)kill(getpid(), write_raises);
        write_raises = 0;
        errno = ENOSPC; /* an OS error: LSC_EIO */
        return -1;
    }
    return __real_write(fd, buf, n);
}

static int setup(void **state)
{
    clock_stands_still = false;
    return device_setup(state);
}

/* ---- A serial port: a peer on a pseudo-terminal ------------------------------------ */

typedef struct peer {
    int master;
    char path[128];
    pthread_t thread;
    bool running;
    size_t expect;     /* bytes to receive (in all) before answering */
    const char *reply; /* hex, or NULL: none */
    bool hang_up;      /* then close the master */
    size_t ngot;
    uint8_t got[4096];
} peer;

static peer P;

static void *peer_main(void *arg)
{
    (void)arg;
    while (P.ngot < P.expect) {
        struct pollfd p = {P.master, POLLIN, 0};
        if (poll(&p, 1, (int)test_ms(5000)) <= 0) {
            return NULL;
        }
        ssize_t r = read(P.master, P.got + P.ngot, sizeof P.got - P.ngot);
        if (r <= 0) {
            return NULL;
        }
        P.ngot += (size_t)r;
    }
    if (P.reply != NULL) {
        uint8_t bytes[512];
        size_t n = test_hex(P.reply, bytes, sizeof bytes);
        assert_true(write(P.master, bytes, n) == (ssize_t)n);
    }
    if (P.hang_up) {
        (void)close(P.master);
        P.master = -1;
    }
    return NULL;
}

/* The peer answers reply once `more` further bytes arrived. */
static void answer(size_t more, const char *reply, bool hang_up)
{
    P.expect = P.ngot + more;
    P.reply = reply;
    P.hang_up = hang_up;
    assert_int_equal(pthread_create(&P.thread, NULL, peer_main, NULL), 0);
    P.running = true;
}

static void answered(void)
{
    if (P.running) {
        assert_int_equal(pthread_join(P.thread, NULL), 0);
        P.running = false;
    }
}

static int pty_setup(void **state)
{
    int slave;
    memset(&P, 0, sizeof P);
    if (openpty(&P.master, &slave, P.path, NULL, NULL) != 0) {
        return -1;
    }
    (void)close(slave);
    return setup(state);
}

static int pty_teardown(void **state)
{
    answered();
    if (P.master >= 0) {
        (void)close(P.master);
    }
    return device_teardown(state);
}

#define BATTERY_REQ 4u
#define POS_REQ_1 6u

/* A reply timeout that a peer thread answering a request meets on a busy
 * machine (its answer must arrive before it ends). */
static uint32_t short_ms(void)
{
    return (uint32_t)test_ms(250);
}

static lsc_device *open_pty(uint32_t timeout_ms)
{
    test_options opt = {9600, timeout_ms, 0, 0};
    lsc_device *d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SERIAL);
    assert_string_equal(lsc_device_name(d), P.path);
    return d;
}

static void serial_requests(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_device *d = open_pty(500);
    answer(BATTERY_REQ, "55 55 04 0F 4C 1D", false);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    answered();
    assert_int_equal(mv, 7500);
    /* a second opener: busy */
    lsc_device *e = open_fails(P.path, NULL, LSC_EBUSY);
    lsc_device_close(e);
    /* a baud rate the port cannot take */
    lsc_device_close(d);
    test_options opt = {12345, 0, 0, 0};
    e = open_fails(P.path, &opt, LSC_EINVAL);
    assert_has(lsc_device_error(e), "unsupported baud rate");
    lsc_device_close(e);
}

/* Each timeout says what did arrive. */
static void serial_timeouts(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_device *d = open_pty(short_ms());
    answer(BATTERY_REQ, NULL, false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "no reply from the controller on ");
    char within[64];
    snprintf(within, sizeof within, " within %u ms: nothing arrived", (unsigned)short_ms());
    assert_has(lsc_device_error(d), within);
    assert_has(lsc_device_error(d), "nothing arrived; check that it is powered "
                                    "and connected, and the port and baud rate (9600); or raise "
                                    "the timeout");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_REPLY);
    answer(BATTERY_REQ, "01 02 03", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "only 3 byte(s) arrived that formed no frame: likely a wrong "
                                    "baud rate (this was 9600");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NOISE);
    answer(BATTERY_REQ, "55 55 02 07", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "only 1 notification(s) arrived (and 0 byte(s)");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_ONLY_NOTIFICATIONS);
    answer(BATTERY_REQ, "55 55 06 15 01 01 DC 05", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    snprintf(within, sizeof within, " within %u ms: 1 frame(s)", (unsigned)short_ms());
    assert_has(lsc_device_error(d), within);
    assert_has(lsc_device_error(d), "did not answer get_battery_voltage (command 15) within ");
    assert_has(lsc_device_error(d), " ms: 1 frame(s) answering something else came instead (the "
                                    "last: mult_servo_pos_read (command 21)), with 0 "
                                    "notification(s)");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_OTHER_FRAMES);
    /* a malformed reply */
    answer(BATTERY_REQ, "55 55 03 0F 01", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EREPLY);
    answered();
    assert_has(lsc_device_error(d), "bad reply from the controller on ");
    assert_has(lsc_device_error(d), ": check the baud rate (9600)");
    /* offsets: LSC boards may not answer */
    const uint8_t id = 1;
    lsc_servo_offset off;
    answer(POS_REQ_1, NULL, false);
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_ETIMEOUT);
    answered();
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_REPLY);
    assert_has(lsc_device_error(d), "LSC-6/16/32 boards may not answer; else check the port, "
                                    "the power and the timeout");
    lsc_device_close(d);
}

/* move --wait on a board whose servos do not report: the move's time is all */
static void serial_settle(void **state)
{
    (void)state;
    const lsc_servo to = {1, 2000};
    lsc_device *d = open_pty(short_ms());
    answer(POS_REQ_1, NULL, false);
    assert_int_equal(lsc_device_settle(d, &to, 1, 20, 10), 1);
    answered();
    assert_null(lsc_device_sim(d)); /* not the virtual controller */
    assert_has(lsc_device_error(d), "does not answer position reads: the move's time has "
                                    "passed");
    answer(POS_REQ_1, "55 55 06 15 01 01 D0 07", false);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), 0);
    answered();
    lsc_device_close(d);
}

/* Waits on a real port: in chunks without limit, to their timeout with one. */
static void serial_waits(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    assert_int_equal(lsc_device_sim_next_event_ms(d), LSC_DEVICE_FOREVER); /* not "sim" */
    answer(7, "55 55 05 06 08 01 00 55 55 05 08 08 01 00", false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, 30, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    assert_int_equal(lsc_device_poll(d, 20), 0);
    lsc_device_close(d);
}

/* The notice of a run just before ours (another program's, of the same
 * group) comes after ours was sent: the 7 and 6 that our run makes the
 * controller send say that start was not ours. A stop with nothing after it,
 * or with another group's start, ends the wait; that start stays queued. */
static void serial_wait_late_start(void **state)
{
    (void)state;
    lsc_notification n;
    /* no wait here ends by a timeout: a long one, so that a peer thread late
     * on a loaded machine is not taken for a group that never started */
    lsc_device *d = open_pty((uint32_t)test_ms(1000));
    answer(7, "55 55 05 06 02 00 00 55 55 02 07 55 55 05 06 02 01 00 55 55 05 08 02 01 00",
           false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 2);

    answer(7, "55 55 05 06 02 01 00 55 55 02 07 55 55 05 06 03 01 00", false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(n.group, 3);

    answer(7, "55 55 05 06 02 01 00 55 55 02 07", false);
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    lsc_device_close(d);
}

/* The port goes away: every call that reads or writes says so. */
static void serial_hang_up(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_notification n;
    const lsc_servo to = {1, 2000};
    lsc_device *d = open_pty(200);
    answer(BATTERY_REQ, NULL, true);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ENODEV);
    answered();
    char msg[256];
    snprintf(msg, sizeof msg, "%s", lsc_device_error(d));
    assert_has(msg, P.path);
    assert_int_equal(lsc_device_poll(d, 10), LSC_ENODEV);
    assert_int_equal(lsc_device_notification(d, 10, &n), LSC_ENODEV);
    assert_int_equal(lsc_device_wait_group(d, LSC_GROUP_ALL, 10, &n), LSC_ENODEV);
    assert_int_equal(lsc_device_run(d, 1, 1), LSC_ENODEV);
    assert_int_equal(lsc_device_settle(d, &to, 1, 10, 10), LSC_ENODEV);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), LSC_ENODEV);
    lsc_device_close(d);
}

#define BIG_PARAMS LSC_PARAMS_MAX /* a 257-byte frame */

/* A write the line never takes: the device says which frame and how much of
 * it went out. */
static void serial_write_stalls(void **state)
{
    (void)state;
    uint8_t params[BIG_PARAMS] = {0};
    lsc_device *d = open_pty(200);
    int r;
    do { /* the pty's buffers fill up: nobody reads the master */
        r = lsc_device_send(d, 0x30, params, sizeof params, false);
    } while (r == 0);
    assert_int_equal(r, LSC_EIO);
    assert_has(lsc_device_error(d), "sending unknown (command 48, 257 bytes): ");
    assert_has(lsc_device_error(d), "of 257 bytes went out");
    lsc_device_close(d);
}

static volatile sig_atomic_t caught;
static char last_said[640];
static int last_word_signal; /* the signal say_last_word catches */

static void on_signal(int sig)
{
    (void)sig;
    caught = 1;
}

/* Keeps the failure's line, then (so that the test lives on) catches the
 * signal that would have ended the process. */
static void say_last_word(void *user, const lsc_device *d)
{
    int *calls = user;
    (*calls)++;
    snprintf(last_said, sizeof last_said, "%s", lsc_device_error(d));
    (void)signal(last_word_signal, on_signal);
}

/* A signal that would end the process comes while a write fails: the
 * failure is said (the last word) while the signal is held back, then the
 * signal takes effect (lscctl's faults.sh sees the process end by it). A
 * signal that is caught, or was blocked before, needs no last word. */
static void serial_last_word_before_signal(void **state)
{
    (void)state;
    int calls = 0;
    const uint8_t id = 1;
    lsc_device *d = open_pty(200);
    lsc_device_set_last_word(d, say_last_word, &calls);
    last_word_signal = SIGHUP;
    (void)signal(SIGHUP, SIG_DFL);
    caught = 0;
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    assert_true(caught); /* after the last word */
    assert_has(last_said, "sending mult_servo_unload (command 20, 6 bytes): ");
    assert_has(last_said, "write");
    assert_string_equal(lsc_device_error(d), last_said);
    /* caught (the handler is still set): nothing to say first */
    caught = 0;
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    assert_true(caught);
    /* blocked by the caller: it stays pending after the call */
    sigset_t hup, old;
    sigemptyset(&hup);
    sigaddset(&hup, SIGHUP);
    (void)signal(SIGHUP, SIG_DFL);
    (void)pthread_sigmask(SIG_BLOCK, &hup, &old);
    write_raises = SIGHUP;
    assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
    assert_int_equal(calls, 1);
    (void)signal(SIGHUP, on_signal);
    caught = 0;
    (void)pthread_sigmask(SIG_SETMASK, &old, NULL);
    assert_true(caught);
    /* without a callback, a write that fails says so as any error */
    lsc_device_set_last_word(d, NULL, NULL);
    assert_int_equal(lsc_device_unload(d, &id, 1), 0);
    (void)signal(SIGHUP, SIG_DFL);
    lsc_device_close(d);
}

/* After the open: the name in the messages of a request, escaped. */
static void serial_name_escaped(void **state)
{
    (void)state;
    uint16_t mv;
    char link[256];
    snprintf(link, sizeof link, "%s/tty\n\033[31m", tmpdir);
    assert_int_equal(symlink(P.path, link), 0);
    test_options opt = {9600, 50, 0, 0};
    lsc_device *d = open_ok(link, &opt);
    assert_string_equal(lsc_device_name(d), link);
    answer(BATTERY_REQ, NULL, false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "/tty\\x0A\\x1B[31m within 50 ms");
    assert_null(strpbrk(lsc_device_error(d), "\n\033"));
    lsc_device_close(d);
    (void)unlink(link);
}

/* ---- More of a serial port ----------------------------------------------------------- */

/* What came instead of the reply: a frame whose command is below the
 * notifications' (6..8) is no notification. */
static void serial_other_frame_low(void **state)
{
    (void)state;
    uint16_t mv;
    lsc_device *d = open_pty((uint32_t)test_ms(1000)); /* the peer's frame comes in time */
    answer(BATTERY_REQ, "55 55 03 01 00", false);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    answered();
    assert_has(lsc_device_error(d), "1 frame(s) answering something else came instead (the "
                                    "last: unknown (command 1))");
    lsc_device_close(d);
}

/* A wait for a group that started: another group's start and end do not
 * end it, its own end does. */
static void serial_wait_started(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    answer(7,
           "55 55 05 06 08 01 00 55 55 05 06 01 01 00 55 55 05 08 01 01 00 "
           "55 55 05 08 08 01 00",
           false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(n.group, 8);
    lsc_device_close(d);
}

/* A stop that ends a wait, followed by anything but the same group's start
 * (here another stop): the wait ends; what followed stays queued. */
static void serial_wait_stop_then_other(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    answer(7, "55 55 05 06 08 01 00 55 55 02 07 55 55 02 07", false);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    answered();
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    lsc_device_close(d);
}

/* SIGINT and SIGTERM that would end the process get the last word too. */

static void serial_last_word_int_term(void **state)
{
    (void)state;
    const uint8_t id = 1;
    static const int sigs[] = {SIGINT, SIGTERM};
    lsc_device *d = open_pty(200);
    for (size_t i = 0; i < 2; i++) {
        int calls = 0;
        lsc_device_set_last_word(d, say_last_word, &calls);
        last_word_signal = sigs[i];
        (void)signal(sigs[i], SIG_DFL);
        caught = 0;
        last_said[0] = '\0';
        write_raises = sigs[i];
        assert_int_equal(lsc_device_unload(d, &id, 1), LSC_EIO);
        assert_int_equal(calls, 1);
        assert_true(caught);
        assert_has(last_said, "sending mult_servo_unload (command 20, 6 bytes): ");
        (void)signal(sigs[i], SIG_DFL);
    }
    lsc_device_close(d);
}

/* A busy port whose name no lscd socket can have: busy, as it is. */
static void serial_busy_long_name(void **state)
{
    (void)state;
    char link[256];
    snprintf(link, sizeof link, "%s/%070d", tmpdir, 0);
    assert_int_equal(symlink(P.path, link), 0);
    test_options opt = {9600, 50, 0, 0};
    lsc_device *d = open_ok(link, &opt);
    /* a profile on a real port changes nothing there */
    static const char text[] = "base 6 bus\n";
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse(text, sizeof text - 1u, "t.conf", &arm, NULL, 0), 0);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    lsc_device *e = open_fails(link, NULL, LSC_EBUSY);
    assert_int_equal(lsc_device_kind_of(e), LSC_DEVICE_SERIAL);
    assert_has(lsc_device_error(e), "port busy");
    lsc_device_close(e);
    lsc_device_close(d);
    (void)unlink(link);
}

/* A poll whose clock stands still while input keeps coming ends after a
 * bounded number of reads (LSC_CLIENT_WAIT_READS_MIN +
 * LSC_CLIENT_READS_PER_MS per ms), as the client's waits do. */
static void serial_poll_clock_stands_still(void **state)
{
    (void)state;
    uint8_t noise[4000];
    memset(noise, 0, sizeof noise);
    lsc_device *d = open_pty(200);
    /* more noise than the reads of a 1 ms poll take (32 bytes each) */
    size_t put = 0;
    while (put < sizeof noise) {
        struct pollfd p = {P.master, POLLOUT, 0};
        assert_true(poll(&p, 1, (int)test_ms(5000)) == 1);
        ssize_t w = write(P.master, noise + put, sizeof noise - put);
        assert_true(w > 0);
        put += (size_t)w;
    }
    still_at = __real_lsc_port_now_ms();
    clock_stands_still = true;
    (void)alarm((unsigned)test_ms(60)); /* a poll without that bound never ends: fail */
    int r = lsc_device_poll(d, 1);
    (void)alarm(0);
    clock_stands_still = false;
    assert_int_equal(r, 0);
    lsc_device_close(d);
}

/* ---- A program's own event loop: lsc_device_fileno, lsc_device_next_event_ms ---------- */

/* Whether fd polls readable within the test's time. */
static bool readable(int fd)
{
    struct pollfd p = {fd, POLLIN, 0};
    return poll(&p, 1, (int)test_ms(5000)) == 1 && (p.revents & POLLIN) != 0;
}

/* Waits until the port's side of the pty holds n bytes. */
static void pty_holds(int fd, int n)
{
    int held = 0;
    for (uint64_t i = 0; i < (uint64_t)test_ms(5000) && held < n; i++) { /* 1 ms each */
        assert_true(readable(fd));
        assert_int_equal(ioctl(fd, FIONREAD, &held), 0);
        if (held < n) {
            struct timespec t = {0, 1000000}; /* (the pty's own queue moves bytes on) */
            (void)nanosleep(&t, NULL);
        }
    }
    assert_true(held >= n);
}

/* A serial port: its descriptor polls readable when a notification came;
 * lsc_device_poll(d, 0) takes it without waiting, at most 64 reads at once
 * (then the deadline is now); a hang-up is the port's error. */
static void events_serial(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_pty(short_ms());
    int fd = lsc_device_fileno(d);
    assert_true(fd >= 0);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    static const uint8_t stop[] = {0x55, 0x55, 0x02, 0x07};
    assert_true(write(P.master, stop, sizeof stop) == (ssize_t)sizeof stop);
    assert_true(readable(fd));
    assert_int_equal(lsc_device_poll(d, 0), 1);
    assert_int_equal(lsc_device_next_event_ms(d), 0);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    /* more than 64 reads of 32 bytes hold: 2048 + 4 bytes of stops */
    uint8_t many[2052];
    for (size_t i = 0; i < sizeof many; i += sizeof stop) {
        memcpy(many + i, stop, sizeof stop);
    }
    assert_true(write(P.master, many, sizeof many) == (ssize_t)sizeof many);
    pty_holds(fd, (int)sizeof many);
    assert_int_equal(lsc_device_poll(d, 0), (int)LSC_DEVICE_QUEUE);
    assert_int_equal(lsc_device_dropped_notifications(d), 512u - LSC_DEVICE_QUEUE);
    for (unsigned i = 0; i < LSC_DEVICE_QUEUE; i++) { /* (the queue only: no read) */
        assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    }
    assert_int_equal(lsc_device_next_event_ms(d), 0); /* input is left */
    assert_int_equal(lsc_device_poll(d, 0), 1);
    assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    /* the other end hangs up */
    (void)close(P.master);
    P.master = -1;
    assert_true(readable(fd));
    assert_int_equal(lsc_device_poll(d, 0), LSC_ENODEV);
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(serial_requests, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_timeouts, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_settle, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_waits, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_late_start, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(events_serial, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_hang_up, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_write_stalls, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_last_word_before_signal, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_name_escaped, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_other_frame_low, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_started, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_wait_stop_then_other, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_last_word_int_term, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_busy_long_name, pty_setup, pty_teardown),
        cmocka_unit_test_setup_teardown(serial_poll_clock_stands_still, pty_setup, pty_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
