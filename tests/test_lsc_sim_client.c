/* lsc-sim end to end with the project's own client and serial transport:
 * starts lsc-sim (path in argv[1]) on a pseudo-terminal, talks to it in real
 * time, stops it with SIGTERM. _POSIX_C_SOURCE comes from tests/CMakeLists.txt. */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/lsc.h"
#include "sim_pty.h"
#include "test_time.h"

static const char *lsc_sim_path;

typedef struct running_sim {
    pid_t pid;
    char tty[256];
    lsc_serial *port;
    lsc_io io;
    lsc_client client;
} running_sim;

/* Starts lsc-sim with extra arguments (NULL-terminated) and opens its pty. */
static void start(running_sim *r, const char *const *extra)
{
    sim_pty_start(lsc_sim_path, extra, &r->pid, r->tty, sizeof r->tty);
    r->port = NULL;
    if (lsc_serial_open(r->tty, 9600, LSC_SERIAL_AUTO, &r->port) != 0) {
        fail_msg("open %s: %s", r->tty, lsc_serial_error_message(r->port));
    }
    lsc_serial_get_io(r->port, &r->io);
    assert_int_equal(lsc_client_init(&r->client, &r->io), 0);
}

/* SIGTERM: lsc-sim must exit 0. */
static void stop(running_sim *r)
{
    lsc_serial_close(r->port);
    sim_pty_stop(&r->pid);
}

static void test_battery_and_positions(void **state)
{
    (void)state;
    running_sim r;
    uint16_t mv = 0;
    uint8_t ids[32];
    lsc_servo out[32];
    const char *const args[] = {"--battery", "7321", NULL};
    start(&r, args);
    assert_int_equal(lsc_client_get_battery(&r.client, &mv, (uint32_t)test_ms(1000)), 0);
    assert_int_equal(mv, 7321);
    for (unsigned i = 0; i < 32; i++) {
        ids[i] = (uint8_t)i;
    }
    assert_int_equal(lsc_client_move_one(&r.client, 5, 2000, 100), 0);
    uint32_t t0 = r.io.now_ms(r.io.ctx);
    assert_int_equal(lsc_client_read_positions(&r.client, ids, 32, out, (uint32_t)test_ms(2000)), 32);
    /* 37 bytes out, 101 back at 9600 baud: at least 101 byte times */
    assert_true(r.io.now_ms(r.io.ctx) - t0 >= 105);
    const struct timespec wait = {0, 150000000L};
    (void)nanosleep(&wait, NULL);
    assert_int_equal(lsc_client_read_positions(&r.client, ids + 5, 1, out, (uint32_t)test_ms(1000)), 1);
    assert_int_equal(out[0].position, 2000);
    stop(&r);
}

static void test_drop_reply_times_out(void **state)
{
    (void)state;
    running_sim r;
    uint16_t mv = 0;
    const char *const args[] = {"--fast", "--drop-replies", "1", NULL};
    start(&r, args);
    assert_int_equal(lsc_client_get_battery(&r.client, &mv, 200), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_get_battery(&r.client, &mv, (uint32_t)test_ms(1000)), 0);
    assert_int_equal(mv, 7500);
    stop(&r);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_battery_and_positions),
        cmocka_unit_test(test_drop_reply_times_out),
    };
    if (argc < 2) {
        (void)fprintf(stderr, "usage: %s PATH/TO/lsc-sim\n", argv[0]);
        return 2;
    }
    lsc_sim_path = argv[1];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
