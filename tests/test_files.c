/* Tests of the action file readers and writers (include/lsc/files.h): each
 * format's edges (empty, one keyframe, missing columns, truncated, wrong
 * magic, values out of range) and round trips. Fixtures are built here. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lsc/lsc.h"

#ifdef LSC_HAVE_SQLITE
#include <sqlite3.h>
#endif

static lsc_file_error err;

static int parse(lsc_file_format f, const void *data, size_t len, lsc_action *a)
{
    memset(&err, 0, sizeof err);
    return lsc_action_parse(f, data, len, a, &err);
}

static int parse_text(lsc_file_format f, const char *text, lsc_action *a)
{
    return parse(f, text, strlen(text), a);
}

/* err's message contains s. */
static void assert_error(unsigned long at, const char *s)
{
    if (strstr(err.message, s) == NULL) {
        fail_msg("message '%s' lacks '%s'", err.message, s);
    }
    assert_int_equal(err.at, at);
}

/* The six-servo action the round trips use. */
static void xarm_action(lsc_action *a, uint32_t count)
{
    static const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    assert_int_equal(lsc_action_init(a, ids, 6), 0);
    for (uint32_t k = 0; k < count; k++) {
        uint16_t pos[6];
        for (size_t i = 0; i < 6; i++) {
            pos[i] = (uint16_t)(((size_t)k * 37u + i * 101u) % 1001u);
        }
        assert_int_equal(lsc_action_append(a, (uint16_t)(100u + k), pos), 0);
    }
}

static void assert_same(const lsc_action *x, const lsc_action *y)
{
    assert_int_equal(x->nservos, y->nservos);
    assert_memory_equal(x->ids, y->ids, x->nservos);
    assert_int_equal(x->count, y->count);
    if (x->count > 0) {
        assert_memory_equal(x->words, y->words, (size_t)x->count * (1u + x->nservos) * 2u);
    }
}

/* a written in f and read back is a. */
static void round_trip(lsc_file_format f, const lsc_action *a)
{
    uint8_t *bytes;
    size_t len;
    lsc_action b;
    assert_int_equal(lsc_action_format(f, a, "x", &bytes, &len, &err), 0);
    int r = parse(f, bytes, len, &b);
    if (r != 0) {
        fail_msg("%s: %s", lsc_file_format_name(f), err.message);
    }
    assert_same(a, &b);
    free(bytes);
    lsc_action_free(&b);
}

/* The written bytes as a C string (they hold no NUL of their own). */
static const char *cstr(uint8_t **bytes, size_t len)
{
    uint8_t *b = realloc(*bytes, len + 1);
    assert_non_null(b);
    b[len] = 0;
    assert_int_equal(strlen((const char *)b), len);
    *bytes = b;
    return (const char *)b;
}

static void test_format_of(void **state)
{
    (void)state;
    assert_int_equal(lsc_file_format_of("a.txt"), LSC_FILE_TEXT);
    assert_int_equal(lsc_file_format_of("dir/A.CSV"), LSC_FILE_CSV);
    assert_int_equal(lsc_file_format_of("arm.Rob"), LSC_FILE_ROB);
    assert_int_equal(lsc_file_format_of("/x/y.d6a"), LSC_FILE_D6A);
    assert_int_equal(lsc_file_format_of("arm.h"), LSC_FILE_HEADER);
    assert_int_equal(lsc_file_format_of("arm.hh"), LSC_FILE_UNKNOWN);
    assert_int_equal(lsc_file_format_of("arm"), LSC_FILE_UNKNOWN);
    assert_int_equal(lsc_file_format_of("d.rob/arm"), LSC_FILE_UNKNOWN);
    assert_int_equal(lsc_file_format_of(NULL), LSC_FILE_UNKNOWN);
    assert_string_equal(lsc_file_format_name(LSC_FILE_D6A), "d6a");
    assert_string_equal(lsc_file_format_name(LSC_FILE_UNKNOWN), "unknown");
    assert_int_equal(lsc_file_group_number("dir/7-wave.rob"), 7);
    assert_int_equal(lsc_file_group_number("254.d6a"), 254);
    assert_int_equal(lsc_file_group_number("255.d6a"), -1);
    assert_int_equal(lsc_file_group_number("9/wave.rob"), -1);
    assert_int_equal(lsc_file_group_number(NULL), -1);
}

static void test_action_memory(void **state)
{
    (void)state;
    lsc_action a;
    lsc_track t;
    static const uint8_t twice[] = {1, 1};
    static const uint16_t pos[] = {5, 6};
    assert_int_equal(lsc_action_init(&a, twice, 2), LSC_EINVAL);
    assert_int_equal(lsc_action_init(&a, twice, 0), LSC_EINVAL);
    assert_int_equal(lsc_action_init(&a, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_action_init(NULL, twice, 1), LSC_EINVAL);
    assert_int_equal(lsc_action_append(&a, 1, pos), LSC_EINVAL); /* no servos */
    assert_int_equal(lsc_action_init(&a, twice, 1), 0);
    for (uint16_t k = 0; k < 100; k++) {
        assert_int_equal(lsc_action_append(&a, k, pos), 0);
    }
    assert_int_equal(lsc_action_append(&a, 1, NULL), LSC_EINVAL);
    lsc_action_track(&a, &t);
    assert_int_equal(t.count, 100);
    assert_int_equal(t.nservos, 1);
    assert_ptr_equal(t.data, a.words);
    assert_true(t.read == NULL); /* a function pointer: not assert_null (ISO C) */
    lsc_action_free(&a);
    assert_int_equal(a.count, 0);
    lsc_action_free(NULL);
    lsc_action_track(NULL, &t);
}

static void test_csv(void **state)
{
    (void)state;
    lsc_action a;
    assert_int_equal(parse_text(LSC_FILE_CSV, "", &a), LSC_EINVAL);
    assert_error(1, "line 1: the file is empty");
    assert_int_equal(parse_text(LSC_FILE_CSV, "\r\n\n", &a), LSC_EINVAL);
    /* header only: no keyframes, which is a file */
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1,2\n", &a), 0);
    assert_int_equal(a.count, 0);
    assert_int_equal(a.nservos, 2);
    lsc_action_free(&a);
    /* one keyframe, CRLF, blank lines, no final newline */
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,9,0\r\n\r\n500,1500,65535", &a), 0);
    assert_int_equal(a.count, 1);
    assert_int_equal(a.ids[0], 9);
    assert_int_equal(a.words[0], 500);
    assert_int_equal(a.words[2], 65535);
    lsc_action_free(&a);
    assert_int_equal(parse_text(LSC_FILE_CSV, "time,1\n", &a), LSC_EINVAL);
    assert_error(1, "time_ms,ID");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1,256\n", &a), LSC_EINVAL);
    assert_error(1, "column 3");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1,1\n", &a), LSC_EINVAL);
    assert_error(1, "servo 1 listed twice");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,\n", &a), LSC_EINVAL);
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1,2\n1,2,3\n4,5\n", &a), LSC_EINVAL);
    assert_error(3, "line 3: too few values: the header has 3 columns");
    assert_int_equal(a.count, 0); /* refused whole */
    assert_null(a.words);
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1\n1,2,3\n", &a), LSC_EINVAL);
    assert_error(2, "too many values");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1\n1,65536\n", &a), LSC_EINVAL);
    assert_error(2, "column 2: a position must be a number 0..65535");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1\n-1,5\n", &a), LSC_EINVAL);
    assert_error(2, "column 1: time_ms");
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1\n1,5,\n", &a), LSC_EINVAL);
    assert_int_equal(parse_text(LSC_FILE_CSV, "time_ms,1\n1, 5\n", &a), LSC_EINVAL);
    char big[400] = "time_ms";
    for (int i = 0; i < 33; i++) {
        snprintf(big + strlen(big), sizeof big - strlen(big), ",%d", i);
    }
    assert_int_equal(parse_text(LSC_FILE_CSV, big, &a), LSC_EINVAL);
    assert_error(1, "more than 32 servos");
    xarm_action(&a, 5);
    round_trip(LSC_FILE_CSV, &a);
    lsc_action_free(&a);
}

/* A .rob image: header with count, then records. */
static size_t rob(uint8_t *out, uint16_t count, size_t records, uint16_t pos)
{
    static const uint8_t magic[6] = {'S', 'O', 'B', 'A', 'R', 'M'};
    memcpy(out, magic, sizeof magic);
    out[6] = (uint8_t)count;
    out[7] = (uint8_t)(count >> 8);
    memset(out + 8, 0, 8);
    for (size_t k = 0; k < records; k++) {
        uint8_t *r = out + 16 + 14 * k;
        r[0] = 0xE8; /* 1000 ms */
        r[1] = 0x03;
        for (size_t i = 0; i < 6; i++) {
            r[2 + 2 * i] = (uint8_t)(pos + i);
            r[3 + 2 * i] = (uint8_t)((pos + i) >> 8);
        }
    }
    return 16 + 14 * records;
}

static void test_rob(void **state)
{
    (void)state;
    uint8_t img[16 + 14 * 4];
    lsc_action a;
    /* empty: a header and no keyframes */
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 0, 0, 0), &a), 0);
    assert_int_equal(a.count, 0);
    assert_int_equal(a.nservos, 6);
    lsc_action_free(&a);
    /* one keyframe */
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 1, 1, 500), &a), 0);
    assert_int_equal(a.count, 1);
    assert_int_equal(a.words[0], 1000);
    assert_int_equal(a.words[1], 500);
    assert_int_equal(a.words[6], 505);
    assert_int_equal(a.ids[5], 6);
    lsc_action_free(&a);
    assert_int_equal(parse(LSC_FILE_ROB, img, 15, &a), LSC_EINVAL);
    assert_error(0, "truncated header: 15 of 16 bytes");
    assert_int_equal(parse(LSC_FILE_ROB, NULL, 0, &a), LSC_EINVAL);
    rob(img, 1, 1, 0);
    img[0] = 'X';
    assert_int_equal(parse(LSC_FILE_ROB, img, 30, &a), LSC_EINVAL);
    assert_error(0, "not a .rob file");
    /* the count says 3, the file holds 2 and a half records */
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 3, 3, 0) - 7, &a), LSC_EINVAL);
    assert_error(3, "record 3: truncated");
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 1, 2, 0), &a), LSC_EINVAL);
    assert_error(2, "14 bytes after the last of the 1 keyframes");
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 2, 2, 995), &a), 0); /* up to 1000 */
    assert_int_equal(a.words[6], 1000);
    lsc_action_free(&a);
    assert_int_equal(parse(LSC_FILE_ROB, img, rob(img, 2, 2, 996), &a), LSC_EINVAL);
    assert_error(1, "record 1: servo 6: position 1001 is out of range 0..1000");
    assert_int_equal(a.count, 0);
    xarm_action(&a, 4);
    round_trip(LSC_FILE_ROB, &a);
    lsc_action_free(&a);
    /* what a .rob cannot hold */
    uint8_t *bytes = NULL;
    size_t len = 0;
    static const uint8_t ids7[] = {1, 2, 3, 4, 5, 7};
    static const uint16_t pos[] = {1, 2, 3, 4, 5, 6};
    static const uint16_t far[] = {1, 2, 3, 4, 5, 1001};
    assert_int_equal(lsc_action_init(&a, ids7, 6), 0);
    assert_int_equal(lsc_action_format(LSC_FILE_ROB, &a, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_error(0, "servo 7: a .rob file holds servos 1..6 only");
    assert_int_equal(lsc_action_init(&a, ids7, 5), 0);
    assert_int_equal(lsc_action_format(LSC_FILE_ROB, &a, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_error(0, "servo 6 missing");
    /* ids in another order are reordered */
    static const uint8_t rev[] = {6, 5, 4, 3, 2, 1};
    assert_int_equal(lsc_action_init(&a, rev, 6), 0);
    assert_int_equal(lsc_action_append(&a, 7, pos), 0);
    assert_int_equal(lsc_action_format(LSC_FILE_ROB, &a, NULL, &bytes, &len, &err), 0);
    assert_int_equal(len, 30);
    assert_int_equal(bytes[16], 7);
    assert_int_equal(bytes[18], 6); /* servo 1 first */
    assert_int_equal(bytes[28], 1);
    free(bytes);
    assert_int_equal(lsc_action_append(&a, 7, far), 0);
    assert_int_equal(lsc_action_format(LSC_FILE_ROB, &a, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_error(2, "keyframe 2: servo 1: position 1001 is out of range");
    lsc_action_free(&a);
}

static void test_text(void **state)
{
    (void)state;
    lsc_action a;
    assert_int_equal(parse_text(LSC_FILE_TEXT, "group 3\n"
                                               "step 500 1:1000 2:2000\n"
                                               "step 300\n"
                                               "step 200 2:1500\n",
                                &a),
                     0);
    assert_int_equal(a.count, 3);
    assert_int_equal(a.nservos, 2);
    static const uint16_t want[] = {500, 1000, 2000, 300, 1000, 2000, 200, 1000, 1500};
    assert_memory_equal(a.words, want, sizeof want);
    lsc_action_free(&a);
    assert_int_equal(parse_text(LSC_FILE_TEXT, "", &a), LSC_EINVAL);
    assert_error(0, "no group in the file");
    assert_int_equal(parse_text(LSC_FILE_TEXT, "group 1\nstep 1 1:1\ngroup 2\nstep 1 1:1\n", &a),
                     LSC_EINVAL);
    assert_error(0, "2 groups: an action file holds one");
    assert_int_equal(parse_text(LSC_FILE_TEXT, "group 1\nstep 1 1:1\nstep 0 1:1\n", &a),
                     LSC_EINVAL);
    assert_error(3, "line 3:6: step time must be 1..65535 ms");
    assert_int_equal(parse_text(LSC_FILE_TEXT, "group 1\nstep 1 1:1\nstep 5 2:1\n", &a),
                     LSC_EINVAL);
    assert_error(1, "step 1: servo 2 has no position");
    assert_int_equal(parse_text(LSC_FILE_TEXT, "group 1\nstep 1\n", &a), LSC_EINVAL);
    assert_error(1, "the group moves no servo");
    char big[600] = "group 1\nstep 1";
    for (int i = 0; i < 33; i++) {
        snprintf(big + strlen(big), sizeof big - strlen(big), " %d:1", i);
    }
    assert_int_equal(parse_text(LSC_FILE_TEXT, big, &a), LSC_EINVAL);
    assert_error(1, "more than 32 servos");
    xarm_action(&a, 6);
    round_trip(LSC_FILE_TEXT, &a);
    uint8_t *bytes;
    size_t len;
    assert_int_equal(lsc_action_format(LSC_FILE_TEXT, &a, "dir/12-wave.txt", &bytes, &len, &err),
                     0);
    assert_non_null(strstr(cstr(&bytes, len), "\ngroup 12\nstep 100 1:0 2:101"));
    free(bytes);
    a.words[7] = 0; /* keyframe 2's time */
    assert_int_equal(lsc_action_format(LSC_FILE_TEXT, &a, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_error(2, "keyframe 2: time 0 ms cannot be a step");
    lsc_action_free(&a);
    assert_int_equal(lsc_action_format(LSC_FILE_TEXT, &a, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_error(0, "no keyframes");
}

static void test_header(void **state)
{
    (void)state;
    lsc_action a;
    uint8_t *bytes;
    size_t len;
    xarm_action(&a, 2);
    assert_int_equal(lsc_action_format(LSC_FILE_HEADER, &a, "out/7-Wave.h", &bytes, &len,
                                       &err),
                     0);
    const char *h = cstr(&bytes, len);
    assert_non_null(strstr(h, "#define KF_7_WAVE_STORAGE PROGMEM"));
    assert_non_null(strstr(h, "static const uint8_t kf_7_wave_ids[KF_7_WAVE_SERVOS] = "
                              "{1, 2, 3, 4, 5, 6};"));
    assert_non_null(strstr(h, "#define KF_7_WAVE_COUNT 2u"));
    assert_non_null(strstr(h, "kf_7_wave_keyframes[KF_7_WAVE_COUNT * (1u + KF_7_WAVE_SERVOS)]"));
    assert_non_null(strstr(h, " = {\n    100, 0, 101, 202, 303, 404, 505,\n"
                              "    101, 37, 138, 239, 340, 441, 542,\n};"));
    free(bytes);
    /* the CSV writer's rows, byte for byte */
    assert_int_equal(lsc_action_format(LSC_FILE_CSV, &a, NULL, &bytes, &len, &err), 0);
    assert_string_equal(cstr(&bytes, len), "time_ms,1,2,3,4,5,6\n100,0,101,202,303,404,505\n"
                                           "101,37,138,239,340,441,542\n");
    free(bytes);
    assert_int_equal(lsc_action_format(LSC_FILE_HEADER, &a, NULL, &bytes, &len, &err), 0);
    assert_non_null(strstr(cstr(&bytes, len), "keyframes_ids"));
    free(bytes);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_format(LSC_FILE_HEADER, &a, NULL, &bytes, &len, &err),
                     LSC_EINVAL);
    assert_error(0, "no keyframes");
    assert_int_equal(parse_text(LSC_FILE_HEADER, "", &a), LSC_EINVAL);
    assert_error(0, "C headers are written, not read");
    assert_int_equal(parse_text(LSC_FILE_UNKNOWN, "", &a), LSC_EINVAL);
    assert_error(0, "unknown file type");
    assert_int_equal(lsc_action_format(LSC_FILE_UNKNOWN, &a, NULL, &bytes, &len, &err),
                     LSC_EINVAL);
    assert_int_equal(lsc_action_format(LSC_FILE_CSV, NULL, NULL, &bytes, &len, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, NULL, 1, &a, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, "", 0, NULL, &err), LSC_EINVAL);
}

#ifdef LSC_HAVE_SQLITE
static char dir[] = "/tmp/lsc-test-files-XXXXXX";

/* A .d6a built by SQLite from sql, read back as bytes into *len. */
static uint8_t *d6a(const char *sql, size_t *len)
{
    char path[64];
    snprintf(path, sizeof path, "%s/t.d6a", dir);
    unlink(path);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, sql, NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static uint8_t buf[1 << 16];
    *len = fread(buf, 1, sizeof buf, f);
    assert_int_equal(fclose(f), 0);
    return buf;
}

#define VENDOR_TABLE "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, "

static void test_d6a(void **state)
{
    (void)state;
    lsc_action a;
    size_t len;
    uint8_t *db;
    assert_non_null(mkdtemp(dir));
    /* empty: the table and no rows */
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT, Servo2 INT);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), 0);
    assert_int_equal(a.count, 0);
    assert_int_equal(a.nservos, 2);
    lsc_action_free(&a);
    /* missing columns (only servos 1, 3, 6), rows out of insertion order */
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT, Servo3 INT, Servo6 INT, Note TEXT);"
                          "INSERT INTO ActionGroup VALUES(2, 300, 10, 30, 60, 'x');"
                          "INSERT INTO ActionGroup VALUES(1, 500, 11, 31, 61, NULL);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), 0);
    assert_int_equal(a.count, 2);
    assert_int_equal(a.nservos, 3);
    static const uint8_t ids[] = {1, 3, 6};
    assert_memory_equal(a.ids, ids, 3);
    static const uint16_t want[] = {500, 11, 31, 61, 300, 10, 30, 60};
    assert_memory_equal(a.words, want, sizeof want);
    lsc_action_free(&a);
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); INSERT INTO ActionGroup VALUES(1, 5, NULL);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(1, "row 1: Servo1 is empty");
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); INSERT INTO ActionGroup VALUES(1, 5, 1);"
                          "INSERT INTO ActionGroup VALUES(2, 5, 65536);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(2, "row 2: Servo1 65536 is out of range 0..65535");
    assert_int_equal(a.count, 0);
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); INSERT INTO ActionGroup VALUES(1, 'a', 1);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(1, "row 1: Time is not a whole number");
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); INSERT INTO ActionGroup VALUES(1, -1, 1);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(1, "row 1: Time -1 is out of range");
    db = d6a(VENDOR_TABLE "Servo1 INT);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "no Time column");
    db = d6a(VENDOR_TABLE "Time INT, Speed INT);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "no ServoN column");
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT, servo01 INT);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "servo 1 has two columns");
    db = d6a("CREATE TABLE Other(x INT);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "no table ActionGroup");
    db = d6a("CREATE TABLE T(Time INT, Servo1 INT); CREATE VIEW ActionGroup AS SELECT * FROM T;",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "ActionGroup is not a table");
    /* not a database; truncated; empty */
    assert_int_equal(parse_text(LSC_FILE_D6A, "SOBARM and more bytes than a header", &a),
                     LSC_EINVAL);
    assert_error(0, "not a .d6a file");
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); INSERT INTO ActionGroup VALUES(1, 5, 1);", &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len / 2, &a), LSC_EINVAL);
    assert_int_equal(parse(LSC_FILE_D6A, NULL, 0, &a), LSC_EINVAL);
    assert_error(0, "it is empty");
    /* round trips, also with ids that are not 1..N */
    xarm_action(&a, 7);
    round_trip(LSC_FILE_D6A, &a);
    lsc_action_free(&a);
    static const uint8_t odd[] = {0, 31, 200};
    static const uint16_t pos[] = {0, 65535, 2500};
    assert_int_equal(lsc_action_init(&a, odd, 3), 0);
    round_trip(LSC_FILE_D6A, &a);
    assert_int_equal(lsc_action_append(&a, 65535, pos), 0);
    round_trip(LSC_FILE_D6A, &a);
    lsc_action_free(&a);
    char path[64];
    snprintf(path, sizeof path, "%s/t.d6a", dir);
    unlink(path);
    rmdir(dir);
}
#endif

/* Whole files: write, read back, errors of the file system. */
static void test_files(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char path[64];
    lsc_action a, b;
    assert_non_null(mkdtemp(d));
    xarm_action(&a, 3);
    static const char *const exts[] = {"csv", "rob", "txt"
#ifdef LSC_HAVE_SQLITE
                                       , "d6a"
#endif
    };
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++) {
        snprintf(path, sizeof path, "%s/arm.%s", d, exts[i]);
        assert_int_equal(lsc_action_write(path, &a, &err), 0);
        assert_int_equal(lsc_action_read(path, &b, &err), 0);
        assert_same(&a, &b);
        lsc_action_free(&b);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/none.csv", d);
    assert_int_equal(lsc_action_read(path, &b, &err), LSC_EIO);
    assert_error(0, "No such file");
    snprintf(path, sizeof path, "%s/no/such/dir.csv", d);
    assert_int_equal(lsc_action_write(path, &a, &err), LSC_EIO);
    snprintf(path, sizeof path, "%s/arm.h", d);
    assert_int_equal(lsc_action_write(path, &a, &err), 0);
    assert_int_equal(lsc_action_read(path, &b, &err), LSC_EINVAL);
    assert_error(0, "C headers are written, not read");
    unlink(path);
    assert_int_equal(lsc_action_read("arm.xyz", &b, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_write("arm.xyz", &a, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read(NULL, &b, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_write(NULL, &a, &err), LSC_EINVAL);
    /* a directory is not a file */
    snprintf(path, sizeof path, "%s/d.csv", d);
    assert_int_equal(mkdir(path, 0700), 0);
    assert_int_equal(lsc_action_read(path, &b, &err), LSC_EIO);
    lsc_action_free(&a);
    rmdir(path);
    rmdir(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_format_of), cmocka_unit_test(test_action_memory),
        cmocka_unit_test(test_csv),       cmocka_unit_test(test_rob),
        cmocka_unit_test(test_text),      cmocka_unit_test(test_header),
#ifdef LSC_HAVE_SQLITE
        cmocka_unit_test(test_d6a),
#endif
        cmocka_unit_test(test_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
