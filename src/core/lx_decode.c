/* The bus-servo protocol's typed decoders: each checks the whole frame, its
 * values included, before writing any output (include/lsc/lx.h). */
#include "lsc/lx.h"

#include "internal.h"
#include "lx_internal.h"

/* LSC_OK if f is w's request (w 0: none) or r's reply (r 0: none) with n
 * parameter bytes, from or to an id that may carry it. */
LSC_NOINLINE static int expect(const lsc_lx_frame *f, uint8_t w, uint8_t r, size_t n)
{
    if (f == NULL || (f->params == NULL && f->nparams > 0u)) {
        return LSC_EINVAL;
    }
    bool shape = f->reply ? f->cmd == r : w != 0u && f->cmd == w;
    return shape && f->nparams == n && lsc_lx_id_ok(f->id, f->cmd, f->reply) ? LSC_OK
                                                                              : LSC_EFRAME;
}

/* The two 16-bit values of f into *a, *b when ok (then 0), else LSC_EFRAME. */
static int get2(const lsc_lx_frame *f, int err, bool (*ok)(uint16_t, uint16_t), uint16_t *a,
                uint16_t *b)
{
    if (err != LSC_OK) {
        return err;
    }
    uint16_t x = lsc_get_u16(&f->params[0]), y = lsc_get_u16(&f->params[2]);
    if (!ok(x, y)) {
        return LSC_EFRAME;
    }
    *a = x;
    *b = y;
    return LSC_OK;
}

/* One byte of f into *v when ok (then 0), else LSC_EFRAME. */
static int get1(const lsc_lx_frame *f, int err, bool ok, uint8_t *v)
{
    if (err != LSC_OK) {
        return err;
    }
    if (!ok) {
        return LSC_EFRAME;
    }
    *v = f->params[0];
    return LSC_OK;
}

static bool move_ok(uint16_t pos, uint16_t time)
{
    return pos <= LSC_LX_POSITION_MAX && time <= LSC_LX_TIME_MAX;
}

static bool angle_ok(uint16_t min, uint16_t max)
{
    return min < max && max <= LSC_LX_POSITION_MAX;
}

static bool vin_ok(uint16_t min, uint16_t max)
{
    return min >= LSC_LX_VIN_MIN && min < max && max <= LSC_LX_VIN_MAX;
}

int lsc_lx_decode_move_time(const lsc_lx_frame *f, uint16_t *position, uint16_t *time_ms)
{
    if (position == NULL || time_ms == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_LX_MOVE_TIME_WRITE, LSC_LX_MOVE_TIME_READ, 4);
    if (err == LSC_EFRAME) {
        err = expect(f, LSC_LX_MOVE_TIME_WAIT_WRITE, LSC_LX_MOVE_TIME_WAIT_READ, 4);
    }
    return get2(f, err, move_ok, position, time_ms);
}

int lsc_lx_decode_angle_limit(const lsc_lx_frame *f, uint16_t *min, uint16_t *max)
{
    if (min == NULL || max == NULL) {
        return LSC_EINVAL;
    }
    return get2(f, expect(f, LSC_LX_ANGLE_LIMIT_WRITE, LSC_LX_ANGLE_LIMIT_READ, 4), angle_ok,
                min, max);
}

int lsc_lx_decode_vin_limit(const lsc_lx_frame *f, uint16_t *min_mv, uint16_t *max_mv)
{
    if (min_mv == NULL || max_mv == NULL) {
        return LSC_EINVAL;
    }
    return get2(f, expect(f, LSC_LX_VIN_LIMIT_WRITE, LSC_LX_VIN_LIMIT_READ, 4), vin_ok, min_mv,
                max_mv);
}

int lsc_lx_decode_id(const lsc_lx_frame *f, uint8_t *value)
{
    if (value == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_LX_ID_WRITE, LSC_LX_ID_READ, 1);
    /* a reply names its servo twice: both must agree */
    return get1(f, err, err == LSC_OK && f->params[0] <= LSC_LX_ID_MAX &&
                            (!f->reply || f->params[0] == f->id),
                value);
}

int lsc_lx_decode_offset(const lsc_lx_frame *f, int8_t *offset)
{
    if (offset == NULL) {
        return LSC_EINVAL;
    }
    uint8_t v = 0;
    int err = expect(f, LSC_LX_OFFSET_ADJUST, LSC_LX_OFFSET_READ, 1);
    /* -125..125 in two's complement: 0..125 or 131..255 */
    err = get1(f, err, err == LSC_OK && (f->params[0] <= 125u || f->params[0] >= 131u), &v);
    if (err == LSC_OK) {
        *offset = (int8_t)v;
    }
    return err;
}

int lsc_lx_decode_temp_limit(const lsc_lx_frame *f, uint8_t *celsius)
{
    if (celsius == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_LX_TEMP_LIMIT_WRITE, LSC_LX_TEMP_LIMIT_READ, 1);
    return get1(f, err, err == LSC_OK && f->params[0] >= LSC_LX_TEMP_LIMIT_MIN &&
                            f->params[0] <= LSC_LX_TEMP_LIMIT_MAX,
                celsius);
}

int lsc_lx_decode_temp(const lsc_lx_frame *f, uint8_t *celsius)
{
    if (celsius == NULL) {
        return LSC_EINVAL;
    }
    return get1(f, expect(f, 0, LSC_LX_TEMP_READ, 1), true, celsius);
}

int lsc_lx_decode_vin(const lsc_lx_frame *f, uint16_t *millivolts)
{
    if (millivolts == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, 0, LSC_LX_VIN_READ, 2);
    if (err == LSC_OK) {
        *millivolts = lsc_get_u16(f->params);
    }
    return err;
}

int lsc_lx_decode_position(const lsc_lx_frame *f, int16_t *position)
{
    if (position == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, 0, LSC_LX_POS_READ, 2);
    if (err == LSC_OK) {
        *position = (int16_t)lsc_get_u16(f->params); /* two's complement on every target */
    }
    return err;
}

int lsc_lx_decode_motor_mode(const lsc_lx_frame *f, uint8_t *mode, int16_t *speed)
{
    if (mode == NULL || speed == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_LX_MOTOR_MODE_WRITE, LSC_LX_MOTOR_MODE_READ, 4);
    if (err != LSC_OK) {
        return err;
    }
    int16_t s = (int16_t)lsc_get_u16(&f->params[2]);
    if (f->params[0] > LSC_LX_MODE_MOTOR || s < -LSC_LX_SPEED_MAX || s > LSC_LX_SPEED_MAX) {
        return LSC_EFRAME;
    }
    *mode = f->params[0];
    *speed = s;
    return LSC_OK;
}

/* A 0/1 byte of w or r into *on (on_value: the byte that means true). */
static int get_bool(const lsc_lx_frame *f, uint8_t w, uint8_t r, uint8_t on_value, bool *on)
{
    if (on == NULL) {
        return LSC_EINVAL;
    }
    uint8_t v = 0;
    int err = expect(f, w, r, 1);
    err = get1(f, err, err == LSC_OK && f->params[0] <= 1u, &v);
    if (err == LSC_OK) {
        *on = v == on_value;
    }
    return err;
}

int lsc_lx_decode_load(const lsc_lx_frame *f, bool *on)
{
    return get_bool(f, LSC_LX_LOAD_WRITE, LSC_LX_LOAD_READ, 1, on);
}

int lsc_lx_decode_led_ctrl(const lsc_lx_frame *f, bool *on)
{
    return get_bool(f, LSC_LX_LED_CTRL_WRITE, LSC_LX_LED_CTRL_READ, 0, on);
}

int lsc_lx_decode_led_error(const lsc_lx_frame *f, uint8_t *mask)
{
    if (mask == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_LX_LED_ERROR_WRITE, LSC_LX_LED_ERROR_READ, 1);
    return get1(f, err, err == LSC_OK && f->params[0] <= LSC_LX_ALARM_ALL, mask);
}
