/* Halt and hold through the device layer (src/device/halt.c), "all" and
 * the wait for a group's start (lsc_device_start_ms): against the built-in
 * "sim" (virtual clock: exact), and against lsc-sim on a pseudo-terminal
 * (argv[1]; real time: a group it does not have never starts, replies
 * dropped, lsc-sim gone mid-hold). _POSIX_C_SOURCE comes from
 * tests/CMakeLists.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lsc/device.h"
#include "lsc/lsc.h"
#include "sim_pty.h"
#include "test_open.h"
#include "test_time.h"
#include "sized_test.h"
#ifdef LSC_TEST_HID_DOUBLE
#include "hid_double.h"
#endif

static const char *lsc_sim_path;

static bool has(const char *text, const char *part)
{
    if (strstr(text, part) == NULL) {
        fprintf(stderr, "'%s' lacks '%s'\n", text, part);
        return false;
    }
    return true;
}

#define assert_has(text, part) assert_true(has((text), (part)))

/* The frames sent, by command (a trace). */
typedef struct sent_frames {
    unsigned total;
    unsigned by_cmd[256];
    uint8_t last_move[LSC_FRAME_MAX];
    size_t last_move_len;
} sent_frames;

static void on_trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    sent_frames *s = user;
    if (dir != LSC_TRACE_TX) {
        return;
    }
    s->total++;
    s->by_cmd[frame[3]]++;
    if (frame[3] == LSC_CMD_SERVO_MOVE) {
        memcpy(s->last_move, frame, n);
        s->last_move_len = n;
    }
}

static lsc_device *open_sim(sent_frames *s)
{
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    if (s != NULL) {
        memset(s, 0, sizeof *s);
        lsc_device_set_trace(d, on_trace, s);
    }
    return d;
}

static lsc_arm *xarm_like(void)
{
    static const char text[] = "gripper 1 bus limits=0..700\nbase 6 bus\n";
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse(text, sizeof text - 1u, "t.conf", &arm, why, sizeof why), 0);
    return arm;
}

static uint16_t read_one(lsc_device *d, uint8_t id)
{
    lsc_servo got;
    assert_int_equal(lsc_device_read(d, &id, 1, &got), 1);
    return got.position;
}

/* ---- "all" ----------------------------------------------------------------------- */

static void all_ids_by_kind(void **state)
{
    (void)state;
    uint8_t ids[40];
    lsc_arm *arm = xarm_like();
    assert_int_equal(lsc_device_all_ids(arm, "sim", ids, sizeof ids), 2);
    assert_int_equal(ids[0], 1);
    assert_int_equal(ids[1], 6);
    assert_int_equal(lsc_device_all_ids(arm, NULL, ids, 1), 2); /* only one written */
    static const char *const six[] = {"hid",         "hid:ARM1",        "/dev/hidraw3",
                                      "lscd:hid",    "lscd:hid-ARM1",   "lx:sim",
                                      "lscd:lx-sim", "lx:/dev/ttyUSB0", "lscd:lx-ttyUSB0"};
    for (size_t i = 0; i < sizeof six / sizeof six[0]; i++) {
        memset(ids, 0, sizeof ids);
        assert_int_equal(lsc_device_all_ids(NULL, six[i], ids, sizeof ids), 6);
        assert_int_equal(ids[0], 1);
        assert_int_equal(ids[5], 6);
        assert_int_equal(ids[6], 0);
    }
    static const char *const many[] = {"sim", "/dev/ttyUSB0", "lscd:ttyUSB0", "lscd:hidden",
                                       "lscd:/run/lsc/x.sock"};
    for (size_t i = 0; i < sizeof many / sizeof many[0]; i++) {
        assert_int_equal(lsc_device_all_ids(NULL, many[i], ids, sizeof ids), 32);
        assert_int_equal(ids[31], 32);
    }
    assert_int_equal(lsc_device_all_ids(NULL, "sim", NULL, 0), 32); /* the count only */
    assert_int_equal(lsc_device_all_ids(NULL, "sim", NULL, 3), LSC_EINVAL);
    /* no name: $LSC_PORT's, else not known before the open */
    assert_int_equal(unsetenv("LSC_PORT"), 0);
    assert_int_equal(lsc_device_all_ids(NULL, NULL, ids, sizeof ids), LSC_ENODEV);
    assert_int_equal(setenv("LSC_PORT", "hid", 1), 0);
    assert_int_equal(lsc_device_all_ids(NULL, NULL, ids, sizeof ids), 6);
    assert_int_equal(unsetenv("LSC_PORT"), 0);
    lsc_arm_free(arm);
}

static void parse_ids_with_all(void **state)
{
    (void)state;
    uint8_t ids[40];
    char why[200];
    lsc_arm *arm = xarm_like();
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", "all", ids, sizeof ids, why,
                                              sizeof why),
                     32);
    assert_int_equal(lsc_device_parse_ids_all(arm, "sim", "all", ids, sizeof ids, why,
                                              sizeof why),
                     2);
    assert_int_equal(ids[1], 6);
    assert_int_equal(lsc_device_parse_ids_all(arm, "sim", "gripper,2-3", ids, sizeof ids, why,
                                              sizeof why),
                     3);
    assert_int_equal(lsc_device_parse_ids_all(NULL, "hid", "1,3-5", ids, sizeof ids, why,
                                              sizeof why),
                     4);
    assert_int_equal(ids[3], 5);
    /* more than there is room for */
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", "all", ids, 6, why, sizeof why),
                     LSC_EINVAL);
    assert_has(why, "'all' is 32 servos here: more than 6");
    /* the kind not known yet */
    assert_int_equal(unsetenv("LSC_PORT"), 0);
    assert_int_equal(lsc_device_parse_ids_all(NULL, NULL, "all", ids, sizeof ids, why,
                                              sizeof why),
                     LSC_ENODEV);
    assert_has(why, "'all' stands for the controller's servos");
    /* "all" only alone; what parse_ids refuses, refused the same */
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", "all,7", ids, sizeof ids, why,
                                              sizeof why),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", NULL, ids, sizeof ids, why,
                                              sizeof why),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", "all", NULL, sizeof ids, why,
                                              sizeof why),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_parse_ids_all(NULL, "sim", "all", ids, 0, why, sizeof why),
                     LSC_EINVAL);
    lsc_arm_free(arm);
}

/* ---- hold ------------------------------------------------------------------------- */

/* A gripper opened by hand past its limit (900, limit 700) is held there,
 * and said to be beyond; a move out of a limit stays refused. */
static void hold_beyond_a_limit(void **state)
{
    (void)state;
    sent_frames s;
    lsc_device *d = open_sim(&s);
    lsc_arm *arm = xarm_like();
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    const uint8_t raw[] = {1, 0, 0, 1, 0x84, 0x03}; /* 0 ms, servo 1 to 900: "by hand" */
    assert_int_equal(lsc_device_send(d, LSC_CMD_SERVO_MOVE, raw, sizeof raw, false), 0);
    const uint8_t limp[] = {1};
    assert_int_equal(lsc_device_unload(d, limp, 1), 0);
    s.total = 0;
    const uint8_t ids[] = {6, 1};
    lsc_hold_result res = {.size = sizeof res};
    assert_int_equal(lsc_device_hold(d, ids, 2, &res), LSC_HOLD_BEYOND);
    assert_int_equal(res.n, 2);
    assert_int_equal(res.held[0].id, 6);
    assert_int_equal(res.held[0].position, 500);
    assert_int_equal(res.held[1].id, 1);
    assert_int_equal(res.held[1].position, 900);
    assert_int_equal(res.nbeyond, 1);
    assert_int_equal(res.beyond[0], 1);
    assert_has(lsc_device_error(d), "held where it is, beyond its limits: position 900 is "
                                    "outside the limits of joint gripper (servo 1)");
    assert_has(lsc_device_error(d), "move it back within them");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NONE);
    assert_int_equal(s.total, 2); /* the read, the move */
    /* the move holds them where they were: 20 ms, 6:500, 1:900 */
    static const uint8_t move[] = {0x55, 0x55, 0x0B, 0x03, 0x02, 0x14, 0x00,
                                   0x06, 0xF4, 0x01, 0x01, 0x84, 0x03};
    assert_int_equal(s.last_move_len, sizeof move);
    assert_memory_equal(s.last_move, move, sizeof move);
    /* the gripper is powered again and stays at 900 */
    assert_int_equal(lsc_device_poll(d, 1000), 0);
    assert_int_equal(read_one(d, 1), 900);
    /* its last position is known (for a move at a speed) */
    uint16_t last = 0;
    assert_int_equal(lsc_device_last_position(d, 1, &last), 0);
    assert_int_equal(last, 900);
    /* moving it further out is still refused */
    lsc_servo out = {1, 950};
    assert_int_equal(lsc_device_move(d, 100, &out, 1), LSC_EINVAL);
    /* within: 0, no message; NULL result */
    assert_int_equal(lsc_device_hold(d, ids, 1, NULL), 0);
    assert_string_equal(lsc_device_error(d), "");
    /* a caller's shorter struct (up to held): nothing written beyond its size */
    lsc_hold_result old;
    const size_t upto = offsetof(lsc_hold_result, nbeyond);
    sized_guard(&old, sizeof old, upto);
    assert_int_equal(lsc_device_hold(d, ids, 2, &old), LSC_HOLD_BEYOND);
    assert_int_equal(old.size, upto);
    assert_int_equal(old.n, 2);
    assert_int_equal(old.held[1].position, 900);
    assert_true(sized_untouched(&old, upto, sizeof old));
    /* below the size field and n: refused, nothing sent or written */
    s.total = 0;
    sized_guard(&old, sizeof old, sizeof old.size);
    assert_int_equal(lsc_device_hold(d, ids, 2, &old), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_hold_result.size is");
    assert_has(lsc_device_error(d), "set it to sizeof(lsc_hold_result); nothing was sent");
    assert_true(sized_untouched(&old, sizeof old.size, sizeof old));
    assert_int_equal(s.total, 0);
    lsc_device_close(d);
}

static void hold_refused(void **state)
{
    (void)state;
    sent_frames s;
    lsc_device *d = open_sim(&s);
    uint8_t ids[LSC_MOVE_MAX + 1u];
    lsc_hold_result res = {.size = sizeof res};
    for (size_t i = 0; i < sizeof ids; i++) {
        ids[i] = (uint8_t)i;
    }
    res.n = 9;
    assert_int_equal(lsc_device_hold(NULL, ids, 1, &res), LSC_EINVAL);
    assert_int_equal(res.n, 9); /* refused: nothing written */
    assert_int_equal(lsc_device_hold(d, NULL, 1, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "holding 0 servos: one hold takes 1..83; nothing was sent");
    assert_int_equal(lsc_device_hold(d, ids, 0, &res), LSC_EINVAL);
    assert_int_equal(lsc_device_hold(d, ids, LSC_MOVE_MAX + 1u, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "holding 84 servos");
    const uint8_t twice[] = {3, 4, 3};
    assert_int_equal(lsc_device_hold(d, twice, 3, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 3 is given twice in one hold; nothing was sent");
    assert_int_equal(s.total, 0);
    /* the most: 83 servos */
    assert_int_equal(lsc_device_hold(d, ids, LSC_MOVE_MAX, &res), 0);
    assert_int_equal(res.n, LSC_MOVE_MAX);
    assert_int_equal(lsc_device_halt(NULL), LSC_EINVAL);
    lsc_device_close(d);
    /* a failed open gives no handle: both refuse NULL */
    lsc_device *bad = NULL;
    assert_int_equal(lsc_device_open("/nonexistent/tty", NULL, &bad), LSC_ENODEV);
    assert_null(bad);
    assert_int_equal(lsc_device_hold(bad, ids, 1, &res), LSC_EINVAL);
    assert_int_equal(lsc_device_halt(bad), LSC_EINVAL);
}

/* Two joints beyond their limits: both listed, the first named. */
static void hold_two_beyond(void **state)
{
    (void)state;
    static const char text[] = "gripper 1 bus limits=0..700\nbase 6 bus limits=400..600\n";
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse(text, sizeof text - 1u, "t.conf", &arm, why, sizeof why), 0);
    lsc_device *d = open_sim(NULL);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    const uint8_t raw[] = {2, 0, 0, 1, 0x84, 0x03, 6, 0x8A, 0x02}; /* 1 to 900, 6 to 650 */
    assert_int_equal(lsc_device_send(d, LSC_CMD_SERVO_MOVE, raw, sizeof raw, false), 0);
    const uint8_t ids[] = {6, 1};
    lsc_hold_result res = {.size = sizeof res};
    assert_int_equal(lsc_device_hold(d, ids, 2, &res), LSC_HOLD_BEYOND);
    assert_int_equal(res.nbeyond, 2);
    assert_int_equal(res.beyond[0], 6);
    assert_int_equal(res.beyond[1], 1);
    assert_has(lsc_device_error(d), "position 650 is outside the limits of joint base (servo 6)");
    lsc_device_close(d);
}

#ifdef LSC_TEST_HID_DOUBLE
/* A trace that unplugs the double's arm 0 as a move goes out (the move
 * itself is written; what follows fails). */
static void unplug_on_move(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)user;
    (void)n;
    if (dir == LSC_TRACE_TX && frame[3] == LSC_CMD_SERVO_MOVE) {
        hid_double_set_flags(0, HID_DOUBLE_UNPLUG);
    }
}

/* Over HID: "all" is 1..6 (halt reads and holds those), and a hold of more
 * than 19 servos is refused before anything is sent. */
static void hold_over_hid(void **state)
{
    (void)state;
    char dir[64], node[96];
    snprintf(dir, sizeof dir, "/tmp/lsc-test-halt-XXXXXX");
    assert_non_null(mkdtemp(dir));
    snprintf(node, sizeof node, "%s/hidraw0", dir);
    FILE *f = fopen(node, "w");
    assert_non_null(f);
    (void)fclose(f);
    hid_double_reset();
    assert_true(hid_double_add(node, "ARM-H", 0, 0) >= 0);
    lsc_device *d = NULL;
    if (lsc_device_open("hid:ARM-H", NULL, &d) != 0) {
        fail_msg("open hid:ARM-H: %s", lsc_device_error(d));
    }
    uint8_t ids[20];
    for (uint8_t i = 0; i < 20; i++) {
        ids[i] = (uint8_t)(i + 1u);
    }
    unsigned writes = hid_double_writes();
    assert_int_equal(lsc_device_hold(d, ids, 20, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a hold of 20 servos on hid:ARM-H: at most 19 servos in one "
                                    "move over HID");
    assert_int_equal(hid_double_writes(), writes);
    assert_int_equal(lsc_device_halt(d), 0);
    assert_int_equal(hid_double_writes(), writes + 3u); /* stop, read, move */
    uint8_t last[65];
    assert_int_equal(hid_double_last_write(last, sizeof last), 65);
    assert_int_equal(last[1 + 3], LSC_CMD_SERVO_MOVE);
    assert_int_equal(last[1 + 4], 6); /* servos 1..6 */
    /* the arm unplugged as the hold's move went out: its time's wait fails */
    lsc_device_set_trace(d, unplug_on_move, NULL);
    int r = lsc_device_hold(d, ids, 2, NULL);
    assert_true(r < 0);
    assert_has(lsc_device_error(d), "read failed");
    lsc_device_close(d);
    unlink(node);
    rmdir(dir);
    assert_int_equal(hid_double_open_handles(), 0);
}
#endif

/* ---- halt ------------------------------------------------------------------------- */

/* During a six-second move: the servo stops where it is, between its start
 * and its target, and stays there (two reads 0.6 s apart agree). */
static void halt_during_a_move(void **state)
{
    (void)state;
    sent_frames s;
    lsc_device *d = open_sim(&s);
    lsc_servo to = {1, 2500};
    assert_int_equal(lsc_device_move(d, 6000, &to, 1), 0);
    assert_int_equal(lsc_device_poll(d, 3000), 0);
    memset(&s, 0, sizeof s);
    assert_int_equal(lsc_device_halt(d), 0);
    assert_int_equal(s.by_cmd[LSC_CMD_GROUP_STOP], 1);
    assert_int_equal(s.by_cmd[LSC_CMD_POS_READ], 1);
    assert_int_equal(s.by_cmd[LSC_CMD_SERVO_MOVE], 1);
    assert_int_equal(s.total, 3);
    /* every id of the board kind: 1..32 */
    assert_int_equal(s.last_move[4], 32);
    uint16_t first = read_one(d, 1);
    assert_int_equal(lsc_device_poll(d, 600), 0);
    uint16_t second = read_one(d, 1);
    assert_int_equal(first, second);
    assert_true(first > 1500 && first < 2500);
    lsc_device_close(d);
}

/* During a looping action group: its stop is sent (the controller reports
 * it), and every servo is held where the group left it. */
static void halt_during_a_group(void **state)
{
    (void)state;
    sent_frames s;
    lsc_device *d = open_sim(&s);
    lsc_arm *arm = xarm_like();
    assert_int_equal(lsc_device_run(d, 8, 0), 0);
    assert_int_equal(lsc_device_poll(d, 1500), 1); /* its start */
    lsc_notification n;
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    memset(&s, 0, sizeof s);
    assert_int_equal(lsc_device_halt(d), 0);
    assert_int_equal(s.by_cmd[LSC_CMD_GROUP_STOP], 1);
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_STOP);
    const uint8_t ids[] = {1, 2, 3};
    lsc_servo before[3], after[3];
    assert_int_equal(lsc_device_read(d, ids, 3, before), 3);
    assert_int_equal(lsc_device_poll(d, 3000), 0); /* nothing more: it stopped */
    assert_int_equal(lsc_device_read(d, ids, 3, after), 3);
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(before[i].position, after[i].position);
    }
    /* with an arm profile: its joints only; one beyond its limit is held */
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    const uint8_t raw[] = {1, 0, 0, 1, 0x84, 0x03}; /* 0 ms, servo 1 to 900 */
    assert_int_equal(lsc_device_send(d, LSC_CMD_SERVO_MOVE, raw, sizeof raw, false), 0);
    assert_int_equal(lsc_device_halt(d), LSC_HOLD_BEYOND);
    assert_has(lsc_device_error(d), "joint gripper (servo 1)");
    assert_int_equal(s.last_move[4], 2);
    lsc_arm_free(arm);
    lsc_device_close(d);
}

/* ---- the start of a group ------------------------------------------------------ */

static void start_window(void **state)
{
    (void)state;
    assert_int_equal(lsc_device_start_ms(NULL), 1000);
    lsc_device *d = open_sim(NULL);
    assert_int_equal(lsc_device_start_ms(d), 15 + 1000); /* 14 bytes at 9600, a reply */
    lsc_device_set_timeout(d, 200);
    assert_int_equal(lsc_device_start_ms(d), 15 + 200);
    lsc_device_set_timeout(d, 30000); /* a long timeout: the wait stays short */
    assert_int_equal(lsc_device_start_ms(d), 15 + 1000);
    lsc_device_close(d);
    test_options opt = {115200, 0, 0, 0};
    assert_int_equal(test_open("sim", &opt, &d), 0);
    assert_int_equal(lsc_device_start_ms(d), 2 + 1000);
    /* a wait resumed after the start was seen: no start to wait for */
    lsc_notification n;
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 8, 100, NULL), LSC_ETIMEOUT);
    assert_true(lsc_device_group_started(d));
    assert_int_equal(lsc_device_wait_group(d, 8, 5000, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    lsc_device_close(d);
}

/* lsc-sim on a pty, started by a test; the teardown ends it if a failed
 * assertion left the test early. */
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

static lsc_device *start(const char *const *extra, char *tty, size_t cap)
{
    lsc_device *d = NULL;
    sim_pty_start(lsc_sim_path, extra, &started, tty, cap);
    test_options opt = {9600, (uint32_t)test_ms(1000), 0, 0};
    if (test_open(tty, &opt, &d) != 0) {
        fail_msg("open %s: %s", tty, lsc_device_error(d));
    }
    return d;
}

/* A group the board does not have never starts: the wait says so within
 * lsc_device_start_ms of the run, long before its own timeout; a group it
 * has starts and ends. */
static void never_started(void **state)
{
    (void)state;
    char tty[256], groups[] = "/tmp/lsc-test-halt-XXXXXX";
    int fd = mkstemp(groups);
    assert_true(fd >= 0);
    static const char text[] = "group 1\nstep 100 1:1000\n";
    assert_int_equal(write(fd, text, sizeof text - 1u), (ssize_t)(sizeof text - 1u));
    assert_int_equal(close(fd), 0);
    const char *const args[] = {"--fast", "--groups", groups, NULL};
    lsc_device *d = start(args, tty, sizeof tty);
    (void)unlink(groups); /* (lsc-sim has read it) */
    uint32_t window = lsc_device_start_ms(d);
    uint32_t limit = window + (uint32_t)test_ms(20000);
    assert_int_equal(lsc_device_run(d, 9, 1), 0);
    uint32_t t0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_wait_group(d, 9, limit, NULL), LSC_ETIMEOUT);
    uint32_t spent = lsc_device_now_ms(d) - t0;
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NEVER_STARTED);
    assert_has(lsc_device_error(d), "group 9 never started: the controller on ");
    assert_has(lsc_device_error(d), "it has no group 9");
    assert_true(spent + 50u >= window);
    assert_true(spent < limit);
    assert_false(lsc_device_group_started(d));
    /* a wait with a shorter timeout than the window ends as a wait does */
    assert_int_equal(lsc_device_run(d, 9, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 9, 10, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    /* ... and resumed past the window: never started, at once */
    assert_int_equal(lsc_device_poll(d, window), 0);
    assert_int_equal(lsc_device_wait_group(d, 9, limit, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NEVER_STARTED);
    /* group 1 of lsc-sim's own starts and ends */
    lsc_notification n;
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 1, limit, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    /* a wait without a run of it has no start window */
    assert_int_equal(lsc_device_wait_group(d, 9, 100, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_WAIT_TIMEOUT);
    lsc_device_close(d);
    sim_pty_stop(&started);
}

/* A board that does not answer position reads: halt sent the stop and says
 * that the servos go on. */
static void halt_without_reads(void **state)
{
    (void)state;
    char tty[256];
    const char *const args[] = {"--fast", "--drop-replies", "100", NULL};
    lsc_device *d = start(args, tty, sizeof tty);
    lsc_device_set_timeout(d, (uint32_t)test_ms(200));
    assert_int_equal(lsc_device_halt(d), LSC_ETIMEOUT);
    assert_has(lsc_device_error(d), "halt: the action group was stopped, but the servos' "
                                    "positions could not be read, so they go on to their "
                                    "last targets: no reply");
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_NO_REPLY);
    lsc_device_close(d);
    sim_pty_stop(&started);
}

/* lsc-sim ends after the positions were read: the hold's move fails with
 * the link's error; before the stop: halt fails at once. */
static void on_reply_kill(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)user;
    (void)n;
    if (dir == LSC_TRACE_RX && frame[3] == LSC_CMD_POS_READ) {
        end_started(NULL);
    }
}

static void halt_link_gone(void **state)
{
    (void)state;
    char tty[256];
    const char *const args[] = {"--fast", NULL};
    lsc_device *d = start(args, tty, sizeof tty);
    lsc_device_set_trace(d, on_reply_kill, NULL);
    const uint8_t ids[] = {1, 2};
    int r = lsc_device_hold(d, ids, 2, NULL);
    assert_true(r < 0 && r != LSC_ETIMEOUT);
    assert_int_equal(lsc_device_halt(d), r); /* the stop's write fails too */
    lsc_device_close(d);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s LSC_SIM\n", argv[0]);
        return 2;
    }
    lsc_sim_path = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(all_ids_by_kind),
        cmocka_unit_test(parse_ids_with_all),
        cmocka_unit_test(hold_beyond_a_limit),
        cmocka_unit_test(hold_refused),
        cmocka_unit_test(hold_two_beyond),
#ifdef LSC_TEST_HID_DOUBLE
        cmocka_unit_test(hold_over_hid),
#endif
        cmocka_unit_test(halt_during_a_move),
        cmocka_unit_test(halt_during_a_group),
        cmocka_unit_test(start_window),
        cmocka_unit_test_teardown(never_started, end_started),
        cmocka_unit_test_teardown(halt_without_reads, end_started),
        cmocka_unit_test_teardown(halt_link_gone, end_started),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
