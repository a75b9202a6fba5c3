/* lsc-panel: the action files in --dir (panel_http.h): listed, read (as
 * CSV or as the teach list's JSON) and saved, by names that cannot leave
 * the directory. */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "panel_http.h"

#define FILES_MAX 1000u /* files listed from --dir */

bool panel_file_name_ok(const char *name)
{
    size_t n = name ? strlen(name) : 0u;
    if (n == 0u || n >= PANEL_NAME_MAX || name[0] == '.') {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '.' || c == '_' || c == '-')) {
            return false;
        }
    }
    lsc_file_format f = lsc_file_format_of(name);
    return f == LSC_FILE_TEXT || f == LSC_FILE_CSV || f == LSC_FILE_ROB || f == LSC_FILE_D6A;
}

/* name= as a path in --dir; refuses (answered) a name that is not allowed. */
static bool file_path(const ctx *x, char *path, size_t cap, enum MHD_Result *ok)
{
    const char *name = http_arg(x, "name");
    if (!panel_file_name_ok(name)) {
        *ok = http_refuse(x->c, MHD_HTTP_BAD_REQUEST,
                          "name= must be a file name in the panel's directory: letters, digits, "
                          "'.', '_' and '-', not starting with '.', at most 63 bytes, ending in "
                          ".rob, .d6a, .csv or .txt");
        return false;
    }
    (void)snprintf(path, cap, "%s/%s", x->p->dir, name);
    struct stat st;
    if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* a link (or a directory...) would reach outside --dir */
        *ok = http_refuse(x->c, MHD_HTTP_BAD_REQUEST,
                          "name= is not a regular file in the panel's directory (a link, a "
                          "directory or a device): lsc-panel reads and writes only its own files");
        return false;
    }
    return true;
}

enum MHD_Result api_save(const ctx *x)
{
    char path[PANEL_PATH_MAX];
    enum MHD_Result ok = MHD_NO;
    lsc_action a;
    lsc_file_error err = {.size = sizeof err};
    if (!file_path(x, path, sizeof path, &ok) || !api_body_action(x, &a, &ok)) {
        return ok;
    }
    int r = lsc_action_write(path, &a, &err);
    lsc_action_free(&a);
    if (r != 0) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "%s: %s", http_arg(x, "name"), err.message);
        return http_refuse(x->c,
                           r == LSC_EINVAL ? MHD_HTTP_BAD_REQUEST
                                           : MHD_HTTP_INTERNAL_SERVER_ERROR,
                           msg);
    }
    return http_send_ok(x->c, MHD_HTTP_OK);
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

enum MHD_Result api_files(const ctx *x)
{
    DIR *d = opendir(x->p->dir);
    if (d == NULL) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "cannot list the directory: %s", strerror(errno));
        return http_refuse(x->c, MHD_HTTP_INTERNAL_SERVER_ERROR, msg);
    }
    char *names[FILES_MAX] = {NULL};
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < FILES_MAX) {
        if (panel_file_name_ok(e->d_name) && (names[n] = strdup(e->d_name)) != NULL) {
            n++;
        }
    }
    (void)closedir(d);
    qsort(names, n, sizeof names[0], by_name);
    panel_buf b = {0};
    panel_buf_str(&b, "{\"files\":[");
    bool first = true;
    for (size_t i = 0; i < n; i++) {
        char path[PANEL_PATH_MAX];
        struct stat st;
        (void)snprintf(path, sizeof path, "%s/%s", x->p->dir, names[i]);
        if (lstat(path, &st) == 0 && S_ISREG(st.st_mode)) { /* no links: see file_path */
            panel_buf_str(&b, first ? "{\"name\":" : ",{\"name\":");
            first = false;
            panel_buf_json(&b, names[i]);
            panel_buf_printf(&b, ",\"bytes\":%lld}", (long long)st.st_size);
        }
        free(names[i]);
    }
    panel_buf_str(&b, "]}");
    return http_send_json(x->c, MHD_HTTP_OK, &b);
}

/* An action as the page's teach list takes it: {"keyframes":[{"time":T,
 * "ids":[..],"pos":[..],"deg":[..]}, ...]} (deg: the joints' angles with
 * --arm, else null). */
static void action_json(const panel *p, const lsc_action *a, panel_buf *b)
{
    size_t w = 1u + a->nservos;
    panel_buf_str(b, "{\"keyframes\":[");
    for (uint32_t k = 0; k < a->count && !b->failed; k++) {
        lsc_servo s[LSC_PLAYER_SERVOS_MAX];
        for (size_t i = 0; i < a->nservos; i++) {
            s[i].id = a->ids[i];
            s[i].position = a->words[k * w + 1u + i];
        }
        panel_buf_printf(b, "%s{\"time\":%u,\"servos\":", k ? "," : "",
                         (unsigned)a->words[k * w]);
        panel_positions_json(p, s, a->nservos, b);
        panel_buf_str(b, "}");
    }
    panel_buf_str(b, "]}");
}

enum MHD_Result api_file(const ctx *x)
{
    char path[PANEL_PATH_MAX];
    enum MHD_Result ok = MHD_NO;
    lsc_action a;
    lsc_file_error err = {.size = sizeof err};
    if (!file_path(x, path, sizeof path, &ok)) {
        return ok;
    }
    const char *as = http_arg(x, "as");
    if (as != NULL && strcmp(as, "json") != 0 && strcmp(as, "csv") != 0) {
        return http_refuse(x->c, MHD_HTTP_BAD_REQUEST, "as= must be csv (the default) or json");
    }
    int r = lsc_action_read(path, &a, &err);
    uint8_t *csv = NULL;
    size_t len = 0;
    if (r == 0 && as != NULL && strcmp(as, "json") == 0) {
        panel_buf b = {0};
        action_json(x->p, &a, &b);
        lsc_action_free(&a);
        return http_send_json(x->c, MHD_HTTP_OK, &b);
    }
    if (r == 0) {
        r = lsc_action_format(LSC_FILE_CSV, &a, path, &csv, &len, &err);
        lsc_action_free(&a);
    }
    if (r != 0) {
        char msg[PANEL_MSG_MAX];
        (void)snprintf(msg, sizeof msg, "%s: %s", http_arg(x, "name"), err.message);
        return http_refuse(x->c,
                           r == LSC_EINVAL  ? MHD_HTTP_UNPROCESSABLE_CONTENT
                           : r == LSC_EIO   ? MHD_HTTP_NOT_FOUND
                                            : MHD_HTTP_INTERNAL_SERVER_ERROR,
                           msg);
    }
    ok = http_send(x->c, MHD_HTTP_OK, "text/csv; charset=utf-8", csv, len);
    free(csv);
    return ok;
}
