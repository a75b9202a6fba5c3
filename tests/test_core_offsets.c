/* The xArm's servo offset commands (23 read, 24 adjust) in the core: exact
 * bytes, round trips, negative offsets, every error path. Evidence for the
 * frames is thin (two public projects; docs/protocol.md "Beyond the vendor
 * document"): these vectors are the project's reading of it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "lsc/core.h"

static lsc_frame frame_of(const uint8_t *buf, int len)
{
    lsc_frame f = {buf[3], (uint8_t)(len - 4), &buf[4]};
    return f;
}

static void test_offset_request(void **state)
{
    (void)state;
    static const uint8_t want[] = {0x55, 0x55, 0x09, 0x17, 0x06, 1, 2, 3, 4, 5, 6};
    const uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    uint8_t buf[32], back[8];
    memset(buf, 0xA5, sizeof buf);
    assert_int_equal(lsc_encode_offset_request(buf, sizeof buf, ids, 6), (int)sizeof want);
    assert_memory_equal(buf, want, sizeof want);
    assert_int_equal(buf[sizeof want], 0xA5);
    lsc_frame f = frame_of(buf, (int)sizeof want);
    assert_int_equal(lsc_decode_offset_request(&f, back, sizeof back), 6);
    assert_memory_equal(back, ids, 6);
    /* refused: no ids, too many, a repeated id, a short buffer, NULLs */
    uint8_t many[LSC_OFFSET_MAX + 1];
    for (size_t i = 0; i < sizeof many; i++) {
        many[i] = (uint8_t)i;
    }
    assert_int_equal(lsc_encode_offset_request(buf, sizeof buf, ids, 0), LSC_EINVAL);
    assert_int_equal(lsc_encode_offset_request(buf, 64, many, LSC_OFFSET_MAX + 1), LSC_EINVAL);
    assert_int_equal(lsc_encode_offset_request(NULL, 0, ids, 1), LSC_ENOSPC);
    const uint8_t twice[2] = {3, 3};
    assert_int_equal(lsc_encode_offset_request(buf, sizeof buf, twice, 2), LSC_EINVAL);
    assert_int_equal(lsc_encode_offset_request(buf, 10, ids, 6), LSC_ENOSPC);
    assert_int_equal(lsc_encode_offset_request(buf, sizeof buf, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_decode_offset_request(&f, back, 5), LSC_ENOSPC);
    assert_int_equal(lsc_decode_offset_request(&f, NULL, 6), LSC_EINVAL);
    assert_int_equal(lsc_decode_offset_request(NULL, back, 6), LSC_EINVAL);
    /* a position request is not an offset request */
    assert_int_equal(lsc_encode_pos_request(buf, sizeof buf, ids, 6), (int)sizeof want);
    f = frame_of(buf, (int)sizeof want);
    assert_int_equal(lsc_decode_offset_request(&f, back, sizeof back), LSC_EFRAME);
}

static void test_offset_reply(void **state)
{
    (void)state;
    /* servo 1 at +5, servo 6 at -3 (0xFD), servo 2 at -128, servo 3 at 127 */
    static const uint8_t want[] = {0x55, 0x55, 0x0B, 0x17, 0x04, 1, 0x05, 6, 0xFD,
                                   2,    0x80, 3,    0x7F};
    const lsc_servo_offset s[4] = {{1, 5}, {6, -3}, {2, -128}, {3, 127}};
    lsc_servo_offset back[4];
    uint8_t buf[32];
    memset(buf, 0xA5, sizeof buf);
    assert_int_equal(lsc_encode_offset_reply(buf, sizeof buf, s, 4), (int)sizeof want);
    assert_memory_equal(buf, want, sizeof want);
    assert_int_equal(buf[sizeof want], 0xA5);
    lsc_frame f = frame_of(buf, (int)sizeof want);
    memset(back, 0, sizeof back);
    assert_int_equal(lsc_decode_offset_reply(&f, back, 4), 4);
    for (size_t i = 0; i < 4; i++) {
        assert_int_equal(back[i].id, s[i].id);
        assert_int_equal(back[i].offset, s[i].offset);
    }
    assert_int_equal(lsc_decode_offset_reply(&f, back, 3), LSC_ENOSPC);
    assert_int_equal(lsc_decode_offset_reply(&f, NULL, 4), LSC_EINVAL);
    const lsc_servo_offset twice[2] = {{1, 0}, {1, 1}};
    assert_int_equal(lsc_encode_offset_reply(buf, sizeof buf, twice, 2), LSC_EINVAL);
    assert_int_equal(lsc_encode_offset_reply(buf, sizeof buf, s, 0), LSC_EINVAL);
    /* a reply whose length contradicts its count, or repeats an id */
    uint8_t bad[] = {0x55, 0x55, 0x06, 0x17, 0x02, 1, 0x05, 6};
    f = frame_of(bad, (int)sizeof bad);
    assert_int_equal(lsc_decode_offset_reply(&f, back, 4), LSC_EFRAME);
    uint8_t rep[] = {0x55, 0x55, 0x07, 0x17, 0x02, 1, 0x05, 1, 0x00};
    f = frame_of(rep, (int)sizeof rep);
    assert_int_equal(lsc_decode_offset_reply(&f, back, 4), LSC_EFRAME);
    uint8_t none[] = {0x55, 0x55, 0x03, 0x17, 0x00};
    f = frame_of(none, (int)sizeof none);
    assert_int_equal(lsc_decode_offset_reply(&f, back, 4), LSC_EFRAME);
}

static void test_offset_adjust(void **state)
{
    (void)state;
    static const uint8_t want[] = {0x55, 0x55, 0x04, 0x18, 0x03, 0xF6};
    uint8_t buf[8], id = 0;
    int8_t off = 0;
    memset(buf, 0xA5, sizeof buf);
    assert_int_equal(lsc_encode_offset_adjust(buf, sizeof buf, 3, -10), 6);
    assert_memory_equal(buf, want, sizeof want);
    assert_int_equal(buf[6], 0xA5);
    lsc_frame f = frame_of(buf, 6);
    assert_int_equal(lsc_decode_offset_adjust(&f, &id, &off), 0);
    assert_int_equal(id, 3);
    assert_int_equal(off, -10);
    assert_int_equal(lsc_encode_offset_adjust(buf, 5, 3, 1), LSC_ENOSPC);
    assert_int_equal(lsc_encode_offset_adjust(NULL, 6, 3, 1), LSC_EINVAL);
    assert_int_equal(lsc_decode_offset_adjust(&f, NULL, &off), LSC_EINVAL);
    assert_int_equal(lsc_decode_offset_adjust(&f, &id, NULL), LSC_EINVAL);
    assert_int_equal(lsc_decode_offset_adjust(NULL, &id, &off), LSC_EINVAL);
    /* the int16 reading of one project (LEN 5) is not this frame; nor is 23 */
    uint8_t wide[] = {0x55, 0x55, 0x05, 0x18, 0x03, 0xF6, 0xFF};
    f = frame_of(wide, (int)sizeof wide);
    id = 9;
    assert_int_equal(lsc_decode_offset_adjust(&f, &id, &off), LSC_EFRAME);
    assert_int_equal(id, 9);
    buf[3] = LSC_CMD_OFFSET_READ;
    f = frame_of(buf, 6);
    assert_int_equal(lsc_decode_offset_adjust(&f, &id, &off), LSC_EFRAME);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offset_request),
        cmocka_unit_test(test_offset_reply),
        cmocka_unit_test(test_offset_adjust),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
