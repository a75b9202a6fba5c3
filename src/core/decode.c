/* Typed decoders: each checks the whole frame before writing any output. */
#include "lsc/core.h"

#include "internal.h"

/* LSC_OK if f is the command cmd with head parameter bytes, then (a list)
 * width more for each of the count its first parameter says. */
LSC_NOINLINE static int expect(const lsc_frame *f, uint8_t cmd, size_t head, size_t width)
{
    if (f == NULL || (f->params == NULL && f->nparams > 0)) {
        return LSC_EINVAL;
    }
    size_t n = f->nparams > 0 ? f->params[0] : 0;
    return f->cmd == cmd && f->nparams == head + width * n ? LSC_OK : LSC_EFRAME;
}

/* Checks that f is that list with 1..max items of distinct ids, and that
 * they fit in the caller's out[cap]; then copies them there (lsc_servo for
 * width 3, lsc_servo_offset for width 2, ids for width 1). Returns the item
 * count or an error. */
static int decode_list(const lsc_frame *f, void *out, size_t cap, unsigned kind)
{
    const lsc_list l = lsc_list_of(kind);
    if (out == NULL && cap > 0) {
        return LSC_EINVAL;
    }
    int err = expect(f, l.cmd, l.head, l.width);
    if (err != LSC_OK) {
        return err;
    }
    size_t n = f->params[0];
    const uint8_t *items = &f->params[l.head];
    /* n - 1 wraps for n = 0: n must be in 1..max */
    if (n - 1u >= l.max || !lsc_ids_distinct(items, l.width, n)) {
        return LSC_EFRAME;
    }
    if (n > cap) {
        return LSC_ENOSPC;
    }
    for (size_t i = 0; i < n; i++, items += l.width) {
        if (l.width == 1) {
            ((uint8_t *)out)[i] = items[0];
        } else if (l.width == 2) {
            lsc_servo_offset *o = &((lsc_servo_offset *)out)[i];
            o->id = items[0];
            o->offset = (int8_t)items[1]; /* two's complement on every target */
        } else {
            lsc_servo *s = &((lsc_servo *)out)[i];
            s->id = items[0];
            s->position = lsc_get_u16(&items[1]);
        }
    }
    return (int)n;
}

int lsc_decode_servo_move(const lsc_frame *f, uint16_t *time_ms, lsc_servo *servos, size_t cap)
{
    if (time_ms == NULL) {
        return LSC_EINVAL;
    }
    int n = decode_list(f, servos, cap, LSC_LIST_MOVE);
    if (n > 0) {
        *time_ms = lsc_get_u16(&f->params[1]);
    }
    return n;
}

int lsc_decode_unload(const lsc_frame *f, uint8_t *ids, size_t cap)
{
    return decode_list(f, ids, cap, LSC_LIST_UNLOAD);
}

int lsc_decode_pos_request(const lsc_frame *f, uint8_t *ids, size_t cap)
{
    /* More ids than a reply can carry: no controller could answer it. */
    return decode_list(f, ids, cap, LSC_LIST_REQUEST);
}

int lsc_decode_pos_reply(const lsc_frame *f, lsc_servo *servos, size_t cap)
{
    return decode_list(f, servos, cap, LSC_LIST_REPLY);
}

/* A frame whose parameters are one byte, stored at a, and one 16-bit value;
 * or (the battery) the value alone. */
LSC_NOINLINE static int decode_u16(const lsc_frame *f, uint8_t cmd, uint8_t *a, uint16_t *b)
{
    if (a == NULL || b == NULL) {
        return LSC_EINVAL;
    }
    size_t n = cmd == LSC_CMD_BATTERY ? 2 : 3;
    int err = expect(f, cmd, n, 0);
    if (err == LSC_OK) {
        const uint8_t *at = f->params;
        *a = at[0];
        *b = lsc_get_u16(&at[n - 2]);
    }
    return err;
}

int lsc_decode_group_run(const lsc_frame *f, uint8_t *group, uint16_t *times)
{
    return decode_u16(f, LSC_CMD_GROUP_RUN, group, times);
}

int lsc_decode_group_stop(const lsc_frame *f)
{
    return expect(f, LSC_CMD_GROUP_STOP, 0, 0);
}

int lsc_decode_group_complete(const lsc_frame *f, uint8_t *group, uint16_t *times)
{
    return decode_u16(f, LSC_CMD_GROUP_COMPLETE, group, times);
}

int lsc_decode_group_speed(const lsc_frame *f, uint8_t *group, uint16_t *percent)
{
    return decode_u16(f, LSC_CMD_GROUP_SPEED, group, percent);
}

int lsc_decode_battery_request(const lsc_frame *f)
{
    return expect(f, LSC_CMD_BATTERY, 0, 0);
}

int lsc_decode_battery_reply(const lsc_frame *f, uint16_t *millivolts)
{
    uint8_t low; /* the value's low byte again: not needed */
    return decode_u16(f, LSC_CMD_BATTERY, &low, millivolts);
}

int lsc_decode_offset_request(const lsc_frame *f, uint8_t *ids, size_t cap)
{
    return decode_list(f, ids, cap, LSC_LIST_OFFSET_REQUEST);
}

int lsc_decode_offset_reply(const lsc_frame *f, lsc_servo_offset *servos, size_t cap)
{
    return decode_list(f, servos, cap, LSC_LIST_OFFSET_REPLY);
}

int lsc_decode_offset_adjust(const lsc_frame *f, uint8_t *id, int8_t *offset)
{
    if (id == NULL || offset == NULL) {
        return LSC_EINVAL;
    }
    int err = expect(f, LSC_CMD_OFFSET_ADJUST, 2, 0);
    if (err == LSC_OK) {
        *id = f->params[0];
        *offset = (int8_t)f->params[1];
    }
    return err;
}
