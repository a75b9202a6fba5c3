/* Frame encoders: every argument is checked before the first byte is written. */
#include "lsc/core.h"

#include "internal.h"

/* Writes the header of a frame with n parameter bytes; returns the frame's
 * total length or an error (then nothing is written). */
static int put_header(uint8_t *buf, size_t cap, uint8_t cmd, size_t n)
{
    /* A LEN of 0x55 would be read back as a header byte: such a frame cannot be sent. */
    if (n > LSC_PARAMS_MAX || n + 2u == LSC_HEADER_BYTE) {
        return LSC_EINVAL;
    }
    if (cap < n + 4u) {
        return LSC_ENOSPC;
    }
    if (buf == NULL) {
        return LSC_EINVAL;
    }
    buf[0] = LSC_HEADER_BYTE;
    buf[1] = LSC_HEADER_BYTE;
    buf[2] = (uint8_t)(n + 2u);
    buf[3] = cmd;
    return (int)(n + 4u);
}

int lsc_encode_frame(uint8_t *buf, size_t cap, uint8_t cmd, const uint8_t *params, size_t n)
{
    if (params == NULL && n > 0) {
        return LSC_EINVAL;
    }
    int total = put_header(buf, cap, cmd, n);
    for (size_t i = 0; total > 0 && i < n; i++) {
        buf[4 + i] = params[i];
    }
    return total;
}

/* Is this a list of 1..max items whose ids (every stride bytes) are distinct? */
static bool list_valid(const uint8_t *ids, size_t stride, size_t n, size_t max)
{
    return ids != NULL && n > 0 && n <= max && lsc_ids_distinct(ids, stride, n);
}

/* A frame of nhead bytes from head, then n servos as (id, pos lo, pos hi). */
static int encode_servos(uint8_t *buf, size_t cap, uint8_t cmd, const uint8_t *head,
                         size_t nhead, const lsc_servo *servos, size_t n, size_t max)
{
    /* A struct's first member (id) is at its address. */
    if (!list_valid((const uint8_t *)servos, sizeof *servos, n, max)) {
        return LSC_EINVAL;
    }
    int total = put_header(buf, cap, cmd, nhead + 3u * n);
    if (total > 0) {
        uint8_t *at = &buf[4];
        for (size_t i = 0; i < nhead; i++) {
            *at++ = head[i];
        }
        for (size_t i = 0; i < n; i++, at += 3) {
            at[0] = servos[i].id;
            lsc_put_u16(&at[1], servos[i].position);
        }
    }
    return total;
}

int lsc_encode_servo_move(uint8_t *buf, size_t cap, uint16_t time_ms, const lsc_servo *servos,
                          size_t n)
{
    uint8_t head[3] = {(uint8_t)n, 0, 0};
    lsc_put_u16(&head[1], time_ms);
    return encode_servos(buf, cap, LSC_CMD_SERVO_MOVE, head, 3, servos, n, LSC_MOVE_MAX);
}

int lsc_encode_pos_reply(uint8_t *buf, size_t cap, const lsc_servo *servos, size_t n)
{
    uint8_t head[1] = {(uint8_t)n};
    return encode_servos(buf, cap, LSC_CMD_POS_READ, head, 1, servos, n, LSC_READ_MAX);
}

/* A frame whose parameters are one byte and one 16-bit value. */
static int encode_u8_u16(uint8_t *buf, size_t cap, uint8_t cmd, uint8_t a, uint16_t b)
{
    uint8_t params[3] = {a, 0, 0};
    lsc_put_u16(&params[1], b);
    return lsc_encode_frame(buf, cap, cmd, params, 3);
}

int lsc_encode_group_run(uint8_t *buf, size_t cap, uint8_t group, uint16_t times)
{
    return encode_u8_u16(buf, cap, LSC_CMD_GROUP_RUN, group, times);
}

int lsc_encode_group_complete(uint8_t *buf, size_t cap, uint8_t group, uint16_t times)
{
    return encode_u8_u16(buf, cap, LSC_CMD_GROUP_COMPLETE, group, times);
}

int lsc_encode_group_speed(uint8_t *buf, size_t cap, uint8_t group, uint16_t percent)
{
    return encode_u8_u16(buf, cap, LSC_CMD_GROUP_SPEED, group, percent);
}

int lsc_encode_group_stop(uint8_t *buf, size_t cap)
{
    return lsc_encode_frame(buf, cap, LSC_CMD_GROUP_STOP, NULL, 0);
}

int lsc_encode_battery_request(uint8_t *buf, size_t cap)
{
    return lsc_encode_frame(buf, cap, LSC_CMD_BATTERY, NULL, 0);
}

int lsc_encode_battery_reply(uint8_t *buf, size_t cap, uint16_t millivolts)
{
    uint8_t params[2];
    lsc_put_u16(params, millivolts);
    return lsc_encode_frame(buf, cap, LSC_CMD_BATTERY, params, 2);
}

/* A frame whose parameters are a count and that many distinct ids. */
static int encode_ids(uint8_t *buf, size_t cap, uint8_t cmd, const uint8_t *ids, size_t n,
                      size_t max)
{
    if (!list_valid(ids, 1, n, max)) {
        return LSC_EINVAL;
    }
    int total = put_header(buf, cap, cmd, n + 1u);
    if (total > 0) {
        buf[4] = (uint8_t)n;
        for (size_t i = 0; i < n; i++) {
            buf[5 + i] = ids[i];
        }
    }
    return total;
}

int lsc_encode_unload(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n)
{
    return encode_ids(buf, cap, LSC_CMD_UNLOAD, ids, n, LSC_UNLOAD_MAX);
}

int lsc_encode_pos_request(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n)
{
    return encode_ids(buf, cap, LSC_CMD_POS_READ, ids, n, LSC_READ_MAX);
}
