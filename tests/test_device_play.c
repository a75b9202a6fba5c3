/* Play and record over a device (src/device/play.c, record.c): against the
 * built-in "sim" (virtual clock: exact times) and against lsc-sim on a
 * pseudo-terminal (argv[1]; real time, fault injection with --drop-replies).
 * _POSIX_C_SOURCE comes from tests/CMakeLists.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lsc/lsc.h"
#include "lsc/device.h"
#include "sim_pty.h"
#include "test_open.h"
#include "test_time.h"
#include "sized_test.h"
#ifdef LSC_TEST_HID_DOUBLE
#include <stdlib.h>

#include "hid_double.h"
#endif

static const char *lsc_sim_path;

/* ---- helpers ------------------------------------------------------------------- */

/* An action of n servos from rows of 1 + n words. */
static void make_action(lsc_action *a, const uint8_t *ids, size_t n, const uint16_t *rows,
                        size_t count)
{
    assert_int_equal(lsc_action_init(a, ids, n), 0);
    for (size_t k = 0; k < count; k++) {
        const uint16_t *row = &rows[k * (1u + n)];
        assert_int_equal(lsc_action_append(a, row[0], row + 1), 0);
    }
}

static lsc_device *open_sim(void)
{
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_non_null(d);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0); /* exact times */
    return d;
}

/* Counts the frames sent (a trace). */
typedef struct tx_count {
    unsigned frames;
    unsigned moves;
    unsigned reads;
} tx_count;

static void count_tx(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    tx_count *c = user;
    (void)n;
    if (dir == LSC_TRACE_TX) {
        c->frames++;
        c->moves += frame[3] == LSC_CMD_SERVO_MOVE;
        c->reads += frame[3] == LSC_CMD_POS_READ;
    }
}

/* What a play's callback saw. */
#define SEEN_MAX 256u
typedef struct seen {
    unsigned steps;
    unsigned idles;
    lsc_player_step s[SEEN_MAX];
    uint32_t at[SEEN_MAX];   /* elapsed at each step */
    uint32_t last_idle;      /* elapsed at the last idle call */
    uint32_t idle_gap_max;   /* the longest gap between two calls */
    uint32_t last_call;
    unsigned stop_after;     /* steps; 0: never */
    bool stop_idle;          /* stop at the first idle call after a step */
    const lsc_play_result *result;
    uint32_t total_seen;     /* result->total_ms as the callback saw it */
} seen;

static bool on_step(void *user, const lsc_player_step *s, uint32_t elapsed)
{
    seen *v = user;
    if (v->result != NULL) {
        v->total_seen = v->result->total_ms;
    }
    if (elapsed - v->last_call > v->idle_gap_max) {
        v->idle_gap_max = elapsed - v->last_call;
    }
    v->last_call = elapsed;
    if (s == NULL) {
        v->idles++;
        v->last_idle = elapsed;
        return !(v->stop_idle && v->steps > 0);
    }
    if (v->steps < SEEN_MAX) {
        v->s[v->steps] = *s;
        v->at[v->steps] = elapsed;
    }
    v->steps++;
    return v->stop_after == 0 || v->steps < v->stop_after;
}

/* ---- play on "sim" --------------------------------------------------------------- */

static const uint8_t two_ids[] = {1, 2};
static const uint16_t two_rows[] = {500, 100, 200, /* */
                                    300, 150, 200, /* servo 2 unchanged */
                                    400, 150, 200, /* a pause: no frame */
                                    250, 900, 800};

static void test_play_schedule(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    lsc_action a;
    make_action(&a, two_ids, 2, two_rows, 4);
    lsc_player_config c = {100, 1, 1000, 0};
    lsc_play_result res = {.size = sizeof res};
    seen v = {.result = &res};
    tx_count tx = {0};
    lsc_device_set_trace(d, count_tx, &tx);
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &v, &res), 0);
    /* the virtual clock: the play took exactly its schedule */
    assert_int_equal(lsc_device_now_ms(d) - t0, 1950);
    assert_int_equal(res.total_ms, 1950);
    assert_int_equal(v.total_seen, 1950);
    assert_int_equal(res.frames, 3);
    assert_int_equal(res.dropped, 0);
    assert_int_equal(res.keyframe, 4);
    assert_int_equal(res.max_late_ms, 0);
    assert_false(res.stopped);
    assert_int_equal(tx.moves, 3);
    assert_int_equal(v.steps, 3);
    assert_true(v.s[0].lead_in);
    assert_int_equal(v.at[0], 0);
    assert_int_equal(v.at[1], 1000);
    assert_int_equal(v.s[1].nservos, 1);
    assert_int_equal(v.at[2], 1700);
    assert_int_equal(v.s[2].keyframe, 3);
    /* called at least every 100 ms while it waited */
    assert_true(v.idles >= 19);
    assert_true(v.idle_gap_max <= 100);
    assert_int_equal(v.last_idle, 1950);
    /* the servos are where the last keyframe put them */
    static const uint8_t ids[] = {1, 2};
    lsc_servo got[2];
    assert_int_equal(lsc_device_read(d, ids, 2, got), 2);
    assert_int_equal(got[0].position, 900);
    assert_int_equal(got[1].position, 800);
    /* result may be NULL; fn too */
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), 0);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* Keyframes faster than the line carries: dropped, counted, and said in
 * the step that follows them; the last keyframe always goes out. */
static void test_play_drops(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    enum { N = 100 };
    static const uint8_t id[] = {1};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, id, 1), 0);
    for (unsigned i = 0; i < N; i++) {
        uint16_t pos = (uint16_t)(500u + i);
        assert_int_equal(lsc_action_append(&a, 2, &pos), 0);
    }
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_play_result res = {.size = sizeof res};
    seen v = {0};
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &v, &res), 0);
    assert_true(res.dropped > N / 2);
    assert_int_equal(res.frames + res.dropped, N);
    assert_int_equal(res.frames, v.steps);
    assert_int_equal(res.keyframe, N);
    uint32_t said = 0;
    for (unsigned i = 0; i < v.steps && i < SEEN_MAX; i++) {
        said += v.s[i].dropped;
    }
    assert_int_equal(said, res.dropped);
    /* the lead-in goes out at once with --lead 0; nothing is later than one
     * frame's line time (10.4 ms) */
    assert_int_equal(v.s[0].keyframe, 0);
    assert_int_equal(v.s[0].dropped, 0);
    assert_true(res.max_late_ms <= 11);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* lead 0 on a file with 500 ms between keyframes: nothing dropped. */
static void test_play_no_lead(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    static const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    static const uint16_t rows[] = {500, 1, 2, 3, 4, 5, 6, 500, 7, 8, 9, 10, 11, 12};
    lsc_action a;
    make_action(&a, ids, 6, rows, 2);
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_play_result res = {.size = sizeof res};
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &res), 0);
    assert_int_equal(res.frames, 2);
    assert_int_equal(res.dropped, 0);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* The result's size: a caller's shorter struct gets nothing beyond it (also
 * while the play goes: the callback reads it); one below the size field and
 * frames is refused with nothing sent; NULL is fine. */
static void test_play_result_size(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    lsc_action a;
    make_action(&a, two_ids, 2, two_rows, 4);
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_play_result old;
    const size_t upto = offsetof(lsc_play_result, dropped); /* size and frames */
    sized_guard(&old, sizeof old, upto);
    seen v = {.result = &old};
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &v, &old), 0);
    assert_int_equal(old.size, upto);
    assert_int_equal(old.frames, 3);
    assert_int_equal(v.steps, 3);
    assert_true(sized_untouched(&old, upto, sizeof old));
    uint64_t sent = sized_frames_sent(d);
    sized_guard(&old, sizeof old, sizeof old.size);
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &old), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "lsc_play_result.size is"));
    assert_non_null(
        strstr(lsc_device_error(d), "set it to sizeof(lsc_play_result); nothing was sent"));
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    assert_int_equal(sized_frames_sent(d), sent);
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), 0);
    assert_int_equal(sized_frames_sent(d), sent + 3u);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* The callback's false stops the play after the frame: nothing more is sent. */
static void test_play_stop(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    lsc_action a;
    make_action(&a, two_ids, 2, two_rows, 4);
    lsc_player_config c = {100, 3, 1000, 9600};
    lsc_play_result res = {.size = sizeof res};
    seen v = {.stop_after = 2};
    tx_count tx = {0};
    lsc_device_set_trace(d, count_tx, &tx);
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &v, &res), 0);
    assert_true(res.stopped);
    assert_int_equal(res.frames, 2);
    assert_int_equal(res.keyframe, 2);
    assert_int_equal(tx.moves, 2);
    assert_int_equal(v.steps, 2);
    /* stopped while waiting: after the lead-in, before keyframe 2 */
    seen w = {.stop_idle = true};
    tx.moves = 0;
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &w, &res), 0);
    assert_true(res.stopped);
    assert_int_equal(res.frames, 1);
    assert_int_equal(res.keyframe, 1);
    assert_int_equal(tx.moves, 1);
    assert_true(w.last_call <= 100);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* With an arm profile, every keyframe is checked before anything is sent. */
static void test_play_limits(void **state)
{
    (void)state;
    static const char profile[] = "gripper 1 bus limits=0..700\n"
                                  "base    6 bus limits=-115deg..115deg\n";
    lsc_arm *arm = NULL;
    char why[LSC_ARM_MESSAGE_MAX];
    assert_int_equal(lsc_arm_parse(profile, sizeof profile - 1u, "t.conf", &arm, why, sizeof why),
                     0);
    lsc_device *d = open_sim();
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    static const uint8_t ids[] = {1, 6};
    static const uint16_t rows[] = {1000, 100, 500, 1000, 700, 500, 1000, 701, 500, 1000, 0, 2000};
    lsc_action a;
    make_action(&a, ids, 2, rows, 4);
    lsc_player_config c = {100, 1, 1000, 0};
    tx_count tx = {0};
    lsc_device_set_trace(d, count_tx, &tx);
    lsc_play_result res = {.size = sizeof res};
    seen v = {0};
    assert_int_equal(lsc_device_play(d, &a, &c, on_step, &v, &res), LSC_EINVAL);
    assert_int_equal(tx.frames, 0);
    assert_int_equal(v.steps + v.idles, 0);
    assert_int_equal(res.frames, 0);
    const char *msg = lsc_device_error(d);
    assert_non_null(strstr(msg, "keyframe 3"));
    assert_non_null(strstr(msg, "gripper"));
    /* the keyframe at the limit passes; the one beyond the base's */
    a.words[7] = 700; /* keyframe 3's gripper */
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "keyframe 4"));
    assert_non_null(strstr(lsc_device_error(d), "base"));
    assert_int_equal(tx.frames, 0);
    a.words[11] = 900; /* keyframe 4's base */
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), 0);
    assert_string_equal(lsc_device_error(d), "");
    assert_true(tx.moves > 0);
    /* servos on no joint pass */
    assert_int_equal(lsc_device_set_arm(d, NULL), 0);
    lsc_action_free(&a);
    lsc_device_close(d);
    lsc_arm_free(arm);
}

static void test_play_refused(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    lsc_action a;
    make_action(&a, two_ids, 2, two_rows, 4);
    lsc_player_config c = {100, 1, 1000, 0};
    lsc_play_result res = {.size = sizeof res};
    tx_count tx = {0};
    lsc_device_set_trace(d, count_tx, &tx);
    assert_int_equal(lsc_device_play(NULL, &a, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_int_equal(lsc_device_play(d, NULL, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_int_equal(lsc_device_play(d, &a, NULL, NULL, NULL, &res), LSC_EINVAL);
    c.speed_pct = 0;
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "speed"));
    c = (lsc_player_config){100, 0, 1000, 0};
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "times"));
    /* longer than 2^32 ms */
    c = (lsc_player_config){1, 65535, 1000, 0};
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "too long"));
    lsc_action empty;
    assert_int_equal(lsc_action_init(&empty, two_ids, 2), 0);
    c = (lsc_player_config){100, 1, 1000, 0};
    assert_int_equal(lsc_device_play(d, &empty, &c, NULL, NULL, &res), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "no keyframes"));
    /* actions made by hand: keyframes counted but none there, no servos */
    lsc_action bad = {0};
    bad.count = 1;
    assert_int_equal(lsc_device_play(d, &bad, &c, NULL, NULL, &res), LSC_EINVAL);
    bad = a;
    bad.nservos = 0;
    assert_int_equal(lsc_device_play(d, &bad, &c, NULL, NULL, &res), LSC_EINVAL);
    bad.nservos = LSC_PLAYER_SERVOS_MAX + 1u;
    assert_int_equal(lsc_device_take_keyframe(d, &bad, 1, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_record(d, &bad, 10, 0, NULL, NULL), LSC_EINVAL);
    assert_int_equal(tx.frames, 0);
    assert_int_equal(res.frames, 0);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* A failed open leaves no handle: NULL is refused (LSC_EINVAL). */
static void test_play_failed_open(void **state)
{
    (void)state;
    lsc_device *d = NULL;
    int r = lsc_device_open("/nonexistent/ttyUSB9", NULL, &d);
    assert_true(r < 0);
    assert_null(d);
    lsc_action a;
    make_action(&a, two_ids, 2, two_rows, 4);
    lsc_player_config c = {100, 1, 1000, 0};
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_take_keyframe(d, &a, 10, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_record(d, &a, 10, 1, NULL, NULL), LSC_EINVAL);
    assert_int_equal(a.count, 4);
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* ---- record on "sim" --------------------------------------------------------------- */

typedef struct rec_seen {
    lsc_device *d;
    unsigned taken;
    unsigned idles;
    unsigned retries;
    uint32_t counts[16];
    uint32_t stop_at;  /* stop after this many taken (0: never) */
    unsigned stop_retry; /* stop at this retry (0: never) */
    bool stop_idle;    /* stop at the first call while waiting */
} rec_seen;

static bool on_keyframe(void *user, const lsc_action *a, bool taken)
{
    rec_seen *v = user;
    if (taken) {
        if (v->taken < 16) {
            v->counts[v->taken] = a->count;
        }
        v->taken++;
        return v->stop_at == 0 || v->taken < v->stop_at;
    }
    if (*lsc_device_error(v->d) != '\0') {
        v->retries++;
        return v->stop_retry == 0 || v->retries < v->stop_retry;
    }
    v->idles++;
    return !v->stop_idle;
}

static void test_record_every(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    static const lsc_servo pose[] = {{1, 1234}, {3, 2100}};
    assert_int_equal(lsc_device_move(d, 0, pose, 2), 0);
    (void)lsc_device_poll(d, 10);
    static const uint8_t ids[] = {1, 3};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, ids, 2), 0);
    rec_seen v = {.d = d};
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_record(d, &a, 20, 3, on_keyframe, &v), 0);
    assert_int_equal(a.count, 3);
    assert_int_equal(v.taken, 3);
    assert_int_equal(v.retries, 0);
    for (size_t k = 0; k < 3; k++) {
        assert_int_equal(v.counts[k], k + 1u);
        assert_int_equal(a.words[k * 3u], 20);
        assert_int_equal(a.words[k * 3u + 1u], 1234);
        assert_int_equal(a.words[k * 3u + 2u], 2100);
    }
    /* keyframes at 0, 20 and 40 ms on the virtual clock */
    assert_int_equal(lsc_device_now_ms(d) - t0, 40);
    assert_true(v.idles >= 2);
    /* count is what a holds in all: 2 more */
    assert_int_equal(lsc_device_record(d, &a, 1000, 5, NULL, NULL), 0);
    assert_int_equal(a.count, 5);
    assert_int_equal(a.words[9], 1000);
    /* the callback ends it */
    rec_seen w = {.d = d, .stop_at = 2};
    assert_int_equal(lsc_device_record(d, &a, 7, 0, on_keyframe, &w), 0);
    assert_int_equal(a.count, 7);
    /* ... also while it waits: after the first keyframe (taken at once) */
    rec_seen x = {.d = d, .stop_idle = true};
    assert_int_equal(lsc_device_record(d, &a, 500, 0, on_keyframe, &x), 0);
    assert_int_equal(a.count, 8);
    assert_int_equal(x.idles, 1);
    /* refused */
    assert_int_equal(lsc_device_record(d, &a, 0, 1, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_record(d, &a, 65536, 1, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_record(d, NULL, 10, 1, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_record(NULL, &a, 10, 1, NULL, NULL), LSC_EINVAL);
    assert_int_equal(a.count, 8);
    lsc_action_free(&a);
    lsc_device_close(d);
}

static void test_take_keyframe(void **state)
{
    (void)state;
    lsc_device *d = open_sim();
    static const uint8_t ids[] = {2};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, ids, 1), 0);
    assert_int_equal(lsc_device_take_keyframe(d, &a, 0, 0), 0);     /* 0 becomes 1 */
    assert_int_equal(lsc_device_take_keyframe(d, &a, 65535, 1), 0); /* kept */
    assert_int_equal(lsc_device_take_keyframe(d, &a, 70000, 0), 0); /* 65535 at most */
    assert_int_equal(a.count, 3);
    assert_int_equal(a.words[0], 1);
    assert_int_equal(a.words[2], 65535);
    assert_int_equal(a.words[4], 65535);
    assert_int_equal(a.words[1], 1500);
    assert_int_equal(lsc_device_take_keyframe(NULL, &a, 1, 0), LSC_EINVAL);
    assert_int_equal(lsc_device_take_keyframe(d, NULL, 1, 0), LSC_EINVAL);
    lsc_action none = {0};
    assert_int_equal(lsc_device_take_keyframe(d, &none, 1, 0), LSC_EINVAL);
    /* a full action: refused before a read is sent */
    tx_count tx = {0};
    lsc_device_set_trace(d, count_tx, &tx);
    uint32_t count = a.count;
    a.count = LSC_ACTION_KEYFRAMES_MAX;
    assert_int_equal(lsc_device_take_keyframe(d, &a, 1, 0), LSC_ENOSPC);
    assert_non_null(strstr(lsc_device_error(d), "the most"));
    assert_int_equal(lsc_device_record(d, &a, 10, 0, NULL, NULL), LSC_ENOSPC);
    assert_int_equal(tx.frames, 0);
    a.count = count;
    lsc_action_free(&a);
    lsc_device_close(d);
}

/* ---- against lsc-sim on a pseudo-terminal ------------------------------------------ */

typedef struct running_sim {
    char tty[256];
    lsc_device *d;
} running_sim;

/* The lsc-sim a test started and has not stopped (a failed assertion leaves
 * the test early): the teardown ends it. */
static pid_t started = -1;

static int end_started(void **state)
{
    (void)state;
    if (started > 0) {
        (void)kill(started, SIGKILL);
        (void)waitpid(started, NULL, 0);
        started = -1;
    }
    return 0;
}

/* Starts lsc-sim with extra arguments (NULL-terminated) and opens its pty. */
static void start(running_sim *r, const char *const *extra)
{
    sim_pty_start(lsc_sim_path, extra, &started, r->tty, sizeof r->tty);
    test_options opt = {9600, (uint32_t)test_ms(1000), 0, 0};
    if (test_open(r->tty, &opt, &r->d) != 0) {
        fail_msg("open %s: %s", r->tty, lsc_device_error(r->d));
    }
}

static void stop(running_sim *r)
{
    lsc_device_close(r->d);
    sim_pty_stop(&started);
}

/* Real time: the frames go out in order, none before its due time, and the
 * servos end where the file does. */
static void test_pty_play(void **state)
{
    (void)state;
    running_sim r;
    const char *const args[] = {"--fast", NULL};
    start(&r, args);
    static const uint8_t ids[] = {1, 2};
    static const uint16_t rows[] = {50, 100, 200, 60, 300, 400, 60, 500, 600};
    lsc_action a;
    make_action(&a, ids, 2, rows, 3);
    lsc_player_config c = {100, 1, 50, 0};
    lsc_play_result res = {.size = sizeof res};
    seen v = {0};
    assert_int_equal(lsc_device_play(r.d, &a, &c, on_step, &v, &res), 0);
    assert_int_equal(res.frames, 3);
    assert_int_equal(v.steps, 3);
    assert_int_equal(res.total_ms, 50 + 60 + 60);
    for (unsigned i = 0; i < 3; i++) {
        assert_int_equal(v.s[i].keyframe, i);
        assert_true(v.at[i] >= v.s[i].due_ms);
    }
    /* the last move ends its time after it reached lsc-sim, a few ms after
     * it was sent: then the servos are where the file ends */
    static const lsc_servo end[] = {{1, 500}, {2, 600}};
    assert_int_equal(lsc_device_settle(r.d, end, 2, 0, 0), 0);
    lsc_action_free(&a);
    stop(&r);
}

/* Replies dropped by lsc-sim: each timed-out read is retried, the callback
 * told before each retry; take_keyframe with one attempt gives up. */
static void test_pty_record_retries(void **state)
{
    (void)state;
    running_sim r;
    const char *const args[] = {"--fast", "--drop-replies", "3", NULL};
    start(&r, args);
    lsc_device_set_timeout(r.d, (uint32_t)test_ms(100));
    static const uint8_t ids[] = {4};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, ids, 1), 0);
    /* one attempt: the first dropped reply is a timeout, nothing taken */
    assert_int_equal(lsc_device_take_keyframe(r.d, &a, 10, 1), LSC_ETIMEOUT);
    assert_int_equal(a.count, 0);
    assert_string_not_equal(lsc_device_error(r.d), "");
    /* record: 2 more dropped, retried, then the keyframes */
    rec_seen v = {.d = r.d};
    assert_int_equal(lsc_device_record(r.d, &a, 10, 2, on_keyframe, &v), 0);
    assert_int_equal(v.retries, 2);
    assert_int_equal(v.taken, 2);
    assert_int_equal(a.count, 2);
    assert_int_equal(a.words[1], 1500);
    assert_int_equal(a.words[3], 1500);
    lsc_action_free(&a);
    stop(&r);
}

/* Every read dropped: take_keyframe's attempts, then LSC_ETIMEOUT; record
 * returns it, a unchanged; a callback may end it during the retries. */
static void test_pty_record_gives_up(void **state)
{
    (void)state;
    running_sim r;
    const char *const args[] = {"--fast", "--drop-replies", "100", NULL};
    start(&r, args);
    lsc_device_set_timeout(r.d, (uint32_t)test_ms(50));
    static const uint8_t ids[] = {1};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, ids, 1), 0);
    rec_seen v = {.d = r.d};
    assert_int_equal(lsc_device_record(r.d, &a, 10, 1, on_keyframe, &v), LSC_ETIMEOUT);
    assert_int_equal(v.retries, 4); /* 5 reads */
    assert_int_equal(a.count, 0);
    rec_seen w = {.d = r.d, .stop_retry = 2};
    assert_int_equal(lsc_device_record(r.d, &a, 10, 1, on_keyframe, &w), 0);
    assert_int_equal(w.retries, 2);
    assert_int_equal(a.count, 0);
    assert_int_equal(lsc_device_take_keyframe(r.d, &a, 10, 3), LSC_ETIMEOUT);
    lsc_action_free(&a);
    stop(&r);
}

#ifdef LSC_TEST_HID_DOUBLE
/* Over HID (the test double of hidapi: an xArm on a virtual clock), a file
 * of more than 19 servos is refused before anything is sent; 19 play. */
static void test_play_hid_bound(void **state)
{
    (void)state;
    char dir[64], node[96];
    snprintf(dir, sizeof dir, "/tmp/lsc-test-play-XXXXXX");
    assert_non_null(mkdtemp(dir));
    snprintf(node, sizeof node, "%s/hidraw0", dir);
    FILE *f = fopen(node, "w");
    assert_non_null(f);
    (void)fclose(f);
    hid_double_reset();
    assert_true(hid_double_add(node, "ARM-P", 0, 0) >= 0);
    lsc_device *d = NULL;
    int r = lsc_device_open("hid:ARM-P", NULL, &d);
    if (r != 0) {
        fail_msg("open hid:ARM-P: %s", lsc_device_error(d));
    }
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_HID);
    uint8_t ids[20];
    uint16_t row[21];
    row[0] = 500;
    for (uint8_t i = 0; i < 20; i++) {
        ids[i] = (uint8_t)(i + 1u);
        row[i + 1u] = (uint16_t)(400u + i);
    }
    lsc_action a;
    make_action(&a, ids, 20, row, 1);
    lsc_player_config c = {100, 1, 100, 0};
    unsigned writes = hid_double_writes();
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, NULL), LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "at most 19 servos in one move over HID"));
    assert_int_equal(hid_double_writes(), writes);
    lsc_action_free(&a);
    make_action(&a, ids, 19, row, 1);
    lsc_play_result res = {.size = sizeof res};
    assert_int_equal(lsc_device_play(d, &a, &c, NULL, NULL, &res), 0);
    assert_int_equal(res.frames, 1);
    assert_int_equal(hid_double_writes(), writes + 1u);
    lsc_action_free(&a);
    lsc_device_close(d);
    unlink(node);
    rmdir(dir);
    assert_int_equal(hid_double_open_handles(), 0);
}
#endif

/* The controller goes away during a play or a record (lsc-sim killed): the
 * error of the send, wait or read comes back; what was done is counted. */
typedef struct killer {
    bool killed;
} killer;

static void kill_sim(killer *k)
{
    if (!k->killed) {
        int status;
        assert_int_equal(kill(started, SIGKILL), 0);
        assert_int_equal(waitpid(started, &status, 0), started);
        started = -1;
        k->killed = true;
    }
}

static bool kill_after_step(void *user, const lsc_player_step *s, uint32_t elapsed)
{
    (void)elapsed;
    if (s != NULL) {
        kill_sim(user);
    }
    return true;
}

static bool kill_after_keyframe(void *user, const lsc_action *a, bool took)
{
    (void)a;
    if (took) {
        kill_sim(user);
    }
    return true;
}

static void test_pty_gone(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1};
    static const uint16_t rows[] = {10, 100, 10, 200, 10, 300, 10, 400};
    lsc_player_config c = {100, 100, 10, 0};
    for (int round = 0; round < 3; round++) {
        running_sim r;
        const char *const args[] = {"--fast", NULL};
        start(&r, args);
        lsc_device_set_timeout(r.d, (uint32_t)test_ms(200));
        killer k = {false};
        lsc_action a;
        if (round < 2) {
            /* round 1: the next frame is due at once and the line model
             * has no time for the frame: the send fails, not a wait */
            lsc_player_config fast = {100, 100, 0, 100000000};
            make_action(&a, ids, 1, rows, 4);
            lsc_play_result res = {.size = sizeof res};
            int e = lsc_device_play(r.d, &a, round == 0 ? &c : &fast, kill_after_step, &k, &res);
            assert_true(e < 0);
            assert_true(res.frames >= 1);
            assert_true(res.frames < 400);
        } else {
            assert_int_equal(lsc_action_init(&a, ids, 1), 0);
            int e = lsc_device_record(r.d, &a, 10, 0, kill_after_keyframe, &k);
            assert_true(e < 0);
            assert_int_equal(a.count, 1);
        }
        assert_string_not_equal(lsc_device_error(r.d), "");
        lsc_action_free(&a);
        lsc_device_close(r.d);
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_play_schedule),
        cmocka_unit_test(test_play_drops),
        cmocka_unit_test(test_play_no_lead),
        cmocka_unit_test(test_play_result_size),
        cmocka_unit_test(test_play_stop),
        cmocka_unit_test(test_play_limits),
        cmocka_unit_test(test_play_refused),
        cmocka_unit_test(test_play_failed_open),
        cmocka_unit_test(test_record_every),
        cmocka_unit_test(test_take_keyframe),
#ifdef LSC_TEST_HID_DOUBLE
        cmocka_unit_test(test_play_hid_bound),
#endif
        cmocka_unit_test_teardown(test_pty_play, end_started),
        cmocka_unit_test_teardown(test_pty_record_retries, end_started),
        cmocka_unit_test_teardown(test_pty_record_gives_up, end_started),
        cmocka_unit_test_teardown(test_pty_gone, end_started),
    };
    if (argc < 2) {
        (void)fprintf(stderr, "usage: %s PATH/TO/lsc-sim\n", argv[0]);
        return 2;
    }
    lsc_sim_path = argv[1];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
