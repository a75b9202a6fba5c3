/* lscd's wire protocol (docs/lscd-protocol.md): the client transport's
 * helpers (lscd_io.c). Internal: not part of the library's API (the shared
 * library does not export these); what the daemon needs of the wire is
 * public (lsc/lscd.h). */
#ifndef LSC_LSCD_PROTO_H
#define LSC_LSCD_PROTO_H

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/lscd.h"

#define LSCD_ARGS_MAX LSC_LSCD_ARGS_MAX
#define LSCD_TIMEOUT_MAX LSC_LSCD_TIMEOUT_MAX

/* Whether a send or receive on an lscd socket failed with e (errno) only
 * because it would block or was interrupted: try again later. */
static inline bool lscd_would_block(int e)
{
#if EAGAIN != EWOULDBLOCK
    if (e == EWOULDBLOCK) {
        return true;
    }
#endif
    return e == EAGAIN || e == EINTR;
}

/* What a client made of bytes from an lscd (lscd_client_digest). */
typedef struct lscd_client_facts {
    size_t frames_read;    /* controller frames the client's reads returned */
    size_t bytes_read;     /* their bytes */
    size_t status_items;   /* STATUS lines it took */
    bool hello;            /* HELLO seen */
    int open_error;        /* the error every later call would return (0: none) */
    int last_read;         /* the last read's result */
    char message[1024];    /* lsc_lscd_error then, cut to fit */
} lscd_client_facts;

/* For the fuzz target (fuzz/fuzz_lscd_client.c) and tests: a client's
 * connection state (no socket) takes data[0..n) as lscd's bytes, in chunks
 * of at most chunk bytes, then its reads drain what waits, then the end of
 * the connection. Each read's bytes go to read_fn (may be NULL). */
void lscd_client_digest(const uint8_t *data, size_t n, size_t chunk,
                        void (*read_fn)(void *user, const uint8_t *p, size_t len), void *user,
                        lscd_client_facts *out);

#endif
