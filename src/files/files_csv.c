/* CSV action files: a header "time_ms,ID,ID,..." and one row per keyframe
 * "MS,POS,POS,...". Plain decimal numbers; CRLF line ends and blank lines are
 * accepted; nothing else (no quotes, no spaces). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <string.h>

#include "files_internal.h"

/* One line of the file: [p, end), its number. */
typedef struct csv_line {
    const char *p, *end;
    unsigned long no;
} csv_line;

/* The next field of l as a number 0..max into *v; false if it is not one.
 * Advances past the field and its comma; *last when no comma followed. */
static bool field(csv_line *l, unsigned long max, unsigned long *v, bool *last)
{
    const char *p = l->p;
    unsigned long n = 0;
    if (p == l->end || *p < '0' || *p > '9') {
        return false;
    }
    while (p < l->end && *p >= '0' && *p <= '9') {
        n = n * 10u + (unsigned long)(*p - '0');
        if (n > max) {
            return false;
        }
        p++;
    }
    if (p < l->end && *p != ',') {
        return false;
    }
    *last = p == l->end;
    l->p = *last ? p : p + 1;
    *v = n;
    return !(!*last && l->p == l->end); /* a trailing comma is an empty field */
}

/* The next non-blank line at or after *pos; false at the end. */
static bool next_line(const char *text, size_t len, size_t *pos, unsigned long *no,
                      csv_line *l)
{
    while (*pos < len) {
        const char *start = text + *pos;
        const char *nl = memchr(start, '\n', len - *pos);
        const char *end = nl != NULL ? nl : text + len;
        *pos = (size_t)(end - text) + (nl != NULL);
        ++*no;
        if (end > start && end[-1] == '\r') {
            end--;
        }
        if (end > start) {
            l->p = start;
            l->end = end;
            l->no = *no;
            return true;
        }
    }
    return false;
}

static const char header_help[] = "the first line must be time_ms,ID,ID,... (ids 0..255)";

static int parse_header(csv_line *l, lsc_action *a, lsc_file_error *err)
{
    static const char key[] = "time_ms,";
    size_t k = sizeof key - 1u;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    size_t n = 0;
    if ((size_t)(l->end - l->p) < k || memcmp(l->p, key, k) != 0) {
        return lsc_files_fail(err, l->no, "line %lu: %s", l->no, header_help);
    }
    l->p += k;
    for (bool last = false; !last;) {
        unsigned long id;
        if (!field(l, 255, &id, &last)) {
            return lsc_files_fail(err, l->no, "line %lu: column %zu: %s", l->no, n + 2u,
                                  header_help);
        }
        if (n == LSC_PLAYER_SERVOS_MAX) {
            return lsc_files_fail(err, l->no, "line %lu: more than %u servos", l->no,
                                  LSC_PLAYER_SERVOS_MAX);
        }
        if (memchr(ids, (int)id, n) != NULL) {
            return lsc_files_fail(err, l->no, "line %lu: servo %lu listed twice", l->no, id);
        }
        ids[n++] = (uint8_t)id;
    }
    (void)lsc_action_init(a, ids, n);
    return 0;
}

int lsc_files_csv_parse(const char *text, size_t len, lsc_action *a, lsc_file_error *err)
{
    size_t pos = 0;
    unsigned long no = 0;
    csv_line l;
    if (!next_line(text, len, &pos, &no, &l)) {
        return lsc_files_fail(err, 1, "line 1: the file is empty: %s", header_help);
    }
    int r = parse_header(&l, a, err);
    while (r == 0 && next_line(text, len, &pos, &no, &l)) {
        uint16_t w[1u + LSC_PLAYER_SERVOS_MAX];
        size_t n = 0;
        for (bool last = false; !last && n <= a->nservos;) {
            unsigned long v;
            if (!field(&l, 65535, &v, &last)) {
                return lsc_files_fail(err, l.no,
                                      "line %lu: column %zu: %s must be a number 0..65535",
                                      l.no, n + 1u, n == 0 ? "time_ms" : "a position");
            }
            w[n++] = (uint16_t)v;
        }
        if (n != 1u + a->nservos || l.p != l.end) {
            return lsc_files_fail(err, l.no, "line %lu: %s values: the header has %u columns",
                                  l.no, l.p != l.end ? "too many" : "too few",
                                  1u + a->nservos);
        }
        r = lsc_files_append(a, w, "line", l.no, err);
    }
    return r;
}

int lsc_files_csv_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err)
{
    (void)err;
    lsc_outbuf_printf(b, "time_ms");
    for (size_t i = 0; i < a->nservos; i++) {
        lsc_outbuf_printf(b, ",%u", a->ids[i]);
    }
    lsc_outbuf_put(b, "\n", 1);
    lsc_outbuf_rows(b, a, "", ",", "");
    return 0;
}
#endif
