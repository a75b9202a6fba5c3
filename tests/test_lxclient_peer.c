/* The bus client (include/lsc/lxclient.h) against a bus it did not write:
 * the stand-in bus of tests/lxbus/lxbus_peer.py, written from the vendor's
 * document alone, on a pseudo-terminal at 115200 baud, through the serial
 * transport (lsc/serial.h). A scan of 0..253 finds exactly its servos (the
 * time it took is printed); a flipped bit is never believed; a bus that
 * echoes reads the same; the id changes it refuses write nothing (the peer's
 * count of ID_WRITE frames proves it); a saved offset survives a power cycle
 * and an adjusted one does not; servos moved together arrive together.
 *
 *   test_lxclient_peer PYTHON lxbus_peer.py
 *
 * Waits scale with LSC_TEST_TIME_SCALE (test_time.h). */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/lxclient.h"
#include "lsc/serial.h"
#include "lx_peer_harness.h"
#include "test_time.h"

static const char *python, *script;

/* The peer with this test's python and script. */
static void peer_start(lx_peer *p, const char *ids, bool echo)
{
    lx_peer_start(p, python, script, ids, echo);
}

/* How many frames of command cmd the peer has received. */
static int count(const lx_peer *p, int cmd)
{
    char line[32], reply[64];
    snprintf(line, sizeof line, "count %d", cmd);
    lx_peer_control_reply(p, line, reply, sizeof reply);
    return (int)strtol(reply + 3, NULL, 10);
}

/* The client on the peer's bus (its own fd: the serial transport). */
typedef struct bus_link {
    lsc_serial *port;
    lsc_lxclient c;
} bus_link;

static void link_open(bus_link *l, const lx_peer *p)
{
    assert_int_equal(lsc_serial_open(p->link, 115200, LSC_SERIAL_TERMIOS, &l->port), 0);
    lsc_io io;
    lsc_serial_get_io(l->port, &io);
    assert_int_equal(lsc_lxclient_init(&l->c, &io), 0);
    lsc_lxclient_set_timeout(&l->c, (uint32_t)test_ms(1000));
}

static void link_close(bus_link *l)
{
    lsc_serial_close(l->port);
}

static void test_scan_whole_bus(void **state)
{
    (void)state;
    lx_peer p;
    bus_link l;
    lsc_lx_scan scan;
    peer_start(&p, "1,2,3,77,253", false);
    link_open(&l, &p);
    long start = lx_peer_now_ms();
    assert_int_equal(lsc_lxclient_scan(&l.c, NULL, 0, 0, &scan), 5);
    long took = lx_peer_now_ms() - start;
    print_message("a scan of 0..253 on the peer's pty at 115200 baud: %ld ms (per id %u ms)\n",
                  took, LSC_LXCLIENT_SCAN_TIMEOUT_MS);
    assert_true(took < test_ms(10000));
    for (unsigned id = 0; id <= 253; id++) {
        bool there = id == 1 || id == 2 || id == 3 || id == 77 || id == 253;
        assert_int_equal(lsc_lx_scan_found(&scan, (uint8_t)id), there);
    }
    link_close(&l);
    lx_peer_stop(&p);
}

static void test_flipped_bit_never_believed(void **state)
{
    (void)state;
    lx_peer p;
    bus_link l;
    peer_start(&p, "1", false);
    link_open(&l, &p);
    int16_t pos = 1234;
    lx_peer_control(&p, "flip");
    /* the whole bad reply comes within the wait; nothing is believed */
    assert_int_equal(lsc_lxclient_read_position(&l.c, 1, &pos), LSC_EREPLY);
    assert_int_equal(pos, 1234);
    assert_int_equal(l.c.parser.bad_checksums, 1);
    assert_int_equal(lsc_lxclient_read_position(&l.c, 1, &pos), 0);
    assert_int_equal(pos, 500);
    link_close(&l);
    lx_peer_stop(&p);
}

static void test_echo_reads_the_same(void **state)
{
    (void)state;
    lsc_lx_info info[2];
    for (int echo = 0; echo <= 1; echo++) {
        lx_peer p;
        bus_link l;
        peer_start(&p, "4", echo != 0);
        link_open(&l, &p);
        lsc_servo s = {4, 250};
        assert_int_equal(lsc_lxclient_move_together(&l.c, &s, 1, 0), 0);
        int16_t pos = 0;
        long end = lx_peer_now_ms() + test_ms(10000);
        while ((lsc_lxclient_read_position(&l.c, 4, &pos) != 0 || pos != 250) &&
               lx_peer_now_ms() < end) {
        }
        assert_int_equal(lsc_lxclient_info(&l.c, 4, &info[echo]), 0);
        assert_int_equal(l.c.parser.bad_checksums, 0);
        if (echo) {
            assert_true(l.c.parser.echoes + l.c.echoes > 0);
        }
        link_close(&l);
        lx_peer_stop(&p);
    }
    assert_int_equal(info[0].position, 250);
    assert_int_equal(info[1].position, 250);
    assert_true(info[0].vin_mv == info[1].vin_mv && info[0].temp_c == info[1].temp_c);
    assert_true(info[0].limit_max == info[1].limit_max && info[0].torque && info[1].torque);
    assert_true(info[0].led == info[1].led && info[0].alarms == info[1].alarms);
}

static void test_id_changes(void **state)
{
    (void)state;
    lx_peer p;
    bus_link l;
    lsc_lx_refusal why = LSC_LX_DONE;
    uint8_t old = 0;
    char dump[4096];
    peer_start(&p, "1-3", false);
    link_open(&l, &p);
    /* 3 answers: refused, no ID_WRITE on the wire */
    assert_int_equal(lsc_lxclient_change_id(&l.c, 1, 3, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_TAKEN);
    assert_int_equal(count(&p, LSC_LX_ID_WRITE), 0);
    /* one unknown servo with three on the bus: refused */
    assert_int_equal(lsc_lxclient_set_id_alone(&l.c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    assert_int_equal(count(&p, LSC_LX_ID_WRITE), 0);
    /* 2 -> 9 */
    assert_int_equal(lsc_lxclient_change_id(&l.c, 2, 9, &why), 0);
    assert_int_equal(count(&p, LSC_LX_ID_WRITE), 1);
    lx_peer_control_reply(&p, "dump", dump, sizeof dump);
    assert_non_null(strstr(dump, "\"id\": 9"));
    assert_null(strstr(dump, "\"id\": 2"));
    /* alone: renamed */
    lx_peer_control(&p, "remove 1");
    lx_peer_control(&p, "remove 3");
    assert_int_equal(lsc_lxclient_set_id_alone(&l.c, 7, 0, &old, &why), 0);
    assert_int_equal(old, 9);
    assert_int_equal(count(&p, LSC_LX_ID_WRITE), 2);
    assert_int_equal(lsc_lxclient_read_id(&l.c, 7), 0);
    link_close(&l);
    lx_peer_stop(&p);
}

static void test_offsets_and_power(void **state)
{
    (void)state;
    lx_peer p;
    bus_link l;
    int8_t off = 0;
    peer_start(&p, "1,3", false);
    link_open(&l, &p);
    assert_int_equal(lsc_lxclient_offset_change(&l.c, 1, 15, true, &off, NULL), 0);
    assert_int_equal(off, 15);
    assert_int_equal(lsc_lxclient_offset_change(&l.c, 3, -20, false, &off, NULL), 0);
    assert_int_equal(off, -20);
    lx_peer_control(&p, "power-cycle");
    assert_int_equal(lsc_lxclient_read_offset(&l.c, 1, &off), 0);
    assert_int_equal(off, 15);
    assert_int_equal(lsc_lxclient_read_offset(&l.c, 3, &off), 0);
    assert_int_equal(off, 0);
    link_close(&l);
    lx_peer_stop(&p);
}

static void test_move_together(void **state)
{
    (void)state;
    lx_peer p;
    bus_link l;
    peer_start(&p, "1-3", false);
    link_open(&l, &p);
    lsc_servo s[2] = {{2, 700}, {3, 250}};
    assert_int_equal(lsc_lxclient_move_together(&l.c, s, 2, 300), 0);
    int16_t pos[3] = {0, 0, 0};
    long end = lx_peer_now_ms() + test_ms(10000);
    do {
        for (uint8_t id = 1; id <= 3; id++) {
            assert_int_equal(lsc_lxclient_read_position(&l.c, id, &pos[id - 1]), 0);
        }
    } while ((pos[1] != 700 || pos[2] != 250) && lx_peer_now_ms() < end);
    assert_true(pos[0] == 500 && pos[1] == 700 && pos[2] == 250);
    assert_int_equal(count(&p, LSC_LX_MOVE_TIME_WAIT_WRITE), 2);
    assert_int_equal(count(&p, LSC_LX_MOVE_START), 1);
    link_close(&l);
    lx_peer_stop(&p);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_lxclient_peer PYTHON lxbus_peer.py\n");
        return 2;
    }
    python = argv[1];
    script = argv[2];
    (void)signal(SIGPIPE, SIG_IGN);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan_whole_bus),
        cmocka_unit_test(test_flipped_bit_never_believed),
        cmocka_unit_test(test_echo_reads_the_same),
        cmocka_unit_test(test_id_changes),
        cmocka_unit_test(test_offsets_and_power),
        cmocka_unit_test(test_move_together),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
