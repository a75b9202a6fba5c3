/* Fault injection through the real serial transport: the client talks over a
 * pseudo-terminal to a "controller" played by a child process, while the
 * test breaks things underneath: read(), write() and poll() interrupted by
 * EINTR before every real call, writes cut to one byte, a device that goes
 * away in the middle of a reply, a peer that never answers, a peer that
 * answers late, a notification storm, a second process on the same port.
 *
 * The interruptions use the linker's --wrap: the library's calls to read,
 * write and poll go to __wrap_* below (tests/CMakeLists.txt), which can fail
 * with EINTR first; the child uses __real_* and is never interrupted. */
#define _DEFAULT_SOURCE /* openpty, ptsname, usleep */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <stdbool.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/client.h"
#include "lsc/serial.h"
#include "../src/serial/serial_internal.h" /* white box: the write timeout */
#include "lsc/sim.h"
#include "test_time.h"

/* ---- Interposed system calls -------------------------------------------------- */

ssize_t __real_read(int fd, void *buf, size_t n);
ssize_t __real_write(int fd, const void *buf, size_t n);
int __real_poll(struct pollfd *fds, nfds_t nfds, int timeout);
ssize_t __wrap_read(int fd, void *buf, size_t n);
ssize_t __wrap_write(int fd, const void *buf, size_t n);
int __wrap_poll(struct pollfd *fds, nfds_t nfds, int timeout);
void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static bool calloc_fails; /* the next calloc fails */

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (calloc_fails) {
        calloc_fails = false;
        return NULL;
    }
    return __real_calloc(n, size);
}

static bool eintr;       /* fail every other call with EINTR */
static bool one_byte;    /* writes take one byte at a time */
static long stall_after = -1; /* >= 0: the line takes this many more bytes, then none */
static unsigned interrupted, short_writes;
static bool toggle_read, toggle_write, toggle_poll;

/* True (and errno = EINTR) on every other call while eintr is set. */
static bool interrupt(bool *toggle)
{
    if (!eintr) {
        return false;
    }
    *toggle = !*toggle;
    if (*toggle) {
        interrupted++;
        errno = EINTR;
    }
    return *toggle;
}

ssize_t __wrap_read(int fd, void *buf, size_t n)
{
    return interrupt(&toggle_read) ? -1 : __real_read(fd, buf, n);
}

ssize_t __wrap_write(int fd, const void *buf, size_t n)
{
    if (interrupt(&toggle_write)) {
        return -1;
    }
    if (one_byte && n > 1) {
        short_writes++;
        n = 1;
    }
    if (stall_after == 0) {
        errno = EAGAIN;
        return -1;
    }
    if (stall_after > 0 && n > (size_t)stall_after) {
        n = (size_t)stall_after;
    }
    ssize_t w = __real_write(fd, buf, n);
    if (stall_after > 0 && w > 0) {
        stall_after -= w;
    }
    return w;
}

int __wrap_poll(struct pollfd *fds, nfds_t nfds, int timeout)
{
    if (interrupt(&toggle_poll)) {
        return -1;
    }
    if (stall_after == 0 && nfds == 1 && (fds[0].events & POLLOUT)) {
        /* a stalled line never becomes writable: wait out the timeout */
        short events = fds[0].events;
        fds[0].events = 0;
        int r = __real_poll(fds, nfds, timeout);
        fds[0].events = events;
        return r;
    }
    return __real_poll(fds, nfds, timeout);
}

/* ---- The port and the controller ----------------------------------------------- */

static const uint8_t BATTERY_REQ[] = {0x55, 0x55, 0x02, 0x0F};
static const uint8_t BATTERY_7500[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
static const uint8_t BATTERY_7400[] = {0x55, 0x55, 0x04, 0x0F, 0xE8, 0x1C};
static const uint8_t GROUP_RUN_8[] = {0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00};

static int master = -1;
static char slave_path[128];
static lsc_serial *port;
static lsc_client client;
static pid_t child = -1;

static uint32_t now_ms(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint32_t)t.tv_sec * 1000u + (uint32_t)(t.tv_nsec / 1000000);
}

static void sleep_ms(unsigned ms)
{
    struct timespec t = {(time_t)(ms / 1000u), (long)(ms % 1000u) * 1000000L};
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

/* In the child: reads exactly n bytes from the master; false on EOF/error. */
static bool peer_read(uint8_t *buf, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t r = __real_read(master, buf + got, n - got);
        if (r <= 0) {
            if (r < 0 && errno == EINTR) {
                continue;
            }
            return false;
        }
        got += (size_t)r;
    }
    return true;
}

static bool peer_write(const uint8_t *buf, size_t n)
{
    size_t done = 0;
    while (done < n) {
        ssize_t r = __real_write(master, buf + done, n - done);
        if (r <= 0) {
            if (r < 0 && errno == EINTR) {
                continue;
            }
            return false;
        }
        done += (size_t)r;
    }
    return true;
}

/* In the child: waits for one battery request; exits 3 if it is not one. */
static void peer_expect_battery_request(void)
{
    uint8_t req[sizeof BATTERY_REQ];
    if (!peer_read(req, sizeof req) || memcmp(req, BATTERY_REQ, sizeof req) != 0) {
        _exit(3);
    }
}

/* Runs behaviour in a child process that plays the controller on the master. */
static void start_peer(void (*behaviour)(void))
{
    child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        eintr = false;
        one_byte = false;
        behaviour();
        _exit(0);
    }
}

/* The child's exit status (it must have exited normally). */
static int wait_peer(void)
{
    int status = 0;
    assert_int_equal(waitpid(child, &status, 0), child);
    child = -1;
    assert_true(WIFEXITED(status));
    return WEXITSTATUS(status);
}

static int setup(void **state)
{
    (void)state;
    int slave = -1;
    if (openpty(&master, &slave, slave_path, NULL, NULL) != 0) {
        return -1;
    }
    (void)close(slave); /* the port opens it again by name */
    port = NULL;
    if (lsc_serial_open(slave_path, 9600, LSC_SERIAL_TERMIOS, &port) != 0) {
        return -1;
    }
    lsc_io io;
    lsc_serial_get_io(port, &io);
    eintr = one_byte = false;
    interrupted = short_writes = 0;
    return lsc_client_init(&client, &io);
}

static int teardown(void **state)
{
    (void)state;
    eintr = one_byte = false;
    stall_after = -1;
    if (child > 0) {
        (void)kill(child, SIGKILL);
        (void)waitpid(child, NULL, 0);
        child = -1;
    }
    lsc_serial_close(port);
    if (master >= 0) {
        (void)close(master);
        master = -1;
    }
    return 0;
}

/* ---- Tests ------------------------------------------------------------------------- */

static void answer_battery(void)
{
    peer_expect_battery_request();
    if (!peer_write(BATTERY_7500, sizeof BATTERY_7500)) {
        _exit(4);
    }
}

/* Every read, write and poll is interrupted once before it works. */
static void eintr_on_every_call(void **state)
{
    (void)state;
    start_peer(answer_battery);
    eintr = true;
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 2000), 0);
    eintr = false;
    assert_int_equal(mv, 7500);
    assert_int_equal(wait_peer(), 0);
    assert_true(interrupted >= 3); /* at least one read, one write, one poll */
}

/* The OS takes one byte per write: the frame still goes out whole. */
static void short_writes_send_the_whole_frame(void **state)
{
    (void)state;
    start_peer(answer_battery); /* exits 3 unless it receives exactly 55 55 02 0F */
    one_byte = true;
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 2000), 0);
    one_byte = false;
    assert_int_equal(mv, 7500);
    assert_int_equal(wait_peer(), 0);
    assert_int_equal(short_writes, 3); /* a 4-byte frame: cut with 4, 3 and 2 bytes left */
}

static void half_reply_then_vanish(void)
{
    peer_expect_battery_request();
    (void)peer_write(BATTERY_7500, 3);
    sleep_ms(50);
    (void)close(master); /* the only remaining descriptor of the master: the device is gone */
}

/* The device disappears in the middle of a reply: a clear LSC_ENODEV at
 * once, not a hang until the timeout. */
static void device_disappears_mid_reply(void **state)
{
    (void)state;
    start_peer(half_reply_then_vanish);
    (void)close(master);
    master = -1;
    uint16_t mv = 0xBEEF;
    uint32_t t0 = now_ms();
    assert_int_equal(lsc_client_get_battery(&client, &mv, (uint32_t)test_ms(3000)), LSC_ENODEV);
    assert_true(now_ms() - t0 < test_ms(1500));
    assert_int_equal(mv, 0xBEEF);
    assert_int_equal(wait_peer(), 0);
    /* and it stays gone: the next call fails the same way, quickly */
    t0 = now_ms();
    assert_int_equal(lsc_client_get_battery(&client, &mv, (uint32_t)test_ms(3000)), LSC_ENODEV);
    assert_true(now_ms() - t0 < test_ms(1500));
}

static void stay_silent(void)
{
    peer_expect_battery_request();
    /* until the test kills it, or the port closes (the test is gone) */
    struct pollfd p = {master, 0, 0};
    while (__real_poll(&p, 1, -1) == 0 || !(p.revents & POLLHUP)) {
    }
}

/* A port where nobody answers: LSC_ETIMEOUT after the timeout, not before. */
static void silent_port_times_out(void **state)
{
    (void)state;
    start_peer(stay_silent);
    uint16_t mv = 0xBEEF;
    uint32_t t0 = now_ms();
    assert_int_equal(lsc_client_get_battery(&client, &mv, 200), LSC_ETIMEOUT);
    uint32_t took = now_ms() - t0;
    assert_true(took >= 195 && took < test_ms(800));
    assert_int_equal(mv, 0xBEEF);
    (void)kill(child, SIGKILL);
    (void)waitpid(child, NULL, 0);
    child = -1;
}

static void answer_late_then_promptly(void)
{
    peer_expect_battery_request();
    sleep_ms(300); /* the client gave up after 100 ms */
    (void)peer_write(BATTERY_7500, sizeof BATTERY_7500);
    peer_expect_battery_request();
    (void)peer_write(BATTERY_7400, sizeof BATTERY_7400);
}

/* A peer that answers very slowly: the first request times out; its late
 * answer is not taken for the second request's. */
static void slow_peer_late_reply_not_taken(void **state)
{
    (void)state;
    start_peer(answer_late_then_promptly);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 100), LSC_ETIMEOUT);
    sleep_ms(400); /* the late reply is now waiting in the port */
    assert_int_equal(lsc_client_get_battery(&client, &mv, 2000), 0);
    assert_int_equal(mv, 7400);
    assert_int_equal(wait_peer(), 0);
}

#define STORM 2000

static void storm_then_answer(void)
{
    static uint8_t burst[STORM * sizeof GROUP_RUN_8];
    for (size_t i = 0; i < STORM; i++) {
        memcpy(&burst[i * sizeof GROUP_RUN_8], GROUP_RUN_8, sizeof GROUP_RUN_8);
    }
    peer_expect_battery_request();
    (void)peer_write(burst, sizeof burst);
    (void)peer_write(BATTERY_7500, sizeof BATTERY_7500);
}

static unsigned storm_seen;

static void count_note(void *user, const lsc_notification *n)
{
    (void)user;
    storm_seen += n->cmd == LSC_CMD_GROUP_RUN && n->group == 8 && n->times == 1;
}

/* 2000 notifications (14 KB, 14 s of a real line) before the reply: every one
 * is delivered, and the reply still ends the request. */
static void notification_storm_over_a_pty(void **state)
{
    (void)state;
    storm_seen = 0;
    lsc_client_set_notify(&client, count_note, NULL);
    start_peer(storm_then_answer);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 5000), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(storm_seen, STORM);
    assert_int_equal(client.notifications, STORM);
    assert_int_equal(wait_peer(), 0);
}

/* No memory for the port: refused, no handle, the reason readable without
 * one; nothing is left open (the port opens at once after). */
static void open_out_of_memory(void **state)
{
    (void)state;
    lsc_serial_close(port);
    port = NULL;
    lsc_serial *other = (lsc_serial *)&other;
    calloc_fails = true;
    assert_int_equal(lsc_serial_open(slave_path, 9600, LSC_SERIAL_TERMIOS, &other), LSC_ENOSPC);
    assert_null(other);
    assert_string_equal(lsc_serial_error_message(NULL), "out of memory");
    assert_int_equal(lsc_serial_open(slave_path, 9600, LSC_SERIAL_TERMIOS, &port), 0);
    assert_string_equal(lsc_serial_error_message(NULL), "");
}

static void open_same_port(void)
{
    lsc_serial *other = NULL;
    int r = lsc_serial_open(slave_path, 9600, LSC_SERIAL_TERMIOS, &other);
    lsc_serial_close(other);
    _exit(r == LSC_EBUSY ? 0 : 10 - r);
}

/* A second process opening the port gets LSC_EBUSY; the first keeps working. */
static void two_processes_one_port(void **state)
{
    (void)state;
    start_peer(open_same_port);
    assert_int_equal(wait_peer(), 0);
    start_peer(answer_battery);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 2000), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(wait_peer(), 0);
}

static void truncated_then_corrupted(void)
{
    peer_expect_battery_request();
    (void)peer_write(BATTERY_7500, 4); /* a reply cut short: then silence */
    peer_expect_battery_request();
    static const uint8_t bad_len[] = {0x55, 0x55, 0x05, 0x0F, 0x4C, 0x1D, 0x00};
    (void)peer_write(bad_len, sizeof bad_len); /* LEN corrupted: malformed */
    peer_expect_battery_request();
    (void)peer_write(BATTERY_7400, sizeof BATTERY_7400);
}

/* A truncated reply times out; a corrupted one is LSC_EREPLY; neither
 * poisons the request after them. */
static void truncated_and_corrupted_replies(void **state)
{
    (void)state;
    start_peer(truncated_then_corrupted);
    uint16_t mv = 0xBEEF;
    assert_int_equal(lsc_client_get_battery(&client, &mv, 150), LSC_ETIMEOUT);
    sleep_ms(80); /* longer than the frame gap: the torn frame is dropped */
    assert_int_equal(lsc_client_get_battery(&client, &mv, 150), LSC_EREPLY);
    assert_int_equal(mv, 0xBEEF);
    sleep_ms(80);
    assert_int_equal(lsc_client_get_battery(&client, &mv, 2000), 0);
    assert_int_equal(mv, 7400);
    assert_int_equal(wait_peer(), 0);
}

static const uint8_t UNLOAD_1_6[] = {0x55, 0x55, 0x09, 0x14, 0x06, 1, 2, 3, 4, 5, 6};
static const uint8_t MOVE_1[] = {0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xDC, 0x05};
#define TORN 4u /* bytes of the unload that reach the line before it stalls */

/* In the child: the torn unload's first bytes, then a silence longer than
 * the controller's frame gap, then the move whole. Exit code: what failed. */
static void torn_then_move(void)
{
    uint8_t got[sizeof MOVE_1];
    if (!peer_read(got, TORN) || memcmp(got, UNLOAD_1_6, TORN) != 0) {
        _exit(3);
    }
    uint32_t torn_at = now_ms();
    if (!peer_read(got, 1)) {
        _exit(4);
    }
    uint32_t quiet = now_ms() - torn_at;
    if (!peer_read(got + 1, sizeof got - 1u) || memcmp(got, MOVE_1, sizeof got) != 0) {
        _exit(5);
    }
    _exit(quiet > LSC_SIM_FRAME_GAP_MS ? 0 : 6);
}

/* The line stalls 4 bytes into an 11-byte frame: the write gives up with
 * LSC_EIO, says how many bytes went out, and keeps the line silent longer
 * than a controller's frame gap before it returns, so the next frame (a
 * move) is not read as the rest of the torn one. */
static void torn_write_is_reported_and_not_glued_to_the_next(void **state)
{
    (void)state;
    start_peer(torn_then_move);
    port->write_timeout_ms = 0; /* white box (serial_internal.h): give up after the bytes' own time (11 ms) */
    stall_after = TORN;
    const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    assert_int_equal(lsc_client_unload(&client, ids, sizeof ids), LSC_EIO);
    stall_after = -1;
    const char *m = lsc_serial_error_message(port);
    assert_non_null(strstr(m, "timed out"));
    assert_non_null(strstr(m, "4 of 11 bytes went out"));
    assert_int_equal(lsc_client_move_one(&client, 1, 1500, 1000), 0);
    assert_int_equal(wait_peer(), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(eintr_on_every_call, setup, teardown),
        cmocka_unit_test_setup_teardown(short_writes_send_the_whole_frame, setup, teardown),
        cmocka_unit_test_setup_teardown(device_disappears_mid_reply, setup, teardown),
        cmocka_unit_test_setup_teardown(silent_port_times_out, setup, teardown),
        cmocka_unit_test_setup_teardown(slow_peer_late_reply_not_taken, setup, teardown),
        cmocka_unit_test_setup_teardown(notification_storm_over_a_pty, setup, teardown),
        cmocka_unit_test_setup_teardown(two_processes_one_port, setup, teardown),
        cmocka_unit_test_setup_teardown(open_out_of_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(truncated_and_corrupted_replies, setup, teardown),
        cmocka_unit_test_setup_teardown(torn_write_is_reported_and_not_glued_to_the_next, setup,
                                        teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
