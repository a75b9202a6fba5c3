/* Action files (include/lsc/files.h): the top of src/files. The format a
 * file name names, parsing and formatting by format (each format is in
 * files_<fmt>.c), reading and writing whole files (fileio.c). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <stdlib.h>
#include <string.h>

#include "files_internal.h"

/* .h is written, never read: the two messages say so alike */
static const char unknown_read[] = "unknown file type: lsc reads .txt, .csv, .rob and .d6a "
                                   "(and writes those and .h)";
static const char unknown_write[] = "unknown file type: lsc writes .txt, .csv, .rob, .d6a and .h";

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

static void clear(lsc_file_error *err)
{
    lsc_files_err_clear(err);
}

int lsc_action_parse(lsc_file_format f, const void *data, size_t len, lsc_action *a,
                     lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (a == NULL || (data == NULL && len > 0)) {
        return LSC_EINVAL;
    }
    memset(a, 0, sizeof *a);
    clear(err);
    static const char empty[1] = "";
    if (data == NULL) {
        data = empty;
    }
    int r;
    switch (f) {
    case LSC_FILE_TEXT: r = lsc_files_text_parse(data, len, -1, a, err); break;
    case LSC_FILE_CSV: r = lsc_files_csv_parse(data, len, a, err); break;
    case LSC_FILE_ROB: r = lsc_files_rob_parse(data, len, a, err); break;
    case LSC_FILE_D6A: r = lsc_files_d6a_parse(data, len, a, err); break;
    case LSC_FILE_HEADER:
        return lsc_files_fail(err, 0, "C headers are written, not read: lsc reads .txt, "
                                      ".csv, .rob and .d6a; convert from the file the header "
                                      "was made from");
    default: return lsc_files_fail(err, 0, "%s", unknown_read);
    }
    if (r != 0) {
        lsc_action_free(a);
    }
    return r;
}

int lsc_action_format(lsc_file_format f, const lsc_action *a, const char *name, uint8_t **out,
                      size_t *len, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (a == NULL || out == NULL || len == NULL || a->nservos == 0 ||
        a->nservos > LSC_PLAYER_SERVOS_MAX || (a->words == NULL && a->count > 0)) {
        return LSC_EINVAL;
    }
    lsc_outbuf b = {NULL, 0, 0, false, false};
    int r;
    *out = NULL;
    *len = 0;
    clear(err);
    if (a->count > LSC_ACTION_KEYFRAMES_MAX) { /* an action built by hand */
        return lsc_files_fail(err, LSC_ACTION_KEYFRAMES_MAX + 1ul,
                              "%lu keyframes: an action holds at most %u",
                              (unsigned long)a->count, LSC_ACTION_KEYFRAMES_MAX);
    }
    switch (f) {
    case LSC_FILE_TEXT: r = lsc_files_text_format(a, name, &b, err); break;
    case LSC_FILE_CSV: r = lsc_files_csv_format(a, &b, err); break;
    case LSC_FILE_ROB: r = lsc_files_rob_format(a, &b, err); break;
    case LSC_FILE_D6A: r = lsc_files_d6a_format(a, &b, err); break;
    case LSC_FILE_HEADER: r = lsc_files_header_format(a, name, &b, err); break;
    default: return lsc_files_fail(err, 0, "%s", unknown_write);
    }
    if (r != 0) {
        free(b.data);
        return r;
    }
    return lsc_outbuf_finish(&b, out, len, err);
}

int lsc_action_read(const char *path, lsc_action *a, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || a == NULL) {
        return LSC_EINVAL;
    }
    memset(a, 0, sizeof *a);
    lsc_file_format f = lsc_file_format_of(path);
    if (f == LSC_FILE_UNKNOWN || f == LSC_FILE_HEADER) {
        return lsc_action_parse(f, NULL, 0, a, err);
    }
    if (f == LSC_FILE_D6A) { /* SQLite opens it */
        clear(err);
        int r = lsc_files_check_regular(path, LSC_FILE_MAX_BYTES, err);
        if (r == 0) {
            r = lsc_files_d6a_read(path, a, err);
        }
        if (r != 0) {
            lsc_action_free(a);
        }
        return r;
    }
    uint8_t *data = NULL;
    size_t len = 0;
    int r = lsc_file_load(path, LSC_FILE_MAX_BYTES, &data, &len, err);
    if (r == 0) {
        r = lsc_action_parse(f, data, len, a, err);
    }
    free(data);
    return r;
}

/* The .txt file at path, loaded: group `group` (-1: the only one) read into
 * a (a non-NULL; freed on error), or its groups listed into groups[0..cap). */
static int from_text(const char *path, int group, lsc_action *a, uint8_t *groups, size_t cap,
                     lsc_file_error *err)
{
    uint8_t *data = NULL;
    size_t len = 0;
    int r = lsc_file_load(path, LSC_FILE_MAX_BYTES, &data, &len, err);
    if (r == 0) {
        clear(err);
        r = a != NULL ? lsc_files_text_parse((const char *)data, len, group, a, err)
                      : lsc_files_text_groups((const char *)data, len, groups, cap, err);
        if (r != 0 && a != NULL) {
            lsc_action_free(a);
        }
    }
    free(data);
    return r;
}

int lsc_action_read_group(const char *path, int group, lsc_action *a, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || a == NULL || group < -1 || group > 254) {
        return LSC_EINVAL;
    }
    lsc_file_format f = lsc_file_format_of(path);
    if (group < 0 || (f != LSC_FILE_TEXT && f != LSC_FILE_UNKNOWN && f != LSC_FILE_HEADER)) {
        int r = lsc_action_read(path, a, err);
        int own = lsc_file_group_number(path);
        own = own >= 0 ? own : 1;
        if (r == 0 && group >= 0 && group != own) { /* one group, numbered by the name */
            lsc_action_free(a);
            return lsc_files_fail(err, 0, "no group %d in the file: it is one group, group %d "
                                          "(numbered by the name it starts with, else 1)",
                                  group, own);
        }
        return r;
    }
    memset(a, 0, sizeof *a);
    if (f != LSC_FILE_TEXT) {
        return lsc_action_parse(f, NULL, 0, a, err);
    }
    return from_text(path, group, a, NULL, 0, err);
}

int lsc_action_groups(const char *path, uint8_t *groups, size_t cap, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || (groups == NULL && cap > 0u)) {
        return LSC_EINVAL;
    }
    if (lsc_file_format_of(path) != LSC_FILE_TEXT) {
        lsc_action a;
        int r = lsc_action_read(path, &a, err);
        if (r != 0) {
            return r;
        }
        lsc_action_free(&a);
        int own = lsc_file_group_number(path);
        if (cap > 0u) {
            groups[0] = (uint8_t)(own >= 0 ? own : 1);
        }
        return 1;
    }
    return from_text(path, -1, NULL, groups, cap, err);
}

int lsc_action_write(const char *path, const lsc_action *a, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || a == NULL) {
        return LSC_EINVAL;
    }
    lsc_file_format f = lsc_file_format_of(path);
    if (f == LSC_FILE_UNKNOWN) {
        clear(err);
        return lsc_files_fail(err, 0, "%s", unknown_write);
    }
    /* a target that cannot be replaced is refused before any work */
    int r = lsc_files_replaceable(path, err);
    uint8_t *bytes = NULL;
    size_t len = 0;
    if (r == 0) {
        r = lsc_action_format(f, a, path, &bytes, &len, err);
    }
    if (r == 0) {
        r = lsc_files_replace(path, bytes, len, err);
    }
    free(bytes);
    return r;
}
#endif
