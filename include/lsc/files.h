/* lsc files: action files (keyframe sequences) read and written on a host.
 * Host only, like lsc/serial.h: it allocates and uses stdio (and SQLite for
 * .d6a). Formats, chosen by the file name's extension (any case):
 *   .txt  lsc's action-group text (docs/action-groups.md): one group, or
 *         one chosen by its number (lsc_action_read_group)
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

/* ---- Limits: one table for readers, writers and record ------------------------ *
 * What lsc writes it reads back: every writer refuses what the readers
 * refuse, with the same bound. */

/* The largest file read or written: 16 MiB. A file of exactly this many
 * bytes is read; one byte more is refused (LSC_EINVAL), and a writer refuses
 * output that would be larger (LSC_EINVAL, nothing written). */
#define LSC_FILE_MAX_BYTES (16ul * 1024ul * 1024ul)
/* The most keyframes an action holds: lsc_action_append refuses the next one
 * (LSC_ENOSPC), the readers refuse a file with more (LSC_EINVAL, naming the
 * line, row or step), the writers an action with more. It is the most a .rob
 * file (a 16-bit count) and a .txt group (65535 steps) hold, and it keeps
 * every CSV and .d6a of 32 servos under LSC_FILE_MAX_BYTES. At one keyframe
 * every 10 ms it is 10 minutes 55 s of recording. */
#define LSC_ACTION_KEYFRAMES_MAX 65535u
/* Per keyframe: 1..LSC_PLAYER_SERVOS_MAX (32) servos with distinct ids
 * 0..255; times and positions 0..65535. Per format, besides: .txt steps take
 * 1..65535 ms (a keyframe of 0 ms is refused when written); .rob holds exactly
 * servos 1..6 with positions 0..LSC_FILE_ROB_POSITION_MAX. */
#define LSC_FILE_ROB_POSITION_MAX 1000u

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

/* Why a file was refused. The caller sets size to sizeof(lsc_file_error)
 * of its headers: fields are only ever added at the end, and those beyond
 * size are not written. Every call that takes one (err may be NULL) refuses a
 * size smaller than the size field and at with LSC_EINVAL, doing nothing and
 * writing nothing. In C99: lsc_file_error err = { .size = sizeof err }; */
typedef struct lsc_file_error {
    size_t size;
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
 * (NULL arguments) or LSC_ENOSPC (out of memory, or a already holds
 * LSC_ACTION_KEYFRAMES_MAX keyframes; a is unchanged). */
LSC_API int lsc_action_append(lsc_action *a, uint16_t time_ms, const uint16_t *positions);
/* Frees what a holds; a is then empty (count 0), its ids kept. */
LSC_API void lsc_action_free(lsc_action *a);
/* A view of a for lsc_player_init() (valid while a is not changed). */
LSC_API void lsc_action_track(const lsc_action *a, lsc_track *t);

/* Reads `len` bytes in format f into a (initialised here; free it with
 * lsc_action_free() after success; on error a is empty). Returns 0,
 * LSC_EINVAL (the bytes do not follow the format, hold more than
 * LSC_ACTION_KEYFRAMES_MAX keyframes, or f cannot be read: err says where and
 * why), LSC_ENOSPC (out of memory). err may be NULL. A .d6a given as bytes
 * is the database file alone: a WAL-mode one is read without its -wal file. */
LSC_API int lsc_action_parse(lsc_file_format f, const void *data, size_t len, lsc_action *a,
                             lsc_file_error *err);
/* Writes a in format f into a new buffer *out of *len bytes (free() it).
 * name: the group number's and the C names' source (a file name; may be
 * NULL). Returns 0, LSC_EINVAL (a does not fit the format, holds more than
 * LSC_ACTION_KEYFRAMES_MAX keyframes, or the output would be larger than
 * LSC_FILE_MAX_BYTES: err says which keyframe and why), LSC_ENOSPC (out of
 * memory). Whatever this returns 0 for, lsc_action_parse reads back as a
 * (not .h, which is not read). */
LSC_API int lsc_action_format(lsc_file_format f, const lsc_action *a, const char *name,
                              uint8_t **out, size_t *len, lsc_file_error *err);

/* The same on files, the format chosen by the extension.
 *
 * Reading takes regular files only (a symbolic link to one is followed): a
 * FIFO, directory, device or socket is refused at once, without waiting for
 * a writer and without opening a device. Returns 0; LSC_EIO when the file
 * cannot be read (missing, not a regular file, no permission, a .d6a with a
 * hot journal: err says why); LSC_EBUSY when another program is writing the
 * .d6a (SQLite's lock, held for more than a second); LSC_EINVAL for an
 * unknown extension, a file larger than LSC_FILE_MAX_BYTES, or content that
 * does not follow its format; LSC_ENOSPC (out of memory).
 *
 * A .d6a is read as SQLite sees it: the last committed state. A rollback
 * journal that another program's open transaction holds is respected; a hot
 * journal (left by a write that was interrupted) is refused, not rolled back
 * (reading does not change the file): opening the file once with a program
 * that may write it, such as `sqlite3 FILE 'PRAGMA integrity_check'`, rolls
 * it back. A WAL-mode file is read with its -wal file (through SQLite, which
 * may then create FILE-shm beside it) or, when there is none, as the file.
 *
 * Writing replaces the file atomically: the bytes go to a temporary file
 * beside it (".NAME.XXXXXX.tmp", created exclusively, with the old file's
 * permissions, and its owner and group when this process may set them; a new
 * file gets 0666 less the umask), which is
 * flushed to the disk (fsync), renamed over path, and the directory flushed.
 * On any failure (a full disk included) the old file is as it was and the
 * temporary file is removed. (Only a failure to flush the directory comes
 * after the rename: LSC_EIO, "cannot flush the directory", the new file in
 * place but perhaps not yet on the disk.) A symbolic link is refused (LSC_EINVAL: lsc
 * writes files, not through links; name the file it points to), and so is
 * an existing path that is not a regular file (a FIFO is not opened, so it
 * cannot block) or a file this process may not write (LSC_EIO). Returns 0,
 * LSC_EINVAL (also: a does not fit the format, as lsc_action_format), LSC_EIO
 * (err says why: "write error: No space left on device"...), LSC_ENOSPC
 * (out of memory). */
LSC_API int lsc_action_read(const char *path, lsc_action *a, lsc_file_error *err);
LSC_API int lsc_action_write(const char *path, const lsc_action *a, lsc_file_error *err);

/* Reads group `group` (0..254) of the file at path into a, as lsc_action_read
 * reads a file (the same rules, returns and errors). A .txt file may hold
 * several groups (lsc-sim's group files, docs/action-groups.md): the one
 * numbered `group` is read, the others are checked as text but not read
 * (LSC_EINVAL, "no group 4 in the file (it holds groups 1, 2, 3)", when it is
 * not there). A .csv, .rob or .d6a file is one group, numbered as lsc-sim
 * numbers it (lsc_file_group_number, else 1): it is read when that is
 * `group`, else refused (LSC_EINVAL, nothing read). group -1 reads the file's
 * only group: lsc_action_read, which refuses a .txt of several groups
 * (LSC_EINVAL, "3 groups: an action file holds one; ... (groups 1, 2, 3)").
 * A group outside -1..254, or NULL path or a: LSC_EINVAL, err untouched. */
LSC_API int lsc_action_read_group(const char *path, int group, lsc_action *a,
                                  lsc_file_error *err);

/* The action groups the file at path holds, ascending, into
 * groups[0..cap) (groups may be NULL when cap is 0): a .txt's groups (0 when
 * it defines none), another format's one group, numbered as
 * lsc_action_read_group numbers it. Returns their number (may exceed cap),
 * or the error of reading the file (err says why); LSC_EINVAL for a NULL
 * path, or NULL groups with cap > 0 (err untouched). For a front end that
 * says how to choose one when lsc_action_read_group(path, -1) refused a file
 * of several. */
LSC_API int lsc_action_groups(const char *path, uint8_t *groups, size_t cap,
                              lsc_file_error *err);

/* Reads a regular file whole, for any text a program takes from a file
 * (action groups, profiles): refuses at once what is not a regular file
 * (LSC_EIO, "not a regular file (a FIFO)"...) and a file larger than
 * max_bytes (LSC_EINVAL, "larger than N bytes"); a file of exactly max_bytes
 * is read. *data (free() it) holds the *len bytes and a NUL after them.
 * Returns 0, LSC_EINVAL (also NULL arguments), LSC_EIO (err says why) or
 * LSC_ENOSPC (out of memory). */
LSC_API int lsc_file_load(const char *path, size_t max_bytes, uint8_t **data, size_t *len,
                          lsc_file_error *err);

/* Replaces the file at path with bytes[0..len), atomically: a temporary file
 * beside it, flushed to the disk, renamed over it, the directory flushed (a
 * reader sees the old file or the new one, whole; a power cut leaves one of
 * them). An existing file keeps its permissions (and its owner and group
 * where this process may set them); a new one gets 0666 less the umask.
 * Refused: a symbolic link, anything not a regular file, a file this process
 * may not write. Returns 0, LSC_EINVAL (NULL arguments), LSC_EIO (err says
 * why; the old file untouched) or LSC_ENOSPC (out of memory). */
LSC_API int lsc_file_replace(const char *path, const void *bytes, size_t len,
                             lsc_file_error *err);

/* ---- The record journal ------------------------------------------------------- *
 * Keyframes that reach the disk as they are taken, so that a recording
 * survives what ends the program (SIGKILL, a crash, a power cut: at most
 * about the last LSC_JOURNAL_SYNC_MS is lost) and a target that cannot be
 * written at the end. The journal is a CSV file beside the target,
 * "TARGET.journal.csv" (the format of .csv files: `lscctl convert` or
 * lsc_action_read read it), appended a row per keyframe.
 *
 *   lsc_journal *j;
 *   lsc_journal_open("wave.rob", &a, &j, &err);         // before the servos go limp
 *   ... lsc_action_append(&a, t, pos); lsc_journal_append(j, t, pos, &err); ...
 *   ... lsc_journal_sync(j, &err) from the idle loop ...
 *   if (lsc_journal_finish(j, &a, &err) != 0)           // wave.rob, then no journal
 *       printf("%s; kept in %s\n", err.message, lsc_journal_path(j));
 *   lsc_journal_close(j);
 *
 * Not thread-safe: one journal, one thread at a time. */
#define LSC_JOURNAL_SYNC_MS 1000u /* the longest a row stays off the disk (see sync) */

typedef struct lsc_journal lsc_journal;

/* Starts the journal of target, for a's servos (a's ids; its keyframes are
 * not copied). Checks up front what the end will need: target's extension
 * names a format lsc writes (LSC_EINVAL), the format holds a's servos (a .rob:
 * exactly 1..6; LSC_EINVAL), target is not a link and, if it exists, a
 * regular file this process may write (lsc_action_write's rules), and the
 * directory is writable: the journal is created in it exclusively (0666
 * less the umask) with its header line and flushed to the disk. A journal
 * that exists already is never overwritten: LSC_EIO, "TARGET.journal.csv
 * exists: ..." (it holds an earlier recording: read or convert it, then
 * remove it). Returns 0 and *out, LSC_EINVAL, LSC_EIO (err says why; nothing
 * created) or LSC_ENOSPC (out of memory). */
LSC_API int lsc_journal_open(const char *target, const lsc_action *a, lsc_journal **out,
                             lsc_file_error *err);
/* Appends a keyframe (time_ms, then the positions of the servos given at
 * open) as one row, with one write(2): once this returns 0 the row survives
 * the end of the process, whatever ends it. The rows reach the disk itself
 * (fdatasync) when the last flush is LSC_JOURNAL_SYNC_MS or more ago (a flush
 * takes from under a millisecond on an SSD to tens of ms on an SD card: once
 * per row would hold up a recording of a keyframe every few ms). Returns 0,
 * LSC_EINVAL (NULL arguments, or j closed by an earlier error), LSC_ENOSPC
 * (the journal holds LSC_ACTION_KEYFRAMES_MAX rows) or LSC_EIO (a full disk:
 * the journal is cut back to its last whole row, and stays readable). */
LSC_API int lsc_journal_append(lsc_journal *j, uint16_t time_ms, const uint16_t *positions,
                               lsc_file_error *err);
/* Flushes the rows not yet on the disk if the last flush is at least
 * LSC_JOURNAL_SYNC_MS ago; cheap otherwise. Call it while waiting between
 * keyframes (every 100 ms or so: lsc_device_record's callback) so that a row
 * followed by no other reaches the disk within about LSC_JOURNAL_SYNC_MS too.
 * Returns 0, LSC_EINVAL (j NULL) or LSC_EIO. */
LSC_API int lsc_journal_sync(lsc_journal *j, lsc_file_error *err);
/* Writes a to the target (lsc_action_write: atomically) and, once it is
 * there, removes the journal. On failure (the format cannot hold a, the disk
 * is full...) the journal stays, flushed, and lsc_journal_path names it:
 * say so. Either way call lsc_journal_close then. Returns lsc_action_write's
 * codes; LSC_EINVAL for NULL arguments. */
LSC_API int lsc_journal_finish(lsc_journal *j, const lsc_action *a, lsc_file_error *err);
/* The journal's path ("TARGET.journal.csv"); valid until lsc_journal_close. */
LSC_API const char *lsc_journal_path(const lsc_journal *j);
/* Flushes and closes the journal and frees j. The journal file stays unless
 * lsc_journal_finish removed it. NULL is allowed. */
LSC_API void lsc_journal_close(lsc_journal *j);

/* The number a file name starts with (its last path part, leading decimal
 * digits, 0..254), or -1 if none: "7-wave.rob" -> 7. */
LSC_API int lsc_file_group_number(const char *path);

#ifdef __cplusplus
}
#endif

#endif /* LSC_FILES_H */
