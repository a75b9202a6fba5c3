/* .d6a, the LSC boards' PC software file: an SQLite 3 database with a table
 * ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT, Servo1 INT,
 * ..., ServoN INT), one row per keyframe in [Index] order; some files leave
 * servo columns out. Read and written with SQLite itself: a file through
 * SQLite on the file (read-only, so that its locks, journal and WAL decide
 * what is committed), bytes and a WAL-mode file without a WAL from memory
 * (sqlite3_deserialize); written in memory (sqlite3_serialize) and then
 * replaced atomically by files.c. A file is untrusted: the connection is
 * defensive, trusts no schema, and gives up after a bounded amount of work
 * (SECURITY.md). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "files_internal.h"

#ifndef LSC_HAVE_SQLITE

int lsc_files_d6a_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err)
{
    (void)data;
    (void)len;
    (void)a;
    return lsc_files_fail(err, 0, ".d6a files need SQLite: this lsc was built without it (install the Debian package libsqlite3-dev, then configure and build lsc again)");
}

int lsc_files_d6a_read(const char *path, lsc_action *a, lsc_file_error *err)
{
    (void)path;
    (void)a;
    return lsc_files_fail(err, 0, ".d6a files need SQLite: this lsc was built without it (install the Debian package libsqlite3-dev, then configure and build lsc again)");
}

int lsc_files_d6a_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err)
{
    (void)a;
    (void)b;
    return lsc_files_fail(err, 0, ".d6a files need SQLite: this lsc was built without it (install the Debian package libsqlite3-dev, then configure and build lsc again)");
}

#else

#include <sqlite3.h>
#include <sys/stat.h>

#include "../util/escape.h"

#define D6A_PROGRESS_STEPS 1000u   /* VM instructions between progress checks */
#define D6A_PROGRESS_LIMIT 100000u /* checks before a query is given up (1e8 steps) */
#define D6A_BUSY_MS 1000           /* how long a reader waits for another's write */

static int give_up(void *ctx)
{
    unsigned *checks = ctx;
    return ++*checks > D6A_PROGRESS_LIMIT;
}

/* Hardens db for untrusted files: defensive, no trusted schema, no triggers or
 * views, bounded lengths, and a bound on the work of every statement. */
static void harden(sqlite3 *db, unsigned *checks)
{
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_DEFENSIVE, 1, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_TRIGGER, 0, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_VIEW, 0, (int *)NULL);
    (void)sqlite3_limit(db, SQLITE_LIMIT_LENGTH, 1000000);
    (void)sqlite3_limit(db, SQLITE_LIMIT_SQL_LENGTH, 100000);
    (void)sqlite3_limit(db, SQLITE_LIMIT_ATTACHED, 0);
    sqlite3_progress_handler(db, (int)D6A_PROGRESS_STEPS, give_up, checks);
}

/* An in-memory connection hardened for untrusted files. */
static sqlite3 *open_db(unsigned *checks)
{
    sqlite3 *db = NULL;
    if (sqlite3_open_v2(":memory:", &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL) !=
        SQLITE_OK) {
        sqlite3_close(db);
        return NULL;
    }
    harden(db, checks);
    return db;
}

/* Why the last call on db failed, as a message: a hot journal (LSC_EIO), a
 * lock held by a writer (LSC_EBUSY), too much work, or SQLite's own text
 * (escaped: it can carry names from the file) after `what`. */
static int db_fail(sqlite3 *db, const unsigned *checks, lsc_file_error *err, unsigned long at,
                   const char *what)
{
    int code = sqlite3_extended_errcode(db);
    if (code == SQLITE_READONLY_ROLLBACK) {
        return lsc_files_fail_code(err, LSC_EIO,
                                   "a write to it was interrupted (its -journal file is hot): "
                                   "open it once with a program that may write it, such as "
                                   "sqlite3, to roll that back");
    }
    if ((code & 0xff) == SQLITE_BUSY || (code & 0xff) == SQLITE_LOCKED) {
        return lsc_files_fail_code(err, LSC_EBUSY,
                                   "another program is writing it (SQLite's lock): try again "
                                   "when it has finished");
    }
    if (*checks > D6A_PROGRESS_LIMIT) {
        return lsc_files_fail(err, at, "%stoo much work for a .d6a file", what);
    }
    char text[sizeof err->message];
    const char *msg = sqlite3_errmsg(db);
    (void)lsc_escape_text(text, sizeof text - 40u, msg, strlen(msg));
    return lsc_files_fail(err, at, "%s%s", what, text);
}

/* "Servo<digits>" (any case) with digits 0..255 into *id. */
static bool servo_column(const char *name, uint8_t *id)
{
    static const char key[] = "servo";
    unsigned v = 0;
    size_t i = 0;
    if (strlen(name) > 8u) { /* "Servo" and at most 3 digits */
        return false;
    }
    for (; key[i] != '\0'; i++) {
        if ((name[i] | 0x20) != key[i]) {
            return false;
        }
    }
    if (name[i] == '\0') {
        return false;
    }
    for (; name[i] != '\0'; i++) {
        if (name[i] < '0' || name[i] > '9' || (v = v * 10u + (unsigned)(name[i] - '0')) > 255u) {
            return false;
        }
    }
    *id = (uint8_t)v;
    return true;
}

static bool same_name(const char *a, const char *b)
{
    return sqlite3_stricmp(a, b) == 0;
}

/* The first keyword after "CREATE " in a CREATE statement as SQLite reads it
 * (blanks and comments skipped), up to n - 1 letters in lower case into kw. */
static void create_keyword(const char *sql, char *kw, size_t n)
{
    size_t k = 0;
    const char *p = sql + 7; /* SQLite loads only entries that start "create " */
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\f' || *p == '\r') {
            p++;
        }
        if (p[0] == '-' && p[1] == '-') {
            while (*p != '\0' && *p != '\n') {
                p++;
            }
        } else if (p[0] == '/' && p[1] == '*') {
            const char *end = strstr(p + 2, "*/");
            p = end != NULL ? end + 2 : p + strlen(p);
        } else {
            break;
        }
    }
    while (k + 1u < n && ((*p | 0x20) >= 'a' && (*p | 0x20) <= 'z')) {
        kw[k++] = (char)(*p++ | 0x20);
    }
    kw[k] = '\0';
}

/* ActionGroup must be exactly one ordinary table: not a view, not a virtual
 * table (whose module would run on the file's arguments), not an index. */
static int check_table(sqlite3 *db, const unsigned *checks, lsc_file_error *err)
{
    sqlite3_stmt *st = NULL;
    int r = 0;
    if (sqlite3_prepare_v2(db,
                           "SELECT type, sql FROM sqlite_master WHERE name = 'ActionGroup' "
                           "COLLATE NOCASE",
                           -1, &st, NULL) != SQLITE_OK) {
        return db_fail(db, checks, err, 0, "not a .d6a file: ");
    }
    int s = sqlite3_step(st);
    if (s == SQLITE_ROW) {
        const char *type = (const char *)sqlite3_column_text(st, 0);
        const char *sql = (const char *)sqlite3_column_text(st, 1);
        char kw[12] = "";
        if (sql != NULL && strlen(sql) > 7u && sqlite3_strnicmp(sql, "create ", 7) == 0) {
            create_keyword(sql, kw, sizeof kw);
        }
        if (type == NULL || strcmp(type, "table") != 0) {
            r = lsc_files_fail(err, 0, "not a .d6a file: ActionGroup is not a table (it is %s)",
                               type != NULL && strcmp(type, "view") == 0    ? "a view"
                               : type != NULL && strcmp(type, "index") == 0 ? "an index"
                                                                            : "something else");
        } else if (strcmp(kw, "table") != 0 && strcmp(kw, "temp") != 0 &&
                   strcmp(kw, "temporary") != 0) {
            r = lsc_files_fail(err, 0, "not a .d6a file: ActionGroup is not a table (it is %s)",
                               strcmp(kw, "virtual") == 0 ? "a virtual table"
                                                          : "not made by CREATE TABLE");
        } else if ((s = sqlite3_step(st)) == SQLITE_ROW) {
            r = lsc_files_fail(err, 0, "not a .d6a file: two objects are named ActionGroup");
        }
    } else if (s == SQLITE_DONE) {
        r = lsc_files_fail(err, 0, "not a .d6a file: no table ActionGroup");
    }
    if (r == 0 && s != SQLITE_DONE) {
        r = db_fail(db, checks, err, 0, "not a .d6a file: ");
    }
    sqlite3_finalize(st);
    return r;
}

/* The columns: Time, the ServoN, whether [Index] exists; the SELECT for them. */
static int read_columns(sqlite3 *db, const unsigned *checks, lsc_action *a, lsc_outbuf *sql,
                        lsc_file_error *err)
{
    sqlite3_stmt *st = NULL;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    char names[LSC_PLAYER_SERVOS_MAX][12];
    size_t n = 0;
    bool time = false, index = false;
    int r = 0;
    if (sqlite3_prepare_v2(db, "SELECT name FROM pragma_table_info('ActionGroup')", -1, &st,
                           NULL) != SQLITE_OK) {
        return db_fail(db, checks, err, 0, "cannot read the table's columns: ");
    }
    int s;
    while (r == 0 && (s = sqlite3_step(st)) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 0);
        uint8_t id;
        if (name == NULL) {
            continue;
        }
        if (same_name(name, "Time")) {
            time = true;
        } else if (same_name(name, "Index")) {
            index = true;
        } else if (servo_column(name, &id)) { /* name: "Servo" and digits, nothing else */
            if (memchr(ids, id, n) != NULL) {
                r = lsc_files_fail(err, 0, "column %s: servo %u has two columns", name, id);
            } else if (n == LSC_PLAYER_SERVOS_MAX) {
                r = lsc_files_fail(err, 0, "more than %u Servo columns", LSC_PLAYER_SERVOS_MAX);
            } else {
                (void)snprintf(names[n], sizeof names[n], "%s", name); /* 8 characters at most */
                ids[n++] = id;
            }
        } /* other columns are not the keyframes' business */
    }
    if (r == 0 && s != SQLITE_DONE) {
        r = db_fail(db, checks, err, 0, "cannot read the table's columns: ");
    }
    sqlite3_finalize(st);
    if (r != 0) {
        return r;
    }
    if (!time) {
        return lsc_files_fail(err, 0, "table ActionGroup has no Time column");
    }
    if (n == 0) {
        return lsc_files_fail(err, 0, "table ActionGroup has no ServoN column");
    }
    if (!index) { /* the rows' order is the rowid's: a WITHOUT ROWID table has none */
        st = NULL;
        int p = sqlite3_prepare_v2(db, "SELECT rowid FROM ActionGroup", -1, &st, NULL);
        sqlite3_finalize(st);
        if (p != SQLITE_OK) {
            return lsc_files_fail(err, 0, "table ActionGroup is a WITHOUT ROWID table and has "
                                          "no Index column: the order of its keyframes is "
                                          "unknown");
        }
    }
    (void)lsc_action_init(a, ids, n);
    lsc_outbuf_printf(sql, "SELECT \"Time\"");
    for (size_t i = 0; i < n; i++) {
        lsc_outbuf_printf(sql, ", \"%s\"", names[i]);
    }
    lsc_outbuf_printf(sql, " FROM ActionGroup ORDER BY %s", index ? "\"Index\"" : "rowid");
    lsc_outbuf_put(sql, "", 1);
    return sql->failed ? lsc_files_oom(err) : 0;
}

/* The keyframes of db (opened and hardened) into a, in one read transaction. */
static int read_db(sqlite3 *db, const unsigned *checks, bool bound_size, lsc_action *a,
                   lsc_file_error *err)
{
    sqlite3_stmt *st = NULL;
    lsc_outbuf sql = {NULL, 0, 0, false, false};
    if (sqlite3_exec(db, "BEGIN", NULL, NULL, NULL) != SQLITE_OK) {
        return db_fail(db, checks, err, 0, "not a .d6a file: ");
    }
    int r = check_table(db, checks, err);
    if (r == 0 && bound_size) { /* a file's committed state, its WAL included */
        sqlite3_int64 size = -1;
        if (sqlite3_prepare_v2(db, "SELECT page_count * page_size FROM pragma_page_count(), "
                                   "pragma_page_size()",
                               -1, &st, NULL) == SQLITE_OK &&
            sqlite3_step(st) == SQLITE_ROW) {
            size = sqlite3_column_int64(st, 0);
        }
        sqlite3_finalize(st);
        st = NULL;
        if (size < 0) {
            r = db_fail(db, checks, err, 0, "not a .d6a file: ");
        } else if ((sqlite3_uint64)size > LSC_FILE_MAX_BYTES) {
            r = lsc_files_fail(err, 0, "larger than %lu bytes", LSC_FILE_MAX_BYTES);
        }
    }
    if (r == 0) {
        r = read_columns(db, checks, a, &sql, err);
    }
    if (r == 0 && sqlite3_prepare_v2(db, (const char *)sql.data, -1, &st, NULL) != SQLITE_OK) {
        r = db_fail(db, checks, err, 0, "cannot read table ActionGroup: ");
    }
    unsigned long row = 0;
    int s = SQLITE_DONE;
    while (r == 0 && (s = sqlite3_step(st)) == SQLITE_ROW) {
        uint16_t w[1u + LSC_PLAYER_SERVOS_MAX];
        row++;
        for (int c = 0; r == 0 && c <= a->nservos; c++) {
            sqlite3_int64 v = sqlite3_column_int64(st, c);
            const char *col = sqlite3_column_name(st, c); /* Time or a checked ServoN */
            int type = sqlite3_column_type(st, c);
            if (type == SQLITE_NULL) {
                r = lsc_files_fail(err, row, "row %lu: %s is empty", row, col);
            } else if (type != SQLITE_INTEGER) {
                r = lsc_files_fail(err, row, "row %lu: %s is not a whole number", row, col);
            } else if (v < 0 || v > 65535) {
                r = lsc_files_fail(err, row, "row %lu: %s %lld is out of range 0..65535", row,
                                   col, (long long)v);
            }
            w[c] = (uint16_t)v;
        }
        if (r == 0) {
            r = lsc_files_append(a, w, "row", row, err);
        }
    }
    if (r == 0 && s != SQLITE_DONE) {
        char where[40];
        (void)snprintf(where, sizeof where, "row %lu: ", row + 1u);
        r = db_fail(db, checks, err, row + 1u, where);
    }
    sqlite3_finalize(st);
    (void)sqlite3_exec(db, "COMMIT", NULL, NULL, NULL); /* nothing was written */
    free(sql.data);
    return r;
}

static const char sqlite_magic[16] = "SQLite format 3"; /* and its NUL */

#define WAL_HEADER 32u       /* a WAL file's header */
#define WAL_FRAME_HEADER 24u /* before each page in a WAL */

static uint32_t be32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3];
}

/* The page size a database header (its first 100 bytes) gives: 512..65536,
 * a power of two; 0 if it gives none (SQLite refuses the file then). */
static uint32_t page_size_of(const uint8_t *head)
{
    uint32_t v = ((uint32_t)head[16] << 8) | head[17];
    v = v == 1u ? 65536u : v;
    return v >= 512u && (v & (v - 1u)) == 0u ? v : 0u;
}

/* SQLite reads the pages a file lacks as zeros: a database cut short is
 * refused here, before SQLite sees it. A file of size bytes is whole pages,
 * and at least as many as its header says it has (that count is kept only
 * while the change counter at 24 matches the one at 92; older writers leave
 * it stale, and then the whole pages are all there is to check). */
static int check_length(const uint8_t *head, sqlite3_uint64 size, lsc_file_error *err)
{
    uint32_t page = page_size_of(head), pages = be32(head + 28);
    if (page == 0u) {
        return 0;
    }
    if (size % page != 0u) {
        return lsc_files_fail(err, 0,
                              "cut short: %llu bytes is not a whole number of its %lu-byte "
                              "pages (the file was not copied whole)",
                              (unsigned long long)size, (unsigned long)page);
    }
    if (pages != 0u && memcmp(head + 24, head + 92, 4) == 0 &&
        size < (sqlite3_uint64)pages * page) {
        return lsc_files_fail(err, 0,
                              "cut short: its header says %lu pages of %lu bytes (%llu bytes), "
                              "the file has %llu (it was not copied whole)",
                              (unsigned long)pages, (unsigned long)page,
                              (unsigned long long)pages * page, (unsigned long long)size);
    }
    return 0;
}

int lsc_files_d6a_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err)
{
    unsigned checks = 0;
    if (len == 0) {
        return lsc_files_fail(err, 0, "not a .d6a file: it is empty (an SQLite database "
                                      "was expected)");
    }
    sqlite3 *db = open_db(&checks);
    unsigned char *copy = sqlite3_malloc64(len);
    if (db == NULL || copy == NULL) {
        sqlite3_free(copy);
        sqlite3_close(db);
        return lsc_files_oom(err);
    }
    memcpy(copy, data, len);
    int r = len >= 100u && memcmp(copy, sqlite_magic, sizeof sqlite_magic) == 0
                ? check_length(copy, len, err)
                : 0;
    if (r != 0) {
        sqlite3_free(copy);
        sqlite3_close(db);
        return r;
    }
    /* a WAL-mode file (format versions 2) is read as the file alone: in
     * memory there is no WAL to look for */
    if (len >= 100u && memcmp(copy, sqlite_magic, sizeof sqlite_magic) == 0 &&
        (copy[18] == 2u || copy[19] == 2u)) {
        copy[18] = 1u;
        copy[19] = 1u;
    }
    if (sqlite3_deserialize(db, "main", copy, (sqlite3_int64)len, (sqlite3_int64)len,
                            SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) !=
        SQLITE_OK) {
        r = lsc_files_oom(err);
    } else {
        r = read_db(db, &checks, false, a, err);
    }
    sqlite3_close(db);
    return r;
}

/* The size of path's "-wal" file: 0 if there is none; -1 out of memory
 * (then SQLite looks for it). */
static long long wal_size(const char *path)
{
    size_t n = strlen(path);
    char *wal = malloc(n + 5u);
    struct stat st;
    long long size = -1;
    if (wal != NULL) {
        memcpy(wal, path, n);
        memcpy(wal + n, "-wal", 5);
        size = stat(wal, &st) == 0 ? (long long)st.st_size : 0;
        free(wal);
    }
    return size;
}

/* A WAL of wal bytes next to a database of page-byte pages: its header, then
 * whole frames (a frame header and a page). SQLite would take one cut short
 * for a write that never finished and silently read the file without it. */
static int check_wal(long long wal, uint32_t page, lsc_file_error *err)
{
    if (wal <= 0 || page == 0u ||
        ((unsigned long long)wal >= WAL_HEADER &&
         ((unsigned long long)wal - WAL_HEADER) % (WAL_FRAME_HEADER + page) == 0u)) {
        return 0;
    }
    return lsc_files_fail(err, 0,
                          "cut short: its -wal file (%lld bytes) is not whole %lu-byte frames "
                          "after its header (it was not copied whole)",
                          wal, (unsigned long)(WAL_FRAME_HEADER + page));
}

/* The whole file db has open, read through SQLite's own descriptor (a
 * descriptor of ours, once closed, would drop the POSIX locks that any
 * SQLite connection of this process holds on the file). NULL and *r set on
 * failure. */
static uint8_t *read_whole(sqlite3 *db, size_t *len, int *r, lsc_file_error *err)
{
    sqlite3_file *f = NULL;
    sqlite3_int64 size = 0;
    if (sqlite3_file_control(db, "main", SQLITE_FCNTL_FILE_POINTER, &f) != SQLITE_OK ||
        f == NULL || f->pMethods == NULL || f->pMethods->xFileSize(f, &size) != SQLITE_OK ||
        size < 0) {
        *r = lsc_files_fail_code(err, LSC_EIO, "read error");
        return NULL;
    }
    if ((sqlite3_uint64)size > LSC_FILE_MAX_BYTES) {
        *r = lsc_files_fail(err, 0, "larger than %lu bytes", LSC_FILE_MAX_BYTES);
        return NULL;
    }
    uint8_t *data = malloc((size_t)size + 1u);
    if (data == NULL) {
        *r = lsc_files_oom(err);
        return NULL;
    }
    if (size > 0 && f->pMethods->xRead(f, data, (int)size, 0) != SQLITE_OK) {
        free(data);
        *r = lsc_files_fail_code(err, LSC_EIO, "read error (the file changed while read?)");
        return NULL;
    }
    *len = (size_t)size;
    return data;
}

int lsc_files_d6a_read(const char *path, lsc_action *a, lsc_file_error *err)
{
    /* A name SQLite could take for a URI is made relative. Opening reads
     * nothing yet and creates nothing. */
    size_t n = strlen(path) + 3u;
    char *name = malloc(n);
    if (name == NULL) {
        return lsc_files_oom(err);
    }
    (void)snprintf(name, n, "%s%s", strncmp(path, "file:", 5) == 0 ? "./" : "", path);
    unsigned checks = 0;
    sqlite3 *db = NULL;
    int r = 0;
    if (sqlite3_open_v2(name, &db, SQLITE_OPEN_READONLY, NULL) != SQLITE_OK) {
        r = db == NULL ? lsc_files_oom(err) : db_fail(db, &checks, err, 0, "cannot open it: ");
    } else {
        harden(db, &checks);
        (void)sqlite3_busy_timeout(db, D6A_BUSY_MS);
        uint8_t head[100];
        sqlite3_file *f = NULL;
        sqlite3_int64 size = 0;
        bool bytes = true; /* read as bytes: not a database, or WAL mode and no WAL */
        if (sqlite3_file_control(db, "main", SQLITE_FCNTL_FILE_POINTER, &f) == SQLITE_OK &&
            f != NULL && f->pMethods != NULL && f->pMethods->xFileSize(f, &size) == SQLITE_OK &&
            size >= (sqlite3_int64)sizeof head &&
            f->pMethods->xRead(f, head, (int)sizeof head, 0) == SQLITE_OK &&
            memcmp(head, sqlite_magic, sizeof sqlite_magic) == 0) {
            /* WAL mode with no WAL: the file is the committed state (and
             * SQLite would create -wal and -shm beside it to read it) */
            bool wal_mode = head[18] == 2u || head[19] == 2u;
            long long wal = wal_mode ? wal_size(path) : 0;
            bytes = wal_mode && wal == 0;
            r = check_length(head, (sqlite3_uint64)size, err);
            if (r == 0) {
                r = check_wal(wal, page_size_of(head), err);
            }
        }
        if (r != 0) {
            /* (refused: cut short) */
        } else if (bytes) {
            size_t len = 0;
            uint8_t *data = read_whole(db, &len, &r, err);
            if (data != NULL) {
                r = lsc_files_d6a_parse(data, len, a, err);
                free(data);
            }
        } else {
            /* its locks, journal and WAL decide what is committed */
            r = read_db(db, &checks, true, a, err);
        }
    }
    sqlite3_close(db);
    free(name);
    return r;
}

/* Runs one statement; false on error. */
static bool exec(sqlite3 *db, const char *sql)
{
    return sqlite3_exec(db, sql, NULL, NULL, NULL) == SQLITE_OK;
}

int lsc_files_d6a_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err)
{
    unsigned checks = 0;
    sqlite3 *db = open_db(&checks);
    sqlite3_stmt *st = NULL;
    lsc_outbuf create = {NULL, 0, 0, false, false}, insert = {NULL, 0, 0, false, false};
    if (db == NULL) {
        return lsc_files_oom(err);
    }
    sqlite3_progress_handler(db, 0, NULL, NULL); /* our own statements: no limit */
    lsc_outbuf_printf(&create, "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY "
                               "AUTOINCREMENT, Time INT");
    lsc_outbuf_printf(&insert, "INSERT INTO ActionGroup(Time");
    for (size_t k = 0; k < a->nservos; k++) {
        lsc_outbuf_printf(&create, ", Servo%u INT", a->ids[k]);
        lsc_outbuf_printf(&insert, ", Servo%u", a->ids[k]);
    }
    lsc_outbuf_put(&create, ")", 2);
    lsc_outbuf_printf(&insert, ") VALUES(?");
    for (size_t k = 0; k < a->nservos; k++) {
        lsc_outbuf_printf(&insert, ", ?");
    }
    lsc_outbuf_put(&insert, ")", 2);
    if (create.failed || insert.failed) {
        free(create.data);
        free(insert.data);
        sqlite3_close(db);
        return lsc_files_oom(err);
    }
    bool ok = exec(db, (const char *)create.data) && exec(db, "BEGIN") &&
              sqlite3_prepare_v2(db, (const char *)insert.data, -1, &st, NULL) == SQLITE_OK;
    free(create.data);
    free(insert.data);
    for (uint32_t k = 0; ok && k < a->count; k++) {
        const uint16_t *w = lsc_action_row(a, k);
        for (int col = 0; col <= a->nservos; col++) {
            ok = ok && sqlite3_bind_int(st, col + 1, w[col]) == SQLITE_OK;
        }
        ok = ok && sqlite3_step(st) == SQLITE_DONE && sqlite3_reset(st) == SQLITE_OK;
    }
    sqlite3_finalize(st);
    ok = ok && exec(db, "COMMIT");
    sqlite3_int64 size = 0;
    unsigned char *bytes = ok ? sqlite3_serialize(db, "main", &size, 0) : NULL;
    int r = 0;
    if (bytes == NULL || size <= 0) {
        r = db_fail(db, &checks, err, 0, "SQLite: ");
    } else {
        lsc_outbuf_put(b, bytes, (size_t)size); /* out of memory: b->failed */
    }
    sqlite3_free(bytes);
    sqlite3_close(db);
    return r;
}

#endif /* LSC_HAVE_SQLITE */
#endif
