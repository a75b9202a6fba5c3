/* Helpers shared by the core's encoders and decoders (not part of the API). */
#ifndef LSC_CORE_INTERNAL_H
#define LSC_CORE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

static inline void lsc_put_u16(uint8_t *at, uint16_t v)
{
    at[0] = (uint8_t)(v & 0xFFu);
    at[1] = (uint8_t)(v >> 8);
}

static inline uint16_t lsc_get_u16(const uint8_t *at)
{
    return (uint16_t)(at[0] | (at[1] << 8));
}

/* True if the n ids at ids[0], ids[stride], ... are all different. */
bool lsc_ids_distinct(const uint8_t *ids, size_t stride, size_t n);

#endif
