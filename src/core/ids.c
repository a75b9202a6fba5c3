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
    uint8_t seen[32] = {0}; /* one bit per possible id */
    for (size_t i = 0; i < n; i++) {
        uint8_t id = ids[i * stride];
        uint8_t bit = (uint8_t)(1u << (id & 7u));
        if (seen[id >> 3] & bit) {
            return false;
        }
        seen[id >> 3] = (uint8_t)(seen[id >> 3] | bit);
    }
    return true;
}
