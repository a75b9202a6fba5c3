/* Tests of the keyframe player (include/lsc/player.h) with a fake clock. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "lsc/lsc.h"

static const lsc_player_config plain = {100, 1, 1000, 9600};

/* One frame as the test saw it. */
typedef struct sent {
    uint32_t at;     /* fake clock when it was handed out */
    lsc_player_step s;
} sent;

/* Plays to the end on a fake clock that moves exactly as asked (start at
 * t0); returns the number of frames sent, at most cap. */
static size_t play(lsc_player *p, uint32_t t0, sent *out, size_t cap)
{
    uint32_t now = t0;
    size_t n = 0;
    for (int guard = 0; guard < 1000000; guard++) {
        lsc_player_step s;
        int r = lsc_player_next(p, now, &s);
        if (r == LSC_PLAYER_DONE) {
            return n;
        }
        if (r == LSC_PLAYER_WAIT) {
            assert_true(s.wait_ms > 0);
            now += s.wait_ms;
        } else {
            assert_int_equal(r, LSC_PLAYER_SEND);
            assert_true(n < cap);
            out[n].at = now;
            out[n].s = s;
            n++;
        }
    }
    fail_msg("the player never finished");
    return n;
}

static void test_schedule(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2};
    static const uint16_t kf[] = {
        500, 100, 200, /* keyframe 0: its time is replaced by the lead-in */
        300, 150, 200, /* servo 2 unchanged: left out */
        400, 150, 200, /* nothing changed: a pause, no frame */
        250, 900, 800,
    };
    lsc_track t = {ids, 2, 4, kf, NULL};
    lsc_player p;
    sent f[8] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &plain), 0);
    assert_int_equal(lsc_player_frames(&p), 4);
    assert_int_equal(lsc_player_total_ms(&p), 1000 + 300 + 400 + 250);
    size_t n = play(&p, 5000, f, 8);
    assert_int_equal(n, 3);
    /* lead-in: every servo, over the lead, at once */
    assert_true(f[0].s.lead_in);
    assert_int_equal(f[0].at, 5000);
    assert_int_equal(f[0].s.due_ms, 0);
    assert_int_equal(f[0].s.time_ms, 1000);
    assert_int_equal(f[0].s.nservos, 2);
    assert_int_equal(f[0].s.servos[0].id, 1);
    assert_int_equal(f[0].s.servos[0].position, 100);
    assert_int_equal(f[0].s.servos[1].position, 200);
    /* keyframe 1 when the lead-in ends, only servo 1 */
    assert_false(f[1].s.lead_in);
    assert_int_equal(f[1].s.keyframe, 1);
    assert_int_equal(f[1].at, 6000);
    assert_int_equal(f[1].s.due_ms, 1000);
    assert_int_equal(f[1].s.time_ms, 300);
    assert_int_equal(f[1].s.nservos, 1);
    assert_int_equal(f[1].s.servos[0].id, 1);
    assert_int_equal(f[1].s.servos[0].position, 150);
    /* keyframe 2 is a pause; keyframe 3 after it */
    assert_int_equal(f[2].s.keyframe, 3);
    assert_int_equal(f[2].s.due_ms, 1000 + 300 + 400);
    assert_int_equal(f[2].s.time_ms, 250);
    assert_int_equal(f[2].s.nservos, 2);
    assert_int_equal(lsc_player_dropped(&p), 0);
    /* done: asking again stays done */
    lsc_player_step s;
    assert_int_equal(lsc_player_next(&p, 5000 + 1950, &s), LSC_PLAYER_DONE);
}

static void test_repetitions_and_speed(void **state)
{
    (void)state;
    static const uint8_t ids[] = {7};
    static const uint16_t kf[] = {100, 10, 200, 20};
    lsc_track t = {ids, 1, 2, kf, NULL};
    lsc_player_config c = {200, 3, 40, 9600}; /* twice as fast, 3 times */
    lsc_player p;
    sent f[8] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    size_t n = play(&p, 0, f, 8);
    assert_int_equal(n, 6);
    /* lead 40, then 200/2, then keyframe 0 again over 100/2, ... */
    static const uint32_t due[] = {0, 40, 140, 190, 290, 340};
    static const uint16_t time[] = {40, 100, 50, 100, 50, 100};
    static const uint16_t kfi[] = {0, 1, 0, 1, 0, 1};
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(f[i].s.due_ms, due[i]);
        assert_int_equal(f[i].at, due[i]);
        assert_int_equal(f[i].s.time_ms, time[i]);
        assert_int_equal(f[i].s.keyframe, kfi[i]);
        assert_int_equal(f[i].s.repetition, i / 2);
    }
    assert_int_equal(lsc_player_total_ms(&p), 440);
}

/* Odd times at an odd speed: due times are exact sums, never drift. */
static void test_no_drift(void **state)
{
    (void)state;
    enum { N = 1000 };
    static uint16_t kf[N * 2];
    static const uint8_t ids[] = {3};
    for (size_t i = 0; i < N; i++) {
        kf[2 * i] = 7;
        kf[2 * i + 1] = (uint16_t)(i % 2 ? 100 : 900);
    }
    lsc_track t = {ids, 1, N, kf, NULL};
    lsc_player_config c = {300, 1, 10, 115200};
    lsc_player p;
    static sent f[N];
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    size_t n = play(&p, 0, f, N);
    assert_int_equal(n, N);
    uint32_t sum = 0;
    for (size_t i = 1; i < n; i++) {
        assert_int_equal(f[i].s.due_ms, 10 + (uint32_t)((i - 1) * 7 * 100 / 300));
        sum += f[i].s.time_ms;
    }
    /* the move times add up to the whole, rounding included */
    assert_int_equal(sum, (N - 1) * 7 * 100 / 300);
    assert_int_equal(lsc_player_total_ms(&p), 10 + sum);
}

/* Keyframes faster than the line: frames are dropped, the latest due goes
 * out, the line is never asked for more than it carries, no frame is late
 * by more than one frame's line time. */
static void test_cannot_keep_up(void **state)
{
    (void)state;
    enum { N = 200 };
    static uint16_t kf[N * 2];
    static const uint8_t ids[] = {1};
    for (size_t i = 0; i < N; i++) {
        kf[2 * i] = 5; /* a one-servo frame takes 10.4 ms at 9600 baud */
        kf[2 * i + 1] = (uint16_t)i;
    }
    lsc_track t = {ids, 1, N, kf, NULL};
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_player p;
    static sent f[N];
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    size_t n = play(&p, 0, f, N);
    assert_true(n < N / 2 + 2);
    assert_true(n > N / 3);
    assert_int_equal(lsc_player_dropped(&p) + n, N);
    uint32_t dropped = 0;
    for (size_t i = 0; i < n; i++) {
        dropped += f[i].s.dropped;
        if (i > 0) {
            assert_true(f[i].at - f[i - 1].at >= 10); /* 10.4 ms, on a ms clock */
            assert_true(f[i].s.keyframe > f[i - 1].s.keyframe);
        }
        assert_true(f[i].at >= f[i].s.due_ms);
        assert_true(f[i].at - f[i].s.due_ms <= 11);
        /* the latest keyframe due when it went out */
        assert_true(f[i].s.due_ms + 5 > f[i].at || f[i].s.keyframe == N - 1);
    }
    assert_int_equal(dropped, lsc_player_dropped(&p));
    assert_int_equal(f[n - 1].s.keyframe, N - 1); /* the last is never dropped */
    /* the line stays full: one frame every 10.417 ms, not every 11 */
    assert_true((uint64_t)(f[n - 2].at - f[0].at) * 1000u <= (uint64_t)(n - 2) * 10417u + 1000u);
}

/* Keyframes just slower than the line: nothing dropped, every frame on time. */
static void test_line_pace(void **state)
{
    (void)state;
    enum { N = 100 };
    static uint16_t kf[N * 2];
    static const uint8_t ids[] = {1};
    for (size_t i = 0; i < N; i++) {
        kf[2 * i] = 11;
        kf[2 * i + 1] = (uint16_t)i;
    }
    lsc_track t = {ids, 1, N, kf, NULL};
    lsc_player_config c = {100, 1, 11, 9600};
    lsc_player p;
    static sent f[N];
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    assert_int_equal(play(&p, 0, f, N), N);
    for (size_t i = 0; i < N; i++) {
        assert_int_equal(f[i].at, 11 * i);
    }
    assert_int_equal(lsc_player_dropped(&p), 0);
    assert_int_equal(lsc_player_line_us(1, 9600), 10417);
    assert_int_equal(lsc_player_line_us(6, 9600), 26042);
    assert_int_equal(lsc_player_line_us(1, 0), UINT32_MAX);
}

/* A caller that comes back late gets the latest keyframe due, not a backlog. */
static void test_late_caller(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1};
    static const uint16_t kf[] = {100, 1, 100, 2, 100, 3, 100, 4, 100, 5};
    lsc_track t = {ids, 1, 5, kf, NULL};
    lsc_player p;
    lsc_player_step s;
    assert_int_equal(lsc_player_init(&p, &t, &plain), 0);
    assert_int_equal(lsc_player_next(&p, 0, &s), LSC_PLAYER_SEND);
    assert_int_equal(lsc_player_next(&p, 1250, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.keyframe, 3); /* due 1200; 1 and 2 dropped */
    assert_int_equal(s.dropped, 2);
    assert_int_equal(s.due_ms, 1200);
    assert_int_equal(s.time_ms, 100);
    assert_int_equal(lsc_player_next(&p, 1250, &s), LSC_PLAYER_WAIT);
    assert_int_equal(s.wait_ms, 50);
    assert_int_equal(lsc_player_next(&p, 99999, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.keyframe, 4);
    assert_int_equal(s.dropped, 0);
    assert_int_equal(lsc_player_next(&p, 99999, &s), LSC_PLAYER_DONE);
    assert_int_equal(lsc_player_dropped(&p), 2);
}

/* What a frame leaves out is compared with the frames sent, not the dropped
 * ones; and only the servos that moved are taken as sent. */
static void test_changed_since_last_sent(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2, 3};
    static const uint16_t kf[] = {100, 10, 20, 30, /* sent whole (lead-in) */
                                  100, 11, 20, 30, /* dropped */
                                  100, 10, 21, 30, /* servo 1 is back where it was sent */
                                  100, 10, 21, 31, /* only servo 3 moves */
                                  100, 12, 22, 31};
    lsc_track t = {ids, 3, 5, kf, NULL};
    lsc_player p;
    lsc_player_step s;
    assert_int_equal(lsc_player_init(&p, &t, &plain), 0);
    assert_int_equal(lsc_player_next(&p, 0, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.nservos, 3);
    assert_int_equal(lsc_player_next(&p, 1150, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.keyframe, 2);
    assert_int_equal(s.dropped, 1);
    assert_int_equal(s.nservos, 1);
    assert_int_equal(s.servos[0].id, 2);
    assert_int_equal(s.servos[0].position, 21);
    assert_int_equal(lsc_player_next(&p, 1200, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.nservos, 1);
    assert_int_equal(s.servos[0].id, 3);
    assert_int_equal(s.servos[0].position, 31);
    assert_int_equal(lsc_player_next(&p, 1300, &s), LSC_PLAYER_SEND);
    assert_int_equal(s.nservos, 2);
    assert_int_equal(s.servos[0].id, 1);
    assert_int_equal(s.servos[0].position, 12);
    assert_int_equal(s.servos[1].id, 2);
    assert_int_equal(s.servos[1].position, 22);
    assert_int_equal(lsc_player_next(&p, 1400, &s), LSC_PLAYER_DONE);
}

/* Keyframes read through an accessor (as from flash), and a clock that wraps. */
static unsigned reads;
static uint16_t read_word(const void *data, size_t i)
{
    reads++;
    const uint8_t *b = data; /* little-endian bytes, like a flash image */
    return (uint16_t)(b[2 * i] | b[2 * i + 1] << 8);
}

static void test_accessor_and_wrap(void **state)
{
    (void)state;
    static const uint8_t ids[] = {4, 9};
    static const uint8_t bytes[] = {0x10, 0x00, 0xE8, 0x03, 0x00, 0x00,  /* 16, 1000, 0 */
                                    0x20, 0x00, 0xE8, 0x03, 0x01, 0x00}; /* 32, 1000, 1 */
    lsc_track t = {ids, 2, 2, bytes, read_word};
    lsc_player p;
    sent f[4] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &plain), 0);
    assert_true(reads > 0);
    assert_int_equal(play(&p, UINT32_MAX - 500, f, 4), 2);
    assert_int_equal(f[0].s.servos[0].position, 1000);
    assert_int_equal(f[0].s.servos[1].position, 0);
    assert_int_equal(f[1].at, UINT32_MAX - 500 + 1000); /* past the wrap */
    assert_int_equal(f[1].s.nservos, 1);
    assert_int_equal(f[1].s.servos[0].id, 9);
    assert_int_equal(f[1].s.servos[0].position, 1);
    assert_int_equal(f[1].s.time_ms, 32);
}

/* A lead-in of 0 ms goes out at once, a move of 0 ms to keyframe 0 with
 * every servo; keyframe 1, due then too, follows when the line is free
 * (13 bytes at 9600 baud: 13.5 ms). Nothing is dropped. */
static void test_no_lead(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2};
    static const uint16_t kf[] = {5, 1, 2, 5, 3, 2};
    lsc_track t = {ids, 2, 2, kf, NULL};
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_player p;
    sent f[4] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    assert_int_equal(play(&p, 0, f, 4), 2);
    assert_true(f[0].s.lead_in);
    assert_int_equal(f[0].s.keyframe, 0);
    assert_int_equal(f[0].at, 0);
    assert_int_equal(f[0].s.time_ms, 0);
    assert_int_equal(f[0].s.nservos, 2);
    assert_int_equal(f[0].s.dropped, 0);
    assert_int_equal(f[1].s.keyframe, 1);
    assert_int_equal(f[1].s.due_ms, 0);
    assert_int_equal(f[1].at, 13);
    assert_int_equal(f[1].s.time_ms, 5);
    assert_int_equal(f[1].s.nservos, 1);
    assert_int_equal(f[1].s.servos[0].position, 3);
    assert_int_equal(f[1].s.dropped, 0);
    assert_int_equal(lsc_player_dropped(&p), 0);
}

/* --lead 0 on a file with 500 ms between keyframes of six servos: every
 * keyframe goes out, none is dropped as faster than the line. */
static void test_no_lead_slow_file(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2, 3, 4, 5, 6};
    static const uint16_t kf[] = {500, 1, 2, 3, 4, 5, 6,
                                  500, 7, 8, 9, 10, 11, 12,
                                  500, 1, 2, 3, 4, 5, 6};
    lsc_track t = {ids, 6, 3, kf, NULL};
    lsc_player_config c = {100, 1, 0, 9600};
    lsc_player p;
    sent f[4] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    assert_int_equal(play(&p, 0, f, 4), 3);
    for (uint32_t i = 0; i < 3; i++) {
        assert_int_equal(f[i].s.keyframe, i);
        assert_int_equal(f[i].s.dropped, 0);
    }
    assert_int_equal(f[0].at, 0);
    assert_int_equal(f[1].at, 26); /* 25 bytes: 26.04 ms */
    assert_int_equal(f[2].at, 500);
    assert_int_equal(lsc_player_dropped(&p), 0);
}

/* Slow speeds stretch moves past what a frame carries: capped at 65535, the
 * schedule keeps the real length. */
static void test_long_moves(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1};
    static const uint16_t kf[] = {1, 1, 60000, 2, 60000, 3};
    lsc_track t = {ids, 1, 3, kf, NULL};
    lsc_player_config c = {50, 1, 1, 9600};
    lsc_player p;
    sent f[4] = {{0}};
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    assert_int_equal(play(&p, 0, f, 4), 3);
    assert_int_equal(f[1].s.time_ms, 65535);
    assert_int_equal(f[2].s.due_ms, 120001);
    assert_int_equal(lsc_player_total_ms(&p), 240001);
}

static void test_invalid(void **state)
{
    (void)state;
    static const uint8_t ids[] = {1, 2, 1};
    static const uint16_t kf[] = {1, 2, 3, 4};
    lsc_track t = {ids, 1, 2, kf, NULL};
    lsc_player p;
    lsc_player_step s;
    lsc_player_config c = plain;
    assert_int_equal(lsc_player_init(NULL, &t, &c), LSC_EINVAL);
    assert_int_equal(lsc_player_init(&p, NULL, &c), LSC_EINVAL);
    assert_int_equal(lsc_player_init(&p, &t, NULL), LSC_EINVAL);
    t.count = 0;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.count = 1;
    t.nservos = 3; /* id 1 twice */
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.nservos = 0;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.nservos = LSC_PLAYER_SERVOS_MAX + 1;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.nservos = 1;
    t.ids = NULL;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.ids = ids;
    t.data = NULL;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    t.data = kf;
    c.speed_pct = 0;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    c = plain;
    c.times = 0;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    c = plain;
    c.baud = 0;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    c.baud = 200000000;
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    /* 65535 repetitions of 65535 ms at 1 %: more than 2^32 ms */
    static const uint16_t slow[] = {65535, 1, 65535, 2};
    t.data = slow;
    t.count = 2;
    c = (lsc_player_config){1, 400, 0, 9600};
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    c = (lsc_player_config){100, 65535, 65535, 9600};
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    c = (lsc_player_config){100, 30000, 0, 9600};
    assert_int_equal(lsc_player_init(&p, &t, &c), 0);
    t.count = 70000; /* times * count beyond 32 bits */
    c = (lsc_player_config){100, 65535, 0, 9600};
    assert_int_equal(lsc_player_init(&p, &t, &c), LSC_EINVAL);
    assert_int_equal(lsc_player_next(NULL, 0, &s), LSC_EINVAL);
    assert_int_equal(lsc_player_next(&p, 0, NULL), LSC_EINVAL);
    memset(&p, 0, sizeof p);
    assert_int_equal(lsc_player_next(&p, 0, &s), LSC_EINVAL);
    assert_int_equal(lsc_player_frames(NULL), 0);
    assert_int_equal(lsc_player_dropped(NULL), 0);
    assert_int_equal(lsc_player_total_ms(NULL), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_schedule),
        cmocka_unit_test(test_repetitions_and_speed),
        cmocka_unit_test(test_no_drift),
        cmocka_unit_test(test_cannot_keep_up),
        cmocka_unit_test(test_line_pace),
        cmocka_unit_test(test_late_caller),
        cmocka_unit_test(test_changed_since_last_sent),
        cmocka_unit_test(test_accessor_and_wrap),
        cmocka_unit_test(test_long_moves),
        cmocka_unit_test(test_no_lead),
        cmocka_unit_test(test_no_lead_slow_file),
        cmocka_unit_test(test_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
