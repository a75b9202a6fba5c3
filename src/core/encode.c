/* Frame encoders: every argument is checked before the first byte is written. */
#include "lsc/core.h"

#include "internal.h"

/* Writes the header of a frame with n parameter bytes; returns the frame's
 * total length or an error (then nothing is written). */
LSC_NOINLINE static int put_header(uint8_t *buf, size_t cap, uint8_t cmd, size_t n)
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

/* A list frame (see lsc_list): the count n, then (for a move) room for the
 * time, then the n items: ids (width 1), offsets as id, offset (width 2) or
 * servos as id, pos lo, pos hi (width 3). */
static int encode_list(uint8_t *buf, size_t cap, const void *items, size_t n, unsigned kind)
{
    const lsc_list l = lsc_list_of(kind);
    /* the id is the first byte of an item in memory (a struct's first member
     * is at its address) */
    size_t stride = l.width == 1   ? 1
                    : l.width == 2 ? sizeof(lsc_servo_offset)
                                    : sizeof(lsc_servo);
    if (items == NULL || n == 0 || n > l.max || !lsc_ids_distinct(items, stride, n)) {
        return LSC_EINVAL;
    }
    int total = put_header(buf, cap, l.cmd, l.head + l.width * n);
    if (total > 0) {
        uint8_t *at = &buf[4];
        *at = (uint8_t)n;
        at += l.head; /* a move's time is its caller's to write */
        /* n <= l.max, under 256: a byte counts it */
        const uint8_t *item = items;
        for (lsc_small left = (lsc_small)n; left != 0; left--, item += stride) {
            if (l.width == 1) {
                *at++ = *item;
            } else if (l.width == 2) {
                const lsc_servo_offset *o = (const lsc_servo_offset *)(const void *)item;
                *at++ = o->id;
                *at++ = (uint8_t)o->offset;
            } else {
                const lsc_servo *s = (const lsc_servo *)(const void *)item;
                *at++ = s->id;
                lsc_put_u16(at, s->position);
                at += 2;
            }
        }
    }
    return total;
}

int lsc_encode_servo_move(uint8_t *buf, size_t cap, uint16_t time_ms, const lsc_servo *servos,
                          size_t n)
{
    int total = encode_list(buf, cap, servos, n, LSC_LIST_MOVE);
    if (total > 0) {
        lsc_put_u16(&buf[5], time_ms);
    }
    return total;
}

int lsc_encode_pos_reply(uint8_t *buf, size_t cap, const lsc_servo *servos, size_t n)
{
    return encode_list(buf, cap, servos, n, LSC_LIST_REPLY);
}

int lsc_encode_unload(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n)
{
    return encode_list(buf, cap, ids, n, LSC_LIST_UNLOAD);
}

int lsc_encode_pos_request(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n)
{
    return encode_list(buf, cap, ids, n, LSC_LIST_REQUEST);
}

/* A frame whose parameters are one byte and one 16-bit value. */
LSC_NOINLINE static int encode_u8_u16(uint8_t *buf, size_t cap, uint8_t cmd, uint8_t a,
                                      uint16_t b)
{
    int total = put_header(buf, cap, cmd, 3);
    if (total > 0) {
        buf[4] = a;
        lsc_put_u16(&buf[5], b);
    }
    return total;
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
    return put_header(buf, cap, LSC_CMD_GROUP_STOP, 0);
}

int lsc_encode_battery_request(uint8_t *buf, size_t cap)
{
    return put_header(buf, cap, LSC_CMD_BATTERY, 0);
}

int lsc_encode_battery_reply(uint8_t *buf, size_t cap, uint16_t millivolts)
{
    int total = put_header(buf, cap, LSC_CMD_BATTERY, 2);
    if (total > 0) {
        lsc_put_u16(&buf[4], millivolts);
    }
    return total;
}

int lsc_encode_offset_request(uint8_t *buf, size_t cap, const uint8_t *ids, size_t n)
{
    return encode_list(buf, cap, ids, n, LSC_LIST_OFFSET_REQUEST);
}

int lsc_encode_offset_reply(uint8_t *buf, size_t cap, const lsc_servo_offset *servos, size_t n)
{
    return encode_list(buf, cap, servos, n, LSC_LIST_OFFSET_REPLY);
}

int lsc_encode_offset_adjust(uint8_t *buf, size_t cap, uint8_t id, int8_t offset)
{
    int total = put_header(buf, cap, LSC_CMD_OFFSET_ADJUST, 2);
    if (total > 0) {
        buf[4] = id;
        buf[5] = (uint8_t)offset;
    }
    return total;
}
