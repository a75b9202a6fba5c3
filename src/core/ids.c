/* Shared by the encoders and the decoders: the shapes of the list messages
 * and the check that ids are distinct. */
#include "lsc/core.h"

#include "internal.h"

const lsc_list lsc_lists[4] = {
    [LSC_LIST_MOVE] = {LSC_CMD_SERVO_MOVE, 3, 3, LSC_MOVE_MAX},
    [LSC_LIST_UNLOAD] = {LSC_CMD_UNLOAD, 1, 1, LSC_UNLOAD_MAX},
    [LSC_LIST_REQUEST] = {LSC_CMD_POS_READ, 1, 1, LSC_READ_MAX},
    [LSC_LIST_REPLY] = {LSC_CMD_POS_READ, 1, 3, LSC_READ_MAX},
};

bool lsc_ids_distinct(const uint8_t *ids, size_t stride, size_t n)
{
    /* one bit per possible id, in machine words (16 or 32 bits) */
    enum { BITS = sizeof(unsigned) * 8u };
    unsigned seen[256 / BITS] = {0};
    for (size_t i = 0; i < n; i++) {
        unsigned id = ids[i * stride];
        unsigned bit = 1u << (id % BITS);
        if (seen[id / BITS] & bit) {
            return false;
        }
        seen[id / BITS] |= bit;
    }
    return true;
}
