/* The bus-servo protocol's typed encoders: every value is checked against
 * the document's ranges before the first byte is written (include/lsc/lx.h). */
#include "lsc/lx.h"

#include "internal.h"
#include "lx_internal.h"

/* The frame of cmd with params p[0..n) when ok, else LSC_EINVAL. */
LSC_NOINLINE static int put(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool ok,
                            const uint8_t *p, size_t n)
{
    return ok ? lsc_lx_encode_frame(buf, cap, id, cmd, p, n) : LSC_EINVAL;
}

/* A frame of two 16-bit values a, b. */
static int put2(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool ok, uint16_t a,
                uint16_t b)
{
    uint8_t p[4];
    lsc_put_u16(&p[0], a);
    lsc_put_u16(&p[2], b);
    return put(buf, cap, id, cmd, ok, p, sizeof p);
}

/* Whether cmd is w (the write) or r (the read whose reply it is). */
static bool either(uint8_t cmd, uint8_t w, uint8_t r)
{
    return cmd == w || cmd == r;
}

int lsc_lx_encode_move_time(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint16_t position,
                            uint16_t time_ms)
{
    bool ok = (either(cmd, LSC_LX_MOVE_TIME_WRITE, LSC_LX_MOVE_TIME_READ) ||
               either(cmd, LSC_LX_MOVE_TIME_WAIT_WRITE, LSC_LX_MOVE_TIME_WAIT_READ)) &&
              position <= LSC_LX_POSITION_MAX && time_ms <= LSC_LX_TIME_MAX;
    return put2(buf, cap, id, cmd, ok, position, time_ms);
}

int lsc_lx_encode_id(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint8_t value)
{
    bool ok = value <= LSC_LX_ID_MAX &&
              (cmd == LSC_LX_ID_WRITE || (cmd == LSC_LX_ID_READ && value == id));
    return put(buf, cap, id, cmd, ok, &value, 1);
}

int lsc_lx_encode_offset(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, int8_t offset)
{
    uint8_t p = (uint8_t)offset; /* two's complement on every target */
    bool ok = either(cmd, LSC_LX_OFFSET_ADJUST, LSC_LX_OFFSET_READ) &&
              offset >= -LSC_LX_OFFSET_MAX && offset <= LSC_LX_OFFSET_MAX;
    return put(buf, cap, id, cmd, ok, &p, 1);
}

int lsc_lx_encode_angle_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint16_t min,
                              uint16_t max)
{
    bool ok = either(cmd, LSC_LX_ANGLE_LIMIT_WRITE, LSC_LX_ANGLE_LIMIT_READ) && min < max &&
              max <= LSC_LX_POSITION_MAX;
    return put2(buf, cap, id, cmd, ok, min, max);
}

int lsc_lx_encode_vin_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint16_t min_mv,
                            uint16_t max_mv)
{
    bool ok = either(cmd, LSC_LX_VIN_LIMIT_WRITE, LSC_LX_VIN_LIMIT_READ) &&
              min_mv >= LSC_LX_VIN_MIN && min_mv < max_mv && max_mv <= LSC_LX_VIN_MAX;
    return put2(buf, cap, id, cmd, ok, min_mv, max_mv);
}

int lsc_lx_encode_temp_limit(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint8_t celsius)
{
    bool ok = either(cmd, LSC_LX_TEMP_LIMIT_WRITE, LSC_LX_TEMP_LIMIT_READ) &&
              celsius >= LSC_LX_TEMP_LIMIT_MIN && celsius <= LSC_LX_TEMP_LIMIT_MAX;
    return put(buf, cap, id, cmd, ok, &celsius, 1);
}

int lsc_lx_encode_temp(uint8_t *buf, size_t cap, uint8_t id, uint8_t celsius)
{
    return put(buf, cap, id, LSC_LX_TEMP_READ, true, &celsius, 1);
}

int lsc_lx_encode_vin(uint8_t *buf, size_t cap, uint8_t id, uint16_t millivolts)
{
    uint8_t p[2];
    lsc_put_u16(p, millivolts);
    return put(buf, cap, id, LSC_LX_VIN_READ, true, p, sizeof p);
}

int lsc_lx_encode_position(uint8_t *buf, size_t cap, uint8_t id, int16_t position)
{
    uint8_t p[2];
    lsc_put_u16(p, (uint16_t)position); /* two's complement on every target */
    return put(buf, cap, id, LSC_LX_POS_READ, true, p, sizeof p);
}

int lsc_lx_encode_motor_mode(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint8_t mode,
                             int16_t speed)
{
    uint8_t p[4] = {mode, 0, 0, 0};
    bool ok = either(cmd, LSC_LX_MOTOR_MODE_WRITE, LSC_LX_MOTOR_MODE_READ) &&
              mode <= LSC_LX_MODE_MOTOR && speed >= -LSC_LX_SPEED_MAX && speed <= LSC_LX_SPEED_MAX;
    lsc_put_u16(&p[2], (uint16_t)speed);
    return put(buf, cap, id, cmd, ok, p, sizeof p);
}

int lsc_lx_encode_load(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool on)
{
    uint8_t p = on ? 1u : 0u;
    return put(buf, cap, id, cmd, either(cmd, LSC_LX_LOAD_WRITE, LSC_LX_LOAD_READ), &p, 1);
}

int lsc_lx_encode_led_ctrl(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, bool on)
{
    uint8_t p = (uint8_t)!on; /* 0 is on */
    return put(buf, cap, id, cmd, either(cmd, LSC_LX_LED_CTRL_WRITE, LSC_LX_LED_CTRL_READ), &p,
               1);
}

int lsc_lx_encode_led_error(uint8_t *buf, size_t cap, uint8_t id, uint8_t cmd, uint8_t mask)
{
    bool ok = either(cmd, LSC_LX_LED_ERROR_WRITE, LSC_LX_LED_ERROR_READ) &&
              mask <= LSC_LX_ALARM_ALL;
    return put(buf, cap, id, cmd, ok, &mask, 1);
}
