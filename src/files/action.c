/* What every action file format shares (files_internal.h): the keyframes in
 * memory (lsc_action_*), the messages, the output buffer. The bottom of
 * src/files: it calls nothing above it. */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/internal.h" /* lsc_ids_distinct */
#include "files_internal.h"
#include "../util/sized.h"

bool lsc_files_err_refused(const lsc_file_error *err)
{
    return err != NULL && err->size < LSC_SIZED_MIN(lsc_file_error, at);
}

void lsc_files_err_clear(lsc_file_error *err)
{
    lsc_file_error none = {.size = sizeof none};
    lsc_sized_give(err, &none, sizeof none);
}

static void set_message(lsc_file_error *err, unsigned long at, const char *fmt, va_list ap)
{
    if (err != NULL) {
        lsc_file_error e = {.size = sizeof e};
        e.at = at;
        (void)vsnprintf(e.message, sizeof e.message, fmt, ap);
        lsc_sized_give(err, &e, sizeof e);
    }
}

int lsc_files_fail(lsc_file_error *err, unsigned long at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    set_message(err, at, fmt, ap);
    va_end(ap);
    return LSC_EINVAL;
}

int lsc_files_fail_code(lsc_file_error *err, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    set_message(err, 0, fmt, ap);
    va_end(ap);
    return code;
}

int lsc_files_oom(lsc_file_error *err)
{
    (void)lsc_files_fail(err, 0, "out of memory");
    return LSC_ENOSPC;
}

int lsc_files_append(lsc_action *a, const uint16_t *w, const char *where, unsigned long at,
                     lsc_file_error *err)
{
    if (a->count >= LSC_ACTION_KEYFRAMES_MAX) {
        return lsc_files_fail(err, at, "%s %lu: more than %u keyframes (the most an action holds)",
                              where, at, LSC_ACTION_KEYFRAMES_MAX);
    }
    return lsc_action_append(a, w[0], w + 1) == 0 ? 0 : lsc_files_oom(err);
}

/* Room for n more bytes in b and `nul` bytes after them that do not count
 * (vsnprintf's NUL); false (and b->failed) when memory is out or b would
 * pass LSC_FILE_MAX_BYTES. */
static bool reserve(lsc_outbuf *b, size_t n, size_t nul)
{
    if (b->failed) {
        return false;
    }
    if (n > LSC_FILE_MAX_BYTES - b->len) {
        b->failed = true;
        b->toobig = true;
        return false;
    }
    if (n + nul > b->cap - b->len) {
        size_t cap = b->cap != 0 ? b->cap : 256u;
        while (cap - b->len < n + nul) {
            cap *= 2u; /* at most 2 x (LSC_FILE_MAX_BYTES + 1) */
        }
        uint8_t *bigger = realloc(b->data, cap);
        if (bigger == NULL) {
            b->failed = true;
            return false;
        }
        b->data = bigger;
        b->cap = cap;
    }
    return true;
}

void lsc_outbuf_put(lsc_outbuf *b, const void *bytes, size_t n)
{
    if (reserve(b, n, 0)) {
        memcpy(b->data + b->len, bytes, n);
        b->len += n;
    }
}

void lsc_outbuf_printf(lsc_outbuf *b, const char *fmt, ...)
{
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    /* room for the text and vsnprintf's NUL, which the next write covers */
    if (n > 0 && reserve(b, (size_t)n, 1)) {
        (void)vsnprintf((char *)b->data + b->len, (size_t)n + 1u, fmt, again);
        b->len += (size_t)n;
    }
    va_end(again);
}

void lsc_outbuf_rows(lsc_outbuf *b, const lsc_action *a, const char *lead, const char *sep,
                     const char *tail)
{
    for (uint32_t k = 0; k < a->count && !b->failed; k++) {
        const uint16_t *w = lsc_action_row(a, k);
        lsc_outbuf_printf(b, "%s%u", lead, w[0]);
        for (size_t i = 0; i < a->nservos; i++) {
            lsc_outbuf_printf(b, "%s%u", sep, w[1 + i]);
        }
        lsc_outbuf_printf(b, "%s\n", tail);
    }
}

int lsc_outbuf_finish(lsc_outbuf *b, uint8_t **out, size_t *len, lsc_file_error *err)
{
    if (b->failed) {
        free(b->data);
        b->data = NULL;
        if (b->toobig) {
            return lsc_files_fail(err, 0, "the file would be larger than %lu bytes (the most "
                                          "lsc reads)",
                                  LSC_FILE_MAX_BYTES);
        }
        return lsc_files_oom(err);
    }
    *out = b->data;
    *len = b->len;
    return 0;
}

int lsc_action_init(lsc_action *a, const uint8_t *ids, size_t n)
{
    if (a == NULL) {
        return LSC_EINVAL;
    }
    memset(a, 0, sizeof *a);
    if (ids == NULL || n == 0 || n > LSC_PLAYER_SERVOS_MAX) {
        return LSC_EINVAL;
    }
    if (!lsc_ids_distinct(ids, 1, n)) {
        return LSC_EINVAL;
    }
    memcpy(a->ids, ids, n);
    a->nservos = (uint8_t)n;
    return 0;
}

int lsc_action_append(lsc_action *a, uint16_t time_ms, const uint16_t *positions)
{
    if (a == NULL || positions == NULL || a->nservos == 0) {
        return LSC_EINVAL;
    }
    if (a->count >= LSC_ACTION_KEYFRAMES_MAX) {
        return LSC_ENOSPC;
    }
    size_t row = 1u + a->nservos;
    if (a->count >= a->cap) {
        uint32_t cap = a->cap != 0 ? a->cap * 2u : 16u;
        if (cap > LSC_ACTION_KEYFRAMES_MAX) {
            cap = LSC_ACTION_KEYFRAMES_MAX;
        }
        uint16_t *bigger = realloc(a->words, (size_t)cap * row * sizeof *bigger);
        if (bigger == NULL) {
            return LSC_ENOSPC;
        }
        a->words = bigger;
        a->cap = cap;
    }
    uint16_t *w = a->words + (size_t)a->count * row;
    w[0] = time_ms;
    memcpy(w + 1, positions, a->nservos * sizeof *w);
    a->count++;
    return 0;
}

void lsc_action_free(lsc_action *a)
{
    if (a != NULL) {
        free(a->words);
        a->words = NULL;
        a->count = 0;
        a->cap = 0;
    }
}

void lsc_action_track(const lsc_action *a, lsc_track *t)
{
    if (a == NULL || t == NULL) {
        return;
    }
    t->ids = a->ids;
    t->nservos = a->nservos;
    t->count = a->count;
    t->data = a->words;
    t->read = NULL;
}

int lsc_file_group_number(const char *path)
{
    if (path == NULL) {
        return -1;
    }
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    int n = -1;
    for (size_t i = 0; base[i] >= '0' && base[i] <= '9'; i++) {
        n = (n < 0 ? 0 : n) * 10 + (base[i] - '0');
        if (n > 254) {
            return -1;
        }
    }
    return n;
}
#endif
