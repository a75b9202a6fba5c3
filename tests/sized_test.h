/* Tests of the structs that grow (a leading size_t size the caller sets to
 * sizeof of its headers): a caller built against older, shorter headers is
 * played by a struct whose size covers only its first fields, the rest
 * guard bytes that must stay as they are. */
#ifndef LSC_TESTS_SIZED_TEST_H
#define LSC_TESTS_SIZED_TEST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "lsc/device.h"
#include "lsc/link.h"

#define SIZED_GUARD 0xA5u

/* Fills the struct s (n bytes) with guard bytes, then sets its size to size. */
static inline void sized_guard(void *s, size_t n, size_t size)
{
    memset(s, (int)SIZED_GUARD, n);
    memcpy(s, &size, sizeof size);
}

/* Whether s's bytes from..n still hold the guard. */
static inline bool sized_untouched(const void *s, size_t from, size_t n)
{
    const unsigned char *b = s;
    for (size_t i = from; i < n; i++) {
        if (b[i] != SIZED_GUARD) {
            return false;
        }
    }
    return true;
}

/* The frames d has sent so far. */
static inline uint64_t sized_frames_sent(const lsc_device *d)
{
    lsc_device_counters c = {.size = sizeof c};
    return lsc_device_get_counters(d, &c) == 0 ? c.frames_sent : UINT64_MAX;
}

#endif
