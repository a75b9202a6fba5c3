/* The rule LSC::readPositions splits a read by (src/LSCReadSplit.h), on the
 * host: for every buffer size, not only the Uno's (the arduino_readsplit test
 * runs it there). Every request it forms must be one the core encodes and one
 * whose reply the client's buffer holds; together they cover the list. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "LSCReadSplit.h"
#include "lsc/core.h"

static void test_per_follows_the_buffer(void **state)
{
    (void)state;
    assert_int_equal(lsc_read_per(LSC_FRAME_MAX), LSC_READ_MAX); /* the default buffer: 84 */
    assert_int_equal(lsc_read_per(32), 9);                       /* AVR's */
    assert_int_equal(lsc_read_per(3u * 9u + 5u - 1u), 8);
    assert_int_equal(lsc_read_per(8), 1);
    assert_int_equal(lsc_read_per(7), 0); /* the smallest buffer the client allows */
    assert_int_equal(lsc_read_per(0), 0);
}

/* 166 servos at 84 per request: 84 then 82 would be next, which cannot be
 * sent; 81 and 1 instead. */
static void test_never_82(void **state)
{
    (void)state;
    assert_int_equal(lsc_read_chunk(166, 84), 84);
    assert_int_equal(lsc_read_chunk(82, 84), 81);
    assert_int_equal(lsc_read_chunk(1, 84), 1);
    assert_int_equal(lsc_read_chunk(83, 84), 83);
    assert_int_equal(lsc_read_chunk(82, 82), 81);
    assert_int_equal(lsc_read_chunk(0, 84), 0);
    assert_int_equal(lsc_read_chunk(20, 0), 0); /* no room: the client refuses n = 0 */
}

/* Splits count servos for a buffer of rx bytes as readPositions does, checking
 * every request: 1..per ids, encodable, its reply no longer than rx. */
static void split_and_check(size_t rx, uint8_t count, const uint8_t *ids)
{
    uint8_t per = lsc_read_per(rx);
    uint8_t frame[LSC_FRAME_MAX];
    lsc_servo servos[LSC_READ_MAX];
    unsigned done = 0;
    while (done < count) {
        uint8_t n = lsc_read_chunk((uint8_t)(count - done), per);
        assert_in_range(n, 1, per);
        assert_in_range(lsc_encode_pos_request(frame, sizeof frame, ids + done, n), 4,
                        LSC_FRAME_MAX);
        for (uint8_t i = 0; i < n; i++) {
            servos[i].id = ids[done + i];
            servos[i].position = 1500;
        }
        assert_in_range(lsc_encode_pos_reply(frame, sizeof frame, servos, n), 4, rx);
        done += n;
    }
    assert_int_equal(done, count);
}

static void test_every_count_every_buffer(void **state)
{
    (void)state;
    uint8_t ids[255];
    for (unsigned i = 0; i < sizeof ids; i++)
        ids[i] = (uint8_t)i;
    for (unsigned count = 1; count <= 255; count++) {
        /* the smallest buffer for each number of servos per request, and the default */
        for (size_t per = 1; per <= LSC_READ_MAX; per++)
            split_and_check(3u * per + 5u, (uint8_t)count, ids);
        split_and_check(LSC_FRAME_MAX, (uint8_t)count, ids);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_per_follows_the_buffer),
        cmocka_unit_test(test_never_82),
        cmocka_unit_test(test_every_count_every_buffer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
