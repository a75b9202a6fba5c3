/* Helpers shared by the core's encoders and decoders (not part of the API). */
#ifndef LSC_CORE_INTERNAL_H
#define LSC_CORE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* For helpers when optimising for size: inlining them into their callers
 * (which -Os does for static functions) makes the core bigger. At -O2 the
 * compiler is left to inline them, for speed. */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define LSC_NOINLINE __attribute__((noinline))
#else
#define LSC_NOINLINE
#endif

/* The slow path of a function with a fast path: kept out of line for speed,
 * so that the fast path needs no stack frame; when optimising for size, left
 * to the compiler (one caller: inlining it saves the call). */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define LSC_COLD __attribute__((noinline))
#else
#define LSC_COLD
#endif

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

/* A list message: its command, the parameter bytes before the items (the
 * count first), the bytes of one item, and the most items it may carry. */
typedef struct lsc_list {
    uint8_t cmd, head, width, max;
} lsc_list;

enum {
    LSC_LIST_MOVE,    /* servo_move: count, time, (id, pos)... */
    LSC_LIST_UNLOAD,  /* mult_servo_unload: count, ids */
    LSC_LIST_REQUEST, /* mult_servo_pos_read request: count, ids */
    LSC_LIST_REPLY,   /* mult_servo_pos_read reply: count, (id, pos)... */
    LSC_LIST_OFFSET_REQUEST, /* servo offset read request: count, ids */
    LSC_LIST_OFFSET_REPLY    /* servo offset read reply: count, (id, offset)... */
};
extern const lsc_list lsc_lists[6]; /* indexed by LSC_LIST_... */

#endif
