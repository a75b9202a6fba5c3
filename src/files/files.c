/* Action files (include/lsc/files.h): the keyframes in memory, the choice of
 * format, reading and writing whole files. Each format is in files_<fmt>.c. */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/internal.h" /* lsc_ids_distinct */
#include "files_internal.h"

#define KEYFRAMES_MAX (1ul << 24) /* far beyond any real file; keeps sizes in range */

int lsc_files_fail(lsc_file_error *err, unsigned long at, const char *fmt, ...)
{
    if (err != NULL) {
        va_list ap;
        err->at = at;
        va_start(ap, fmt);
        (void)vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return LSC_EINVAL;
}

int lsc_files_oom(lsc_file_error *err)
{
    (void)lsc_files_fail(err, 0, "out of memory");
    return LSC_ENOSPC;
}

/* Room for n more bytes in b; false (and b->failed) when memory is out. */
static bool reserve(lsc_outbuf *b, size_t n)
{
    if (b->failed) {
        return false;
    }
    if (n > b->cap - b->len) {
        size_t cap = b->cap != 0 ? b->cap : 256u;
        while (cap - b->len < n) {
            cap *= 2u;
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
    if (reserve(b, n)) {
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
    if (n > 0 && reserve(b, (size_t)n + 1u)) {
        (void)vsnprintf((char *)b->data + b->len, (size_t)n + 1u, fmt, again);
        b->len += (size_t)n;
    }
    va_end(again);
}

void lsc_outbuf_rows(lsc_outbuf *b, const lsc_action *a, const char *lead, const char *sep,
                     const char *tail)
{
    for (uint32_t k = 0; k < a->count; k++) {
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
        return lsc_files_oom(err);
    }
    *out = b->data;
    *len = b->len;
    return 0;
}

lsc_file_format lsc_file_format_of(const char *path)
{
    static const struct {
        const char *ext;
        lsc_file_format f;
    } exts[] = {{"txt", LSC_FILE_TEXT}, {"csv", LSC_FILE_CSV}, {"rob", LSC_FILE_ROB},
                {"d6a", LSC_FILE_D6A},  {"h", LSC_FILE_HEADER}};
    const char *dot = path != NULL ? strrchr(path, '.') : NULL;
    if (dot == NULL || strchr(dot, '/') != NULL) {
        return LSC_FILE_UNKNOWN;
    }
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++) {
        const char *e = exts[i].ext;
        size_t k = 0;
        while (e[k] != '\0' && (dot[1 + k] | 0x20) == e[k]) {
            k++;
        }
        if (e[k] == '\0' && dot[1 + k] == '\0') {
            return exts[i].f;
        }
    }
    return LSC_FILE_UNKNOWN;
}

const char *lsc_file_format_name(lsc_file_format f)
{
    switch (f) {
    case LSC_FILE_TEXT: return "text";
    case LSC_FILE_CSV: return "csv";
    case LSC_FILE_ROB: return "rob";
    case LSC_FILE_D6A: return "d6a";
    case LSC_FILE_HEADER: return "header";
    default: return "unknown";
    }
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
    size_t row = 1u + a->nservos;
    if (a->count == a->cap) {
        if (a->cap >= KEYFRAMES_MAX) {
            return LSC_ENOSPC;
        }
        uint32_t cap = a->cap != 0 ? a->cap * 2u : 16u;
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

int lsc_action_parse(lsc_file_format f, const void *data, size_t len, lsc_action *a,
                     lsc_file_error *err)
{
    if (a == NULL || (data == NULL && len > 0)) {
        return LSC_EINVAL;
    }
    memset(a, 0, sizeof *a);
    if (err != NULL) {
        err->at = 0;
        err->message[0] = '\0';
    }
    static const char empty[1] = "";
    if (data == NULL) {
        data = empty;
    }
    int r;
    switch (f) {
    case LSC_FILE_TEXT: r = lsc_files_text_parse(data, len, a, err); break;
    case LSC_FILE_CSV: r = lsc_files_csv_parse(data, len, a, err); break;
    case LSC_FILE_ROB: r = lsc_files_rob_parse(data, len, a, err); break;
    case LSC_FILE_D6A: r = lsc_files_d6a_parse(data, len, a, err); break;
    case LSC_FILE_HEADER:
        return lsc_files_fail(err, 0, "C headers are written, not read: convert from the "
                                      "file the header was made from");
    default:
        return lsc_files_fail(err, 0, "unknown file type: use .txt, .csv, .rob, .d6a or .h");
    }
    if (r != 0) {
        lsc_action_free(a);
    }
    return r;
}

int lsc_action_format(lsc_file_format f, const lsc_action *a, const char *name, uint8_t **out,
                      size_t *len, lsc_file_error *err)
{
    if (a == NULL || out == NULL || len == NULL || a->nservos == 0 ||
        a->nservos > LSC_PLAYER_SERVOS_MAX || (a->words == NULL && a->count > 0)) {
        return LSC_EINVAL;
    }
    lsc_outbuf b = {NULL, 0, 0, false};
    int r;
    *out = NULL;
    *len = 0;
    switch (f) {
    case LSC_FILE_TEXT: r = lsc_files_text_format(a, name, &b, err); break;
    case LSC_FILE_CSV: r = lsc_files_csv_format(a, &b, err); break;
    case LSC_FILE_ROB: r = lsc_files_rob_format(a, &b, err); break;
    case LSC_FILE_D6A: r = lsc_files_d6a_format(a, &b, err); break;
    case LSC_FILE_HEADER: r = lsc_files_header_format(a, name, &b, err); break;
    default:
        return lsc_files_fail(err, 0, "unknown file type: use .txt, .csv, .rob, .d6a or .h");
    }
    if (r != 0) {
        free(b.data);
        return r;
    }
    return lsc_outbuf_finish(&b, out, len, err);
}

int lsc_action_read(const char *path, lsc_action *a, lsc_file_error *err)
{
    if (path == NULL || a == NULL) {
        return LSC_EINVAL;
    }
    memset(a, 0, sizeof *a);
    lsc_file_format f = lsc_file_format_of(path);
    if (f == LSC_FILE_UNKNOWN || f == LSC_FILE_HEADER) {
        return lsc_action_parse(f, NULL, 0, a, err);
    }
    FILE *in = fopen(path, "rb");
    if (in == NULL) {
        (void)lsc_files_fail(err, 0, "%s", strerror(errno));
        return LSC_EIO;
    }
    size_t cap = 0, len = 0;
    uint8_t *data = NULL;
    int r = 0;
    for (;;) {
        if (len == cap) {
            if (cap >= LSC_FILE_MAX_BYTES) {
                r = lsc_files_fail(err, 0, "larger than %lu bytes", LSC_FILE_MAX_BYTES);
                break;
            }
            cap = cap != 0 ? cap * 2u : 4096u;
            uint8_t *bigger = realloc(data, cap + 1u);
            if (bigger == NULL) {
                r = lsc_files_oom(err);
                break;
            }
            data = bigger;
        }
        size_t n = fread(data + len, 1, cap - len, in);
        len += n;
        if (n == 0) {
            if (ferror(in)) {
                (void)lsc_files_fail(err, 0, "read error: %s", strerror(errno));
                r = LSC_EIO;
            }
            break;
        }
    }
    (void)fclose(in);
    if (r == 0) {
        r = lsc_action_parse(f, data, len, a, err);
    }
    free(data);
    return r;
}

int lsc_action_write(const char *path, const lsc_action *a, lsc_file_error *err)
{
    if (path == NULL || a == NULL) {
        return LSC_EINVAL;
    }
    uint8_t *bytes = NULL;
    size_t len = 0;
    int r = lsc_action_format(lsc_file_format_of(path), a, path, &bytes, &len, err);
    if (r != 0) {
        return r;
    }
    FILE *out = fopen(path, "wb");
    if (out == NULL) {
        (void)lsc_files_fail(err, 0, "%s", strerror(errno));
        free(bytes);
        return LSC_EIO;
    }
    size_t n = fwrite(bytes, 1, len, out);
    int closed = fclose(out);
    free(bytes);
    if (n != len || closed != 0) {
        (void)lsc_files_fail(err, 0, "write error: %s", strerror(errno));
        return LSC_EIO;
    }
    return 0;
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
#else
typedef int lsc_files_empty_unit; /* ISO C forbids an empty translation unit */
#endif
