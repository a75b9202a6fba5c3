/* Every example frame of the protocol document (docs/protocol.md and
 * tests/cli/frames.txt), both directions: each encodes to exactly these
 * bytes with its typed encoder, the parser yields it, and its typed decoder
 * gives back the values. The document's errata are named in the test names. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "core_util.h"
#include "lsc/core.h"

#define GUARD ((size_t)8) /* canary bytes each side of an output buffer */
#define CANARY 0xA5u

/* Checks that an encoder wrote exactly `expect` into the guarded buffer g
 * (GUARD canary bytes each side of a buffer of exactly the frame's size). */
static void check_encoded(int got, const uint8_t *g, const uint8_t *expect, size_t n)
{
    assert_int_equal(got, (int)n);
    assert_memory_equal(&g[GUARD], expect, n);
    for (size_t i = 0; i < GUARD; i++) {
        assert_int_equal(g[i], CANARY);
        assert_int_equal(g[GUARD + n + i], CANARY);
    }
}

/* Parses the bytes with a fresh parser: it must yield exactly this frame. */
static void parse(const uint8_t *bytes, size_t n, lsc_frame *f, uint8_t *buf)
{
    lsc_parser p;
    assert_int_equal(lsc_parser_init(&p, buf, LSC_FRAME_MAX), 0);
    parse_exactly(&p, bytes, n, f);
    assert_int_equal(p.frames, 1);
    assert_int_equal(p.discarded, 0);
    assert_int_equal(p.errors, 0);
}

/* Declares the guarded output buffer g and the frame's expected bytes. */
#define VECTOR(...)                                                                      \
    static const uint8_t v[] = {__VA_ARGS__};                                            \
    uint8_t g[sizeof v + 2 * GUARD];                                                     \
    memset(g, CANARY, sizeof g);                                                         \
    uint8_t pbuf[LSC_FRAME_MAX];                                                         \
    lsc_frame f;                                                                         \
    uint8_t *out = &g[GUARD];                                                            \
    (void)out

/* ---- Host -> controller ---- */

static void test_servo_move_1000ms_id1_to_2000(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xD0, 0x07);
    const lsc_servo s[] = {{1, 2000}};
    check_encoded(lsc_encode_servo_move(out, sizeof v, 1000, s, 1), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint16_t time = 0;
    lsc_servo d[4];
    assert_int_equal(lsc_decode_servo_move(&f, &time, d, 4), 1);
    assert_int_equal(time, 1000);
    assert_int_equal(d[0].id, 1);
    assert_int_equal(d[0].position, 2000);
}

static void test_servo_move_800ms_erratum_servo2_to_1200_not_2000(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x0B, 0x03, 0x02, 0x20, 0x03, 0x02, 0xB0, 0x04, 0x09, 0xFC, 0x08);
    const lsc_servo s[] = {{2, 1200}, {9, 2300}};
    check_encoded(lsc_encode_servo_move(out, sizeof v, 800, s, 2), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint16_t time = 0;
    lsc_servo d[2];
    assert_int_equal(lsc_decode_servo_move(&f, &time, d, 2), 2);
    assert_int_equal(time, 800);
    assert_int_equal(d[0].id, 2);
    assert_int_equal(d[0].position, 1200); /* the document's text says 2000 */
    assert_int_equal(d[1].id, 9);
    assert_int_equal(d[1].position, 2300);
}

static void check_u8_u16(const lsc_frame *f, int (*decode)(const lsc_frame *, uint8_t *, uint16_t *),
                         uint8_t a, uint16_t b)
{
    uint8_t x = 0;
    uint16_t y = 0;
    assert_int_equal(decode(f, &x, &y), 0);
    assert_int_equal(x, a);
    assert_int_equal(y, b);
}

/* A vector of a message whose parameters are one byte a and a 16-bit b. */
static void u8_u16_vector(const uint8_t *v, size_t n,
                          int (*encode)(uint8_t *, size_t, uint8_t, uint16_t),
                          int (*decode)(const lsc_frame *, uint8_t *, uint16_t *), uint8_t a,
                          uint16_t b)
{
    uint8_t g[LSC_FRAME_MAX + 2 * GUARD];
    memset(g, CANARY, sizeof g);
    check_encoded(encode(&g[GUARD], n, a, b), g, v, n);
    uint8_t pbuf[LSC_FRAME_MAX];
    lsc_frame f;
    parse(v, n, &f, pbuf);
    check_u8_u16(&f, decode, a, b);
}

/* A vector of a message without parameters. */
static void empty_vector(const uint8_t *v, size_t n, int (*encode)(uint8_t *, size_t),
                         int (*decode)(const lsc_frame *))
{
    uint8_t g[LSC_FRAME_MAX + 2 * GUARD];
    memset(g, CANARY, sizeof g);
    check_encoded(encode(&g[GUARD], n), g, v, n);
    uint8_t pbuf[LSC_FRAME_MAX];
    lsc_frame f;
    parse(v, n, &f, pbuf);
    assert_int_equal(decode(&f), 0);
}

static void test_group_run_group8_once(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_run, lsc_decode_group_run, 8, 1);
}

static void test_group_run_group2_forever(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x06, 0x02, 0x00, 0x00};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_run, lsc_decode_group_run, 2, 0);
}

static void test_group_stop(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x02, 0x07};
    (void)state;
    empty_vector(v, sizeof v, lsc_encode_group_stop, lsc_decode_group_stop);
}

static void test_group_speed_group8_50_percent(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x0B, 0x08, 0x32, 0x00};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_speed, lsc_decode_group_speed, 8, 50);
}

static void test_group_speed_all_groups_300_percent(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x0B, 0xFF, 0x2C, 0x01};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_speed, lsc_decode_group_speed, LSC_GROUP_ALL, 300);
}

static void test_battery_request_erratum_command_15_not_11(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x02, 0x0F);
    assert_int_equal(LSC_CMD_BATTERY, 15); /* the document's text says 11 */
    check_encoded(lsc_encode_battery_request(out, sizeof v), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    assert_int_equal(f.cmd, 15);
    assert_int_equal(lsc_decode_battery_request(&f), 0);
}

static void check_ids(int n, const uint8_t *ids, const uint8_t *expect, size_t count)
{
    assert_int_equal(n, (int)count);
    assert_memory_equal(ids, expect, count);
}

static void test_unload_ids_1_2_3(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x06, 0x14, 0x03, 0x01, 0x02, 0x03);
    const uint8_t ids[] = {1, 2, 3};
    check_encoded(lsc_encode_unload(out, sizeof v, ids, 3), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint8_t d[8];
    check_ids(lsc_decode_unload(&f, d, sizeof d), d, ids, 3);
}

static void test_unload_ids_1_to_6(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x09, 0x14, 0x06, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06);
    const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    check_encoded(lsc_encode_unload(out, sizeof v, ids, 6), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint8_t d[6];
    check_ids(lsc_decode_unload(&f, d, sizeof d), d, ids, 6);
}

static void test_pos_request_ids_1_to_6(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x09, 0x15, 0x06, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06);
    const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    check_encoded(lsc_encode_pos_request(out, sizeof v, ids, 6), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint8_t d[6];
    check_ids(lsc_decode_pos_request(&f, d, sizeof d), d, ids, 6);
    lsc_servo s[6];
    assert_int_equal(lsc_decode_pos_reply(&f, s, 6), LSC_EFRAME); /* a request, not a reply */
}

/* ---- Controller -> host ---- */

static void test_battery_reply_7500mV_erratum_command_15_not_11(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D);
    check_encoded(lsc_encode_battery_reply(out, sizeof v, 7500), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    uint16_t mv = 0;
    assert_int_equal(lsc_decode_battery_reply(&f, &mv), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(lsc_decode_battery_request(&f), LSC_EFRAME); /* a reply, not a request */
}

/* Erratum: the reply's LEN is 3N+3 (0x15 for 6 servos), not N. Misprint: the
 * document prints each position 500 as bytes 01 F4 (big-endian); every other
 * 16-bit field is little-endian, so 500 is F4 01, as here. */
static void test_pos_reply_ids_1_to_6_at_500_erratum_len_3n_plus_3_misprint_F4_01(void **state)
{
    (void)state;
    VECTOR(0x55, 0x55, 0x15, 0x15, 0x06, 0x01, 0xF4, 0x01, 0x02, 0xF4, 0x01, 0x03, 0xF4, 0x01,
           0x04, 0xF4, 0x01, 0x05, 0xF4, 0x01, 0x06, 0xF4, 0x01);
    const lsc_servo s[] = {{1, 500}, {2, 500}, {3, 500}, {4, 500}, {5, 500}, {6, 500}};
    assert_int_equal(v[2], 3 * 6 + 3);
    check_encoded(lsc_encode_pos_reply(out, sizeof v, s, 6), g, v, sizeof v);
    parse(v, sizeof v, &f, pbuf);
    lsc_servo d[6];
    assert_int_equal(lsc_decode_pos_reply(&f, d, 6), 6);
    for (size_t i = 0; i < 6; i++) {
        assert_int_equal(d[i].id, s[i].id);
        assert_int_equal(d[i].position, 500);
    }
    uint8_t ids[32];
    assert_int_equal(lsc_decode_pos_request(&f, ids, sizeof ids), LSC_EFRAME);
}

static void test_group_run_notification_group8_started_times1(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_run, lsc_decode_group_run, 8, 1);
}

static void test_group_stop_notification_forced_to_stop(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x02, 0x07};
    (void)state;
    empty_vector(v, sizeof v, lsc_encode_group_stop, lsc_decode_group_stop);
}

static void test_group_complete_group8_times1(void **state)
{
    static const uint8_t v[] = {0x55, 0x55, 0x05, 0x08, 0x08, 0x01, 0x00};
    (void)state;
    u8_u16_vector(v, sizeof v, lsc_encode_group_complete, lsc_decode_group_complete, 8, 1);
    const lsc_frame f = {v[3], 3, &v[4]};
    uint8_t a;
    uint16_t b;
    assert_int_equal(lsc_decode_group_run(&f, &a, &b), LSC_EFRAME); /* not a group start */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_servo_move_1000ms_id1_to_2000),
        cmocka_unit_test(test_servo_move_800ms_erratum_servo2_to_1200_not_2000),
        cmocka_unit_test(test_group_run_group8_once),
        cmocka_unit_test(test_group_run_group2_forever),
        cmocka_unit_test(test_group_stop),
        cmocka_unit_test(test_group_speed_group8_50_percent),
        cmocka_unit_test(test_group_speed_all_groups_300_percent),
        cmocka_unit_test(test_battery_request_erratum_command_15_not_11),
        cmocka_unit_test(test_unload_ids_1_2_3),
        cmocka_unit_test(test_unload_ids_1_to_6),
        cmocka_unit_test(test_pos_request_ids_1_to_6),
        cmocka_unit_test(test_battery_reply_7500mV_erratum_command_15_not_11),
        cmocka_unit_test(test_pos_reply_ids_1_to_6_at_500_erratum_len_3n_plus_3_misprint_F4_01),
        cmocka_unit_test(test_group_run_notification_group8_started_times1),
        cmocka_unit_test(test_group_stop_notification_forced_to_stop),
        cmocka_unit_test(test_group_complete_group8_times1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
