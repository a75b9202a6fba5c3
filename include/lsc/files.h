/* lsc files: action files (keyframe sequences) read and written on a host.
 * Host only, like lsc/serial.h: it allocates and uses stdio (and SQLite for
 * .d6a). Formats, chosen by the file name's extension (any case):
 *   .txt  lsc's action-group text (docs/action-groups.md), one group
 *   .csv  a header "time_ms,ID,ID,..." then one row per keyframe
 *   .rob  the xArm PC software's file (servos 1..6, positions 0..1000)
 *   .d6a  the LSC boards' PC software file (SQLite, table ActionGroup)
 *   .h    a C header with the keyframes as const arrays (written only)
 * docs/action-files.md describes each format and every error.
 *
 * A file that does not follow its format is refused whole: the functions
 * return LSC_EINVAL and say where (line, record or row) and why in *err. */
#ifndef LSC_FILES_H
#define LSC_FILES_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/player.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_FILE_MAX_BYTES (16ul * 1024ul * 1024ul) /* larger files are refused */

typedef enum lsc_file_format {
    LSC_FILE_UNKNOWN = 0,
    LSC_FILE_TEXT,   /* .txt */
    LSC_FILE_CSV,    /* .csv */
    LSC_FILE_ROB,    /* .rob */
    LSC_FILE_D6A,    /* .d6a */
    LSC_FILE_HEADER  /* .h (written only) */
} lsc_file_format;

/* A sequence of keyframes in memory: `count` rows of 1 + nservos words (the
 * time since the previous keyframe in ms, then the position of each id), the
 * layout lsc_track reads. Start from lsc_action_init(), end with
 * lsc_action_free(). Fields are the caller's to read. */
typedef struct lsc_action {
    uint8_t nservos;                    /* 1..LSC_PLAYER_SERVOS_MAX */
    uint8_t ids[LSC_PLAYER_SERVOS_MAX]; /* distinct */
    uint32_t count;                     /* keyframes */
    uint32_t cap;                       /* keyframes words has room for */
    uint16_t *words;                    /* count * (1 + nservos), allocated */
} lsc_action;

/* Why a file was refused. */
typedef struct lsc_file_error {
    unsigned long at;  /* 1-based line (.txt, .csv), record (.rob), row (.d6a),
                          step (.txt after parsing) or keyframe (writing); 0:
                          the whole file */
    char message[200]; /* one line, without the file name: "line 3: ..." */
} lsc_file_error;

/* The format a path's extension names (LSC_FILE_UNKNOWN if none). */
LSC_API lsc_file_format lsc_file_format_of(const char *path);
/* "text", "csv", "rob", "d6a", "header" or "unknown". */
LSC_API const char *lsc_file_format_name(lsc_file_format f);

/* Empties a and sets its servos (n distinct ids, 1..LSC_PLAYER_SERVOS_MAX).
 * Returns 0 or LSC_EINVAL. Allocates nothing yet. */
LSC_API int lsc_action_init(lsc_action *a, const uint8_t *ids, size_t n);
/* Adds a keyframe: time_ms, then positions[0..nservos). Returns 0, LSC_EINVAL
 * (NULL arguments) or LSC_ENOSPC (out of memory, or 2^24 keyframes). */
LSC_API int lsc_action_append(lsc_action *a, uint16_t time_ms, const uint16_t *positions);
/* Frees what a holds; a is then empty (count 0), its ids kept. */
LSC_API void lsc_action_free(lsc_action *a);
/* A view of a for lsc_player_init() (valid while a is not changed). */
LSC_API void lsc_action_track(const lsc_action *a, lsc_track *t);

/* Reads `len` bytes in format f into a (initialised here; free it with
 * lsc_action_free() after success; on error a is empty). Returns 0,
 * LSC_EINVAL (the bytes do not follow the format, or f cannot be read: err
 * says where and why), LSC_ENOSPC (out of memory). err may be NULL. */
LSC_API int lsc_action_parse(lsc_file_format f, const void *data, size_t len, lsc_action *a,
                             lsc_file_error *err);
/* Writes a in format f into a new buffer *out of *len bytes (free() it).
 * name: the group number's and the C names' source (a file name; may be
 * NULL). Returns 0, LSC_EINVAL (a does not fit the format: err says which
 * keyframe and why), LSC_ENOSPC (out of memory). */
LSC_API int lsc_action_format(lsc_file_format f, const lsc_action *a, const char *name,
                              uint8_t **out, size_t *len, lsc_file_error *err);

/* The same on files, the format chosen by the extension. Reading: LSC_EIO
 * when the file cannot be read (err says why), LSC_EINVAL for an unknown
 * extension, a file larger than LSC_FILE_MAX_BYTES, or content that does not
 * follow its format. Writing replaces the file. */
LSC_API int lsc_action_read(const char *path, lsc_action *a, lsc_file_error *err);
LSC_API int lsc_action_write(const char *path, const lsc_action *a, lsc_file_error *err);

/* The number a file name starts with (its last path part, leading decimal
 * digits, 0..254), or -1 if none: "7-wave.rob" -> 7. */
LSC_API int lsc_file_group_number(const char *path);

#ifdef __cplusplus
}
#endif

#endif /* LSC_FILES_H */
