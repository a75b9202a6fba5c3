/* The bus-servo codec (include/lsc/lx.h) against a bus it did not write: the
 * stand-in bus of tests/lxbus/lxbus_peer.py, written from the vendor's
 * document alone, on a pseudo-terminal at 115200 baud. A scan finds exactly
 * its servos; a move and the readings come back as sent; answers of several
 * servos that collide, and a reply with a flipped bit, are never believed;
 * a bus that echoes reads the same.
 *
 *   test_lx_peer PYTHON lxbus_peer.py
 *
 * Waits scale with LSC_TEST_TIME_SCALE (test_time.h). */
#include <fcntl.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include <cmocka.h>

#include "lsc/lx.h"
#include "lx_peer_harness.h"
#include "test_time.h"

static const char *python, *script;

/* The peer with this test's python and script, and the test's end of its
 * bus, raw at 115200 baud. */
typedef struct peer {
    lx_peer lx;
    int fd; /* the bus */
} peer;

static void peer_start(peer *p, const char *ids, bool echo)
{
    lx_peer_start(&p->lx, python, script, ids, echo);
    p->fd = open(p->lx.link, O_RDWR | O_NOCTTY);
    assert_true(p->fd >= 0);
    struct termios tio;
    assert_int_equal(tcgetattr(p->fd, &tio), 0);
    cfmakeraw(&tio);
    cfsetispeed(&tio, B115200);
    cfsetospeed(&tio, B115200);
    assert_int_equal(tcsetattr(p->fd, TCSANOW, &tio), 0);
}

static void peer_stop(peer *p)
{
    close(p->fd);
    lx_peer_stop(&p->lx);
}

/* Sends frame[0..n) (an encoder's result), after dropping what came before. */
static void send_frame(peer *p, lsc_lx_parser *ps, const uint8_t *frame, int n)
{
    assert_true(n > 0);
    assert_int_equal(tcflush(p->fd, TCIFLUSH), 0);
    lsc_lx_parser_reset(ps);
    assert_int_equal(write(p->fd, frame, (size_t)n), n);
    if (p->lx.echo) {
        assert_int_equal(lsc_lx_parser_expect_echo(ps, frame, (size_t)n), 0);
    }
}

/* Reads until `want` bytes came or a reply to cmd from id completes (then
 * true), or until ms pass. *bytes counts what came. */
static bool await(peer *p, lsc_lx_parser *ps, uint8_t id, uint8_t cmd, size_t want, long ms,
                  lsc_lx_frame *f, size_t *bytes)
{
    long end = lx_peer_now_ms() + ms;
    *bytes = 0;
    while (*bytes < want) {
        long left = end - lx_peer_now_ms();
        if (left <= 0) {
            return false;
        }
        struct pollfd pfd = {p->fd, POLLIN, 0};
        if (poll(&pfd, 1, (int)left) != 1) {
            return false;
        }
        uint8_t buf[64];
        ssize_t r = read(p->fd, buf, sizeof buf);
        assert_true(r > 0);
        for (ssize_t i = 0; i < r; i++) {
            (*bytes)++;
            if (lsc_lx_parser_feed(ps, buf[i], f) == 1 && f->reply && f->cmd == cmd &&
                f->id == id) {
                return true;
            }
        }
    }
    return false;
}

static bool ask(peer *p, lsc_lx_parser *ps, uint8_t id, uint8_t cmd, long ms, lsc_lx_frame *f)
{
    uint8_t frame[LSC_LX_FRAME_MAX];
    size_t bytes;
    send_frame(p, ps, frame, lsc_lx_encode_request(frame, sizeof frame, id, cmd));
    return await(p, ps, id, cmd, SIZE_MAX, ms, f, &bytes);
}

static int16_t position(peer *p, lsc_lx_parser *ps, uint8_t id)
{
    lsc_lx_frame f;
    int16_t pos = -999;
    assert_true(ask(p, ps, id, LSC_LX_POS_READ, test_ms(10000), &f));
    assert_int_equal(lsc_lx_decode_position(&f, &pos), 0);
    return pos;
}

static void test_scan_move_read(void **state)
{
    (void)state;
    peer p;
    lsc_lx_parser ps;
    lsc_lx_frame f;
    peer_start(&p, "1-3", false);
    assert_int_equal(lsc_lx_parser_init(&ps), 0);
    /* ids 0..5: exactly 1, 2, 3 answer, each with its id */
    unsigned found = 0;
    for (uint8_t id = 0; id <= 5; id++) {
        uint8_t got = 0;
        if (ask(&p, &ps, id, LSC_LX_ID_READ, test_ms(1000), &f)) {
            assert_int_equal(lsc_lx_decode_id(&f, &got), 0);
            assert_int_equal(got, id);
            found |= 1u << id;
        }
    }
    assert_int_equal(found, 0x0Eu);
    /* a move at once, then where it is */
    uint8_t frame[LSC_LX_FRAME_MAX];
    send_frame(&p, &ps, frame,
               lsc_lx_encode_move_time(frame, sizeof frame, 2, LSC_LX_MOVE_TIME_WRITE, 700, 0));
    long end = lx_peer_now_ms() + test_ms(10000);
    while (position(&p, &ps, 2) != 700 && lx_peer_now_ms() < end) {
    }
    assert_int_equal(position(&p, &ps, 2), 700);
    assert_int_equal(position(&p, &ps, 1), 500);
    uint16_t mv = 0;
    assert_true(ask(&p, &ps, 3, LSC_LX_VIN_READ, test_ms(10000), &f));
    assert_int_equal(lsc_lx_decode_vin(&f, &mv), 0);
    assert_int_equal(mv, 7400);
    uint16_t lo = 0, hi = 0;
    assert_true(ask(&p, &ps, 3, LSC_LX_ANGLE_LIMIT_READ, test_ms(10000), &f));
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &lo, &hi), 0);
    assert_int_equal(hi, 1000);
    assert_int_equal(ps.bad_checksums, 0);
    peer_stop(&p);
}

/* ID_READ to 254 with three servos: their answers collide; whatever came,
 * no frame is believed. */
static void test_collision_never_believed(void **state)
{
    (void)state;
    peer p;
    lsc_lx_parser ps;
    lsc_lx_frame f;
    peer_start(&p, "1-3", false);
    assert_int_equal(lsc_lx_parser_init(&ps), 0);
    uint8_t frame[LSC_LX_FRAME_MAX];
    size_t bytes = 0;
    send_frame(&p, &ps, frame,
               lsc_lx_encode_request(frame, sizeof frame, LSC_LX_BROADCAST, LSC_LX_ID_READ));
    /* one answer's worth of bytes (7) arrives, ANDed: no frame */
    assert_false(await(&p, &ps, 1, LSC_LX_ID_READ, 7, test_ms(10000), &f, &bytes));
    assert_int_equal(bytes, 7);
    assert_int_equal(ps.frames, 0);
    assert_int_equal(ps.bad_checksums, 1);
    peer_stop(&p);
}

/* A reply with a flipped bit is never believed; the next one is. */
static void test_flipped_bit_never_believed(void **state)
{
    (void)state;
    peer p;
    lsc_lx_parser ps;
    lsc_lx_frame f;
    peer_start(&p, "1", false);
    assert_int_equal(lsc_lx_parser_init(&ps), 0);
    lx_peer_control(&p.lx, "flip");
    uint8_t frame[LSC_LX_FRAME_MAX];
    size_t bytes = 0;
    send_frame(&p, &ps, frame, lsc_lx_encode_request(frame, sizeof frame, 1, LSC_LX_POS_READ));
    assert_false(await(&p, &ps, 1, LSC_LX_POS_READ, 8, test_ms(10000), &f, &bytes));
    assert_int_equal(bytes, 8);
    assert_int_equal(ps.frames, 0);
    assert_int_equal(ps.bad_checksums, 1);
    assert_int_equal(position(&p, &ps, 1), 500);
    peer_stop(&p);
}

/* A bus that echoes: the echo is dropped, the readings are the same. */
static void test_echo_reads_the_same(void **state)
{
    (void)state;
    peer p;
    lsc_lx_parser ps;
    peer_start(&p, "4", true);
    assert_int_equal(lsc_lx_parser_init(&ps), 0);
    assert_int_equal(position(&p, &ps, 4), 500);
    assert_int_equal(ps.echoes, 1);
    uint8_t frame[LSC_LX_FRAME_MAX];
    send_frame(&p, &ps, frame,
               lsc_lx_encode_move_time(frame, sizeof frame, 4, LSC_LX_MOVE_TIME_WRITE, 250, 0));
    long end = lx_peer_now_ms() + test_ms(10000);
    while (position(&p, &ps, 4) != 250 && lx_peer_now_ms() < end) {
    }
    assert_int_equal(position(&p, &ps, 4), 250);
    assert_int_equal(ps.bad_checksums, 0);
    peer_stop(&p);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_lx_peer PYTHON lxbus_peer.py\n");
        return 2;
    }
    python = argv[1];
    script = argv[2];
    (void)signal(SIGPIPE, SIG_IGN);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan_move_read),
        cmocka_unit_test(test_collision_never_believed),
        cmocka_unit_test(test_flipped_bit_never_believed),
        cmocka_unit_test(test_echo_reads_the_same),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
