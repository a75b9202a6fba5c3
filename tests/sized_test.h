/* Tests of the structs that grow (a leading size_t size the caller sets to
 * sizeof of its headers): a caller built against older, shorter headers is
 * played by a struct whose size covers only its first fields, the rest
 * guard bytes that must stay as they are. */
#ifndef LSC_TESTS_SIZED_TEST_H
#define LSC_TESTS_SIZED_TEST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
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

/* The bytes of element i of an array of elements of size bytes at buf. */
static inline unsigned char *sized_element(void *buf, size_t size, size_t i)
{
    return (unsigned char *)buf + i * size;
}

/* The size field of the element at e. */
static inline size_t sized_size(const void *e)
{
    size_t size;
    memcpy(&size, e, sizeof size);
    return size;
}

/* A listing into elements that grow (lsc_serial_list_ports, lsc_hid_list):
 * out[0..cap), its line in message[0..msgcap). */
typedef int (*sized_list_fn)(void *out, size_t cap, char *message, size_t msgcap);

/* A listing into elements of stride bytes (out[0].size: a program built
 * against shorter or longer headers) in the n bytes at room, cap of them:
 * its count when each element written has its size set and no byte is
 * written past the first known of each (what this library's struct has) nor
 * after the cap-th; else -1, what differs said on stderr (cap elements that
 * do not fit in room: -1, nothing listed). */
static inline int sized_list_stride(sized_list_fn list, void *room, size_t n, size_t stride,
                                    size_t cap, size_t known)
{
    if (cap * stride > n) {
        (void)fprintf(stderr, "%zu elements of %zu bytes do not fit in %zu\n", cap, stride, n);
        return -1;
    }
    sized_guard(room, n, stride);
    int r = list(room, cap, NULL, 0);
    bool ok = r >= (int)cap && sized_untouched(room, cap * stride, n);
    for (size_t i = 0; i < cap; i++) {
        const unsigned char *e = sized_element(room, stride, i);
        ok = ok && sized_size(e) == stride && sized_untouched(e, known, stride);
    }
    if (!ok) {
        (void)fprintf(stderr, "elements of %zu bytes: %d, or a size not set, or a byte "
                              "written past the first %zu of one or after the %zu-th\n",
                      stride, r, known, cap);
    }
    return ok ? r : -1;
}

/* Whether list refuses an out[0].size below least (0, the size field
 * alone, least - 1) of two elements of n bytes at room (type: the struct's
 * name): LSC_EINVAL with its line, no byte written. Says what differs on
 * stderr. */
static inline bool sized_list_refuses_small(sized_list_fn list, void *room, size_t n,
                                            size_t least, const char *type)
{
    const size_t too_small[] = {0, sizeof(size_t), least - 1u};
    for (size_t k = 0; k < sizeof too_small / sizeof too_small[0]; k++) {
        char msg[256] = "", want[256];
        (void)snprintf(want, sizeof want,
                       "%s.size is %zu, less than %zu: set out[0].size to sizeof(%s); "
                       "nothing was listed",
                       type, too_small[k], least, type);
        sized_guard(room, 2u * n, too_small[k]);
        int r = list(room, 2, msg, sizeof msg);
        if (r != LSC_EINVAL || strcmp(msg, want) != 0 || sized_size(room) != too_small[k] ||
            !sized_untouched(room, sizeof(size_t), 2u * n)) {
            (void)fprintf(stderr, "size %zu: %d '%s', want LSC_EINVAL '%s', nothing written\n",
                          too_small[k], r, msg, want);
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
