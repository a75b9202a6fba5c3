/* Tests of the action file readers and writers (include/lsc/files.h): each
 * format's edges (empty, one keyframe, missing columns, truncated, wrong
 * magic, values out of range) and round trips; the limits at their exact
 * bounds; only regular files read and written (FIFOs, directories,
 * devices, links); files replaced atomically, also on a full disk (a tmpfs
 * when the test may mount one, and RLIMIT_FSIZE); .d6a files with another
 * connection writing, a hot journal, WAL mode, virtual tables; the record
 * journal, SIGKILL included. Fixtures are built here. */
#define _GNU_SOURCE 1 /* unshare */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sched.h>
#include <sys/mount.h>
#endif

#include "lsc/lsc.h"
#include "sized_test.h"

#ifdef LSC_HAVE_SQLITE
#include <sqlite3.h>
#endif

static lsc_file_error err = {.size = sizeof err};

static int parse(lsc_file_format f, const void *data, size_t len, lsc_action *a)
{
    memset(&err, 0, sizeof err);
    err.size = sizeof err;
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

/* lsc_file_error grows: a caller's shorter struct (up to at) gets nothing
 * beyond its size; one below the size field and at is refused at once
 * (LSC_EINVAL, nothing read or written); NULL is fine. */
static void test_error_size(void **state)
{
    (void)state;
    lsc_action a;
    lsc_file_error old;
    const size_t upto = offsetof(lsc_file_error, message);
    sized_guard(&old, sizeof old, upto);
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, "", 0, &a, &old), LSC_EINVAL);
    assert_int_equal(old.size, upto);
    assert_int_equal(old.at, 1);
    assert_true(sized_untouched(&old, upto, sizeof old));
    sized_guard(&old, sizeof old, offsetof(lsc_file_error, at));
    a.count = 77;
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, "time_ms,1\n", 10, &a, &old), LSC_EINVAL);
    assert_int_equal(a.count, 77); /* refused before anything */
    assert_int_equal(lsc_action_read("/nonexistent/x.csv", &a, &old), LSC_EINVAL);
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    uint8_t *bytes = NULL;
    size_t len = 0;
    assert_int_equal(lsc_file_load("/nonexistent/x.csv", 100, &bytes, &len, &old), LSC_EINVAL);
    assert_int_equal(lsc_file_replace("/nonexistent/x.csv", "", 0, &old), LSC_EINVAL);
    lsc_journal *j = NULL;
    assert_int_equal(lsc_journal_open("/nonexistent/x.csv", &a, &j, &old), LSC_EINVAL);
    assert_null(j);
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, "", 0, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_action_parse(LSC_FILE_CSV, "time_ms,1\n", 10, &a, NULL), 0);
    /* every call that takes one: refused, where it would have gone on */
    assert_int_equal(lsc_action_format(LSC_FILE_CSV, &a, NULL, &bytes, &len, &old), LSC_EINVAL);
    assert_null(bytes);
    assert_int_equal(lsc_action_write("/nonexistent/x.csv", &a, &old), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group("/nonexistent/x.csv", 1, &a, &old), LSC_EINVAL);
    uint8_t groups[4];
    assert_int_equal(lsc_action_groups("/nonexistent/x.csv", groups, 4, &old), LSC_EINVAL);
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    lsc_file_error e = {.size = sizeof e};
    char tmp[] = "/tmp/lsc-files-size-XXXXXX";
    assert_non_null(mkdtemp(tmp));
    char path[64];
    (void)snprintf(path, sizeof path, "%s/x.csv", tmp);
    assert_int_equal(lsc_journal_open(path, &a, &j, &e), 0);
    const uint16_t pos[1] = {500};
    assert_int_equal(lsc_journal_append(j, 100, pos, &old), LSC_EINVAL);
    assert_int_equal(lsc_journal_sync(j, &old), LSC_EINVAL);
    assert_int_equal(lsc_journal_finish(j, &a, &old), LSC_EINVAL);
    assert_int_equal(lsc_journal_finish(j, &a, &e), 0);
    lsc_journal_close(j);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(rmdir(tmp), 0);
    lsc_action_free(&a);
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

/* lsc_action_read_group: one group of a .txt of several; the one group of
 * an action file, numbered by its name. */
static void test_read_group(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char path[256], rob_path[256], other[256];
    lsc_action a, b;
    assert_non_null(mkdtemp(d));
    snprintf(path, sizeof path, "%s/arm.txt", d);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("group 1\nstep 500 1:1000 2:2000\n"
          "group 7\nstep 300 6:600\nstep 200 6:700 1:5\n"
          "group 3\nstep 100 1:1\n",
          f);
    assert_int_equal(fclose(f), 0);
    /* group 7's first step leaves servo 1 out: the group chosen is checked */
    assert_int_equal(lsc_action_read_group(path, 7, &a, &err), LSC_EINVAL);
    assert_error(1, "step 1: servo 1 has no position");
    assert_int_equal(lsc_action_read_group(path, 3, &a, &err), 0);
    assert_int_equal(a.count, 1);
    lsc_action_free(&a);
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("group 1\nstep 500 1:1000 2:2000\n"
          "group 7\nstep 300 6:600 1:4\nstep 200 6:700 1:5\n"
          "group 3\nstep 100 1:1\n",
          f);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(lsc_action_read_group(path, 7, &a, &err), 0);
    static const uint16_t want[] = {300, 600, 4, 200, 700, 5};
    assert_int_equal(a.nservos, 2);
    assert_int_equal(a.ids[0], 6);
    assert_int_equal(a.ids[1], 1);
    assert_int_equal(a.count, 2);
    assert_memory_equal(a.words, want, sizeof want);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_read_group(path, 1, &a, &err), 0);
    static const uint16_t want1[] = {500, 1000, 2000};
    assert_int_equal(a.count, 1);
    assert_memory_equal(a.words, want1, sizeof want1);
    lsc_action_free(&a);
    /* a group that is not there, and the file read without choosing */
    assert_int_equal(lsc_action_read_group(path, 4, &a, &err), LSC_EINVAL);
    assert_error(0, "no group 4 in the file (it holds groups 1, 3, 7)");
    assert_int_equal(a.count, 0);
    assert_null(a.words);
    assert_int_equal(lsc_action_read_group(path, -1, &a, &err), LSC_EINVAL);
    assert_error(0, "3 groups: an action file holds one; read one of them by its number "
                    "(groups 1, 3, 7)");
    assert_int_equal(lsc_action_read(path, &a, &err), LSC_EINVAL);
    assert_error(0, "3 groups: an action file holds one");
    /* what a front end asks then: the groups it holds */
    uint8_t groups[4] = {0};
    assert_int_equal(lsc_action_groups(path, groups, 2, &err), 3);
    assert_int_equal(groups[0], 1);
    assert_int_equal(groups[1], 3);
    assert_int_equal(groups[2], 0); /* beyond cap: untouched */
    assert_int_equal(lsc_action_groups(path, NULL, 0, &err), 3);
    assert_int_equal(lsc_action_groups(path, NULL, 1, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_groups(NULL, groups, 1, &err), LSC_EINVAL);
    /* the other groups are checked: a bad one anywhere refuses the file */
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("group 1\nstep 500 1:1000\ngroup 2\nstep 0 1:1\n", f);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(lsc_action_read_group(path, 1, &a, &err), LSC_EINVAL);
    assert_error(4, "line 4:6: step time must be 1..65535 ms");
    /* many groups: the first eight listed */
    f = fopen(path, "w");
    assert_non_null(f);
    for (int g = 10; g < 30; g++) {
        fprintf(f, "group %d\nstep 5 1:%d\n", g, g);
    }
    assert_int_equal(fclose(f), 0);
    assert_int_equal(lsc_action_read_group(path, 9, &a, &err), LSC_EINVAL);
    assert_error(0, "(it holds groups 10, 11, 12, 13, 14, 15, 16, 17, ...)");
    assert_int_equal(lsc_action_read_group(path, 29, &a, &err), 0);
    assert_int_equal(a.words[1], 29);
    lsc_action_free(&a);
    /* a one-group file: the group its name numbers, else 1 */
    xarm_action(&b, 2);
    snprintf(rob_path, sizeof rob_path, "%s/10.rob", d);
    assert_int_equal(lsc_action_write(rob_path, &b, &err), 0);
    assert_int_equal(lsc_action_read_group(rob_path, 10, &a, &err), 0);
    assert_same(&a, &b);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_read_group(rob_path, -1, &a, &err), 0);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_read_group(rob_path, 1, &a, &err), LSC_EINVAL);
    assert_error(0, "no group 1 in the file: it is one group, group 10");
    assert_int_equal(a.count, 0);
    uint8_t one[1] = {0};
    assert_int_equal(lsc_action_groups(rob_path, one, 1, &err), 1);
    assert_int_equal(one[0], 10);
    assert_int_equal(lsc_action_groups(rob_path, NULL, 0, &err), 1);
    snprintf(other, sizeof other, "%s/wave.csv", d);
    assert_int_equal(lsc_action_write(other, &b, &err), 0);
    assert_int_equal(lsc_action_read_group(other, 1, &a, &err), 0);
    assert_same(&a, &b);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_read_group(other, 2, &a, &err), LSC_EINVAL);
    assert_error(0, "it is one group, group 1");
    assert_int_equal(lsc_action_groups(other, one, 1, &err), 1);
    assert_int_equal(one[0], 1); /* no number in its name */
    /* the read's own errors come first */
    unlink(other);
    assert_int_equal(lsc_action_read_group(other, 1, &a, &err), LSC_EIO);
    assert_error(0, "No such file");
    snprintf(other, sizeof other, "%s/none.txt", d);
    assert_int_equal(lsc_action_read_group(other, 1, &a, &err), LSC_EIO);
    assert_error(0, "No such file");
    assert_int_equal(lsc_action_groups(other, NULL, 0, &err), LSC_EIO);
    assert_int_equal(lsc_action_groups("arm.xyz", NULL, 0, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group("arm.h", 1, &a, &err), LSC_EINVAL);
    assert_error(0, "C headers are written, not read");
    assert_int_equal(lsc_action_read_group("arm.xyz", 1, &a, &err), LSC_EINVAL);
    assert_error(0, "unknown file type");
    /* bad arguments */
    assert_int_equal(lsc_action_read_group(path, 255, &a, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group(path, -2, &a, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group(NULL, 1, &a, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group(path, 1, NULL, &err), LSC_EINVAL);
    assert_int_equal(lsc_action_read_group(path, 29, &a, NULL), 0);
    lsc_action_free(&a);
    lsc_action_free(&b);
    unlink(rob_path);
    unlink(path);
    rmdir(d);
}

/* ---- Helpers for the tests on files ---------------------------------------------- */

/* d/name into p (room for 256 bytes). */
static const char *in(char *p, const char *d, const char *name)
{
    int n = snprintf(p, 256, "%s/%s", d, name);
    assert_true(n > 0 && n < 256);
    return p;
}

static void put_file(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

/* The bytes of path (malloc'd, a NUL after them), *len; NULL if missing. */
static uint8_t *get_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    *len = 0;
    if (f == NULL) {
        return NULL;
    }
    uint8_t *b = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? cap * 2 : 4096;
            uint8_t *bigger = realloc(b, cap + 1);
            assert_non_null(bigger);
            b = bigger;
        }
        size_t k = fread(b + n, 1, cap - n, f);
        n += k;
        if (k == 0) {
            break;
        }
    }
    assert_int_equal(fclose(f), 0);
    b[n] = 0;
    *len = n;
    return b;
}

/* How many entries of directory d have a name that ends with suffix. */
static int count_entries(const char *d, const char *suffix)
{
    DIR *dp = opendir(d);
    assert_non_null(dp);
    int n = 0;
    size_t k = strlen(suffix);
    for (struct dirent *e; (e = readdir(dp)) != NULL;) {
        size_t m = strlen(e->d_name);
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0 && m >= k &&
            strcmp(e->d_name + m - k, suffix) == 0) {
            n++;
        }
    }
    closedir(dp);
    return n;
}

/* Removes d and what is in it (files, links, FIFOs, empty directories). */
static void remove_dir(const char *d)
{
    char p[256];
    DIR *dp = opendir(d);
    if (dp == NULL) {
        return;
    }
    for (struct dirent *e; (e = readdir(dp)) != NULL;) {
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0 &&
            unlink(in(p, d, e->d_name)) != 0) {
            rmdir(p);
        }
    }
    closedir(dp);
    rmdir(d);
}

/* A refusal of err at 0 whose message contains s, with return r == want. */
static void assert_refused(int r, int want, const char *s)
{
    if (r != want) {
        fail_msg("returned %d, not %d (%s)", r, want, err.message);
    }
    assert_error(err.at, s);
}

/* ---- One table of limits ------------------------------------------------------ */

/* The largest action: 32 servos (ids 100..131), every value 65535, the most
 * keyframes. */
static void largest_action(lsc_action *a)
{
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    uint16_t pos[LSC_PLAYER_SERVOS_MAX];
    for (size_t i = 0; i < LSC_PLAYER_SERVOS_MAX; i++) {
        ids[i] = (uint8_t)(100 + i);
        pos[i] = 65535;
    }
    assert_int_equal(lsc_action_init(a, ids, LSC_PLAYER_SERVOS_MAX), 0);
    for (uint32_t k = 0; k < LSC_ACTION_KEYFRAMES_MAX; k++) {
        if (lsc_action_append(a, 65535, pos) != 0) {
            fail_msg("append %u", (unsigned)k);
        }
    }
}

static void test_limits_keyframes(void **state)
{
    (void)state;
    lsc_action a, b;
    static const uint8_t one[] = {1};
    static const uint16_t pos[] = {500};
    uint8_t *bytes;
    size_t len;
    assert_int_equal(LSC_ACTION_KEYFRAMES_MAX, 65535);
    /* lsc_action_append takes exactly LSC_ACTION_KEYFRAMES_MAX */
    assert_int_equal(lsc_action_init(&a, one, 1), 0);
    for (uint32_t k = 0; k < LSC_ACTION_KEYFRAMES_MAX; k++) {
        if (lsc_action_append(&a, 1, pos) != 0) {
            fail_msg("append %u", (unsigned)k);
        }
    }
    assert_int_equal(lsc_action_append(&a, 1, pos), LSC_ENOSPC);
    assert_int_equal(a.count, LSC_ACTION_KEYFRAMES_MAX);
    /* CSV: 65535 rows read back; a row more is refused on its line */
    assert_int_equal(lsc_action_format(LSC_FILE_CSV, &a, NULL, &bytes, &len, &err), 0);
    assert_int_equal(parse(LSC_FILE_CSV, bytes, len, &b), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    uint8_t *more = realloc(bytes, len + 7);
    assert_non_null(more);
    bytes = more;
    (void)snprintf((char *)bytes + len, 7, "%s", "1,500\n");
    assert_int_equal(parse(LSC_FILE_CSV, bytes, len + 6, &b), LSC_EINVAL);
    assert_error(65537, "line 65537: more than 65535 keyframes");
    assert_int_equal(b.count, 0);
    free(bytes);
    /* text: 65535 steps read back; a step more is refused on its line */
    assert_int_equal(lsc_action_format(LSC_FILE_TEXT, &a, "x.txt", &bytes, &len, &err), 0);
    assert_int_equal(parse(LSC_FILE_TEXT, bytes, len, &b), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    more = realloc(bytes, len + 8);
    assert_non_null(more);
    bytes = more;
    (void)snprintf((char *)bytes + len, 8, "%s", "step 1\n");
    assert_int_equal(parse(LSC_FILE_TEXT, bytes, len + 7, &b), LSC_EINVAL);
    assert_error(65538, "line 65538: more than 65535 steps"); /* a comment, group, steps */
    free(bytes);
#ifdef LSC_HAVE_SQLITE
    assert_int_equal(lsc_action_format(LSC_FILE_D6A, &a, NULL, &bytes, &len, &err), 0);
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len, &b), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    free(bytes);
#endif
    /* an action built by hand with a keyframe more: every writer refuses it */
    uint16_t *w = realloc(a.words, (size_t)(LSC_ACTION_KEYFRAMES_MAX + 1u) * 2u * sizeof *w);
    assert_non_null(w);
    a.words = w;
    a.count = a.cap = LSC_ACTION_KEYFRAMES_MAX + 1u;
    static const lsc_file_format all[] = {LSC_FILE_TEXT, LSC_FILE_CSV, LSC_FILE_ROB,
                                          LSC_FILE_D6A, LSC_FILE_HEADER};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        bytes = NULL;
        assert_int_equal(lsc_action_format(all[i], &a, NULL, &bytes, &len, &err), LSC_EINVAL);
        assert_error(65536, "65536 keyframes: an action holds at most 65535");
        assert_null(bytes);
    }
    lsc_action_free(&a);
}

/* The most a file holds: what lsc writes it reads back. */
static void test_limits_bytes(void **state)
{
    (void)state;
    lsc_action a, b;
    uint8_t *bytes;
    size_t len;
    largest_action(&a);
    /* the largest CSV and .d6a are under LSC_FILE_MAX_BYTES and read back */
    assert_int_equal(lsc_action_format(LSC_FILE_CSV, &a, NULL, &bytes, &len, &err), 0);
    assert_true(len <= LSC_FILE_MAX_BYTES);
    assert_int_equal(parse(LSC_FILE_CSV, bytes, len, &b), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    free(bytes);
#ifdef LSC_HAVE_SQLITE
    assert_int_equal(lsc_action_format(LSC_FILE_D6A, &a, NULL, &bytes, &len, &err), 0);
    assert_true(len <= LSC_FILE_MAX_BYTES);
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len, &b), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    free(bytes);
#endif
    /* its text would be 21.7 MB: refused, not written to be refused on reading */
    bytes = NULL;
    assert_int_equal(lsc_action_format(LSC_FILE_TEXT, &a, "x.txt", &bytes, &len, &err),
                     LSC_EINVAL);
    assert_error(0, "the file would be larger than 16777216 bytes");
    assert_null(bytes);
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256];
    assert_non_null(mkdtemp(d));
    assert_int_equal(lsc_action_write(in(p, d, "big.txt"), &a, &err), LSC_EINVAL);
    assert_error(0, "larger than 16777216 bytes");
    assert_int_equal(count_entries(d, ""), 0); /* nothing written */
    lsc_action_free(&a);
    /* a file of exactly 16 MiB is read, a byte more is refused */
    size_t max = LSC_FILE_MAX_BYTES;
    assert_int_equal(max, 16777216);
    uint8_t *big = malloc(max + 1);
    assert_non_null(big);
    static const char head[] = "time_ms,1\n1,2\n";
    memcpy(big, head, sizeof head - 1);
    memset(big + sizeof head - 1, '\n', max + 1 - (sizeof head - 1));
    put_file(in(p, d, "big.csv"), big, max);
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_int_equal(b.count, 1);
    lsc_action_free(&b);
    put_file(p, big, max + 1);
    assert_int_equal(lsc_action_read(p, &b, &err), LSC_EINVAL);
    assert_error(0, "larger than 16777216 bytes");
    /* lsc_file_load's bound, both sides */
    uint8_t *data;
    assert_int_equal(lsc_file_load(p, max + 1, &data, &len, &err), 0);
    assert_int_equal(len, max + 1);
    assert_int_equal(data[len], 0);
    free(data);
    put_file(p, "0123456789", 10);
    assert_int_equal(lsc_file_load(p, 10, &data, &len, &err), 0);
    assert_int_equal(len, 10);
    assert_string_equal((const char *)data, "0123456789");
    free(data);
    assert_int_equal(lsc_file_load(p, 9, &data, &len, &err), LSC_EINVAL);
    assert_error(0, "larger than 9 bytes");
    assert_null(data);
    assert_int_equal(lsc_file_load(NULL, 9, &data, &len, &err), LSC_EINVAL);
    free(big);
    remove_dir(d);
}

/* ---- Only regular files ----------------------------------------------------------- */

static void test_only_regular_files(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256], q[256];
    lsc_action a, b;
    uint8_t *data;
    size_t len;
    assert_non_null(mkdtemp(d));
    xarm_action(&a, 2);
    alarm(60); /* a read or write that waits on a FIFO ends the test here */
    static const char *const fifos[] = {"fifo.csv", "fifo.txt", "fifo.rob", "fifo.d6a"};
    for (size_t i = 0; i < sizeof fifos / sizeof fifos[0]; i++) {
        assert_int_equal(mkfifo(in(p, d, fifos[i]), 0600), 0);
        assert_refused(lsc_action_read(p, &b, &err), LSC_EIO, "not a regular file (a FIFO)");
        assert_null(b.words);
        /* writing: refused, not opened (the FIFO stays a FIFO) */
        assert_refused(lsc_action_write(p, &a, &err), LSC_EINVAL, "not a regular file (a FIFO)");
        struct stat st;
        assert_int_equal(lstat(p, &st), 0);
        assert_true(S_ISFIFO(st.st_mode));
    }
    assert_refused(lsc_file_load(p, 100, &data, &len, &err), LSC_EIO,
                   "not a regular file (a FIFO)");
    /* a directory */
    assert_int_equal(mkdir(in(p, d, "dir.csv"), 0700), 0);
    assert_refused(lsc_action_read(p, &b, &err), LSC_EIO, "not a regular file (a directory)");
    assert_refused(lsc_action_write(p, &a, &err), LSC_EINVAL, "(a directory)");
    assert_int_equal(mkdir(in(p, d, "dir.d6a"), 0700), 0);
    assert_refused(lsc_action_read(p, &b, &err), LSC_EIO, "(a directory)");
    /* a device, directly and through a link */
    assert_refused(lsc_file_load("/dev/null", 100, &data, &len, &err), LSC_EIO,
                   "not a regular file (a character device)");
    assert_int_equal(symlink("/dev/null", in(p, d, "null.csv")), 0);
    assert_refused(lsc_action_read(p, &b, &err), LSC_EIO, "(a character device)");
    assert_int_equal(symlink("/dev/null", in(p, d, "null.d6a")), 0);
    assert_refused(lsc_action_read(p, &b, &err), LSC_EIO, "(a character device)");
    /* writing through a link is refused; the link and its file stay */
    assert_int_equal(lsc_action_write(in(q, d, "real.csv"), &a, &err), 0);
    size_t before_len, after_len;
    uint8_t *before = get_file(q, &before_len);
    assert_int_equal(symlink("real.csv", in(p, d, "link.csv")), 0);
    lsc_action c;
    xarm_action(&c, 5);
    assert_refused(lsc_action_write(p, &c, &err), LSC_EINVAL, "a symbolic link");
    uint8_t *after = get_file(q, &after_len);
    assert_int_equal(before_len, after_len);
    assert_memory_equal(before, after, before_len);
    struct stat st;
    assert_int_equal(lstat(p, &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    /* reading through a link to a regular file is fine */
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    free(before);
    free(after);
    alarm(0);
    lsc_action_free(&a);
    lsc_action_free(&c);
    remove_dir(d);
}

/* ---- Atomic writes ------------------------------------------------------------------ */

static void test_atomic_write(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256];
    lsc_action a, big, b;
    struct stat st1, st2;
    assert_non_null(mkdtemp(d));
    xarm_action(&a, 2);
    xarm_action(&big, 2000);
    mode_t old_umask = umask(022);
    /* a new file: 0666 less the umask */
    assert_int_equal(lsc_action_write(in(p, d, "keep.csv"), &a, &err), 0);
    assert_int_equal(stat(p, &st1), 0);
    assert_int_equal(st1.st_mode & 07777, 0644);
    umask(077);
    char q[256];
    assert_int_equal(lsc_action_write(in(q, d, "private.csv"), &a, &err), 0);
    assert_int_equal(stat(q, &st2), 0);
    assert_int_equal(st2.st_mode & 07777, 0600);
    umask(old_umask);
    /* replacing keeps the old file's mode, and is a new file renamed over it */
    assert_int_equal(chmod(p, 0640), 0);
    assert_int_equal(lsc_action_write(p, &big, &err), 0);
    assert_int_equal(stat(p, &st2), 0);
    assert_int_equal(st2.st_mode & 07777, 0640);
    assert_true(st1.st_ino != st2.st_ino);
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_same(&big, &b);
    lsc_action_free(&b);
    assert_int_equal(count_entries(d, ".tmp"), 0);
    /* a write that fails (RLIMIT_FSIZE: EFBIG, as a full disk gives ENOSPC)
     * leaves the old file as it was and no temporary file */
    assert_int_equal(lsc_action_write(p, &a, &err), 0);
    static const char *const names[] = {"keep.csv", "keep.rob", "keep.txt"
#ifdef LSC_HAVE_SQLITE
                                        , "keep.d6a"
#endif
    };
    struct rlimit saved, small;
    void (*was)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &saved), 0);
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        size_t old_len, now_len;
        assert_int_equal(lsc_action_write(in(p, d, names[i]), &a, &err), 0);
        uint8_t *old = get_file(p, &old_len);
        small = saved;
        small.rlim_cur = 8192 + 1024; /* above a small .d6a (two pages), below the big one */
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &small), 0);
        int r = lsc_action_write(p, &big, &err);
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &saved), 0);
        assert_refused(r, LSC_EIO, "write error: File too large");
        uint8_t *now = get_file(p, &now_len);
        assert_int_equal(old_len, now_len);
        assert_memory_equal(old, now, old_len);
        assert_int_equal(lsc_action_read(p, &b, &err), 0);
        assert_same(&a, &b);
        lsc_action_free(&b);
        assert_int_equal(count_entries(d, ".tmp"), 0);
        free(old);
        free(now);
    }
    (void)signal(SIGXFSZ, was);
    /* a missing directory: nothing to clean up, the reason said */
    assert_refused(lsc_action_write("/tmp/lsc-no-such-dir/x/a.csv", &a, &err), LSC_EIO,
                   "No such file or directory");
    lsc_action_free(&a);
    lsc_action_free(&big);
    remove_dir(d);
}

#ifdef __linux__
/* In a child with a mount namespace of its own: a 128 KiB tmpfs on d, filled
 * up; then lsc_action_write of each format over a file there, and a journal
 * append. Exit 0 when the old files survive whole and no temporary remains,
 * 77 when no tmpfs can be mounted (the reason on stderr), 1 otherwise. */
static int full_disk_child(const char *d)
{
    char p[256], fill[256];
    lsc_action a, big, b;
    lsc_file_error e = {.size = sizeof e};
    if (unshare(CLONE_NEWNS) != 0 || mount("none", "/", "none", MS_REC | MS_PRIVATE, NULL) != 0 ||
        mount("lsc-test", d, "tmpfs", 0, "size=128k") != 0) {
        fprintf(stderr, "test_files: full disk: cannot mount a tmpfs (%s): not root, or no "
                        "CAP_SYS_ADMIN in this container\n",
                strerror(errno));
        return 77;
    }
#define CHILD_CHECK(c)                                                                            \
    do {                                                                                          \
        if (!(c)) {                                                                               \
            fprintf(stderr, "test_files: full disk: line %d: %s (%s)\n", __LINE__, #c,            \
                    e.message);                                                                   \
            return 1;                                                                             \
        }                                                                                         \
    } while (0)
    xarm_action(&a, 3);
    xarm_action(&big, 3000); /* 80 KB as CSV */
    static const char *const names[] = {"keep.csv", "keep.rob", "keep.txt"
#ifdef LSC_HAVE_SQLITE
                                        , "keep.d6a"
#endif
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        CHILD_CHECK(lsc_action_write(in(p, d, names[i]), &a, &e) == 0);
    }
    lsc_journal *j = NULL;
    CHILD_CHECK(lsc_journal_open(in(p, d, "rec.csv"), &a, &j, &e) == 0);
    CHILD_CHECK(lsc_journal_append(j, 10, a.words + 1, &e) == 0);
    /* fill the disk: big blocks, then single bytes */
    int fd = open(in(fill, d, "fill"), O_WRONLY | O_CREAT, 0600);
    CHILD_CHECK(fd >= 0);
    static const char block[4096];
    while (write(fd, block, sizeof block) > 0) {
    }
    while (write(fd, block, 1) > 0) {
    }
    CHILD_CHECK(errno == ENOSPC);
    close(fd);
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        in(p, d, names[i]);
        CHILD_CHECK(lsc_action_write(p, &big, &e) == LSC_EIO);
        CHILD_CHECK(strstr(e.message, "No space left on device") != NULL);
        CHILD_CHECK(lsc_action_read(p, &b, &e) == 0);
        CHILD_CHECK(b.count == a.count && memcmp(a.words, b.words, (size_t)3u * 7u * 2u) == 0);
        lsc_action_free(&b);
        CHILD_CHECK(count_entries(d, ".tmp") == 0);
    }
    /* the journal: the row that does not fit is cut off, the rest stays */
    int r = 0;
    for (int k = 0; k < 10000 && r == 0; k++) {
        r = lsc_journal_append(j, 10, a.words + 1, &e);
    }
    CHILD_CHECK(r == LSC_EIO && strstr(e.message, "No space left on device") != NULL);
    CHILD_CHECK(lsc_journal_finish(j, &big, &e) == LSC_EIO);
    CHILD_CHECK(lsc_action_read(lsc_journal_path(j), &b, &e) == 0 && b.count > 1);
    lsc_action_free(&b);
    lsc_journal_close(j);
    CHILD_CHECK(count_entries(d, ".tmp") == 0);
    lsc_action_free(&a);
    lsc_action_free(&big);
    return 0;
#undef CHILD_CHECK
}
#endif

static void test_full_disk(void **state)
{
    (void)state;
#ifdef __linux__
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    assert_non_null(mkdtemp(d));
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        _exit(full_disk_child(d));
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    remove_dir(d); /* the tmpfs went with the child's namespace */
    assert_true(WIFEXITED(status));
    if (WEXITSTATUS(status) == 77) {
        print_message("test_files: full disk on a tmpfs skipped (reason above); "
                      "test_atomic_write covers a failed write with RLIMIT_FSIZE\n");
        skip();
    }
    assert_int_equal(WEXITSTATUS(status), 0);
#else
    print_message("test_files: full disk on a tmpfs skipped: not Linux\n");
    skip();
#endif
}

/* ---- The record journal -------------------------------------------------------------- */

static void test_journal(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256], q[256];
    lsc_action a, b;
    lsc_journal *j;
    assert_non_null(mkdtemp(d));
    xarm_action(&a, 4);
    /* open: the journal is there at once, a CSV with its header */
    assert_int_equal(lsc_journal_open(in(p, d, "rec.rob"), &a, &j, &err), 0);
    in(q, d, "rec.rob.journal.csv");
    assert_string_equal(lsc_journal_path(j), q);
    assert_int_equal(lsc_action_read(q, &b, &err), 0);
    assert_int_equal(b.count, 0);
    assert_int_equal(b.nservos, 6);
    lsc_action_free(&b);
    /* each row is in the file as soon as append returns */
    for (uint32_t k = 0; k < a.count; k++) {
        const uint16_t *w = a.words + (size_t)k * 7u;
        assert_int_equal(lsc_journal_append(j, w[0], w + 1, &err), 0);
        assert_int_equal(lsc_action_read(q, &b, &err), 0);
        assert_int_equal(b.count, k + 1);
        assert_memory_equal(b.words, a.words, (size_t)(k + 1) * 7u * 2u);
        lsc_action_free(&b);
    }
    assert_int_equal(lsc_journal_sync(j, &err), 0);
    /* a second recording to the same target while this one runs is refused */
    lsc_journal *j2;
    assert_refused(lsc_journal_open(p, &a, &j2, &err), LSC_EIO,
                   "rec.rob.journal.csv exists (an earlier recording that did not end)");
    /* finish: the target written, the journal gone */
    assert_int_equal(lsc_journal_finish(j, &a, &err), 0);
    lsc_journal_close(j);
    assert_int_equal(access(q, F_OK), -1);
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    /* a target the format cannot take at the end: the journal stays, whole */
    static const uint16_t far[6] = {1001, 0, 0, 0, 0, 0};
    assert_int_equal(lsc_journal_open(p, &a, &j, &err), 0);
    assert_int_equal(lsc_journal_append(j, 5, far, &err), 0);
    assert_int_equal(lsc_action_append(&a, 5, far), 0);
    assert_refused(lsc_journal_finish(j, &a, &err), LSC_EINVAL, "out of range 0..1000");
    assert_string_equal(lsc_journal_path(j), q);
    lsc_journal_close(j);
    assert_int_equal(lsc_action_read(q, &b, &err), 0);
    assert_int_equal(b.count, 1);
    assert_int_equal(b.words[1], 1001);
    lsc_action_free(&b);
    assert_int_equal(unlink(q), 0);
    /* what open checks before anything is recorded */
    assert_refused(lsc_journal_open(in(p, d, "no/such/dir.csv"), &a, &j, &err), LSC_EIO,
                   "No such file or directory");
    assert_null(j);
    assert_refused(lsc_journal_open(in(p, d, "rec.xyz"), &a, &j, &err), LSC_EINVAL,
                   "unknown file type");
    static const uint8_t two[] = {1, 2};
    lsc_action a2;
    assert_int_equal(lsc_action_init(&a2, two, 2), 0);
    assert_refused(lsc_journal_open(in(p, d, "two.rob"), &a2, &j, &err), LSC_EINVAL,
                   "servo 3 missing");
    assert_int_equal(mkfifo(in(p, d, "fifo.csv"), 0600), 0);
    assert_refused(lsc_journal_open(p, &a2, &j, &err), LSC_EINVAL, "(a FIFO)");
    assert_int_equal(symlink("x.csv", in(p, d, "link.csv")), 0);
    assert_refused(lsc_journal_open(p, &a2, &j, &err), LSC_EINVAL, "a symbolic link");
    assert_int_equal(count_entries(d, ".journal.csv"), 0); /* none of these left one */
    assert_int_equal(lsc_journal_open(NULL, &a2, &j, &err), LSC_EINVAL);
    assert_int_equal(lsc_journal_append(NULL, 1, far, &err), LSC_EINVAL);
    assert_int_equal(lsc_journal_sync(NULL, &err), LSC_EINVAL);
    assert_int_equal(lsc_journal_finish(NULL, &a2, &err), LSC_EINVAL);
    assert_null(lsc_journal_path(NULL));
    lsc_journal_close(NULL);
    /* at most LSC_ACTION_KEYFRAMES_MAX rows: the journal stays readable */
    static const uint16_t pos2[] = {1, 2};
    assert_int_equal(lsc_journal_open(in(p, d, "long.csv"), &a2, &j, &err), 0);
    for (uint32_t k = 0; k < LSC_ACTION_KEYFRAMES_MAX; k++) {
        if (lsc_journal_append(j, 1, pos2, &err) != 0) {
            fail_msg("append %u: %s", (unsigned)k, err.message);
        }
    }
    assert_refused(lsc_journal_append(j, 1, pos2, &err), LSC_ENOSPC, "65535 keyframes");
    lsc_journal_close(j);
    assert_int_equal(lsc_action_read(in(q, d, "long.csv.journal.csv"), &b, &err), 0);
    assert_int_equal(b.count, LSC_ACTION_KEYFRAMES_MAX);
    lsc_action_free(&b);
    lsc_action_free(&a2);
    lsc_action_free(&a);
    remove_dir(d);
}

/* SIGKILL in the middle of a recording: every row appended is in the journal. */
static void test_journal_sigkill(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256];
    lsc_action a, b;
    assert_non_null(mkdtemp(d));
    xarm_action(&a, 50);
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        lsc_journal *j;
        lsc_file_error e = {.size = sizeof e};
        if (lsc_journal_open(in(p, d, "rec.d6a"), &a, &j, &e) != 0) {
            _exit(1);
        }
        for (uint32_t k = 0; k < a.count; k++) {
            if (lsc_journal_append(j, a.words[(size_t)k * 7u], a.words + (size_t)k * 7u + 1, &e) != 0) {
                _exit(2);
            }
        }
        (void)kill(getpid(), SIGKILL); /* returns only if it failed */
        _exit(3);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    assert_int_equal(lsc_action_read(in(p, d, "rec.d6a.journal.csv"), &b, &err), 0);
    assert_same(&a, &b);
    lsc_action_free(&b);
    assert_int_equal(access(in(p, d, "rec.d6a"), F_OK), -1);
    lsc_action_free(&a);
    remove_dir(d);
}

/* ---- .d6a as SQLite means it ------------------------------------------------------- */
#ifdef LSC_HAVE_SQLITE

static void exec_ok(sqlite3 *db, const char *sql)
{
    char *msg = NULL;
    if (sqlite3_exec(db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        fail_msg("%s: %s", sql, msg);
    }
}

/* A vendor table of n rows at path: row k is (k+1, 100 + k % 50, k % 1000). */
static sqlite3 *vendor_db(const char *path, unsigned n)
{
    sqlite3 *db;
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    exec_ok(db, VENDOR_TABLE "Time INT, Servo1 INT); BEGIN");
    assert_int_equal(sqlite3_prepare_v2(db, "INSERT INTO ActionGroup(Time, Servo1) VALUES(?, ?)",
                                        -1, &st, NULL),
                     SQLITE_OK);
    for (unsigned k = 0; k < n; k++) {
        sqlite3_bind_int(st, 1, (int)(100 + k % 50));
        sqlite3_bind_int(st, 2, (int)(k % 1000));
        assert_int_equal(sqlite3_step(st), SQLITE_DONE);
        sqlite3_reset(st);
    }
    sqlite3_finalize(st);
    exec_ok(db, "COMMIT");
    return db;
}

/* b holds vendor_db's n rows as committed. */
static void assert_vendor(const lsc_action *b, unsigned n)
{
    assert_int_equal(b->count, n);
    for (unsigned k = 0; k < n; k++) {
        const uint16_t *w = b->words + (size_t)2 * k;
        if (w[0] != 100 + k % 50 || w[1] != k % 1000) {
            fail_msg("row %u: %u %u", k + 1, w[0], w[1]);
        }
    }
}

/* Copies from to to with cp(1): a close() in this process would drop the
 * POSIX locks of its SQLite connections on the file. */
static void copy_in_child(const char *from, const char *to)
{
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        execlp("cp", "cp", from, to, (char *)NULL);
        _exit(127);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

/* Another connection writes: the committed state, or a refusal; never a mix. */
static void test_d6a_concurrent_writer(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256], j[256], h[256], hj[256];
    lsc_action b;
    assert_non_null(mkdtemp(d));
    sqlite3 *w = vendor_db(in(p, d, "d.d6a"), 20000);
    in(j, d, "d.d6a-journal");
    /* an open write transaction that fits in its cache: the committed rows */
    exec_ok(w, "BEGIN; DELETE FROM ActionGroup WHERE Time % 3 = 0; "
               "UPDATE ActionGroup SET Servo1 = 7");
    assert_int_equal(access(j, F_OK), 0);
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_vendor(&b, 20000);
    lsc_action_free(&b);
    exec_ok(w, "ROLLBACK");
    /* one that spilled into the file (an exclusive lock): refused, not a mix */
    exec_ok(w, "PRAGMA cache_size = 10; BEGIN; UPDATE ActionGroup SET Servo1 = Servo1 + 1000");
    assert_refused(lsc_action_read(p, &b, &err), LSC_EBUSY, "another program is writing it");
    assert_null(b.words);
    /* the file and its journal as a crash would leave them: a hot journal */
    copy_in_child(p, in(h, d, "h.d6a"));
    copy_in_child(j, in(hj, d, "h.d6a-journal"));
    exec_ok(w, "ROLLBACK");
    sqlite3_close(w);
    size_t len0, len1;
    uint8_t *before = get_file(h, &len0);
    assert_refused(lsc_action_read(h, &b, &err), LSC_EIO,
                   "a write to it was interrupted (its -journal file is hot)");
    assert_int_equal(access(hj, F_OK), 0); /* reading changed nothing */
    uint8_t *after = get_file(h, &len1);
    assert_int_equal(len0, len1);
    assert_memory_equal(before, after, len0);
    free(before);
    free(after);
    /* settled the way the message says: the committed rows */
    sqlite3 *s;
    assert_int_equal(sqlite3_open(h, &s), SQLITE_OK);
    exec_ok(s, "SELECT count(*) FROM ActionGroup");
    sqlite3_close(s);
    assert_int_equal(lsc_action_read(h, &b, &err), 0);
    assert_vendor(&b, 20000);
    lsc_action_free(&b);
    remove_dir(d);
}

static void test_d6a_wal(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256];
    lsc_action b;
    assert_non_null(mkdtemp(d));
    sqlite3 *w = vendor_db(in(p, d, "w.d6a"), 3);
    exec_ok(w, "PRAGMA journal_mode = WAL");
    sqlite3_close(w);
    assert_int_equal(count_entries(d, ""), 1); /* closed cleanly: no -wal, no -shm */
    /* WAL mode, no WAL: read as the file, nothing created beside it */
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_vendor(&b, 3);
    lsc_action_free(&b);
    assert_int_equal(count_entries(d, ""), 1);
    size_t len;
    uint8_t *bytes = get_file(p, &len);
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len, &b), 0);
    assert_vendor(&b, 3);
    lsc_action_free(&b);
    free(bytes);
    /* commits still in the WAL, a writer holding it open: read with them */
    assert_int_equal(sqlite3_open(p, &w), SQLITE_OK);
    exec_ok(w, "PRAGMA wal_autocheckpoint = 0; "
               "INSERT INTO ActionGroup(Time, Servo1) VALUES(103, 3); "
               "INSERT INTO ActionGroup(Time, Servo1) VALUES(104, 4)");
    assert_int_equal(count_entries(d, "-wal"), 1);
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_vendor(&b, 5);
    lsc_action_free(&b);
    /* and an open transaction: the committed state */
    exec_ok(w, "BEGIN; INSERT INTO ActionGroup(Time, Servo1) VALUES(105, 5)");
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_vendor(&b, 5);
    lsc_action_free(&b);
    exec_ok(w, "COMMIT");
    assert_int_equal(lsc_action_read(p, &b, &err), 0);
    assert_vendor(&b, 6);
    lsc_action_free(&b);
    sqlite3_close(w);
    remove_dir(d);
}

/* A .d6a cut short (SQLite would read the missing pages as zeros): refused,
 * as bytes and as a file; a WAL cut short too. */
static void test_d6a_cut_short(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char p[256], q[256], wal[256];
    lsc_action b;
    assert_non_null(mkdtemp(d));
    sqlite3_close(vendor_db(in(p, d, "v.d6a"), 5000));
    size_t len;
    uint8_t *bytes = get_file(p, &len);
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len, &b), 0);
    assert_vendor(&b, 5000);
    lsc_action_free(&b);
    /* one byte less: not whole pages */
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len - 1u, &b), LSC_EINVAL);
    assert_error(0, "cut short");
    put_file(in(q, d, "cut.d6a"), bytes, len - 1u);
    assert_int_equal(lsc_action_read(q, &b, &err), LSC_EINVAL);
    assert_error(0, "cut short");
    /* a whole page less: fewer pages than its header says */
    uint32_t page = ((uint32_t)bytes[16] << 8) | bytes[17];
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len - page, &b), LSC_EINVAL);
    assert_error(0, "its header says");
    put_file(q, bytes, len - page);
    assert_int_equal(lsc_action_read(q, &b, &err), LSC_EINVAL);
    assert_error(0, "its header says");
    /* a stale page count (an old writer's: change counters differ) is not trusted */
    bytes[95] ^= 0xFFu;
    assert_int_equal(parse(LSC_FILE_D6A, bytes, len, &b), 0);
    lsc_action_free(&b);
    free(bytes);
    /* a WAL cut short: refused, not read as if its last commit never happened */
    sqlite3 *w;
    assert_int_equal(sqlite3_open(p, &w), SQLITE_OK);
    exec_ok(w, "PRAGMA journal_mode = WAL; PRAGMA wal_autocheckpoint = 0; "
               "INSERT INTO ActionGroup(Time, Servo1) VALUES(100, 0)");
    uint8_t *wbytes = get_file(in(wal, d, "v.d6a-wal"), &len);
    sqlite3_close(w); /* (checkpoints and removes the WAL) */
    assert_int_equal(rename(p, in(q, d, "c.d6a")), 0);
    put_file(in(wal, d, "c.d6a-wal"), wbytes, len - 1u);
    assert_int_equal(lsc_action_read(q, &b, &err), LSC_EINVAL);
    assert_error(0, "-wal");
    free(wbytes);
    remove_dir(d);
}

/* A path SQLite could take for a URI ("file:...") is a file name. */
static void test_d6a_uri_name(void **state)
{
    (void)state;
    char d[] = "/tmp/lsc-test-files-XXXXXX";
    char cwd[512];
    lsc_action b;
    assert_non_null(mkdtemp(d));
    assert_non_null(getcwd(cwd, sizeof cwd));
    assert_int_equal(chdir(d), 0);
    sqlite3_close(vendor_db("./file:x.d6a", 2)); /* SQLite itself takes "file:" as a URI */
    assert_int_equal(access("file:x.d6a", F_OK), 0);
    assert_int_equal(lsc_action_read("file:x.d6a", &b, &err), 0);
    assert_vendor(&b, 2);
    lsc_action_free(&b);
    assert_int_equal(chdir(cwd), 0);
    remove_dir(d);
}

static void test_d6a_table_kinds(void **state)
{
    (void)state;
    lsc_action a;
    size_t len;
    uint8_t *db;
    strcpy(dir, "/tmp/lsc-test-files-XXXXXX"); /* test_d6a used it */
    assert_non_null(mkdtemp(dir));
    /* virtual tables: refused before their module is touched */
    db = d6a("CREATE VIRTUAL TABLE ActionGroup USING fts5(Time, Servo1);", &len);
    assert_refused(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL,
                   "ActionGroup is not a table (it is a virtual table)");
    db = d6a("CREATE VIRTUAL TABLE ActionGroup USING rtree(id, Time, Servo1);", &len);
    assert_refused(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL, "(it is a virtual table)");
    /* ... also when the schema hides the keyword behind a comment */
    db = d6a("PRAGMA writable_schema = ON; INSERT INTO sqlite_master VALUES('table', "
             "'ActionGroup', 'ActionGroup', 0, 'CREATE /* x */ VIRTUAL TABLE ActionGroup "
             "USING rtree(id, Time, Servo1)');",
             &len);
    assert_refused(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL, "(it is a virtual table)");
    /* a view (views are off; the message says what it is) */
    db = d6a("CREATE TABLE T(Time INT, Servo1 INT); CREATE VIEW ActionGroup AS SELECT * FROM T;",
             &len);
    assert_refused(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL,
                   "ActionGroup is not a table (it is a view)");
    /* WITHOUT ROWID: no order without an Index column, a clear message */
    db = d6a("CREATE TABLE ActionGroup(Time INT, Servo1 INT, PRIMARY KEY(Time)) WITHOUT ROWID;"
             "INSERT INTO ActionGroup VALUES(10, 1);",
             &len);
    assert_refused(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL,
                   "WITHOUT ROWID table and has no Index column");
    db = d6a("CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY, Time INT, Servo1 INT) "
             "WITHOUT ROWID; INSERT INTO ActionGroup VALUES(2, 20, 200);"
             "INSERT INTO ActionGroup VALUES(1, 10, 100);",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), 0);
    static const uint16_t want[] = {10, 100, 20, 200};
    assert_int_equal(a.count, 2);
    assert_memory_equal(a.words, want, sizeof want);
    lsc_action_free(&a);
    /* SQLite's message names an object of the file: its control characters are
     * escaped, so it cannot clear the screen or forge a second line */
    db = d6a(VENDOR_TABLE "Time INT, Servo1 INT); PRAGMA writable_schema = ON; "
                          "INSERT INTO sqlite_master VALUES('table', 'x' || char(27) || '[2J' || "
                          "char(10) || 'lscctl: play: all good', 'x', 0, 'CREATE TABLE x(');",
             &len);
    assert_int_equal(parse(LSC_FILE_D6A, db, len, &a), LSC_EINVAL);
    assert_error(0, "malformed database schema (x\\x1B[2J\\x0Alscctl: play: all good)");
    for (const char *c = err.message; *c != '\0'; c++) {
        assert_true((unsigned char)*c >= 0x20 && *c != 0x7f);
    }
    char path[64];
    snprintf(path, sizeof path, "%s/t.d6a", dir);
    unlink(path);
    rmdir(dir);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_format_of), cmocka_unit_test(test_action_memory),
        cmocka_unit_test(test_error_size),
        cmocka_unit_test(test_csv),       cmocka_unit_test(test_rob),
        cmocka_unit_test(test_text),      cmocka_unit_test(test_header),
#ifdef LSC_HAVE_SQLITE
        cmocka_unit_test(test_d6a),
        cmocka_unit_test(test_d6a_concurrent_writer),
        cmocka_unit_test(test_d6a_wal),
        cmocka_unit_test(test_d6a_cut_short),
        cmocka_unit_test(test_d6a_uri_name),
        cmocka_unit_test(test_d6a_table_kinds),
#endif
        cmocka_unit_test(test_files),
        cmocka_unit_test(test_read_group),
        cmocka_unit_test(test_limits_keyframes),
        cmocka_unit_test(test_limits_bytes),
        cmocka_unit_test(test_only_regular_files),
        cmocka_unit_test(test_atomic_write),
        cmocka_unit_test(test_full_disk),
        cmocka_unit_test(test_journal),
        cmocka_unit_test(test_journal_sigkill),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
