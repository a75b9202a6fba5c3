/* lscd: what a client's bytes ask for (docs/lscd-protocol.md). Pure: no I/O,
 * no allocation; the state is the caller's. The fuzz target fuzz_lscd runs
 * it on any input. */
#ifndef LSCD_WIRE_H
#define LSCD_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <errno.h>

#include "lsc/core.h"
#include "lsc/lscd.h"

/* ---- The daemon's side of the wire (docs/lscd-protocol.md; the numbers and
 * the control frame's encoder are public: lsc/lscd.h) --------------------- */

#define LSCD_ARGS_MAX LSC_LSCD_ARGS_MAX
#define LSCD_TIMEOUT_MAX LSC_LSCD_TIMEOUT_MAX

/* lsc_lscd_encode_ctl (lsc/lscd.h). */
static inline int lscd_encode_ctl(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *args,
                                  size_t n)
{
    return lsc_lscd_encode_ctl(buf, cap, op, args, n);
}

/* The same with text as the arguments after `prefix_n` bytes of prefix: the
 * text is cut to fit one frame (and so that LEN is never 0x55). */
int lscd_encode_ctl_text(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *prefix,
                         size_t prefix_n, const char *text);

/* What the daemon does with a controller frame a client sent. */
typedef enum lscd_job_kind {
    LSCD_JOB_SEND = 0,    /* no reply expected: sent as it is */
    LSCD_JOB_BATTERY = 1, /* 15 with no parameters: the battery request */
    LSCD_JOB_READ = 2,    /* 21, a valid position request: ids */
    LSCD_JOB_OFFSETS = 3, /* 23, a valid offset request: ids */
    LSCD_JOB_HALT = 4     /* OP_HALT: lsc_device_halt (cmd LSC_LSCD_CMD) */
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

/* Whether a send or receive on a socket failed with e (errno) only because
 * it would block or was interrupted: try again later. */
static inline bool lscd_would_block(int e)
{
#if EAGAIN != EWOULDBLOCK
    if (e == EWOULDBLOCK) {
        return true;
    }
#endif
    return e == EAGAIN || e == EINTR;
}

/* Whether cmd is a controller notification (6, 7, 8). */
static inline bool lscd_is_notification(uint8_t cmd)
{
    return cmd == LSC_CMD_GROUP_RUN || cmd == LSC_CMD_GROUP_STOP ||
           cmd == LSC_CMD_GROUP_COMPLETE;
}

/* ---- What a client's bytes ask for ----------------------------------------------- */

/* One thing a client asked for. */
typedef enum lscd_in_kind {
    LSCD_IN_NONE = 0,   /* the bytes so far complete nothing */
    LSCD_IN_FRAME,      /* a controller frame: `job` says what to do with it */
    LSCD_IN_CONTROL,    /* a control request: op and its arguments */
    LSCD_IN_BAD_CONTROL /* a control frame refused: op, why */
} lscd_in_kind;

/* A controller frame to handle: the frame's command and parameters (copied),
 * and what kind of job it is. */
typedef struct lscd_job {
    lscd_job_kind kind;
    uint8_t cmd;
    uint8_t nparams;
    uint8_t params[LSC_PARAMS_MAX];
    uint8_t ids[LSC_READ_MAX]; /* READ, OFFSETS: the ids asked for */
    size_t nids;
} lscd_job;

typedef struct lscd_in {
    lscd_in_kind kind;
    lscd_job job;      /* FRAME */
    uint8_t op;        /* CONTROL, BAD_CONTROL */
    uint32_t a, b;     /* CONTROL arguments: SUBSCRIBE/MODE a (0..255), TIMEOUT a,
                          LEASE a = ms, b = wait_ms, PING a = token */
    const char *why;   /* BAD_CONTROL: static text */
} lscd_in;

typedef struct lscd_wire {
    lsc_parser parser;
    uint8_t buf[LSC_FRAME_MAX];
} lscd_wire;

void lscd_wire_init(lscd_wire *w);

/* Feeds data[0..n) up to and including the byte that completes something
 * (then *out says what) and returns how many bytes were used (1..n when
 * n > 0; 0 when n is 0). When all n are used and nothing completed,
 * out->kind is LSCD_IN_NONE. Malformed input is skipped (the parser's
 * counters: w->parser.discarded, w->parser.errors). */
size_t lscd_wire_feed(lscd_wire *w, const uint8_t *data, size_t n, lscd_in *out);

/* Decodes one control frame (cmd LSC_LSCD_CMD) into out (CONTROL or
 * BAD_CONTROL). */
void lscd_wire_control(const lsc_frame *f, lscd_in *out);

#endif
