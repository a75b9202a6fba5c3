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

/* Optimising for speed (any GCC-compatible build not at -Os): the parser
 * then has a fast path for parameter bytes in lsc_parser_feed, a bulk path of
 * its own in lsc_parser_feed_buf (a whole frame at once when the input holds
 * one), the slow paths of both out of line (LSC_SLOW), and its per-byte
 * checks inlined (LSC_STEP, LSC_REJECT).
 * When optimising for size (or with another compiler), lsc_parser_feed_buf
 * feeds byte by byte through lsc_parser_feed (the same results). */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define LSC_FAST 1
#define LSC_SLOW __attribute__((noinline))
#if defined(__OPTIMIZE__)
#define LSC_STEP __attribute__((always_inline)) inline
#define LSC_REJECT __attribute__((always_inline)) inline
#else /* -O0 (the coverage build): one copy each, so every branch counts once */
#define LSC_STEP
#define LSC_REJECT
#endif
#else
#define LSC_FAST 0
#define LSC_SLOW
#define LSC_STEP
#if defined(__AVR__) && defined(__GNUC__)
/* AVR: where a sketch inlines the parser's step into its one caller, and
 * the counters it never reads are dropped, the rules inlined there too are
 * smaller than a call (examples/arduino/VendorParityRead: 3606 B, 3680 B
 * with the call; the parser's object alone is 757 B, 737 B with the call) */
#define LSC_REJECT __attribute__((always_inline)) inline
#else
#define LSC_REJECT LSC_NOINLINE
#endif
#endif

/* A byte-sized value in arithmetic (the parser's positions, LEN, counts):
 * a byte on AVR, whose registers are 8 bits wide (a wider value costs a
 * register pair and an instruction more per operation), the native
 * unsigned elsewhere (where a byte costs a zero-extension per use: on
 * x86-64 uint_fast8_t is a byte, 2.6 instructions more per byte through
 * the parser). Values that may wrap are reduced where they must be. */
#if defined(__AVR__)
typedef uint8_t lsc_small;
#else
typedef unsigned lsc_small;
#endif

/* Constant tables: in flash on AVR, where other constants are copied to RAM
 * at start-up (LSC_ROM on the definition, lsc_rom_u8 to read a byte of it:
 * the LPM instruction); ordinary constants elsewhere. */
#if defined(__AVR__) && defined(__GNUC__)
#define LSC_ROM __attribute__((__progmem__))
static inline uint8_t lsc_rom_u8(const uint8_t *at)
{
    /* a byte the compiler knows (a constant index, after inlining) needs no
     * read at all: only then is *at used, folded to its value */
    if (__builtin_constant_p(*at)) {
        return *at;
    }
    uint8_t v;
    __asm__("lpm %0, Z" : "=r"(v) : "z"(at));
    return v;
}
#else
#define LSC_ROM
static inline uint8_t lsc_rom_u8(const uint8_t *at)
{
    return *at;
}
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
/* The lists' shapes, indexed by LSC_LIST_...: cmd, head, width, max. */
extern const uint8_t lsc_lists[6][4] LSC_ROM;

static inline lsc_list lsc_list_of(unsigned kind)
{
    const uint8_t *at = lsc_lists[kind];
    lsc_list l = {lsc_rom_u8(&at[0]), lsc_rom_u8(&at[1]), lsc_rom_u8(&at[2]), lsc_rom_u8(&at[3])};
    return l;
}

#endif
