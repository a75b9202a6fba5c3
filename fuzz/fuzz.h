/* Shared by every fuzz harness and the driver (fuzz/driver.c). */
#ifndef LSC_FUZZ_H
#define LSC_FUZZ_H

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

#endif
