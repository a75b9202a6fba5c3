/* Inside src/files: the layers, each calling only the ones below it.
 *
 *   journal.c           the record journal (lsc_journal_*)
 *   files.c             the dispatcher: the format of a file name, parse and
 *                       format by format, reading and writing whole files
 *   files_<format>.c    one reader and one writer per format
 *   action.c            what every format shares: the keyframes in memory
 *                       (lsc_action_*), the messages, the output buffer
 *   fileio.c            regular files read whole, files replaced atomically
 *
 * The formats never call files.c or journal.c. */
#ifndef LSC_FILES_INTERNAL_H
#define LSC_FILES_INTERNAL_H

#include <stdbool.h>

#include "lsc/files.h"

/* ---- action.c ------------------------------------------------------------------ */

/* Whether err (a struct that grows: src/util/sized.h) is refused: not NULL
 * and its size smaller than the size field and at. Every public call that
 * takes one returns LSC_EINVAL at once then. */
bool lsc_files_err_refused(const lsc_file_error *err);
/* Sets err (if not NULL) to at 0 and no message, up to its size. */
void lsc_files_err_clear(lsc_file_error *err);

/* Sets err (if not NULL) to "at" and the formatted message (up to its
 * size); returns LSC_EINVAL. */
int lsc_files_fail(lsc_file_error *err, unsigned long at, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The same for out of memory: returns LSC_ENOSPC. */
int lsc_files_oom(lsc_file_error *err);
/* Sets err like lsc_files_fail and returns code (LSC_EIO, LSC_EBUSY...). */
int lsc_files_fail_code(lsc_file_error *err, int code, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A reader's lsc_action_append: keyframe w (time, then the positions) read
 * at `where` `at` ("line", "row"...). Returns 0, LSC_EINVAL ("WHERE AT: more
 * than LSC_ACTION_KEYFRAMES_MAX keyframes") or LSC_ENOSPC (out of memory). */
int lsc_files_append(lsc_action *a, const uint16_t *w, const char *where, unsigned long at,
                     lsc_file_error *err);

/* A growing output buffer; `failed` once an allocation failed or it would
 * pass LSC_FILE_MAX_BYTES (`toobig`). */
typedef struct lsc_outbuf {
    uint8_t *data;
    size_t len, cap;
    bool failed, toobig;
} lsc_outbuf;
void lsc_outbuf_put(lsc_outbuf *b, const void *bytes, size_t n);
void lsc_outbuf_printf(lsc_outbuf *b, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Every keyframe of a as a line: lead, the time, then each position after
 * sep, then tail and a newline (CSV: "", ",", ""; C: "    ", ", ", ","). */
void lsc_outbuf_rows(lsc_outbuf *b, const lsc_action *a, const char *lead, const char *sep,
                     const char *tail);
/* Hands the bytes over (0), or frees them and reports out of memory
 * (LSC_ENOSPC) or a file larger than LSC_FILE_MAX_BYTES (LSC_EINVAL). */
int lsc_outbuf_finish(lsc_outbuf *b, uint8_t **out, size_t *len, lsc_file_error *err);

/* Row k's words (time, then positions). */
static inline const uint16_t *lsc_action_row(const lsc_action *a, uint32_t k)
{
    return a->words + (size_t)k * (1u + a->nservos);
}

/* ---- files_<format>.c ----------------------------------------------------------- */

/* One reader and one writer per format. Readers get an initialised, empty
 * action and leave it filled or empty. */
/* group: the group to read (0..254), or -1 for the file's only one. */
int lsc_files_text_parse(const char *text, size_t len, int group, lsc_action *a,
                         lsc_file_error *err);
/* The groups a text defines, ascending, into out[0..cap) (out may be NULL);
 * returns their number (may exceed cap) or an error. */
int lsc_files_text_groups(const char *text, size_t len, uint8_t *out, size_t cap,
                          lsc_file_error *err);
int lsc_files_text_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                          lsc_file_error *err);
int lsc_files_csv_parse(const char *text, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_csv_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_rob_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_rob_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_d6a_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err);
/* The .d6a file at path (a regular file: lsc_files_check_regular), through
 * SQLite on the file so that its locks, journal and WAL decide what is
 * committed (LSC_EIO: a hot journal; LSC_EBUSY: another program is writing
 * it); a WAL-mode file without a WAL, and a file that is not a database, as
 * its bytes (read through SQLite's descriptor: never open()ed and closed
 * here, which would drop this process's SQLite locks on it). */
int lsc_files_d6a_read(const char *path, lsc_action *a, lsc_file_error *err);
int lsc_files_d6a_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_header_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                            lsc_file_error *err);

/* ---- fileio.c ------------------------------------------------------------------- */

/* Whether path is a regular file (a link to one is followed) of at most max
 * bytes, without opening it: 0, LSC_EIO (missing, not a regular file: err
 * says what it is) or LSC_EINVAL ("larger than MAX bytes"). */
int lsc_files_check_regular(const char *path, size_t max, lsc_file_error *err);
/* Replaces path with len bytes atomically: a temporary file beside it
 * (O_EXCL; the target's mode, else 0666 less the umask), written, fsync'd,
 * renamed over path, the directory fsync'd. On any failure path is as it was
 * and the temporary file is gone. Refuses a symbolic link and anything but a
 * regular file (LSC_EINVAL), a target it may not write (LSC_EIO). Returns 0,
 * LSC_EINVAL, LSC_EIO or LSC_ENOSPC (out of memory). */
int lsc_files_replace(const char *path, const uint8_t *bytes, size_t len, lsc_file_error *err);
/* Whether path may be replaced: it does not exist, or is a regular file (not a
 * link) this process may write; 0 or lsc_files_replace's refusal. */
int lsc_files_replaceable(const char *path, lsc_file_error *err);
/* fsyncs the directory that holds path; 0 or LSC_EIO. */
int lsc_files_sync_dir(const char *path, lsc_file_error *err);

#endif
