/* Shared by the action file readers and writers (src/files). */
#ifndef LSC_FILES_INTERNAL_H
#define LSC_FILES_INTERNAL_H

#include <stdbool.h>

#include "lsc/files.h"

/* Sets err (if not NULL) to "at" and the formatted message; returns LSC_EINVAL. */
int lsc_files_fail(lsc_file_error *err, unsigned long at, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The same for out of memory: returns LSC_ENOSPC. */
int lsc_files_oom(lsc_file_error *err);

/* A growing output buffer; `failed` once an allocation failed. */
typedef struct lsc_outbuf {
    uint8_t *data;
    size_t len, cap;
    bool failed;
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
/* Hands the bytes over (0), or frees them and reports out of memory. */
int lsc_outbuf_finish(lsc_outbuf *b, uint8_t **out, size_t *len, lsc_file_error *err);

/* Row k's words (time, then positions). */
static inline const uint16_t *lsc_action_row(const lsc_action *a, uint32_t k)
{
    return a->words + (size_t)k * (1u + a->nservos);
}

/* One reader and one writer per format (files_<format>.c). Readers get an
 * initialised, empty action and leave it filled or empty. */
int lsc_files_text_parse(const char *text, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_text_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                          lsc_file_error *err);
int lsc_files_csv_parse(const char *text, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_csv_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_rob_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_rob_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_d6a_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err);
int lsc_files_d6a_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err);
int lsc_files_header_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                            lsc_file_error *err);

#endif
