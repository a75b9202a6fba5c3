/* The bus-servo protocol's frames: every command's lengths, the checksum, the
 * byte-by-byte check the parser uses, and the frame encoders that take raw
 * parameters (include/lsc/lx.h). */
#include "lsc/lx.h"

#include "internal.h"
#include "lx_internal.h"

/* Each command's LEN: request | reply << 4 (reply 0: a write, no reply);
 * 0 for a value that is no command. */
#define RQ(len) (len)
#define RD(len) (3u | (len) << 4)
static const uint8_t lens[LSC_LX_LED_ERROR_READ + 1] LSC_ROM = {
    [LSC_LX_MOVE_TIME_WRITE] = RQ(7),      [LSC_LX_MOVE_TIME_READ] = RD(7),
    [LSC_LX_MOVE_TIME_WAIT_WRITE] = RQ(7), [LSC_LX_MOVE_TIME_WAIT_READ] = RD(7),
    [LSC_LX_MOVE_START] = RQ(3),           [LSC_LX_MOVE_STOP] = RQ(3),
    [LSC_LX_ID_WRITE] = RQ(4),             [LSC_LX_ID_READ] = RD(4),
    [LSC_LX_OFFSET_ADJUST] = RQ(4),        [LSC_LX_OFFSET_WRITE] = RQ(3),
    [LSC_LX_OFFSET_READ] = RD(4),          [LSC_LX_ANGLE_LIMIT_WRITE] = RQ(7),
    [LSC_LX_ANGLE_LIMIT_READ] = RD(7),     [LSC_LX_VIN_LIMIT_WRITE] = RQ(7),
    [LSC_LX_VIN_LIMIT_READ] = RD(7),       [LSC_LX_TEMP_LIMIT_WRITE] = RQ(4),
    [LSC_LX_TEMP_LIMIT_READ] = RD(4),      [LSC_LX_TEMP_READ] = RD(4),
    [LSC_LX_VIN_READ] = RD(5),             [LSC_LX_POS_READ] = RD(5),
    [LSC_LX_MOTOR_MODE_WRITE] = RQ(7),     [LSC_LX_MOTOR_MODE_READ] = RD(7),
    [LSC_LX_LOAD_WRITE] = RQ(4),           [LSC_LX_LOAD_READ] = RD(4),
    [LSC_LX_LED_CTRL_WRITE] = RQ(4),       [LSC_LX_LED_CTRL_READ] = RD(4),
    [LSC_LX_LED_ERROR_WRITE] = RQ(4),      [LSC_LX_LED_ERROR_READ] = RD(4),
};

unsigned lsc_lx_len(uint8_t cmd, bool reply)
{
    unsigned e = cmd < sizeof lens ? lsc_rom_u8(&lens[cmd]) : 0u;
    return reply ? e >> 4 : e & 15u;
}

uint8_t lsc_lx_checksum(const uint8_t *b, size_t n)
{
    unsigned sum = 0;
    for (size_t i = 2; i + 1u < n; i++) {
        sum += b[i];
    }
    return (uint8_t)(~sum & 0xFFu);
}

int lsc_lx_reject(const uint8_t *b, size_t pos)
{
    unsigned v = b[pos];
    switch (pos) {
    case 0:
    case 1:
        return v == LSC_LX_HEADER_BYTE ? 0 : LSC_ESYNC;
    case 2:
        return v <= LSC_LX_BROADCAST ? 0 : LSC_EFRAME;
    case 3:
        return v >= LSC_LX_LEN_MIN && v <= LSC_LX_LEN_MAX ? 0 : LSC_EFRAME;
    case 4:
        /* LEN is never 0: a command without lengths matches neither */
        return b[3] == lsc_lx_len((uint8_t)v, false) || b[3] == lsc_lx_len((uint8_t)v, true)
                   ? 0
                   : LSC_EFRAME;
    default:
        /* a parameter, or (the frame's last byte) the checksum */
        return pos + 1u < b[3] + 3u || v == lsc_lx_checksum(b, pos + 1u) ? 0 : LSC_LX_BADSUM;
    }
}

int lsc_lx_check(const uint8_t *b, size_t n)
{
    int why = 0;
    for (size_t i = 0; i < n && why == 0; i++) {
        why = lsc_lx_reject(b, i);
    }
    return why;
}

bool lsc_lx_id_ok(uint8_t id, uint8_t cmd, bool reply)
{
    if (reply) {
        return id <= LSC_LX_ID_MAX;
    }
    return id < LSC_LX_BROADCAST || (id == LSC_LX_BROADCAST &&
                                      (cmd == LSC_LX_ID_READ || lsc_lx_len(cmd, true) == 0u));
}

int lsc_lx_encode_frame(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, const uint8_t *params,
                        size_t n)
{
    if (params == NULL && n > 0u) {
        return LSC_EINVAL;
    }
    /* a LEN of 3 + n; lsc_lx_len is 0 for what is not a shape of cmd */
    bool reply = n + 3u != lsc_lx_len(cmd, false);
    if ((reply && n + 3u != lsc_lx_len(cmd, true)) || !lsc_lx_id_ok(id, cmd, reply)) {
        return LSC_EINVAL;
    }
    size_t total = n + 6u;
    if (cap < total) {
        return LSC_ENOSPC;
    }
    if (buf == NULL) {
        return LSC_EINVAL;
    }
    buf[0] = LSC_LX_HEADER_BYTE;
    buf[1] = LSC_LX_HEADER_BYTE;
    buf[2] = id;
    buf[3] = (uint8_t)(n + 3u);
    buf[4] = cmd;
    for (size_t i = 0; i < n; i++) {
        buf[5 + i] = params[i];
    }
    buf[total - 1u] = lsc_lx_checksum(buf, total);
    return (int)total;
}

int lsc_lx_encode_request(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd)
{
    return lsc_lx_encode_frame(buf, cap, id, cmd, NULL, 0);
}
