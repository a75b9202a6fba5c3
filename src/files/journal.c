/* The record journal (include/lsc/files.h, lsc_journal_*): keyframes
 * appended to "TARGET.journal.csv" as they are taken, turned into TARGET at
 * the end. The top of src/files: it uses files.c (the formats, the atomic
 * write) and fileio.c. */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#define _DEFAULT_SOURCE 1 /* fdatasync, ftruncate, O_NOFOLLOW, O_CLOEXEC */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../util/escape.h"
#include "files_internal.h"

#ifdef __APPLE__
#define fdatasync fsync /* not declared there */
#endif

#define JOURNAL_SUFFIX ".journal.csv"
/* the longest row: "65535" and ",65535" per servo, a newline */
#define ROW_MAX (6u * (1u + LSC_PLAYER_SERVOS_MAX) + 1u)

struct lsc_journal {
    int fd;               /* the journal, O_APPEND; -1 once closed */
    char *target;         /* what lsc_journal_finish writes */
    char *path;           /* TARGET.journal.csv */
    uint8_t nservos;      /* positions per row */
    uint32_t rows;        /* rows written */
    off_t whole;          /* bytes of the header and the whole rows */
    bool dirty;           /* rows written since the last flush */
    bool damaged;         /* a failed write could not be cut back */
    bool removed;         /* lsc_journal_finish removed the file */
    uint64_t synced_ms;   /* the last flush, on the monotonic clock */
};

static uint64_t now_ms(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_MONOTONIC, &t) != 0) {
        return 0;
    }
    return (uint64_t)t.tv_sec * 1000u + (uint64_t)t.tv_nsec / 1000000u;
}

static int io_fail(lsc_file_error *err, const char *what, int e)
{
    return lsc_files_fail_code(err, LSC_EIO, "%s%s", what, strerror(e));
}

/* Writes all of s[0..n) at the journal's end; 0 or an errno. */
static int write_all(int fd, const char *s, size_t n)
{
    while (n > 0) {
        ssize_t k = write(fd, s, n);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            return k < 0 ? errno : ENOSPC;
        }
        s += k;
        n -= (size_t)k;
    }
    return 0;
}

static int flush(lsc_journal *j, lsc_file_error *err)
{
    if (fdatasync(j->fd) != 0) {
        return io_fail(err, "cannot flush the journal: ", errno);
    }
    j->dirty = false;
    j->synced_ms = now_ms();
    return 0;
}

/* Whether target's format can hold keyframes of a's servos: one keyframe of
 * 1 ms, every position 0, formatted (a .rob: servos 1..6 exactly). */
static int check_format(const char *target, const lsc_action *a, lsc_file_error *err)
{
    static const uint16_t zeros[LSC_PLAYER_SERVOS_MAX] = {0};
    lsc_action probe;
    uint8_t *bytes = NULL;
    size_t len = 0;
    lsc_file_format f = lsc_file_format_of(target);
    if (lsc_action_init(&probe, a->ids, a->nservos) != 0) {
        return LSC_EINVAL;
    }
    int r = lsc_action_append(&probe, 1, zeros);
    if (r == 0) {
        r = lsc_action_format(f, &probe, target, &bytes, &len, err);
    }
    free(bytes);
    lsc_action_free(&probe);
    return r;
}

int lsc_journal_open(const char *target, const lsc_action *a, lsc_journal **out,
                     lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (target == NULL || a == NULL || out == NULL || a->nservos == 0 ||
        a->nservos > LSC_PLAYER_SERVOS_MAX) {
        return LSC_EINVAL;
    }
    *out = NULL;
    lsc_files_err_clear(err);
    int r = check_format(target, a, err);
    if (r == 0) {
        r = lsc_files_replaceable(target, err);
    }
    if (r != 0) {
        return r;
    }
    size_t n = strlen(target);
    lsc_journal *j = calloc(1, sizeof *j);
    char *path = malloc(n + sizeof JOURNAL_SUFFIX);
    char *copy = malloc(n + 1u);
    if (j == NULL || path == NULL || copy == NULL) {
        free(j);
        free(path);
        free(copy);
        return lsc_files_oom(err);
    }
    memcpy(copy, target, n + 1u);
    (void)snprintf(path, n + sizeof JOURNAL_SUFFIX, "%s" JOURNAL_SUFFIX, target);
    j->target = copy;
    j->path = path;
    j->nservos = a->nservos;
    j->fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (j->fd < 0) {
        int e = errno;
        if (e == EEXIST) {
            const char *base = strrchr(path, '/');
            char name[120];
            base = base != NULL ? base + 1 : path;
            (void)lsc_escape_text(name, sizeof name, base, strlen(base));
            r = lsc_files_fail_code(err, LSC_EIO,
                                    "%s exists (an earlier recording that did not end): "
                                    "convert or remove it first",
                                    name);
        } else {
            r = io_fail(err, "cannot create its journal: ", e);
        }
        lsc_journal_close(j);
        return r;
    }
    char header[8u + 4u * LSC_PLAYER_SERVOS_MAX + 2u] = "time_ms";
    size_t len = 7;
    for (size_t i = 0; i < a->nservos; i++) {
        len += (size_t)snprintf(header + len, sizeof header - len, ",%u", a->ids[i]);
    }
    header[len++] = '\n';
    int e = write_all(j->fd, header, len);
    if (e != 0) {
        r = io_fail(err, "cannot write its journal: ", e);
    } else {
        j->whole = (off_t)len;
        j->dirty = true;
        r = flush(j, err);
    }
    if (r == 0) {
        r = lsc_files_sync_dir(path, err); /* the journal's name is on the disk too */
    }
    if (r != 0) {
        (void)unlink(path);
        j->removed = true;
        lsc_journal_close(j);
        return r;
    }
    *out = j;
    return 0;
}

int lsc_journal_append(lsc_journal *j, uint16_t time_ms, const uint16_t *positions,
                       lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (j == NULL || positions == NULL || j->fd < 0 || j->removed) {
        return LSC_EINVAL;
    }
    if (j->damaged) {
        return lsc_files_fail_code(err, LSC_EIO, "the journal's last row could not be cut "
                                                 "back after a failed write: it takes no more");
    }
    if (j->rows >= LSC_ACTION_KEYFRAMES_MAX) {
        return lsc_files_fail_code(err, LSC_ENOSPC, "the journal holds %u keyframes, the most "
                                                    "an action holds",
                                   LSC_ACTION_KEYFRAMES_MAX);
    }
    char row[ROW_MAX + 1u];
    size_t len = (size_t)snprintf(row, sizeof row, "%u", time_ms);
    for (size_t i = 0; i < j->nservos; i++) {
        len += (size_t)snprintf(row + len, sizeof row - len, ",%u", positions[i]);
    }
    row[len++] = '\n';
    int e = write_all(j->fd, row, len);
    if (e != 0) {
        /* a full disk: cut the partial row off, so the journal stays a CSV */
        if (ftruncate(j->fd, j->whole) != 0) {
            j->damaged = true;
        }
        return io_fail(err, "cannot write the journal: ", e);
    }
    j->whole += (off_t)len;
    j->rows++;
    j->dirty = true;
    return lsc_journal_sync(j, err);
}

int lsc_journal_sync(lsc_journal *j, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (j == NULL || j->fd < 0) {
        return LSC_EINVAL;
    }
    if (!j->dirty || now_ms() - j->synced_ms < LSC_JOURNAL_SYNC_MS) {
        return 0;
    }
    return flush(j, err);
}

int lsc_journal_finish(lsc_journal *j, const lsc_action *a, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (j == NULL || a == NULL || j->fd < 0 || j->removed) {
        return LSC_EINVAL;
    }
    int r = lsc_action_write(j->target, a, err);
    if (r != 0) {
        (void)flush(j, NULL); /* what the journal holds is what is left */
        return r;
    }
    /* the target is on the disk (written, flushed, renamed, directory
     * flushed): the journal can go */
    if (unlink(j->path) == 0) {
        j->removed = true;
        (void)lsc_files_sync_dir(j->path, NULL);
    }
    return 0;
}

const char *lsc_journal_path(const lsc_journal *j)
{
    return j != NULL ? j->path : NULL;
}

void lsc_journal_close(lsc_journal *j)
{
    if (j == NULL) {
        return;
    }
    if (j->fd >= 0) {
        if (j->dirty && !j->removed) {
            (void)fdatasync(j->fd);
        }
        (void)close(j->fd);
    }
    free(j->target);
    free(j->path);
    free(j);
}
#endif
