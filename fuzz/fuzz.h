/* Shared by every fuzz harness and the driver (fuzz/driver.c). */
#ifndef LSC_FUZZ_H
#define LSC_FUZZ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* The entry point libFuzzer calls; the driver calls it too. Returns 0. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A property that must hold on any input: on failure, say which and abort
 * (libFuzzer and AFL++ record the input; the driver's ctest run fails). */
#define FUZZ_CHECK(cond)                                                                      \
    do {                                                                                      \
        if (!(cond)) {                                                                        \
            (void)fprintf(stderr, "%s:%d: property failed: %s\n", __FILE__, __LINE__, #cond);  \
            abort();                                                                          \
        }                                                                                     \
    } while (0)

/* The byte every harness fills its buffers' surroundings with. */
#define FUZZ_CANARY 0xA5u

/* True if the n bytes at p are all FUZZ_CANARY (nothing was written there). */
static inline bool fuzz_all_canary(const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++) {
        if (b[i] != FUZZ_CANARY) {
            return false;
        }
    }
    return true;
}

/* Reads an input as a stream of fields; past its end every byte is 0. */
typedef struct fuzz_cursor {
    const uint8_t *data;
    size_t size, at;
} fuzz_cursor;

static inline uint8_t fuzz_next(fuzz_cursor *c)
{
    return c->at < c->size ? c->data[c->at++] : 0;
}

#endif
