/* The byte transport a client talks through, supplied by the caller: a
 * serial port on a host (lsc/serial.h), a Stream on Arduino, a UART on an
 * STM32, or the in-process virtual controller (lsc/sim.h). */
#ifndef LSC_IO_H
#define LSC_IO_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/version.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lsc_io {
    void *ctx; /* passed back to every function below */
    /* Sends all n bytes; returns n, or a negative LSC_E... code (LSC_EIO,
     * LSC_ENODEV, ...). Never sends part of them and returns success. */
    int (*write)(void *ctx, const uint8_t *data, size_t n);
    /* Waits up to timeout_ms for at least one byte, then returns as many as
     * are available (1..cap); returns 0 when nothing arrived in time, or a
     * negative LSC_E... code. timeout_ms 0 polls. */
    int (*read)(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms);
    /* A monotonic clock in milliseconds (wraps around at 2^32). */
    uint32_t (*now_ms)(void *ctx);
} lsc_io;

#ifdef __cplusplus
}
#endif

#endif /* LSC_IO_H */
