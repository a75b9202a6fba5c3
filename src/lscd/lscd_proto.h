/* lscd's wire protocol (docs/lscd-protocol.md): the helpers the daemon
 * (daemon/) and the client transport (lscd_io.c) share. Internal: not part of
 * the library's API (the shared library does not export these). */
#ifndef LSC_LSCD_PROTO_H
#define LSC_LSCD_PROTO_H

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/lscd.h"

/* Most argument bytes a control frame carries (after its op byte). */
#define LSCD_ARGS_MAX (LSC_PARAMS_MAX - 1u)

/* Longest a client may ask for as its per-frame timeout (ms). */
#define LSCD_TIMEOUT_MAX 600000u

static inline void lscd_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)((v >> 24) & 0xFFu);
}

static inline uint32_t lscd_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

/* Writes the control frame 55 55 LEN CD OP ARGS[0..n) at buf; returns its
 * length, or LSC_EINVAL (n > LSCD_ARGS_MAX, or n == 82: LEN would be 0x55)
 * or LSC_ENOSPC. */
int lscd_encode_ctl(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *args, size_t n);

/* The same with text as the arguments after `prefix_n` bytes of prefix: the
 * text is cut to fit one frame (and so that LEN is never 0x55). */
int lscd_encode_ctl_text(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *prefix,
                         size_t prefix_n, const char *text);

/* What the daemon does with a controller frame a client sent. */
typedef enum lscd_job_kind {
    LSCD_JOB_SEND = 0,    /* no reply expected: sent as it is */
    LSCD_JOB_BATTERY = 1, /* 15 with no parameters: the battery request */
    LSCD_JOB_READ = 2,    /* 21, a valid position request: ids */
    LSCD_JOB_OFFSETS = 3  /* 23, a valid offset request: ids */
} lscd_job_kind;

/* Classifies a frame (valid as the parser returned it): its kind and, for
 * READ and OFFSETS, the ids (ids[LSC_READ_MAX], *nids). Never fails: a frame
 * that is not a valid request is SEND. */
lscd_job_kind lscd_classify(const lsc_frame *f, uint8_t *ids, size_t *nids);

/* Whether a controller command is one this protocol knows to have no reply
 * (3, 6, 7, 8, 11, 20, 24) or to be a request whose reply lscd routes (15,
 * 21, 23). Frames with any other command may be answered by frames lscd
 * does not know: it routes those to the client that last sent one. */
bool lscd_cmd_known(uint8_t cmd);

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

/* lscd's record of the port it holds (lsc/lscd.h, LSC_LSCD_RECORD_SUFFIX;
 * lscd_record.c). lscd_record_path: DIR/NAME.record of port, into out[cap];
 * its length, or lsc_lscd_name's and lsc_lscd_socket_path's errors.
 * lscd_record_write: writes the record of port (this process serves it on
 * socket_path; both made absolute) atomically, making DIR if missing (its
 * last component), and its path to record[cap]; 0, or LSC_EACCES (DIR not
 * writable), LSC_EINVAL (a path with a newline), LSC_ENOSPC, LSC_EIO. The
 * caller removes it (unlink) when it stops. */
int lscd_record_path(const char *port, char *out, size_t cap);
int lscd_record_write(const char *port, const char *socket_path, char *record, size_t cap);

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

/* Whether cmd is a controller notification (6, 7, 8). */
static inline bool lscd_is_notification(uint8_t cmd)
{
    return cmd == LSC_CMD_GROUP_RUN || cmd == LSC_CMD_GROUP_STOP ||
           cmd == LSC_CMD_GROUP_COMPLETE;
}

#endif
