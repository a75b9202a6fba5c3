/* The device layer (src/device, lsc/device.h) through lscd, a daemon of the
 * test's own on a Unix socket: a busy port that lscd serves, the device's
 * timeout reaching it, no reply, refusals, the controller going away, a
 * program's own event loop. No wraps. */
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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
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
#include "lsc/lscd.h"
#include "test_hex.h"
#include "test_time.h"

/* A pseudo-terminal lscd_busy_port holds as the serial port lscd serves. */
static struct {
    int master;
    char path[128];
} P;


/* ---- lscd: a daemon of the test's own on a Unix socket --------------------------------- */

/* What the daemon does with the Nth controller frame it gets: sends
 * `before` (hex), a VERDICT with `verdict`, then `after` (hex), all in one
 * write. */
typedef struct lscd_step {
    const char *before;
    int verdict;
    const char *after;
} lscd_step;

typedef struct lscd_daemon {
    int listener, fd;
    char path[108];
    char name[120]; /* "lscd:PATH" */
    pthread_t thread;
    bool running;
    const lscd_step *script; /* the last step repeats */
    size_t nsteps;
    unsigned frames;     /* controller frames it got */
    uint32_t timeout_ms; /* the value of the last TIMEOUT it got */
    uint8_t version;     /* the protocol version its HELLO says (0: the right one) */
} lscd_daemon;

static lscd_daemon L;

/* (A device that closed at once, its answer still on the way, is not the
 * test's failure: an assertion in this thread would end the whole program.) */
static void lscd_send(const uint8_t *data, size_t n)
{
    ssize_t sent = send(L.fd, data, n, MSG_NOSIGNAL);
    assert_true(sent == (ssize_t)n || (sent < 0 && (errno == EPIPE || errno == ECONNRESET)));
}

static size_t lscd_event(uint8_t *out, uint8_t op, const uint8_t *args, size_t n)
{
    uint8_t params[8];
    params[0] = op;
    memcpy(params + 1, args, n);
    int len = lsc_encode_frame(out, LSC_FRAME_MAX, LSC_LSCD_CMD, params, n + 1u);
    assert_true(len > 0);
    return (size_t)len;
}

static void lscd_frame(const lsc_frame *f)
{
    uint8_t out[1024];
    size_t len = 0;
    if (f->cmd == LSC_LSCD_CMD) {
        if (f->nparams == 5 && f->params[0] == LSC_LSCD_OP_PING) {
            len = lscd_event(out, LSC_LSCD_EV_PONG, f->params + 1, 4);
            lscd_send(out, len);
        } else if (f->nparams == 5 && f->params[0] == LSC_LSCD_OP_TIMEOUT) {
            const uint8_t *a = f->params + 1;
            L.timeout_ms = (uint32_t)a[0] | (uint32_t)a[1] << 8 | (uint32_t)a[2] << 16 |
                           (uint32_t)a[3] << 24;
        }
        return;
    }
    const lscd_step *s = &L.script[L.frames < L.nsteps ? L.frames : L.nsteps - 1u];
    L.frames++;
    if (s->before != NULL) {
        len += test_hex(s->before, out, 256);
    }
    const uint8_t verdict[] = {f->cmd, (uint8_t)(int8_t)s->verdict};
    len += lscd_event(out + len, LSC_LSCD_EV_VERDICT, verdict, sizeof verdict);
    if (s->after != NULL) {
        len += test_hex(s->after, out + len, 256);
    }
    lscd_send(out, len);
}

static void *lscd_main(void *arg)
{
    (void)arg;
    struct pollfd p = {L.listener, POLLIN, 0};
    if (poll(&p, 1, (int)test_ms(5000)) != 1) {
        return NULL;
    }
    L.fd = accept(L.listener, NULL, NULL);
    if (L.fd < 0) {
        return NULL;
    }
    uint8_t out[16];
    const uint8_t hello[] = {L.version != 0u ? L.version : LSC_LSCD_PROTOCOL, 1};
    lscd_send(out, lscd_event(out, LSC_LSCD_EV_HELLO, hello, sizeof hello));
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser parser;
    (void)lsc_parser_init(&parser, buf, sizeof buf);
    for (;;) {
        uint8_t in[512];
        struct pollfd q = {L.fd, POLLIN, 0};
        if (poll(&q, 1, (int)test_ms(5000)) != 1) {
            return NULL;
        }
        ssize_t n = read(L.fd, in, sizeof in);
        if (n <= 0) {
            return NULL; /* the device closed */
        }
        const uint8_t *at = in;
        size_t left = (size_t)n;
        while (left > 0) {
            lsc_frame f;
            int res = 0;
            size_t used = lsc_parser_feed_buf(&parser, at, left, &f, &res);
            at += used;
            left -= used;
            if (res == 1) {
                lscd_frame(&f);
            }
        }
    }
}

/* Starts the daemon with script (steps); its name is L.name. */
static void lscd_start(const lscd_step *script, size_t nsteps)
{
    L.script = script;
    L.nsteps = nsteps;
    assert_int_equal(pthread_create(&L.thread, NULL, lscd_main, NULL), 0);
    L.running = true;
}

/* Waits for the daemon's end (the device closed). */
static void lscd_done(void)
{
    if (L.running) {
        assert_int_equal(pthread_join(L.thread, NULL), 0);
        L.running = false;
    }
}

static int lscd_setup(void **state)
{
    if (device_setup(state) != 0) {
        return -1;
    }
    memset(&L, 0, sizeof L);
    L.fd = -1;
    snprintf(L.path, sizeof L.path, "%s/d.sock", tmpdir);
    snprintf(L.name, sizeof L.name, "lscd:%s", L.path);
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", L.path);
    L.listener = socket(AF_UNIX, SOCK_STREAM, 0);
    if (L.listener < 0 || bind(L.listener, (struct sockaddr *)&addr, sizeof addr) != 0 ||
        listen(L.listener, 1) != 0) {
        return -1;
    }
    return 0;
}

static int lscd_teardown(void **state)
{
    lscd_done();
    if (L.fd >= 0) {
        (void)close(L.fd);
    }
    (void)close(L.listener);
    (void)unlink(L.path);
    return device_teardown(state);
}

/* Writes lscd's record for port (in $LSC_LSCD_DIR) by hand. */
static void write_record(const char *record, long pid, const char *port, const char *sock)
{
    FILE *f = fopen(record, "w");
    assert_non_null(f);
    (void)fprintf(f, "pid %ld\nport %s\nsocket %s\n", pid, port, sock);
    assert_int_equal(fclose(f), 0);
}

/* A busy serial port that lscd serves: through its socket in lscd's
 * directory, or through the one its record names wherever it is; a record
 * whose process is gone is ignored (busy, the port's own message); a socket
 * that is not lscd's makes it busy, naming lscd and the socket. */
static void lscd_busy_port(void **state)
{
    (void)state;
    static const lscd_step ok[] = {{NULL, 0, NULL}};
    char dir[128], record[256], sock[256], name[LSC_LSCD_NAME_MAX];
    int slave;
    memset(&P, 0, sizeof P);
    assert_int_equal(openpty(&P.master, &slave, P.path, NULL, NULL), 0);
    (void)close(slave);
    assert_true(lsc_lscd_name(P.path, name, sizeof name) > 0);
    snprintf(dir, sizeof dir, "%s/run", tmpdir);
    snprintf(record, sizeof record, "%s/%s" LSC_LSCD_RECORD_SUFFIX, dir, name);
    snprintf(sock, sizeof sock, "%s/%s.sock", dir, name);
    assert_int_equal(mkdir(dir, 0755), 0);
    assert_int_equal(setenv("LSC_LSCD_DIR", dir, 1), 0);
    test_options opt = {9600, (uint32_t)test_ms(2000), 0, 0};
    lsc_device *held = open_ok(P.path, &opt);

    /* no record, no socket: busy as it is (this process holds it: so it says) */
    lsc_device *e = open_fails(P.path, &opt, LSC_EBUSY);
    assert_int_equal(lsc_device_kind_of(e), LSC_DEVICE_SERIAL);
    assert_has(lsc_device_error(e), "port busy: this program has it open already");
    lsc_device_close(e);

    /* a record left by an lscd that is gone */
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        _exit(0);
    }
    assert_int_equal(waitpid(child, NULL, 0), child);
    write_record(record, (long)child, P.path, L.path);
    e = open_fails(P.path, &opt, LSC_EBUSY);
    assert_has(lsc_device_error(e), "port busy: this program has it open already");
    lsc_device_close(e);

    /* a live record whose socket answers, but not as lscd */
    write_record(record, (long)getpid(), P.path, L.path);
    L.version = 99;
    lscd_start(ok, 1);
    e = open_fails(P.path, &opt, LSC_EBUSY);
    lscd_done();
    (void)close(L.fd);
    assert_has(lsc_device_error(e), "port busy: lscd holds it");
    assert_has(lsc_device_error(e), L.path);
    lsc_device_close(e);

    /* ... and as lscd */
    L.version = 0;
    lscd_start(ok, 1);
    lsc_device *d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    assert_non_null(lsc_device_lscd(d));
    assert_null(lsc_device_lscd(held));
    assert_null(lsc_device_lscd(NULL));
    lsc_device_close(d);
    lscd_done();
    (void)close(L.fd);

    /* no record, the socket in lscd's directory */
    assert_int_equal(unlink(record), 0);
    assert_int_equal(symlink(L.path, sock), 0);
    lscd_start(ok, 1);
    d = open_ok(P.path, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    lsc_device_close(d);
    lscd_done();
    (void)close(L.fd);
    L.fd = -1;

    lsc_device_close(held);
    (void)unlink(sock);
    (void)rmdir(dir);
    (void)unsetenv("LSC_LSCD_DIR");
    (void)close(P.master);
}

/* The device's timeout reaches lscd: at the open and when it is set. */
static void lscd_timeout_set(void **state)
{
    (void)state;
    static const lscd_step battery[] = {{"55 55 04 0F 4C 1D", 0, NULL}};
    uint16_t mv = 0;
    lscd_start(battery, 1);
    const uint32_t later = (uint32_t)test_ms(5000) + 1u;
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_LSCD);
    lsc_device_set_timeout(d, later);
    assert_int_equal(lsc_device_timeout(d), later);
    assert_int_equal(lsc_device_battery(d, &mv), 0); /* after the TIMEOUT, in order */
    assert_int_equal(mv, 7500);
    lsc_device_close(d);
    lscd_done();
    assert_int_equal(L.frames, 1);
    assert_int_equal(L.timeout_ms, later);
}

/* No reply through lscd: the message speaks of lscd's port and baud rate,
 * not the device's own (it has none). */
static void lscd_no_reply(void **state)
{
    (void)state;
    static const lscd_step silent[] = {{NULL, LSC_ETIMEOUT, NULL}};
    uint16_t mv;
    lscd_start(silent, 1);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "no reply from the controller behind lscd:");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_LSCD_NO_REPLY);
    assert_has(lsc_device_error(d), "nothing arrived; check that it is powered and connected, "
                                    "and the port and baud rate lscd serves (its --port and "
                                    "--baud)");
    lsc_device_close(d);
    lscd_done();
}

/* lscd refuses frames (verdict -1, then -7): every call says so in lscd's
 * words, naming the frame. */
static void lscd_refusals(void **state)
{
    (void)state;
    static const lscd_step refuse[] = {{NULL, LSC_EINVAL, NULL}, {NULL, LSC_EINVAL, NULL},
                                       {NULL, LSC_EINVAL, NULL}, {NULL, LSC_EINVAL, NULL},
                                       {NULL, LSC_EIO, NULL}};
    uint16_t mv;
    uint8_t reply[4];
    const uint8_t id = 1, params[] = {1, 1, 0};
    lsc_servo_offset off;
    lscd_start(refuse, 5);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_stop(d), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending action_group_stop (command 7, 4 bytes): lscd at ");
    assert_has(lsc_device_error(d), ": command 7: invalid argument");
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending get_battery_voltage (command 15, 4 bytes): lscd at ");
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending servo_offset_read (command 23, 6 bytes): lscd at ");
    assert_int_equal(lsc_device_request(d, 0x30, NULL, 0, 0x31, reply, sizeof reply),
                     LSC_EINVAL);
    assert_has(lsc_device_error(d), "sending unknown (command 48, 4 bytes): lscd at ");
    assert_int_equal(lsc_device_send(d, 8, params, 3, true), LSC_EIO);
    assert_has(lsc_device_error(d), "sending action_group_complete (command 8, 7 bytes): lscd at ");
    assert_has(lsc_device_error(d), ": command 8: I/O error");
    lsc_device_close(d);
    lscd_done();
    assert_int_equal(L.frames, 5);
}

/* The controller goes away while servos settle: the wait between two reads
 * says so; later requests fail with lscd's word for it. */
static void lscd_controller_gone(void **state)
{
    (void)state;
    static const lscd_step gone[] = {
        {"55 55 06 15 01 01 DC 05", 0, "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"},
        {NULL, LSC_ENODEV, NULL}};
    const lsc_servo to = {1, 2000};
    const uint8_t id = 1;
    lsc_servo_offset off;
    lscd_start(gone, 2);
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_settle(d, &to, 1, 0, 10), LSC_ENODEV);
    assert_has(lsc_device_error(d), "the controller of lscd at ");
    assert_has(lsc_device_error(d), " went away: unplugged (lscd opens it again when it is back)");
    assert_int_equal(lsc_device_read_offsets(d, &id, 1, &off), LSC_ENODEV);
    assert_has(lsc_device_error(d), "sending servo_offset_read (command 23, 6 bytes): the "
                                    "controller of lscd at ");
    lsc_device_close(d);
    lscd_done();
}

/* The controller goes away just after a stop ended a wait (while the wait
 * looks for the same group's start at once): the wait says so. */
static void lscd_gone_after_stop(void **state)
{
    (void)state;
    static const lscd_step run[] = {
        {NULL, 0,
         "55 55 05 06 08 01 00 55 55 02 07 "
         "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"}};
    lsc_notification n;
    lscd_start(run, 1);
    const test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), LSC_ENODEV);
    assert_has(lsc_device_error(d), " went away: unplugged (lscd opens it again when it is back)");
    lsc_device_close(d);
    lscd_done();
}

/* ---- A program's own event loop: lsc_device_fileno, lsc_device_next_event_ms ---------- */

/* lscd: the socket; frames a request took off it, and the controller's
 * loss it heard of, make the deadline now. */
static void events_lscd(void **state)
{
    (void)state;
    static const lscd_step script[] = {
        /* a battery reply, then 8 stops: more than the request reads */
        {"55 55 04 0F 4C 1D 55 55 02 07 55 55 02 07 55 55 02 07 55 55 02 07 55 55 02 07 "
         "55 55 02 07 55 55 02 07 55 55 02 07",
         0, NULL},
        {NULL, 0, "55 55 0D CD 83 00 75 6E 70 6C 75 67 67 65 64"}};
    uint16_t mv = 0;
    lscd_start(script, 2);
    test_options opt = {0, (uint32_t)test_ms(5000), 0, 0};
    lsc_device *d = open_ok(L.name, &opt);
    assert_true(lsc_device_fileno(d) >= 0);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    /* the request read 32 bytes: the reply and 6 stops (taken from the
     * queue without a read); the rest stays in the transport */
    for (unsigned i = 0; i < 6u; i++) {
        assert_int_equal(lsc_device_notification(d, 0, NULL), 0);
    }
    assert_int_equal(lsc_device_next_event_ms(d), 0); /* the rest waits in the transport */
    assert_true(lsc_device_poll(d, 0) > 0);
    while (lsc_device_notification(d, 0, NULL) == 0) {
    }
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    /* a stop, answered with the controller's loss */
    assert_int_equal(lsc_device_stop(d), 0);
    assert_int_equal(lsc_device_next_event_ms(d), 0);
    assert_int_equal(lsc_device_poll(d, 0), LSC_ENODEV);
    lsc_device_close(d);
    lscd_done();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(events_lscd, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_timeout_set, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_busy_port, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_refusals, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_no_reply, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_controller_gone, lscd_setup, lscd_teardown),
        cmocka_unit_test_setup_teardown(lscd_gone_after_stop, lscd_setup, lscd_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
