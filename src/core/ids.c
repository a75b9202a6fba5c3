/* Shared by the encoders and the decoders: the shapes of the list messages
 * and the check that ids are distinct. */
#include "lsc/core.h"

#include "internal.h"

const uint8_t lsc_lists[6][4] LSC_ROM = {
    [LSC_LIST_MOVE] = {LSC_CMD_SERVO_MOVE, 3, 3, LSC_MOVE_MAX},
    [LSC_LIST_UNLOAD] = {LSC_CMD_UNLOAD, 1, 1, LSC_UNLOAD_MAX},
    [LSC_LIST_REQUEST] = {LSC_CMD_POS_READ, 1, 1, LSC_READ_MAX},
    [LSC_LIST_REPLY] = {LSC_CMD_POS_READ, 1, 3, LSC_READ_MAX},
    [LSC_LIST_OFFSET_REQUEST] = {LSC_CMD_OFFSET_READ, 1, 1, LSC_OFFSET_MAX},
    [LSC_LIST_OFFSET_REPLY] = {LSC_CMD_OFFSET_READ, 1, 2, LSC_OFFSET_MAX},
};

/* The first id in ids[0..end) (every stride bytes) that an earlier one
 * repeats, or end: each id against the ones before it, no table on the
 * stack, at most 252 * 251 / 2 comparisons; pointers rather than indexes
 * (on AVR, no multiplication by the stride and no 16-bit counters). */
static const uint8_t *repeat_at(const uint8_t *ids, size_t stride, const uint8_t *end)
{
    const uint8_t *at = ids;
    for (; at != end; at += stride) {
        for (const uint8_t *before = ids; before != at; before += stride) {
            if (*before == *at) {
                return at;
            }
        }
    }
    return at;
}

size_t lsc_ids_first_repeat(const uint8_t *ids, size_t stride, size_t n)
{
    if (n == 0) {
        return 0; /* ids may be NULL: no arithmetic on it */
    }
    const uint8_t *at = repeat_at(ids, stride, ids + n * stride);
    size_t i = 0;
    for (const uint8_t *item = ids; item != at; item += stride) {
        i++;
    }
    return i;
}

bool lsc_ids_distinct(const uint8_t *ids, size_t stride, size_t n)
{
    const uint8_t *end = ids + n * stride;
    return repeat_at(ids, stride, end) == end;
}
