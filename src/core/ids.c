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

size_t lsc_ids_first_repeat(const uint8_t *ids, size_t stride, size_t n)
{
    /* each id against the ones before it: no table on the stack, at most
     * 252 * 251 / 2 comparisons; a pointer walks the ids (on AVR, no
     * multiplication by the stride), never past the last one */
    const uint8_t *at = ids;
    for (size_t i = 1; i < n; i++) {
        at += stride;
        for (const uint8_t *before = ids; before != at; before += stride) {
            if (*before == *at) {
                return i;
            }
        }
    }
    return n;
}

bool lsc_ids_distinct(const uint8_t *ids, size_t stride, size_t n)
{
    return lsc_ids_first_repeat(ids, stride, n) == n;
}
