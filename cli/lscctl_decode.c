/* lscctl decode: hex from the arguments or standard input, into frames. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lscctl.h"
#include "lscctl_parse.h"

typedef struct decoder {
    const lscctl_opts *o;
    lsc_parser p;
    uint8_t buf[LSC_FRAME_MAX];
    uint8_t pending[LSC_FRAME_MAX + 1]; /* bytes fed since the last frame or discard */
    size_t npending;
    uint8_t bad[64];   /* discarded bytes not yet reported */
    size_t nbad;
    const char *bad_why;
    unsigned long invalid; /* bytes reported as not a valid frame */
} decoder;

static void flush_bad(decoder *d)
{
    if (d->nbad > 0) {
        char hex[LSCCTL_HEX_MAX];
        lscctl_hex(hex, sizeof hex, d->bad, d->nbad);
        lscctl_error_print(stdout, d->o->json, d->bad_why, hex);
        d->invalid += d->nbad;
        d->nbad = 0;
    }
}

static void add_bad(decoder *d, const uint8_t *bytes, size_t n, const char *why)
{
    for (size_t i = 0; i < n; i++) {
        if (d->nbad == sizeof d->bad || (d->nbad > 0 && strcmp(why, d->bad_why) != 0)) {
            flush_bad(d);
        }
        d->bad_why = why;
        d->bad[d->nbad++] = bytes[i];
    }
}

/* The core's own words: noise, or a malformed frame (with a full-size parser
 * buffer every other parser error is one). */
static const char *reason(int err)
{
    return lsc_strerror(err == LSC_ESYNC ? LSC_ESYNC : LSC_EFRAME);
}

static bool all_header(const uint8_t *bytes, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (bytes[i] != LSC_HEADER_BYTE) {
            return false;
        }
    }
    return true;
}

static void feed(decoder *d, uint8_t byte)
{
    lsc_frame f;
    uint32_t before = d->p.discarded;
    int r = lsc_parser_feed(&d->p, byte, &f);
    d->pending[d->npending++] = byte;
    size_t dropped = d->p.discarded - before;
    if (dropped > 0) { /* always the oldest pending bytes */
        add_bad(d, d->pending, dropped, reason(r < 0 ? r : LSC_EFRAME));
        d->npending -= dropped;
        memmove(d->pending, d->pending + dropped, d->npending);
    }
    if (r != 1) {
        return;
    }
    if (d->nbad > 0 && strcmp(d->bad_why, reason(LSC_ESYNC)) == 0 &&
        all_header(d->bad, d->nbad)) {
        d->nbad = 0; /* 55 55 55 02 07: extra header bytes before a frame */
    }
    char hex[LSCCTL_HEX_MAX], why[96];
    lscctl_msg m;
    lscctl_hex(hex, sizeof hex, d->pending, d->npending);
    d->npending = 0;
    if (lscctl_msg_decode(&m, &f, d->o->from, why, sizeof why) != 0) {
        flush_bad(d);
        lscctl_error_print(stdout, d->o->json, why, hex);
        d->invalid += f.nparams + 4u;
        return;
    }
    flush_bad(d);
    lscctl_msg_print(stdout, &m, d->o->json, true, hex);
}

/* Reports what is left at the end of the input. */
static int finish(decoder *d)
{
    add_bad(d, d->pending, d->npending, "incomplete frame");
    flush_bad(d);
    if (d->invalid > 0) {
        return lscctl_fail(d->o, LSCCTL_EXIT_FAIL,
                           "%lu byte%s not a valid frame (see the error lines)", d->invalid,
                           d->invalid == 1 ? " was" : "s were");
    }
    return LSCCTL_EXIT_OK;
}

int lscctl_cmd_decode(const lscctl_opts *o, int argc, char **argv)
{
    decoder d;
    char why[160];
    memset(&d, 0, sizeof d);
    d.o = o;
    lsc_parser_init(&d.p, d.buf, sizeof d.buf);
    if (argc > 0) { /* check every argument before printing anything */
        size_t total = 0, n = 0;
        for (int i = 0; i < argc; i++) {
            total += strlen(argv[i]) / 2u + 1u;
        }
        uint8_t *bytes = malloc(total);
        if (bytes == NULL) {
            return lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
        }
        for (int i = 0; i < argc; i++) {
            if (lscctl_parse_hex(argv[i], bytes, total, &n, why, sizeof why) != 0) {
                free(bytes);
                return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
            }
        }
        for (size_t i = 0; i < n; i++) {
            feed(&d, bytes[i]);
        }
        free(bytes);
        return finish(&d);
    }
    if (isatty(STDIN_FILENO)) {
        fprintf(stderr, "lscctl: decode: reading hex from standard input (end with Ctrl-D)\n");
    }
    char *line = NULL;
    size_t linecap = 0;
    unsigned long lineno = 0;
    ssize_t len;
    while ((len = getline(&line, &linecap, stdin)) >= 0) {
        size_t n = 0, text = strlen(line), cap = text / 2u + 1u;
        lineno++;
        if (text != (size_t)len) { /* a NUL byte: the parser would stop there */
            size_t column = text + 1u;
            free(line);
            fflush(stdout);
            return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                               "line %lu: a NUL byte (column %zu) is not hex: write pairs of "
                               "hex digits like 55 55 02 07",
                               lineno, column);
        }
        uint8_t *bytes = malloc(cap);
        if (bytes == NULL || lscctl_parse_hex(line, bytes, cap, &n, why, sizeof why) != 0) {
            free(bytes);
            free(line);
            fflush(stdout);
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "line %lu: %s", lineno,
                               bytes ? why : "out of memory");
        }
        for (size_t i = 0; i < n; i++) {
            feed(&d, bytes[i]);
        }
        free(bytes);
        fflush(stdout);
    }
    free(line);
    if (ferror(stdin)) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "cannot read standard input");
    }
    return finish(&d);
}
