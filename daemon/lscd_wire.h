/* lscd: what a client's bytes ask for (docs/lscd-protocol.md). Pure: no I/O,
 * no allocation; the state is the caller's. The fuzz target fuzz_lscd runs
 * it on any input. */
#ifndef LSCD_WIRE_H
#define LSCD_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lscd_proto.h"

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
