/* Typed decoders: each checks the whole frame before writing any output. */
#include "lsc/core.h"

#include "internal.h"

/* LSC_OK if f is the command cmd with exactly nparams parameter bytes. */
static int expect(const lsc_frame *f, uint8_t cmd, size_t nparams)
{
    if (f == NULL || (f->params == NULL && f->nparams > 0)) {
        return LSC_EINVAL;
    }
    return f->cmd == cmd && f->nparams == nparams ? LSC_OK : LSC_EFRAME;
}

/* The count byte of a list frame (0 if there is none), whose items take
 * `width` bytes each after `head` bytes of parameters. */
static size_t list_count(const lsc_frame *f, size_t head, size_t width)
{
    if (f == NULL || f->nparams <= head || f->params == NULL) {
        return 0;
    }
    size_t n = f->params[0];
    return f->nparams == head + width * n ? n : 0;
}

/* Validates a list of n items of `width` bytes at `items` (the id first):
 * n >= 1 and distinct ids, and that n fits the caller's cap. */
static int check_list(const uint8_t *items, size_t n, size_t width, size_t cap)
{
    if (n == 0 || !lsc_ids_distinct(items, width, n)) {
        return LSC_EFRAME;
    }
    return n > cap ? LSC_ENOSPC : LSC_OK;
}

static void get_servos(const uint8_t *items, size_t n, lsc_servo *servos)
{
    for (size_t i = 0; i < n; i++) {
        servos[i].id = items[3 * i];
        servos[i].position = lsc_get_u16(&items[3 * i + 1]);
    }
}

int lsc_decode_servo_move(const lsc_frame *f, uint16_t *time_ms, lsc_servo *servos, size_t cap)
{
    if (time_ms == NULL || (servos == NULL && cap > 0)) {
        return LSC_EINVAL;
    }
    size_t n = list_count(f, 3, 3);
    int err = expect(f, LSC_CMD_SERVO_MOVE, 3 + 3 * n);
    if (err == LSC_OK) {
        err = check_list(&f->params[3], n, 3, cap);
    }
    if (err != LSC_OK) {
        return err;
    }
    *time_ms = lsc_get_u16(&f->params[1]);
    get_servos(&f->params[3], n, servos);
    return (int)n;
}

/* A frame whose parameters are one byte and one 16-bit value. */
static int decode_u8_u16(const lsc_frame *f, uint8_t cmd, uint8_t *a, uint16_t *b)
{
    if (a == NULL || b == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, cmd, 3);
    if (err == LSC_OK) {
        *a = f->params[0];
        *b = lsc_get_u16(&f->params[1]);
    }
    return err;
}

int lsc_decode_group_run(const lsc_frame *f, uint8_t *group, uint16_t *times)
{
    return decode_u8_u16(f, LSC_CMD_GROUP_RUN, group, times);
}

int lsc_decode_group_stop(const lsc_frame *f)
{
    return expect(f, LSC_CMD_GROUP_STOP, 0);
}

int lsc_decode_group_complete(const lsc_frame *f, uint8_t *group, uint16_t *times)
{
    return decode_u8_u16(f, LSC_CMD_GROUP_COMPLETE, group, times);
}

int lsc_decode_group_speed(const lsc_frame *f, uint8_t *group, uint16_t *percent)
{
    return decode_u8_u16(f, LSC_CMD_GROUP_SPEED, group, percent);
}

int lsc_decode_battery_request(const lsc_frame *f)
{
    return expect(f, LSC_CMD_BATTERY, 0);
}

int lsc_decode_battery_reply(const lsc_frame *f, uint16_t *millivolts)
{
    if (millivolts == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_CMD_BATTERY, 2);
    if (err == LSC_OK) {
        *millivolts = lsc_get_u16(f->params);
    }
    return err;
}

/* A frame whose parameters are a count and that many (at most max) distinct ids. */
static int decode_ids(const lsc_frame *f, uint8_t cmd, uint8_t *ids, size_t cap, size_t max)
{
    if (ids == NULL && cap > 0) {
        return LSC_EINVAL;
    }
    size_t n = list_count(f, 1, 1);
    int err = expect(f, cmd, 1 + n);
    if (err == LSC_OK) {
        err = check_list(&f->params[1], n > max ? 0 : n, 1, cap);
    }
    if (err != LSC_OK) {
        return err;
    }
    for (size_t i = 0; i < n; i++) {
        ids[i] = f->params[1 + i];
    }
    return (int)n;
}

int lsc_decode_unload(const lsc_frame *f, uint8_t *ids, size_t cap)
{
    return decode_ids(f, LSC_CMD_UNLOAD, ids, cap, LSC_UNLOAD_MAX);
}

int lsc_decode_pos_request(const lsc_frame *f, uint8_t *ids, size_t cap)
{
    /* More ids than a reply can carry: no controller could answer it. */
    return decode_ids(f, LSC_CMD_POS_READ, ids, cap, LSC_READ_MAX);
}

int lsc_decode_pos_reply(const lsc_frame *f, lsc_servo *servos, size_t cap)
{
    if (servos == NULL && cap > 0) {
        return LSC_EINVAL;
    }
    size_t n = list_count(f, 1, 3);
    int err = expect(f, LSC_CMD_POS_READ, 1 + 3 * n);
    if (err == LSC_OK) {
        err = check_list(&f->params[1], n, 3, cap);
    }
    if (err != LSC_OK) {
        return err;
    }
    get_servos(&f->params[1], n, servos);
    return (int)n;
}
