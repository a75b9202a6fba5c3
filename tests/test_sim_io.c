/* Tests of the lsc_io adapter over the model: virtual time as the client waits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <limits.h>
#include <string.h>

#include "sim_util.h"

static lsc_sim sim;
static lsc_sim_groups groups;
static lsc_io io;

static const uint8_t battery_req[] = {0x55, 0x55, 0x02, 0x0F};
static const uint8_t battery_rep[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};

static int setup(void **state)
{
    (void)state;
    assert_int_equal(lsc_sim_init(&sim), 0);
    assert_int_equal(lsc_sim_io_init(&sim, &io), 0);
    return 0;
}

static void test_battery_answers_at_once(void **state)
{
    (void)state;
    uint8_t buf[16];
    assert_int_equal(io.write(io.ctx, battery_req, sizeof battery_req), 4);
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 1000), 6);
    assert_memory_equal(buf, battery_rep, 6);
    assert_int_equal(io.now_ms(io.ctx), 0);
    /* polling with nothing there returns 0 and leaves the clock alone */
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 0), 0);
    assert_int_equal(lsc_sim_now_us(&sim), 0);
}

static void test_timeout_advances_clock(void **state)
{
    (void)state;
    uint8_t buf[16];
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 250), 0);
    assert_int_equal(io.now_ms(io.ctx), 250);
    assert_int_equal(lsc_sim_now_us(&sim), 250000);
}

static void test_read_returns_when_bytes_appear(void **state)
{
    (void)state;
    uint8_t buf[16];
    sim_util_load(&sim, &groups, "group 3\nstep 500 1:2000\n");
    assert_int_equal(lsc_sim_group_run(&sim, 3, 1), 0);
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 1000), 7); /* started */
    assert_int_equal(buf[3], LSC_CMD_GROUP_RUN);
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 1000), 7); /* complete at 500 ms */
    assert_int_equal(buf[3], LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(io.now_ms(io.ctx), 500);
    assert_int_equal(lsc_sim_position(&sim, 1), 2000);
}

static void test_delay_longer_than_timeout(void **state)
{
    (void)state;
    uint8_t buf[16];
    lsc_sim_fault_delay(&sim, 300);
    assert_int_equal(io.write(io.ctx, battery_req, sizeof battery_req), 4);
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 100), 0);
    assert_int_equal(io.now_ms(io.ctx), 100);
    assert_int_equal(io.read(io.ctx, buf, sizeof buf, 1000), 6);
    assert_int_equal(io.now_ms(io.ctx), 300);
}

static void test_wire_time(void **state)
{
    (void)state;
    uint8_t buf[16];
    size_t got = 0;
    lsc_sim_set_baud(&sim, 9600);
    assert_int_equal(io.write(io.ctx, battery_req, sizeof battery_req), 4);
    assert_int_equal(lsc_sim_now_us(&sim), 4 * 1042); /* the request crossed the line */
    while (got < 6) {
        int n = io.read(io.ctx, buf + got, sizeof buf - got, 100);
        assert_int_equal(n, 1); /* bytes trickle in, one byte time apart */
        got += (size_t)n;
    }
    assert_memory_equal(buf, battery_rep, 6);
    assert_int_equal(lsc_sim_now_us(&sim), 4 * 1042 + 6250);
    assert_int_equal(io.now_ms(io.ctx), 10);
}

static void test_small_buffer_and_bad_arguments(void **state)
{
    (void)state;
    uint8_t buf[2];
    assert_int_equal(io.write(io.ctx, battery_req, sizeof battery_req), 4);
    assert_int_equal(io.read(io.ctx, buf, 2, 10), 2);
    assert_int_equal(io.read(io.ctx, buf, 2, 10), 2);
    assert_int_equal(io.read(io.ctx, buf, 2, 10), 2);
    assert_memory_equal(buf, "\x4C\x1D", 2);
    assert_int_equal(io.read(io.ctx, NULL, 2, 10), LSC_EINVAL);
    assert_int_equal(io.read(io.ctx, buf, 0, 10), LSC_EINVAL);
    assert_int_equal(io.write(io.ctx, NULL, 1), LSC_EINVAL);
    assert_int_equal(io.write(io.ctx, NULL, 0), 0);
    /* counts an int cannot return are refused (write) or capped (read) */
    assert_int_equal(io.write(io.ctx, battery_req, (size_t)INT_MAX + 1u), LSC_EINVAL);
    assert_int_equal(io.write(io.ctx, battery_req, sizeof battery_req), 4);
    uint8_t big[8];
    assert_int_equal(io.read(io.ctx, big, SIZE_MAX, 10), 6); /* only 6 bytes are there */
    assert_int_equal(lsc_sim_io_init(NULL, &io), LSC_EINVAL);
    assert_int_equal(lsc_sim_io_init(&sim, NULL), LSC_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_battery_answers_at_once, setup),
        cmocka_unit_test_setup(test_timeout_advances_clock, setup),
        cmocka_unit_test_setup(test_read_returns_when_bytes_appear, setup),
        cmocka_unit_test_setup(test_delay_longer_than_timeout, setup),
        cmocka_unit_test_setup(test_wire_time, setup),
        cmocka_unit_test_setup(test_small_buffer_and_bad_arguments, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
