#include "internal.h"

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
