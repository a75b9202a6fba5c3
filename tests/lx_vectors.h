/* Frames of the bus-servo protocol, one for every command that carries
 * values, with their checksums worked out by hand from the document's rule
 * (CHK = ~(ID + LEN + CMD + P1 + ... + Pn) & 0xFF), and helpers that encode
 * and decode one with the typed function of its command. Shared by the
 * codec's and the parser's tests. Test code only. */
#ifndef LSC_TEST_LX_VECTORS_H
#define LSC_TEST_LX_VECTORS_H

#include <stdint.h>

#include "lsc/lx.h"

typedef struct lx_vector {
    const char *what;
    uint8_t id, cmd;
    int32_t a, b; /* the values, as the typed functions take them */
    uint8_t n;
    uint8_t bytes[LSC_LX_FRAME_MAX];
} lx_vector;

static const lx_vector lx_vectors[] = {
    {"move_time_write id1 500 in 1000 ms", 1, 1, 500, 1000, 10, {0x55, 0x55, 0x01, 0x07, 0x01, 0xF4, 0x01, 0xE8, 0x03, 0x16}},
    {"move_time_read reply", 1, 2, 1000, 30000, 10, {0x55, 0x55, 0x01, 0x07, 0x02, 0xE8, 0x03, 0x30, 0x75, 0x65}},
    {"move_time_wait_write broadcast", 254, 7, 0, 0, 10, {0x55, 0x55, 0xFE, 0x07, 0x07, 0x00, 0x00, 0x00, 0x00, 0xF3}},
    {"move_time_wait_read reply", 3, 8, 250, 300, 10, {0x55, 0x55, 0x03, 0x07, 0x08, 0xFA, 0x00, 0x2C, 0x01, 0xC6}},
    {"id_write 1 -> 9", 1, 13, 9, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x0D, 0x09, 0xE4}},
    {"id_read reply id 7", 7, 14, 7, 0, 7, {0x55, 0x55, 0x07, 0x04, 0x0E, 0x07, 0xDF}},
    {"offset_adjust -20", 3, 17, -20, 0, 7, {0x55, 0x55, 0x03, 0x04, 0x11, 0xEC, 0xFB}},
    {"offset_read reply 125", 2, 19, 125, 0, 7, {0x55, 0x55, 0x02, 0x04, 0x13, 0x7D, 0x69}},
    {"angle_limit_write 100..900", 1, 20, 100, 900, 10, {0x55, 0x55, 0x01, 0x07, 0x14, 0x64, 0x00, 0x84, 0x03, 0xF8}},
    {"angle_limit_read reply 0..1000", 1, 21, 0, 1000, 10, {0x55, 0x55, 0x01, 0x07, 0x15, 0x00, 0x00, 0xE8, 0x03, 0xF7}},
    {"vin_limit_write 4500..12000", 1, 22, 4500, 12000, 10, {0x55, 0x55, 0x01, 0x07, 0x16, 0x94, 0x11, 0xE0, 0x2E, 0x2E}},
    {"vin_limit_read reply 6500..10000", 1, 23, 6500, 10000, 10, {0x55, 0x55, 0x01, 0x07, 0x17, 0x64, 0x19, 0x10, 0x27, 0x2C}},
    {"temp_limit_write 85", 1, 24, 85, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x18, 0x55, 0x8D}},
    {"temp_limit_read reply 100", 1, 25, 100, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x19, 0x64, 0x7D}},
    {"temp_read reply 31", 1, 26, 31, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x1A, 0x1F, 0xC1}},
    {"vin_read reply 7400", 1, 27, 7400, 0, 8, {0x55, 0x55, 0x01, 0x05, 0x1B, 0xE8, 0x1C, 0xDA}},
    {"pos_read reply -20", 1, 28, -20, 0, 8, {0x55, 0x55, 0x01, 0x05, 0x1C, 0xEC, 0xFF, 0xF2}},
    {"motor_mode_write motor -1000", 1, 29, 1, -1000, 10, {0x55, 0x55, 0x01, 0x07, 0x1D, 0x01, 0x00, 0x18, 0xFC, 0xC5}},
    {"motor_mode_read reply servo 0", 1, 30, 0, 0, 10, {0x55, 0x55, 0x01, 0x07, 0x1E, 0x00, 0x00, 0x00, 0x00, 0xD9}},
    {"load_write on", 1, 31, 1, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x1F, 0x01, 0xDA}},
    {"load_read reply off", 1, 32, 0, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x20, 0x00, 0xDA}},
    {"led_ctrl_write off", 1, 33, 0, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x21, 0x01, 0xD8}},
    {"led_ctrl_read reply on", 1, 34, 1, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x22, 0x00, 0xD8}},
    {"led_error_write 7", 1, 35, 7, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x23, 0x07, 0xD0}},
    {"led_error_read reply 4", 1, 36, 4, 0, 7, {0x55, 0x55, 0x01, 0x04, 0x24, 0x04, 0xD2}},
    /* requests without parameters (lsc_lx_encode_request) */
    {"move_time_read request", 1, 2, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x02, 0xF9}},
    {"move_time_wait_read request", 1, 8, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x08, 0xF3}},
    {"move_start request", 1, 11, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x0B, 0xF0}},
    {"move_start broadcast", 254, 11, 0, 0, 6, {0x55, 0x55, 0xFE, 0x03, 0x0B, 0xF3}},
    {"move_stop request", 1, 12, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x0C, 0xEF}},
    {"id_read request", 1, 14, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x0E, 0xED}},
    {"id_read broadcast", 254, 14, 0, 0, 6, {0x55, 0x55, 0xFE, 0x03, 0x0E, 0xF0}},
    {"offset_write request", 1, 18, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x12, 0xE9}},
    {"offset_read request", 1, 19, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x13, 0xE8}},
    {"angle_limit_read request", 1, 21, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x15, 0xE6}},
    {"vin_limit_read request", 1, 23, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x17, 0xE4}},
    {"temp_limit_read request", 1, 25, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x19, 0xE2}},
    {"temp_read request", 1, 26, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x1A, 0xE1}},
    {"vin_read request", 1, 27, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x1B, 0xE0}},
    {"pos_read request", 1, 28, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x1C, 0xDF}},
    {"motor_mode_read request", 1, 30, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x1E, 0xDD}},
    {"load_read request", 1, 32, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x20, 0xDB}},
    {"led_ctrl_read request", 1, 34, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x22, 0xD9}},
    {"led_error_read request", 1, 36, 0, 0, 6, {0x55, 0x55, 0x01, 0x03, 0x24, 0xD7}},
};
#define LX_NVECTORS (sizeof lx_vectors / sizeof lx_vectors[0])

/* Encodes v with the typed encoder of its command into buf[cap]. */
static inline int lx_vector_encode(const lx_vector *v, uint8_t *buf, size_t cap)
{
    uint8_t id = v->id, cmd = v->cmd;
    if (v->n == 6) {
        return lsc_lx_encode_request(buf, cap, id, cmd);
    }
    switch (cmd) {
    case 1: case 2: case 7: case 8:
        return lsc_lx_encode_move_time(buf, cap, id, cmd, (uint16_t)v->a, (uint16_t)v->b);
    case 13: case 14:
        return lsc_lx_encode_id(buf, cap, id, cmd, (uint8_t)v->a);
    case 17: case 19:
        return lsc_lx_encode_offset(buf, cap, id, cmd, (int8_t)v->a);
    case 20: case 21:
        return lsc_lx_encode_angle_limit(buf, cap, id, cmd, (uint16_t)v->a, (uint16_t)v->b);
    case 22: case 23:
        return lsc_lx_encode_vin_limit(buf, cap, id, cmd, (uint16_t)v->a, (uint16_t)v->b);
    case 24: case 25:
        return lsc_lx_encode_temp_limit(buf, cap, id, cmd, (uint8_t)v->a);
    case 26:
        return lsc_lx_encode_temp(buf, cap, id, (uint8_t)v->a);
    case 27:
        return lsc_lx_encode_vin(buf, cap, id, (uint16_t)v->a);
    case 28:
        return lsc_lx_encode_position(buf, cap, id, (int16_t)v->a);
    case 29: case 30:
        return lsc_lx_encode_motor_mode(buf, cap, id, cmd, (uint8_t)v->a, (int16_t)v->b);
    case 31: case 32:
        return lsc_lx_encode_load(buf, cap, id, cmd, v->a != 0);
    case 33: case 34:
        return lsc_lx_encode_led_ctrl(buf, cap, id, cmd, v->a != 0);
    default:
        return lsc_lx_encode_led_error(buf, cap, id, cmd, (uint8_t)v->a);
    }
}

/* Decodes f with the typed decoder of its command into *a, *b (b 0 when the
 * command has one value). Returns what the decoder returns. */
static inline int lx_vector_decode(const lsc_lx_frame *f, int32_t *a, int32_t *b)
{
    uint16_t u1 = 0, u2 = 0;
    uint8_t u8 = 0;
    int8_t s8 = 0;
    int16_t s16 = 0;
    bool on = false;
    int r;
    *b = 0;
    switch (f->cmd) {
    case 1: case 2: case 7: case 8:
        r = lsc_lx_decode_move_time(f, &u1, &u2);
        *a = u1, *b = u2;
        return r;
    case 13: case 14:
        r = lsc_lx_decode_id(f, &u8);
        *a = u8;
        return r;
    case 17: case 19:
        r = lsc_lx_decode_offset(f, &s8);
        *a = (int32_t)s8; /* the signed offset: sign extension is meant */
        return r;
    case 20: case 21:
        r = lsc_lx_decode_angle_limit(f, &u1, &u2);
        *a = u1, *b = u2;
        return r;
    case 22: case 23:
        r = lsc_lx_decode_vin_limit(f, &u1, &u2);
        *a = u1, *b = u2;
        return r;
    case 24: case 25:
        r = lsc_lx_decode_temp_limit(f, &u8);
        *a = u8;
        return r;
    case 26:
        r = lsc_lx_decode_temp(f, &u8);
        *a = u8;
        return r;
    case 27:
        r = lsc_lx_decode_vin(f, &u1);
        *a = u1;
        return r;
    case 28:
        r = lsc_lx_decode_position(f, &s16);
        *a = s16;
        return r;
    case 29: case 30:
        r = lsc_lx_decode_motor_mode(f, &u8, &s16);
        *a = u8, *b = s16;
        return r;
    case 31: case 32:
        r = lsc_lx_decode_load(f, &on);
        *a = on;
        return r;
    case 33: case 34:
        r = lsc_lx_decode_led_ctrl(f, &on);
        *a = on;
        return r;
    default:
        r = lsc_lx_decode_led_error(f, &u8);
        *a = u8;
        return r;
    }
}

#endif
