/* A program built with another LSC_CLIENT_RX_MAX than the library (this
 * file: 40, tests/CMakeLists.txt) is refused by lsc_client_init, not
 * corrupted: LSC_EINVAL, nothing written past the client's io (the bytes
 * after it keep a pattern), and every later call refuses the client. The
 * size given must be the library's too. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <string.h>

#include "lsc/client.h"

#if LSC_CLIENT_RX_MAX != 40
#error "this test is built with LSC_CLIENT_RX_MAX 40 (tests/CMakeLists.txt)"
#endif

static int no_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    (void)data;
    return (int)n;
}

static int no_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)buf;
    (void)cap;
    (void)timeout_ms;
    return 0;
}

static uint32_t no_time(void *ctx)
{
    (void)ctx;
    return 0;
}

static void other_rx_max_refused(void **state)
{
    (void)state;
    const lsc_io io = {NULL, no_write, no_read, no_time};
    /* the client with room after it: the library's is larger */
    struct {
        lsc_client c;
        uint8_t after[512];
    } room;
    const lsc_servo s = {1, 1500};
    uint16_t mv = 0;
    memset(&room, 0xa5, sizeof room);
    assert_int_equal(lsc_client_init(&room.c, &io), LSC_EINVAL);
    assert_null(room.c.io.write);
    assert_null(room.c.io.read);
    assert_null(room.c.io.now_ms);
    for (size_t i = sizeof room.c.io; i < sizeof room; i++) {
        assert_int_equal(((const uint8_t *)&room)[i], 0xa5);
    }
    assert_int_equal(lsc_client_move(&room.c, 100, &s, 1), LSC_EINVAL);
    assert_int_equal(lsc_client_get_battery(&room.c, &mv, 10), LSC_EINVAL);
}

/* The right RX max but another size: refused as well. */
static void other_size_refused(void **state)
{
    (void)state;
    const lsc_io io = {NULL, no_write, no_read, no_time};
    lsc_client c;
    memset(&c, 0, sizeof c);
    assert_int_equal(lsc_client_init_checked(&c, &io, sizeof c, (size_t)LSC_FRAME_MAX),
                     LSC_EINVAL);
    assert_int_equal(lsc_client_init_checked(NULL, &io, sizeof c, 40), LSC_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(other_rx_max_refused),
        cmocka_unit_test(other_size_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
