/* .d6a, the LSC boards' PC software file: an SQLite 3 database with a table
 * ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT, Servo1 INT,
 * ..., ServoN INT), one row per keyframe in [Index] order; some files leave
 * servo columns out. Read and written with SQLite itself, the database held in
 * memory (sqlite3_deserialize / sqlite3_serialize). A file is untrusted: the
 * connection is defensive, trusts no schema, and gives up after a bounded
 * amount of work (SECURITY.md). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)
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
    return lsc_files_fail(err, 0, ".d6a files need SQLite: this lsc was built without it");
}

int lsc_files_d6a_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err)
{
    (void)a;
    (void)b;
    return lsc_files_fail(err, 0, ".d6a files need SQLite: this lsc was built without it");
}

#else

#include <sqlite3.h>

#define D6A_PROGRESS_STEPS 1000u   /* VM instructions between progress checks */
#define D6A_PROGRESS_LIMIT 100000u /* checks before a query is given up (1e8 steps) */

static int give_up(void *ctx)
{
    unsigned *checks = ctx;
    return ++*checks > D6A_PROGRESS_LIMIT;
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
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_DEFENSIVE, 1, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_TRIGGER, 0, (int *)NULL);
    (void)sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_VIEW, 0, (int *)NULL);
    (void)sqlite3_limit(db, SQLITE_LIMIT_LENGTH, 1000000);
    (void)sqlite3_limit(db, SQLITE_LIMIT_SQL_LENGTH, 100000);
    sqlite3_progress_handler(db, (int)D6A_PROGRESS_STEPS, give_up, checks);
    return db;
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

/* The columns: Time, the ServoN, whether [Index] exists; the SELECT for them. */
static int read_columns(sqlite3 *db, lsc_action *a, lsc_outbuf *sql, lsc_file_error *err)
{
    sqlite3_stmt *st = NULL;
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    char names[LSC_PLAYER_SERVOS_MAX][12];
    size_t n = 0;
    bool time = false, index = false;
    int r = 0;
    if (sqlite3_prepare_v2(db, "SELECT name FROM pragma_table_info('ActionGroup')", -1, &st,
                           NULL) != SQLITE_OK) {
        return lsc_files_fail(err, 0, "cannot read the table's columns: %s", sqlite3_errmsg(db));
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
        } else if (servo_column(name, &id)) {
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
        r = lsc_files_fail(err, 0, "cannot read the table's columns: %s", sqlite3_errmsg(db));
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
    (void)lsc_action_init(a, ids, n);
    lsc_outbuf_printf(sql, "SELECT \"Time\"");
    for (size_t i = 0; i < n; i++) {
        lsc_outbuf_printf(sql, ", \"%s\"", names[i]);
    }
    lsc_outbuf_printf(sql, " FROM ActionGroup ORDER BY %s", index ? "\"Index\"" : "rowid");
    lsc_outbuf_put(sql, "", 1);
    return sql->failed ? lsc_files_oom(err) : 0;
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
    int r = 0;
    sqlite3_stmt *st = NULL;
    lsc_outbuf sql = {NULL, 0, 0, false};
    if (sqlite3_deserialize(db, "main", copy, (sqlite3_int64)len, (sqlite3_int64)len,
                            SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) !=
        SQLITE_OK) {
        r = lsc_files_oom(err);
    } else if (sqlite3_prepare_v2(db,
                                  "SELECT type FROM sqlite_master WHERE name = 'ActionGroup' "
                                  "COLLATE NOCASE",
                                  -1, &st, NULL) != SQLITE_OK) {
        r = lsc_files_fail(err, 0, "not a .d6a file: %s", sqlite3_errmsg(db));
    } else {
        int s = sqlite3_step(st);
        if (s == SQLITE_ROW) {
            const char *type = (const char *)sqlite3_column_text(st, 0);
            if (type == NULL || strcmp(type, "table") != 0) {
                r = lsc_files_fail(err, 0, "not a .d6a file: ActionGroup is not a table");
            }
        } else if (s == SQLITE_DONE) {
            r = lsc_files_fail(err, 0, "not a .d6a file: no table ActionGroup");
        } else {
            r = lsc_files_fail(err, 0, "not a .d6a file: %s", sqlite3_errmsg(db));
        }
    }
    sqlite3_finalize(st);
    st = NULL;
    if (r == 0) {
        r = read_columns(db, a, &sql, err);
    }
    if (r == 0 && sqlite3_prepare_v2(db, (const char *)sql.data, -1, &st, NULL) != SQLITE_OK) {
        r = lsc_files_fail(err, 0, "cannot read table ActionGroup: %s", sqlite3_errmsg(db));
    }
    unsigned long row = 0;
    int s = SQLITE_DONE;
    while (r == 0 && (s = sqlite3_step(st)) == SQLITE_ROW) {
        uint16_t w[1u + LSC_PLAYER_SERVOS_MAX];
        row++;
        for (int c = 0; r == 0 && c <= a->nservos; c++) {
            sqlite3_int64 v = sqlite3_column_int64(st, c);
            const char *col = sqlite3_column_name(st, c);
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
        if (r == 0 && lsc_action_append(a, w[0], w + 1) != 0) {
            r = lsc_files_oom(err);
        }
    }
    if (r == 0 && s != SQLITE_DONE) {
        r = lsc_files_fail(err, row + 1u, "row %lu: %s", row + 1u,
                           checks > D6A_PROGRESS_LIMIT ? "too much work for a .d6a file"
                                                       : sqlite3_errmsg(db));
    }
    sqlite3_finalize(st);
    sqlite3_close(db);
    free(sql.data);
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
    lsc_outbuf create = {NULL, 0, 0, false}, insert = {NULL, 0, 0, false};
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
        r = lsc_files_fail(err, 0, "SQLite: %s", sqlite3_errmsg(db));
    } else {
        lsc_outbuf_put(b, bytes, (size_t)size); /* out of memory: b->failed */
    }
    sqlite3_free(bytes);
    sqlite3_close(db);
    return r;
}

#endif /* LSC_HAVE_SQLITE */
#else
typedef int lsc_files_empty_unit; /* ISO C forbids an empty translation unit */
#endif
