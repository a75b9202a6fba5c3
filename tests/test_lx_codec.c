/* The bus-servo codec (include/lsc/lx.h): every command's lengths, every
 * encoder's bytes and ranges, every decoder's checks, and the document's
 * errata, each named in a test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/lx.h"
#include "lx_vectors.h"

#define GUARD 8u
#define CANARY 0xA5u

/* Parses exactly the n bytes at bytes: one frame at the last, none before. */
static void parse_one(lsc_lx_parser *p, const uint8_t *bytes, size_t n, lsc_lx_frame *f)
{
    assert_int_equal(lsc_lx_parser_init(p), 0);
    for (size_t i = 0; i + 1u < n; i++) {
        assert_int_equal(lsc_lx_parser_feed(p, bytes[i], f), 0);
    }
    assert_int_equal(lsc_lx_parser_feed(p, bytes[n - 1u], f), 1);
}

/* Every vector: its encoder writes exactly its bytes into a buffer of exactly
 * its size (nothing around it), one byte less is LSC_ENOSPC with nothing
 * written, the parser yields it, and its decoder gives back its values. */
static void test_vectors(void **state)
{
    (void)state;
    for (size_t k = 0; k < LX_NVECTORS; k++) {
        const lx_vector *v = &lx_vectors[k];
        uint8_t g[LSC_LX_FRAME_MAX + 2u * GUARD];
        print_message("%s\n", v->what);
        memset(g, CANARY, sizeof g);
        assert_int_equal(lx_vector_encode(v, &g[GUARD], v->n - 1u), LSC_ENOSPC);
        for (size_t i = 0; i < sizeof g; i++) {
            assert_int_equal(g[i], CANARY);
        }
        assert_int_equal(lx_vector_encode(v, &g[GUARD], v->n), v->n);
        assert_memory_equal(&g[GUARD], v->bytes, v->n);
        for (size_t i = 0; i < GUARD; i++) {
            assert_int_equal(g[i], CANARY);
            assert_int_equal(g[GUARD + v->n + i], CANARY);
        }
        /* the raw encoder makes the same frame */
        uint8_t raw[LSC_LX_FRAME_MAX];
        assert_int_equal(lsc_lx_encode_frame(raw, sizeof raw, v->id, v->cmd, &v->bytes[5],
                                             v->n - 6u),
                         v->n);
        assert_memory_equal(raw, v->bytes, v->n);

        lsc_lx_parser p;
        lsc_lx_frame f;
        parse_one(&p, v->bytes, v->n, &f);
        assert_int_equal(f.id, v->id);
        assert_int_equal(f.cmd, v->cmd);
        assert_int_equal(f.nparams, v->n - 6u);
        assert_int_equal(f.reply, v->n - 3u != lsc_lx_len(v->cmd, false));
        if (v->n > 6) {
            int32_t a = -1, b = -1;
            assert_int_equal(lx_vector_decode(&f, &a, &b), 0);
            assert_int_equal(a, v->a);
            assert_int_equal(b, v->b);
        }
    }
}

/* The lengths of every command of the document: requests, and replies of
 * the reads; nothing else is a command. */
static void test_lengths(void **state)
{
    (void)state;
    static const struct {
        uint8_t cmd, req, rep;
    } t[] = {{1, 7, 0},  {2, 3, 7},  {7, 7, 0},  {8, 3, 7},  {11, 3, 0}, {12, 3, 0}, {13, 4, 0},
             {14, 3, 4}, {17, 4, 0}, {18, 3, 0}, {19, 3, 4}, {20, 7, 0}, {21, 3, 7}, {22, 7, 0},
             {23, 3, 7}, {24, 4, 0}, {25, 3, 4}, {26, 3, 4}, {27, 3, 5}, {28, 3, 5}, {29, 7, 0},
             {30, 3, 7}, {31, 4, 0}, {32, 3, 4}, {33, 4, 0}, {34, 3, 4}, {35, 4, 0}, {36, 3, 4}};
    unsigned known = 0;
    for (unsigned cmd = 0; cmd < 256; cmd++) {
        unsigned req = 0, rep = 0;
        for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
            if (t[i].cmd == cmd) {
                req = t[i].req;
                rep = t[i].rep;
                known++;
            }
        }
        assert_int_equal(lsc_lx_len((uint8_t)cmd, false), req);
        assert_int_equal(lsc_lx_len((uint8_t)cmd, true), rep);
    }
    assert_int_equal(known, 28);
}

/* Erratum: the document's detail section gives ANGLE_OFFSET_READ as command 9
 * with LEN 7; its table's 19 with LEN 3 (a reply of LEN 4) is right. */
static void test_erratum_offset_read_is_19_len_3(void **state)
{
    (void)state;
    assert_int_equal(LSC_LX_OFFSET_READ, 19);
    assert_int_equal(lsc_lx_len(19, false), 3);
    assert_int_equal(lsc_lx_len(19, true), 4);
    assert_int_equal(lsc_lx_len(9, false), 0);
    assert_int_equal(lsc_lx_len(9, true), 0);
    uint8_t buf[LSC_LX_FRAME_MAX];
    assert_int_equal(lsc_lx_encode_request(buf, sizeof buf, 1, 9), LSC_EINVAL);
}

/* Erratum: a reply heading reads MOVE_TIME_READ with value 8; 8 is
 * MOVE_TIME_WAIT_READ (and MOVE_TIME_READ is 2). */
static void test_erratum_8_is_move_time_wait_read(void **state)
{
    (void)state;
    assert_int_equal(LSC_LX_MOVE_TIME_READ, 2);
    assert_int_equal(LSC_LX_MOVE_TIME_WAIT_READ, 8);
    uint8_t buf[LSC_LX_FRAME_MAX];
    lsc_lx_parser p;
    lsc_lx_frame f;
    uint16_t pos = 0, time = 0;
    assert_int_equal(lsc_lx_encode_move_time(buf, sizeof buf, 3, 8, 250, 300), 10);
    parse_one(&p, buf, 10, &f);
    assert_true(f.reply);
    assert_int_equal(lsc_lx_decode_move_time(&f, &pos, &time), 0);
    assert_int_equal(pos, 250);
    assert_int_equal(time, 300);
}

/* Erratum: VIN_LIMIT_READ's reply text says "6500v" and 6500..10000, and
 * calls it "read the angle limit value"; the write's 4500..12000 (mV) are the
 * limits, and the read is of the voltage limits: both ends decode. */
static void test_erratum_vin_limit_read_range(void **state)
{
    (void)state;
    uint8_t buf[LSC_LX_FRAME_MAX];
    lsc_lx_parser p;
    lsc_lx_frame f;
    uint16_t lo = 0, hi = 0;
    assert_int_equal(lsc_lx_encode_vin_limit(buf, sizeof buf, 1, LSC_LX_VIN_LIMIT_READ, 4500,
                                             12000),
                     10);
    parse_one(&p, buf, 10, &f);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &lo, &hi), 0);
    assert_int_equal(lo, 4500);
    assert_int_equal(hi, 12000);
    /* and it is not the angle limits */
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &lo, &hi), LSC_EFRAME);
}

/* Erratum of a public transcription: LEN is not "command + parameters"; it
 * counts LEN, CMD, the parameters and CHK (n + 3), and the frame is LEN + 3
 * bytes. */
static void test_erratum_len_is_n_plus_3(void **state)
{
    (void)state;
    uint8_t buf[LSC_LX_FRAME_MAX];
    assert_int_equal(lsc_lx_encode_id(buf, sizeof buf, 1, LSC_LX_ID_WRITE, 9), 7);
    assert_int_equal(buf[3], 4); /* one parameter */
    assert_int_equal(lsc_lx_encode_move_time(buf, sizeof buf, 1, 1, 500, 1000), 10);
    assert_int_equal(buf[3], 7); /* four */
    assert_int_equal(lsc_lx_encode_request(buf, sizeof buf, 1, LSC_LX_POS_READ), 6);
    assert_int_equal(buf[3], 3); /* none */
}

/* A widely quoted frame: the position read of servo 1. */
static void test_pos_read_request_bytes(void **state)
{
    (void)state;
    static const uint8_t v[] = {0x55, 0x55, 0x01, 0x03, 0x1C, 0xDF};
    uint8_t buf[6];
    assert_int_equal(lsc_lx_encode_request(buf, sizeof buf, 1, LSC_LX_POS_READ), 6);
    assert_memory_equal(buf, v, 6);
}

/* Out of range -> LSC_EINVAL, nothing written (the buffer is big enough). */
#define REFUSED(call)                                                                     \
    do {                                                                                  \
        memset(buf, CANARY, sizeof buf);                                                  \
        assert_int_equal((call), LSC_EINVAL);                                             \
        for (size_t i_ = 0; i_ < sizeof buf; i_++) {                                      \
            assert_int_equal(buf[i_], CANARY);                                            \
        }                                                                                 \
    } while (0)
#define TAKEN(call, len) assert_int_equal((call), (len))

static void test_encoder_ranges(void **state)
{
    (void)state;
    uint8_t buf[LSC_LX_FRAME_MAX + 4];
    const size_t cap = sizeof buf;
    /* move: position 0..1000, time 0..30000; commands 1, 2, 7, 8 only */
    TAKEN(lsc_lx_encode_move_time(buf, cap, 0, 1, 1000, 30000), 10);
    REFUSED(lsc_lx_encode_move_time(buf, cap, 1, 1, 1001, 0));
    REFUSED(lsc_lx_encode_move_time(buf, cap, 1, 7, 0, 30001));
    REFUSED(lsc_lx_encode_move_time(buf, cap, 1, 3, 0, 0));
    REFUSED(lsc_lx_encode_move_time(buf, cap, 1, 11, 0, 0));
    TAKEN(lsc_lx_encode_move_time(buf, cap, 253, 8, 0, 0), 10);
    /* ids: 255 never; 254 for requests of writes, not for replies */
    REFUSED(lsc_lx_encode_move_time(buf, cap, 255, 1, 0, 0));
    REFUSED(lsc_lx_encode_move_time(buf, cap, 254, 2, 0, 0));
    TAKEN(lsc_lx_encode_move_time(buf, cap, 254, 1, 0, 0), 10);
    /* id write: 0..253; the reply names its own id */
    TAKEN(lsc_lx_encode_id(buf, cap, 254, 13, 253), 7);
    REFUSED(lsc_lx_encode_id(buf, cap, 1, 13, 254));
    TAKEN(lsc_lx_encode_id(buf, cap, 0, 14, 0), 7);
    REFUSED(lsc_lx_encode_id(buf, cap, 1, 14, 2));
    REFUSED(lsc_lx_encode_id(buf, cap, 254, 14, 254));
    REFUSED(lsc_lx_encode_id(buf, cap, 1, 12, 1));
    /* offset -125..125 */
    TAKEN(lsc_lx_encode_offset(buf, cap, 1, 17, -125), 7);
    TAKEN(lsc_lx_encode_offset(buf, cap, 1, 19, 125), 7);
    REFUSED(lsc_lx_encode_offset(buf, cap, 1, 17, -126));
    REFUSED(lsc_lx_encode_offset(buf, cap, 1, 17, 126));
    REFUSED(lsc_lx_encode_offset(buf, cap, 1, 18, 0));
    /* angle limits 0 <= min < max <= 1000 */
    TAKEN(lsc_lx_encode_angle_limit(buf, cap, 1, 20, 0, 1), 10);
    TAKEN(lsc_lx_encode_angle_limit(buf, cap, 1, 21, 999, 1000), 10);
    REFUSED(lsc_lx_encode_angle_limit(buf, cap, 1, 20, 500, 500));
    REFUSED(lsc_lx_encode_angle_limit(buf, cap, 1, 20, 0, 1001));
    REFUSED(lsc_lx_encode_angle_limit(buf, cap, 1, 22, 0, 1000));
    /* vin limits 4500 <= min < max <= 12000 */
    TAKEN(lsc_lx_encode_vin_limit(buf, cap, 1, 22, 4500, 4501), 10);
    REFUSED(lsc_lx_encode_vin_limit(buf, cap, 1, 22, 4499, 5000));
    REFUSED(lsc_lx_encode_vin_limit(buf, cap, 1, 22, 6000, 6000));
    REFUSED(lsc_lx_encode_vin_limit(buf, cap, 1, 23, 6000, 12001));
    REFUSED(lsc_lx_encode_vin_limit(buf, cap, 1, 20, 6000, 7000));
    /* temperature limit 50..100 */
    TAKEN(lsc_lx_encode_temp_limit(buf, cap, 1, 24, 50), 7);
    TAKEN(lsc_lx_encode_temp_limit(buf, cap, 1, 25, 100), 7);
    REFUSED(lsc_lx_encode_temp_limit(buf, cap, 1, 24, 49));
    REFUSED(lsc_lx_encode_temp_limit(buf, cap, 1, 24, 101));
    REFUSED(lsc_lx_encode_temp_limit(buf, cap, 1, 26, 60));
    /* readings: any value; replies only, from a servo's id */
    TAKEN(lsc_lx_encode_temp(buf, cap, 1, 255), 7);
    TAKEN(lsc_lx_encode_vin(buf, cap, 1, 65535), 8);
    TAKEN(lsc_lx_encode_position(buf, cap, 1, -32768), 8);
    REFUSED(lsc_lx_encode_position(buf, cap, 254, 0));
    /* motor mode: mode 0/1, speed -1000..1000 */
    TAKEN(lsc_lx_encode_motor_mode(buf, cap, 1, 29, 0, 1000), 10);
    TAKEN(lsc_lx_encode_motor_mode(buf, cap, 1, 30, 1, -1000), 10);
    REFUSED(lsc_lx_encode_motor_mode(buf, cap, 1, 29, 2, 0));
    REFUSED(lsc_lx_encode_motor_mode(buf, cap, 1, 29, 1, 1001));
    REFUSED(lsc_lx_encode_motor_mode(buf, cap, 1, 29, 1, -1001));
    REFUSED(lsc_lx_encode_motor_mode(buf, cap, 1, 31, 1, 0));
    /* load, LED, alarms */
    TAKEN(lsc_lx_encode_load(buf, cap, 1, 31, false), 7);
    TAKEN(lsc_lx_encode_load(buf, cap, 1, 32, true), 7);
    REFUSED(lsc_lx_encode_load(buf, cap, 1, 33, true));
    TAKEN(lsc_lx_encode_led_ctrl(buf, cap, 1, 33, true), 7);
    assert_int_equal(buf[5], 0); /* 0 is on */
    TAKEN(lsc_lx_encode_led_ctrl(buf, cap, 1, 34, false), 7);
    assert_int_equal(buf[5], 1);
    REFUSED(lsc_lx_encode_led_ctrl(buf, cap, 1, 31, true));
    TAKEN(lsc_lx_encode_led_error(buf, cap, 1, 35, 0), 7);
    TAKEN(lsc_lx_encode_led_error(buf, cap, 1, 36, 7), 7);
    REFUSED(lsc_lx_encode_led_error(buf, cap, 1, 35, 8));
    REFUSED(lsc_lx_encode_led_error(buf, cap, 1, 33, 1));
}

/* Requests without parameters: reads (to 254 only ID_READ), 11, 12, 18. */
static void test_requests(void **state)
{
    (void)state;
    uint8_t buf[LSC_LX_FRAME_MAX + 4];
    const size_t cap = sizeof buf;
    for (unsigned cmd = 0; cmd < 256; cmd++) {
        bool ok = lsc_lx_len((uint8_t)cmd, false) == 3u;
        bool read = lsc_lx_len((uint8_t)cmd, true) != 0u;
        if (ok) {
            TAKEN(lsc_lx_encode_request(buf, cap, 0, (uint8_t)cmd), 6);
            TAKEN(lsc_lx_encode_request(buf, cap, 253, (uint8_t)cmd), 6);
        } else {
            REFUSED(lsc_lx_encode_request(buf, cap, 1, (uint8_t)cmd));
        }
        if (ok && (!read || cmd == LSC_LX_ID_READ)) {
            TAKEN(lsc_lx_encode_request(buf, cap, 254, (uint8_t)cmd), 6);
        } else {
            REFUSED(lsc_lx_encode_request(buf, cap, 254, (uint8_t)cmd));
        }
        REFUSED(lsc_lx_encode_request(buf, cap, 255, (uint8_t)cmd));
    }
}

/* The raw encoder: shapes only, and its buffer rules (shared by all). */
static void test_encode_frame(void **state)
{
    (void)state;
    uint8_t buf[LSC_LX_FRAME_MAX + 4];
    const size_t cap = sizeof buf;
    static const uint8_t p[4] = {1, 2, 3, 4};
    REFUSED(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_ID_WRITE, NULL, 1));
    REFUSED(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_ID_WRITE, p, 2));
    REFUSED(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_POS_READ, p, 1));
    REFUSED(lsc_lx_encode_frame(buf, cap, 1, 0, p, 0));
    REFUSED(lsc_lx_encode_frame(buf, cap, 1, 200, p, 4));
    TAKEN(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_POS_READ, p, 2), 8);
    TAKEN(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_POS_READ, NULL, 0), 6);
    /* values are not checked here: a position of 0x0201 */
    TAKEN(lsc_lx_encode_frame(buf, cap, 1, LSC_LX_MOVE_TIME_WRITE, p, 4), 10);
    /* cap: too small is LSC_ENOSPC even without a buffer; NULL with room is EINVAL */
    assert_int_equal(lsc_lx_encode_frame(NULL, 0, 1, LSC_LX_POS_READ, NULL, 0), LSC_ENOSPC);
    assert_int_equal(lsc_lx_encode_frame(NULL, 6, 1, LSC_LX_POS_READ, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_lx_encode_temp(buf, 6, 1, 20), LSC_ENOSPC);
}

/* A frame as the caller builds it, to try the decoders' checks. */
static lsc_lx_frame frame(uint8_t id, uint8_t cmd, bool reply, const uint8_t *params,
                          uint8_t n)
{
    lsc_lx_frame f = {id, cmd, n, reply, params};
    return f;
}

static void test_decoder_checks(void **state)
{
    (void)state;
    uint16_t a = 7, b = 7;
    uint8_t u8 = 7;
    int8_t s8 = 7;
    int16_t s16 = 7;
    bool on = false;
    static const uint8_t ok4[4] = {0xF4, 0x01, 0xE8, 0x03}; /* 500, 1000 */
    lsc_lx_frame f = frame(1, 1, false, ok4, 4);
    /* NULL arguments */
    assert_int_equal(lsc_lx_decode_move_time(NULL, &a, &b), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_move_time(&f, NULL, &b), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, NULL), LSC_EINVAL);
    lsc_lx_frame nul = frame(1, 1, false, NULL, 4);
    assert_int_equal(lsc_lx_decode_move_time(&nul, &a, &b), LSC_EINVAL);
    nul = frame(1, 1, false, NULL, 0); /* no parameters: NULL is fine, the shape is not */
    assert_int_equal(lsc_lx_decode_move_time(&nul, &a, &b), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, NULL, &b), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, NULL, &b), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_id(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_offset(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_temp_limit(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_temp(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_vin(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_position(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, NULL, &s16), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_load(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_led_ctrl(&f, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lx_decode_led_error(&f, NULL), LSC_EINVAL);
    /* the shape: command, direction, length, id */
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), 0);
    f = frame(1, 1, true, ok4, 4); /* 1 has no reply */
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 2, false, ok4, 4); /* 2's request has no values */
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 7, false, ok4, 3);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(254, 8, true, ok4, 4); /* no reply comes from 254 */
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(254, 7, false, ok4, 4);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), 0);
    f = frame(255, 7, false, ok4, 4);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 20, false, ok4, 4);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    /* a reading's request is no reading; cmd 0 is no command */
    static const uint8_t one[1] = {30};
    f = frame(1, 26, false, one, 1);
    assert_int_equal(lsc_lx_decode_temp(&f, &u8), LSC_EFRAME);
    f = frame(1, 0, false, one, 1);
    assert_int_equal(lsc_lx_decode_temp(&f, &u8), LSC_EFRAME);
    f = frame(1, 26, true, one, 1);
    assert_int_equal(lsc_lx_decode_temp(&f, &u8), 0);
    assert_int_equal(u8, 30);
    assert_int_equal(lsc_lx_decode_vin(&f, &a), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_position(&f, &s16), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_id(&f, &u8), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_offset(&f, &s8), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_temp_limit(&f, &u8), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_load(&f, &on), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_led_ctrl(&f, &on), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_led_error(&f, &u8), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, &s16), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &a, &b), LSC_EFRAME);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &a, &b), LSC_EFRAME);
}

/* Values outside the ranges: LSC_EFRAME, outputs untouched. */
static void test_decoder_ranges(void **state)
{
    (void)state;
    uint16_t a = 7, b = 7;
    uint8_t u8 = 7;
    int8_t s8;
    int16_t s16 = 7;
    bool on = false;
    lsc_lx_frame f;
    static const uint8_t pos1001[4] = {0xE9, 0x03, 0, 0}, time30001[4] = {0, 0, 0x31, 0x75};
    f = frame(1, 1, false, pos1001, 4);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 2, true, time30001, 4);
    assert_int_equal(lsc_lx_decode_move_time(&f, &a, &b), LSC_EFRAME);
    assert_int_equal(a, 7);
    assert_int_equal(b, 7);
    static const uint8_t eq[4] = {10, 0, 10, 0}, over[4] = {0, 0, 0xE9, 0x03};
    f = frame(1, 20, false, eq, 4);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 21, true, over, 4);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &a, &b), LSC_EFRAME);
    static const uint8_t vlow[4] = {0x93, 0x11, 0x10, 0x27}, veq[4] = {0x94, 0x11, 0x94, 0x11},
                         vhigh[4] = {0x94, 0x11, 0xE1, 0x2E};
    f = frame(1, 22, false, vlow, 4);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 22, false, veq, 4);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &a, &b), LSC_EFRAME);
    f = frame(1, 23, true, vhigh, 4);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &a, &b), LSC_EFRAME);
    assert_int_equal(a, 7);
    /* id: 0..253; a reply names its sender */
    static const uint8_t id254[1] = {254}, id2[1] = {2};
    f = frame(1, 13, false, id254, 1);
    assert_int_equal(lsc_lx_decode_id(&f, &u8), LSC_EFRAME);
    f = frame(1, 14, true, id2, 1);
    assert_int_equal(lsc_lx_decode_id(&f, &u8), LSC_EFRAME);
    f = frame(2, 14, true, id2, 1);
    assert_int_equal(lsc_lx_decode_id(&f, &u8), 0);
    assert_int_equal(u8, 2);
    /* offsets: 126..130 (as bytes: 126, 127, 128 = -128, 129 = -127, 130 = -126) */
    for (unsigned v = 0; v < 256; v++) {
        uint8_t p = (uint8_t)v;
        f = frame(1, 17, false, &p, 1);
        s8 = 7;
        int r = lsc_lx_decode_offset(&f, &s8);
        if (v >= 126 && v <= 130) {
            assert_int_equal(r, LSC_EFRAME);
            assert_int_equal(s8, 7);
        } else {
            assert_int_equal(r, 0);
            assert_int_equal(s8, (int8_t)p);
        }
    }
    static const uint8_t t49[1] = {49}, t101[1] = {101}, two[1] = {2}, eight[1] = {8};
    f = frame(1, 24, false, t49, 1);
    assert_int_equal(lsc_lx_decode_temp_limit(&f, &u8), LSC_EFRAME);
    f = frame(1, 25, true, t101, 1);
    assert_int_equal(lsc_lx_decode_temp_limit(&f, &u8), LSC_EFRAME);
    f = frame(1, 31, false, two, 1);
    assert_int_equal(lsc_lx_decode_load(&f, &on), LSC_EFRAME);
    f = frame(1, 34, true, two, 1);
    assert_int_equal(lsc_lx_decode_led_ctrl(&f, &on), LSC_EFRAME);
    f = frame(1, 35, false, eight, 1);
    assert_int_equal(lsc_lx_decode_led_error(&f, &u8), LSC_EFRAME);
    assert_int_equal(u8, 2);
    assert_false(on);
    /* motor mode: mode 0/1, speed -1000..1000, the unused byte ignored */
    static const uint8_t m2[4] = {2, 0, 0, 0}, fast[4] = {1, 0, 0xE9, 0x03},
                         back[4] = {1, 0, 0x17, 0xFC}, junk[4] = {1, 0x5A, 0x18, 0xFC};
    f = frame(1, 29, false, m2, 4);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, &s16), LSC_EFRAME);
    f = frame(1, 29, false, fast, 4);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, &s16), LSC_EFRAME);
    f = frame(1, 30, true, back, 4);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, &s16), LSC_EFRAME);
    assert_int_equal(s16, 7);
    f = frame(1, 30, true, junk, 4);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &u8, &s16), 0);
    assert_int_equal(u8, 1);
    assert_int_equal(s16, -1000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vectors),
        cmocka_unit_test(test_lengths),
        cmocka_unit_test(test_erratum_offset_read_is_19_len_3),
        cmocka_unit_test(test_erratum_8_is_move_time_wait_read),
        cmocka_unit_test(test_erratum_vin_limit_read_range),
        cmocka_unit_test(test_erratum_len_is_n_plus_3),
        cmocka_unit_test(test_pos_read_request_bytes),
        cmocka_unit_test(test_encoder_ranges),
        cmocka_unit_test(test_requests),
        cmocka_unit_test(test_encode_frame),
        cmocka_unit_test(test_decoder_checks),
        cmocka_unit_test(test_decoder_ranges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
