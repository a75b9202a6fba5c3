/* Tests of the hand through the device layer (lsc_device_where,
 * lsc_device_reach, lsc_device_move_time, lsc_device_move_speed,
 * lsc_device_last_position in
 * lsc/device.h) on the built-in virtual controller "sim" (its own clock:
 * exact and fast), with the xArm's profile. Frames sent are counted and
 * decoded through the trace. With hidapi's test double (tests/hid_double.c),
 * a controller that goes away mid-way; calloc is wrapped for out of memory. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "lsc/lsc.h"
#include "sized_test.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#ifdef LSC_TEST_HID
#include "hid_double.h"
#include "test_open.h"
#endif

void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
static int calloc_fails_in; /* N: the Nth call from now fails */

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (calloc_fails_in > 0 && --calloc_fails_in == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

#define XARM                                                                                     \
    "gripper 1 bus limits=0..700\n"                                                              \
    "wrist-rotate 2 bus limits=-115deg..115deg\n"                                                \
    "wrist 3 bus limits=-115deg..115deg\n"                                                       \
    "elbow 4 bus limits=-115deg..115deg\n"                                                       \
    "shoulder 5 bus limits=-115deg..115deg\n"                                                    \
    "base 6 bus limits=-115deg..115deg\n"
#define GEOMETRY                                                                                 \
    "chain: base shoulder elbow wrist wrist-rotate gripper\n"                                    \
    "links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm\n"

/* the chain's servos, base to wrist roll */
static const uint8_t chain_ids[LSC_KIN_JOINTS] = {6, 5, 4, 3, 2};

static lsc_arm *profile(const char *text)
{
    lsc_arm *arm = NULL;
    char why[LSC_ARM_MESSAGE_MAX];
    if (lsc_arm_parse(text, strlen(text), "t.conf", &arm, why, sizeof why) != 0) {
        fail_msg("%s", why);
    }
    return arm;
}

/* The moves sent (their servos), through the trace. */
typedef struct sent {
    size_t frames; /* every frame sent */
    size_t moves;
    lsc_servo pos[300][LSC_KIN_JOINTS];
    uint16_t time_ms[300];
    size_t any_moves;     /* moves of any number of servos */
    uint16_t last_move_ms; /* ... the last one's time */
} sent;

static void on_trace(void *user, lsc_trace_dir dir, const uint8_t *f, size_t n)
{
    sent *s = user;
    if (dir != LSC_TRACE_TX) {
        return;
    }
    s->frames++;
    if (n >= 7 && f[3] == LSC_CMD_SERVO_MOVE) {
        s->any_moves++;
        s->last_move_ms = (uint16_t)(f[5] | f[6] << 8);
    }
    if (n >= 7 && f[3] == LSC_CMD_SERVO_MOVE && f[4] == LSC_KIN_JOINTS && s->moves < 300) {
        s->time_ms[s->moves] = (uint16_t)(f[5] | f[6] << 8);
        for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
            const uint8_t *p = f + 7 + 3 * i;
            s->pos[s->moves][i].id = p[0];
            s->pos[s->moves][i].position = (uint16_t)(p[1] | p[2] << 8);
        }
        s->moves++;
    }
}

/* Servo id of d's virtual controller at 1500, with no range: an arm's bus
 * servo where no bus servo can be (the stand-in starts at 0 degrees). */
static void at_1500(lsc_device *d, uint8_t id)
{
    assert_int_equal(lsc_sim_set_servo(lsc_device_sim(d), id, 1500, 0, 0), 0);
}

static lsc_device *open_arm(const char *text, sent *s)
{
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0); /* exact times */
    if (text != NULL) {
        lsc_arm *arm = profile(text);
        assert_int_equal(lsc_device_set_arm(d, arm), 0);
        lsc_arm_free(arm);
    }
    if (s != NULL) {
        memset(s, 0, sizeof *s);
        lsc_device_set_trace(d, on_trace, s);
    }
    return d;
}

/* bus servo position of an angle (0.24 degree a unit, 0 at 500) */
static uint16_t bus(float deg)
{
    return (uint16_t)lroundf(500.0f + deg / 0.24f);
}

/* Moves the chain to angles q (rounded to positions) and lets it arrive. */
static void put(lsc_device *d, const float *q)
{
    lsc_servo s[LSC_KIN_JOINTS];
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        s[i].id = chain_ids[i];
        s[i].position = bus(q[i]);
    }
    assert_int_equal(lsc_device_move(d, 100, s, LSC_KIN_JOINTS), 0);
    assert_true(lsc_device_poll(d, 200) >= 0);
}

/* every joint of the chain at 0 degrees */
static const float at_rest[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};

/* The xArm with geometry on "sim", its chain at rest, frames counted in s. */
static lsc_device *open_at_rest(sent *s)
{
    lsc_device *d = open_arm(XARM GEOMETRY, s);
    put(d, at_rest);
    return d;
}

static lsc_kin_chain xarm_chain(void)
{
    lsc_kin_chain c;
    lsc_arm *arm = profile(XARM GEOMETRY);
    assert_int_equal(lsc_arm_chain(arm, &c, NULL, NULL, 0), 0);
    lsc_arm_free(arm);
    return c;
}

/* The grasp point of a move's positions. */
static lsc_kin_pose pose_of(const lsc_servo *s)
{
    lsc_kin_chain c = xarm_chain();
    float q[LSC_KIN_JOINTS];
    lsc_kin_pose p;
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        q[i] = ((float)s[i].position - 500.0f) * 0.24f;
    }
    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
    return p;
}

static void assert_has(const char *s, const char *part)
{
    if (strstr(s, part) == NULL) {
        fail_msg("'%s' does not say '%s'", s, part);
    }
}

static float dist3(float ax, float ay, float az, float bx, float by, float bz)
{
    return sqrtf((ax - bx) * (ax - bx) + (ay - by) * (ay - by) + (az - bz) * (az - bz));
}

/* ---- where ------------------------------------------------------------------- */

static void where_needs_geometry(void **state)
{
    (void)state;
    lsc_kin_pose p;
    lsc_reach r = {.size = sizeof r};
    lsc_servo s = {6, 500};
    uint16_t t, pos;
    assert_int_equal(lsc_device_where(NULL, NULL, &p), LSC_EINVAL);
    assert_int_equal(lsc_device_reach(NULL, &r, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_move_time(NULL, &s, 1, 90, &t), LSC_EINVAL);
    assert_int_equal(lsc_device_last_position(NULL, 6, &pos), LSC_EINVAL);
    lsc_device *d = open_arm(NULL, NULL);
    assert_int_equal(lsc_device_last_position(d, 6, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_last_position(d, 6, &pos), LSC_EINVAL);
    assert_int_equal(lsc_device_where(d, NULL, &p), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no arm profile: the hand's position needs one that states "
                                    "its geometry (docs/kinematics.md)");
    assert_int_equal(lsc_device_reach(d, &r, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no arm profile");
    lsc_arm *arm = profile(XARM);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    assert_int_equal(lsc_device_where(d, NULL, &p), LSC_EINVAL);
    assert_has(lsc_device_error(d), "the arm profile states no geometry: add its chain: and "
                                    "links: lines");
    assert_int_equal(lsc_device_where(d, NULL, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no pose");
    assert_int_equal(lsc_device_reach(d, NULL, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "no reach");
    lsc_device_close(d);
    /* a failed open leaves no handle: NULL is refused */
    assert_int_equal(lsc_device_open("/nonexistent/tty", NULL, &d), LSC_ENODEV);
    assert_null(d);
    assert_int_equal(lsc_device_where(d, NULL, &p), LSC_EINVAL);
    lsc_where w = {.size = sizeof w};
    assert_int_equal(lsc_device_where_ex(d, &w), LSC_EINVAL);
    assert_int_equal(lsc_device_reach(d, &r, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_move_time(d, &s, 1, 90, &t), LSC_EINVAL);
    assert_int_equal(lsc_device_move_speed(d, &s, 1, 90, false, 0, 0, &t, NULL), LSC_EINVAL);
}

static void where_reads_the_angles(void **state)
{
    (void)state;
    lsc_kin_pose p, want;
    float q[LSC_KIN_JOINTS];
    lsc_device *d = open_arm(XARM GEOMETRY, NULL);
    /* a servo at 1500: outside a bus servo's range */
    at_1500(d, 6);
    assert_int_equal(lsc_device_where(d, q, &p), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 6 is at position 1500, outside its joint's range "
                                    "0..1000");
    const float at[LSC_KIN_JOINTS] = {24.0f, 30.0f, 40.08f, -19.92f, 12.0f};
    put(d, at);
    assert_int_equal(lsc_device_where(d, q, &p), 0);
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        assert_true(fabsf(q[i] - at[i]) < 0.001f);
    }
    lsc_kin_chain c = xarm_chain();
    assert_int_equal(lsc_kin_forward(&c, at, &want), 0);
    assert_true(dist3(p.x_mm, p.y_mm, p.z_mm, want.x_mm, want.y_mm, want.z_mm) < 0.001f);
    assert_true(fabsf(p.pitch_deg - want.pitch_deg) < 0.001f);
    assert_int_equal(lsc_device_where(d, NULL, &p), 0);
    /* where_ex: the same, the chain, and the joints near an end (within 5
     * degrees: the shoulder at 112.08 of 115, the elbow at -111.84) */
    lsc_where w = {.size = sizeof w};
    assert_int_equal(lsc_device_where_ex(d, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_device_where_ex: no result");
    assert_int_equal(lsc_device_where_ex(d, &w), 0);
    assert_int_equal(w.near_end, 0u);
    assert_true(fabsf(w.pose.x_mm - p.x_mm) < 0.001f);
    assert_true(w.chain.max_deg[LSC_KIN_SHOULDER] == 115.0f);
    assert_int_equal(w.joint[LSC_KIN_BASE], 5); /* the profile's sixth line */
    const float edge[LSC_KIN_JOINTS] = {0.0f, 112.08f, -111.84f, 0.0f, 0.0f};
    put(d, edge);
    assert_int_equal(lsc_device_where_ex(d, &w), 0);
    assert_int_equal(w.near_end,
                     LSC_KIN_NEAR_HIGH(LSC_KIN_SHOULDER) | LSC_KIN_NEAR_LOW(LSC_KIN_ELBOW));
    put(d, at);
    /* what was read is known */
    uint16_t pos = 0;
    assert_int_equal(lsc_device_last_position(d, 6, &pos), 0);
    assert_int_equal(pos, 600);
    lsc_device_close(d);
}

/* ---- reach ------------------------------------------------------------------- */

static lsc_reach to(float x, float y, float z)
{
    lsc_reach r = {.size = sizeof r};
    r.target.x_mm = x;
    r.target.y_mm = y;
    r.target.z_mm = z;
    return r;
}

static void reach_points(void **state)
{
    (void)state;
    sent s;
    lsc_reach_result res = {.size = sizeof res};
    lsc_kin_pose p;
    lsc_device *d = open_arm(XARM GEOMETRY, &s);
    const float rest[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};
    put(d, rest);
    /* across the workspace: in front, to the side, high, low, pitches -90..30 */
    static const float targets[][4] = {
        {150, 0, 0, -90},    {150, 150, 50, -60}, {250, 0, 30, -45},  {0, 250, 150, 0},
        {120, -180, 250, 30}, {100, 50, 280, 10}, {60, -60, 200, 0},  {200, 0, 100, -45},
        {150, 150, 80, -30},  {120, 0, 30, -90},
    };
    for (size_t k = 0; k < sizeof targets / sizeof targets[0]; k++) {
        lsc_reach r = to(targets[k][0], targets[k][1], targets[k][2]);
        r.target.has_pitch = true;
        r.target.pitch_deg = targets[k][3];
        r.wait = true;
        r.tolerance = 1;
        size_t before = s.moves;
        assert_int_equal(lsc_device_reach(d, &r, &res), 0);
        assert_int_equal(s.moves, before + 1);
        assert_int_equal(res.waypoints, 1);
        assert_int_equal(res.time_ms, 1000);
        assert_int_equal(s.time_ms[before], 1000);
        assert_int_equal(res.kin.status, LSC_KIN_OK);
        assert_int_equal(lsc_device_where(d, NULL, &p), 0);
        if (dist3(p.x_mm, p.y_mm, p.z_mm, r.target.x_mm, r.target.y_mm, r.target.z_mm) > 2.0f ||
            fabsf(p.pitch_deg - r.target.pitch_deg) > 0.5f) {
            fail_msg("target %zu: at %.2f %.2f %.2f pitch %.2f", k, (double)p.x_mm,
                     (double)p.y_mm, (double)p.z_mm, (double)p.pitch_deg);
        }
    }
    /* a time, no wait, no result wanted; the pitch chosen */
    lsc_reach r = to(200, 0, 100);
    r.time_ms = 300;
    assert_int_equal(lsc_device_reach(d, &r, NULL), 0);
    assert_int_equal(s.time_ms[s.moves - 1], 300);
    lsc_device_close(d);
}

/* The structs that grow: a caller's shorter lsc_where, lsc_reach,
 * lsc_reach_result and lsc_settle_result get nothing written beyond their
 * size, and lsc_reach's fields beyond it take their defaults; a size below
 * the size field and the first member is refused with nothing sent. */
static void sizes(void **state)
{
    (void)state;
    sent s;
    lsc_device *d = open_at_rest(&s);
    /* where: up to q */
    lsc_where w;
    const size_t wq = offsetof(lsc_where, pose);
    sized_guard(&w, sizeof w, wq);
    assert_int_equal(lsc_device_where_ex(d, &w), 0);
    assert_int_equal(w.size, wq);
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        assert_true(fabsf(w.q[i] - at_rest[i]) < 0.3f);
    }
    assert_true(sized_untouched(&w, wq, sizeof w));
    size_t frames = s.frames;
    sized_guard(&w, sizeof w, offsetof(lsc_where, q));
    assert_int_equal(lsc_device_where_ex(d, &w), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_where.size is");
    assert_has(lsc_device_error(d), "set it to sizeof(lsc_where); nothing was sent");
    assert_true(sized_untouched(&w, sizeof w.size, sizeof w));
    assert_int_equal(s.frames, frames);
    /* reach: a caller's lsc_reach up to target, the rest garbage: the
     * defaults (1000 ms, one move, no wait); the whole result, settle's size
     * set */
    lsc_reach r;
    const size_t rt = offsetof(lsc_reach, time_ms);
    sized_guard(&r, sizeof r, rt);
    r.target = (lsc_kin_target){200.0f, 0.0f, 100.0f, 0.0f, 0.0f, false, false};
    lsc_reach_result res;
    memset(&res, 0, sizeof res);
    res.size = sizeof res;
    size_t moves = s.moves;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(s.moves, moves + 1u);
    assert_int_equal(s.time_ms[moves], 1000);
    assert_int_equal(res.waypoints, 1);
    assert_int_equal(res.time_ms, 1000);
    assert_int_equal(res.settle.size, sizeof(lsc_settle_result));
    assert_int_equal(res.settle.nstopped, 0);
    /* a caller's result up to kin */
    const size_t rk = offsetof(lsc_reach_result, waypoints);
    sized_guard(&res, sizeof res, rk);
    r.target.x_mm = 180.0f;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(s.moves, moves + 2u);
    assert_int_equal(res.size, rk);
    assert_int_equal(res.kin.status, LSC_KIN_OK);
    assert_true(sized_untouched(&res, rk, sizeof res));
    /* too small: refused, nothing sent or written */
    frames = s.frames;
    r.size = offsetof(lsc_reach, target);
    assert_int_equal(lsc_device_reach(d, &r, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_reach.size is");
    assert_has(lsc_device_error(d), "set it to sizeof(lsc_reach); nothing was sent");
    r.size = rt;
    sized_guard(&res, sizeof res, offsetof(lsc_reach_result, kin));
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_reach_result.size is");
    assert_true(sized_untouched(&res, sizeof res.size, sizeof res));
    assert_int_equal(s.frames, frames);
    /* move_speed's settle: up to nstopped (nstopped 0 without a wait); too
     * small: refused */
    lsc_settle_result st;
    const size_t sn = offsetof(lsc_settle_result, stopped);
    sized_guard(&st, sizeof st, sn);
    lsc_servo base = {6, 520};
    uint16_t t = 0;
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, false, 0, 0, &t, &st), 0);
    assert_int_equal(st.size, sn);
    assert_int_equal(st.nstopped, 0);
    assert_true(sized_untouched(&st, sn, sizeof st));
    frames = s.frames;
    sized_guard(&st, sizeof st, offsetof(lsc_settle_result, nstopped));
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, true, 0, 0, &t, &st), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_settle_result.size is");
    assert_true(sized_untouched(&st, sizeof st.size, sizeof st));
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

static void reach_refused(void **state)
{
    (void)state;
    sent s;
    lsc_reach_result res = {.size = sizeof res};
    lsc_device *d = open_at_rest(&s);
    size_t frames = s.frames;
    lsc_reach r = to(0, 0, 600);
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_int_equal(res.kin.status, LSC_KIN_OUT_OF_REACH);
    assert_has(lsc_device_error(d), "(0.0, 0.0, 600.0) mm is out of reach by 183.0 mm; nothing "
                                    "was sent");
    r.target.has_pitch = true;
    r.target.pitch_deg = 90;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "out of reach by 183.0 mm at that pitch; no pitch reaches it "
                                    "within the joints' limits; nothing was sent");
    r = to(-250, 0, 64.7f);
    r.target.has_pitch = true;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_int_equal(res.kin.status, LSC_KIN_BEYOND_LIMIT);
    /* the pitches that do reach it: leaning back, the base turned round */
    assert_has(lsc_device_error(d), "(-250.0, 0.0, 64.7) mm needs joint base (the base, servo 6) "
                                    "at 180.00deg, beyond its upper limit 115.00deg; pitches "
                                    "-165.6..-129.3, 131.6..165.6 reach it; nothing was sent");
    assert_int_equal(s.frames, frames); /* not even a read */
    r.target.has_pitch = false;         /* and without one: reached */
    r.time_ms = 1;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_true(res.kin.pitch_deg >= 131.5f);
    put(d, at_rest);
    frames = s.frames;
    r = to(200, 0, 100);
    r.target.has_pitch = true;
    r.target.pitch_deg = -45;
    r.target.has_roll = true;
    r.target.roll_deg = -120;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "needs joint wrist-rotate (the wrist roll, servo 2) at "
                                    "-120.00deg, beyond its lower limit -115.00deg");
    assert_int_equal(s.frames, frames); /* not even a read */
    /* on the base's axis the current base angle counts: read, then refused */
    r = to(0, 0, 64.7f);
    r.target.has_pitch = true;
    r.target.pitch_deg = -90;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_int_equal(res.kin.status, LSC_KIN_BEYOND_LIMIT);
    assert_has(lsc_device_error(d), "(0.0, 0.0, 64.7) mm needs joint");
    r = to(NAN, 0, 100);
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_int_equal(res.kin.status, LSC_KIN_BAD_INPUT);
    assert_has(lsc_device_error(d), "the target or the profile's geometry is refused");
    r.target.has_pitch = true; /* (no pitches to tell) */
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "the target or the profile's geometry is refused");
    r = to(200, 0, 100);
    r.speed_dps = -1;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a speed of -1 degrees a second: give 0.01..100000");
    r.speed_dps = 0;
    r.line = true;
    r.step_mm = 0.01f;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a step of 0.01 mm between waypoints: give 0.1..1000");
    r.step_mm = 2000;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    r.line = false; /* the step is a line's only */
    r.flags = 2u; /* not a settle flag */
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_device_reach: unknown flags 0x2; nothing was sent");
    assert_int_equal(s.frames, frames);
    r.flags = 0;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    frames = s.frames;
    /* out of memory for the plan */
    calloc_fails_in = 1;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_ENOSPC);
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

/* A joint held short of its target (an obstacle) ends the wait as soon as it
 * stopped: not an error by default (res->settle says where), an error with
 * LSC_SETTLE_STRICT. */
static void reach_held(void **state)
{
    (void)state;
    sent s;
    lsc_reach_result res = {.size = sizeof res};
    lsc_device *d = open_at_rest(&s);
    lsc_reach r = to(200, 0, 100);
    r.target.has_pitch = true;
    r.target.pitch_deg = -45;
    r.time_ms = 500;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0); /* where the joints go */
    size_t most = 0; /* the joint that turns the most is held half way */
    for (size_t i = 1; i < LSC_KIN_JOINTS; i++) {
        if (abs(s.pos[s.moves - 1u][i].position - bus(0)) >
            abs(s.pos[s.moves - 1u][most].position - bus(0))) {
            most = i;
        }
    }
    uint8_t id = s.pos[s.moves - 1u][most].id;
    uint16_t target = s.pos[s.moves - 1u][most].position;
    assert_true(abs(target - bus(0)) > 40);
    bool up = target > bus(0);
    uint16_t at = (uint16_t)((target + bus(0)) / 2u);
    r.wait = true;
    for (int strict = 0; strict < 2; strict++) {
        put(d, at_rest);
        assert_int_equal(lsc_sim_block(lsc_device_sim(d), id, at,
                                       up ? LSC_SIM_BLOCK_ABOVE : LSC_SIM_BLOCK_BELOW),
                         0);
        r.flags = strict ? LSC_SETTLE_STRICT : 0u;
        uint64_t before = lsc_sim_now_us(lsc_device_sim(d));
        int e = lsc_device_reach(d, &r, &res);
        uint64_t took = (lsc_sim_now_us(lsc_device_sim(d)) - before) / 1000u;
        assert_int_equal(e, strict ? LSC_ETIMEOUT : LSC_SETTLE_STOPPED);
        assert_int_equal(lsc_device_error_cause(d),
                         strict ? LSC_DEVICE_CAUSE_STOPPED_SHORT : LSC_DEVICE_CAUSE_NONE);
        assert_int_equal(res.settle.nstopped, 1);
        assert_int_equal(res.settle.stopped[0].id, id);
        assert_int_equal(res.settle.stopped[0].position, at);
        assert_int_equal(res.settle.stopped[0].target, target);
        char msg[96];
        snprintf(msg, sizeof msg, "servo %u stopped at %u, %d short of its target %u", id, at,
                 abs((int)target - (int)at), target);
        assert_has(lsc_device_error(d), msg);
        /* at once: the move's time and the still window, not the timeout */
        assert_true(took < 500u + LSC_SETTLE_STILL_MS + 200u);
        assert_int_equal(lsc_sim_block(lsc_device_sim(d), id, 0, LSC_SIM_BLOCK_NONE), 0);
    }
    /* unblocked: all arrive, nothing listed */
    put(d, at_rest);
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(res.settle.nstopped, 0);
    lsc_device_close(d);
}

/* The position rounds beyond a limit the angle is inside; an angle the limits
 * allow beyond the servo's range. */
static void reach_positions_checked(void **state)
{
    (void)state;
    lsc_reach_result res = {.size = sizeof res};
    sent s;
    lsc_kin_chain c = xarm_chain();
    lsc_kin_pose p;
    const float q[LSC_KIN_JOINTS] = {0, 9.99f, 40, 30, 0};
    lsc_device *d = open_arm("gripper 1 bus\nwrist-rotate 2 bus\nwrist 3 bus "
                             "limits=-150deg..150deg\nelbow 4 bus\nshoulder 5 bus "
                             "limits=-10deg..10deg\nbase 6 bus\n" GEOMETRY,
                             &s);
    const float rest[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};
    put(d, rest);
    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
    lsc_reach r = to(p.x_mm, p.y_mm, p.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = p.pitch_deg;
    /* 9.99 degrees is within the shoulder's limits, its nearest position
     * (542: 10.08 degrees) is not: the next one inside, 541 */
    r.time_ms = 1;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(s.pos[s.moves - 1][1].position, 541);
    /* -9.99: 458 is beyond, 457 too: 459 */
    const float low[LSC_KIN_JOINTS] = {0, -9.99f, 40, 30, 0};
    put(d, rest);
    assert_int_equal(lsc_kin_forward(&c, low, &p), 0);
    r = to(p.x_mm, p.y_mm, p.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = p.pitch_deg;
    r.time_ms = 1;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(s.pos[s.moves - 1][1].position, 459);
    size_t frames = s.frames;
    /* an angle whose position is beyond the servo's range: refused */
    const float bent[LSC_KIN_JOINTS] = {0, 0, 0, 130, 0};
    assert_int_equal(lsc_kin_forward(&c, bent, &p), 0);
    r = to(p.x_mm, p.y_mm, p.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = p.pitch_deg;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "joint wrist (servo 3) at 130.00deg");
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

/* The distance of point p from the segment a..b. */
static float off_segment(const lsc_kin_pose *p, const lsc_kin_pose *a, const float *b)
{
    const float ab[3] = {b[0] - a->x_mm, b[1] - a->y_mm, b[2] - a->z_mm};
    const float ap[3] = {p->x_mm - a->x_mm, p->y_mm - a->y_mm, p->z_mm - a->z_mm};
    float len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    float f = (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    return dist3(p->x_mm, p->y_mm, p->z_mm, a->x_mm + ab[0] * f, a->y_mm + ab[1] * f,
                 a->z_mm + ab[2] * f);
}

/* Refused without a pitch: the reason that holds at every pitch, or the
 * joint at the nearest pitch that reaches it; with one: the pitches that do. */
static void reach_refused_every_pitch(void **state)
{
    (void)state;
    lsc_reach_result res = {.size = sizeof res};
    /* the base held within +-45: a point to the side is beyond it either way */
    lsc_device *d = open_arm("gripper 1 bus\nwrist-rotate 2 bus limits=-115deg..115deg\n"
                             "wrist 3 bus\nelbow 4 bus\nshoulder 5 bus limits=-20deg..20deg\n"
                             "base 6 bus limits=-45deg..45deg\n" GEOMETRY,
                             NULL);
    put(d, at_rest);
    lsc_reach r = to(0, 250, 100);
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "(0.0, 250.0, 100.0) mm needs joint base (the base, servo 6) "
                                    "at 90.00deg, beyond its upper limit 45.00deg at every "
                                    "pitch; nothing was sent");
    r = to(200, 0, 100);
    r.target.has_roll = true;
    r.target.roll_deg = 120;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "needs joint wrist-rotate (the wrist roll, servo 2) at "
                                    "120.00deg, beyond its upper limit 115.00deg at every pitch");
    /* far and level: the shoulder cannot lean that far at any pitch */
    r = to(330, 0, 64.7f);
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_int_equal(res.kin.status, LSC_KIN_BEYOND_LIMIT);
    assert_has(lsc_device_error(d), "(330.0, 0.0, 64.7) mm is within reach but at no pitch within "
                                    "the joints' limits: at pitch");
    assert_has(lsc_device_error(d), "(the nearest that reaches it) it needs joint shoulder");
    lsc_device_close(d);
    /* no hand and the wrist held straight: a pitch for each elbow and side,
     * four single pitches; the message shows three */
    d = open_arm("gripper 1 bus\nwrist-rotate 2 bus\nwrist 3 bus limits=0deg..0deg\n"
                 "elbow 4 bus\nshoulder 5 bus\nbase 6 bus\n"
                 "chain: base shoulder elbow wrist wrist-rotate gripper\n"
                 "links: height=64.7mm upper=98.8mm fore=94.7mm tool=0mm\n",
                 NULL);
    put(d, at_rest);
    r = to(0, 120, 200);
    r.target.has_pitch = true;
    r.target.pitch_deg = 3;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "; pitches 27.1..27.1, 69.7..69.7, 110.3..110.3, ... reach "
                                    "it; nothing was sent");
    lsc_device_close(d);
}

static void reach_line(void **state)
{
    (void)state;
    sent s;
    lsc_reach_result res = {.size = sizeof res};
    lsc_kin_pose from;
    lsc_device *d = open_arm(XARM GEOMETRY, &s);
    lsc_kin_chain c = xarm_chain();
    const float start[LSC_KIN_JOINTS] = {-30, 40, 50, 50, 0};
    put(d, start);
    assert_int_equal(lsc_device_where(d, NULL, &from), 0);
    const float end[3] = {150, 150, 80};
    lsc_reach r = to(end[0], end[1], end[2]);
    r.target.has_pitch = true;
    r.target.pitch_deg = -30;
    r.line = true;
    r.time_ms = 2000;
    r.wait = true;
    r.tolerance = 1;
    size_t before = s.moves;
    if (lsc_device_reach(d, &r, &res) != 0) {
        fail_msg("%s", lsc_device_error(d));
    }
    float len = dist3(from.x_mm, from.y_mm, from.z_mm, end[0], end[1], end[2]);
    assert_int_equal(res.waypoints, (size_t)ceilf(len / LSC_REACH_STEP_MM));
    assert_int_equal(s.moves, before + res.waypoints);
    assert_int_equal(res.time_ms, 2000);
    uint32_t total = 0;
    for (size_t k = 0; k < res.waypoints; k++) {
        lsc_kin_pose p = pose_of(s.pos[before + k]);
        total += s.time_ms[before + k];
        /* each waypoint on the segment (within the positions' rounding) */
        if (off_segment(&p, &from, end) > 2.0f) {
            fail_msg("waypoint %zu is %.2f mm off the line", k,
                     (double)off_segment(&p, &from, end));
        }
        /* halfway between two waypoints (the servos' own straight move in
         * their positions) the grasp point stays near the line too */
        if (k > 0) {
            lsc_servo mid[LSC_KIN_JOINTS];
            for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
                mid[i].id = s.pos[before + k][i].id;
                mid[i].position = (uint16_t)((s.pos[before + k][i].position +
                                              s.pos[before + k - 1][i].position) / 2u);
            }
            lsc_kin_pose m = pose_of(mid);
            assert_true(off_segment(&m, &from, end) <= 3.0f);
        }
    }
    assert_int_equal(total, 2000);
    lsc_kin_pose last = pose_of(s.pos[s.moves - 1]);
    assert_true(dist3(last.x_mm, last.y_mm, last.z_mm, end[0], end[1], end[2]) < 2.0f);
    assert_true(fabsf(last.pitch_deg + 30) < 0.5f);
    (void)c;

    /* wider steps: fewer waypoints; the pitch chosen; the roll turning */
    put(d, start);
    r = to(end[0], end[1], end[2]);
    r.line = true;
    r.step_mm = 40;
    r.target.has_roll = true;
    r.target.roll_deg = 40;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(res.waypoints, (size_t)ceilf(len / 40));
    float roll = ((float)s.pos[s.moves - 1][LSC_KIN_ROLL].position - 500.0f) * 0.24f;
    assert_true(fabsf(roll - 40) < 0.2f);
    /* at most LSC_REACH_WAYPOINTS_MAX, however small the step */
    put(d, start);
    r.step_mm = 0.1f;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(res.waypoints, LSC_REACH_WAYPOINTS_MAX);
    /* to where it is already: one waypoint */
    lsc_kin_pose here;
    assert_int_equal(lsc_device_where(d, NULL, &here), 0);
    r = to(here.x_mm, here.y_mm, here.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = here.pitch_deg;
    r.line = true;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_int_equal(res.waypoints, 1);
    /* a line through where the arm cannot go: refused whole, nothing sent */
    const float side[LSC_KIN_JOINTS] = {0, 30, 60, 90, 0};
    put(d, side);
    size_t frames = s.frames;
    r = to(-150, 0, 60);
    r.target.has_pitch = true;
    r.target.pitch_deg = 0;
    r.line = true;
    const float back[LSC_KIN_JOINTS] = {0, -30, -60, -90, 0};
    lsc_kin_pose bp;
    assert_int_equal(lsc_kin_forward(&c, back, &bp), 0);
    r = to(bp.x_mm, bp.y_mm, bp.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = bp.pitch_deg;
    r.line = true;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "waypoint ");
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

static void reach_speed(void **state)
{
    (void)state;
    sent s;
    lsc_reach_result res = {.size = sizeof res};
    lsc_kin_chain c = xarm_chain();
    lsc_kin_pose p;
    lsc_device *d = open_arm(XARM GEOMETRY, &s);
    const float start[LSC_KIN_JOINTS] = {0, 30, 40, 20, 0};
    put(d, start);
    const float turned[LSC_KIN_JOINTS] = {45, 30, 40, 20, 0};
    assert_int_equal(lsc_kin_forward(&c, turned, &p), 0);
    lsc_reach r = to(p.x_mm, p.y_mm, p.z_mm);
    r.target.has_pitch = true;
    r.target.pitch_deg = p.pitch_deg;
    r.speed_dps = 90;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_true(res.time_ms >= 500 && res.time_ms <= 502); /* 45 degrees at 90 a second */
    /* a line at a speed: every move the same time */
    put(d, start);
    r.line = true;
    assert_int_equal(lsc_device_reach(d, &r, &res), 0);
    assert_true(res.waypoints > 1);
    for (size_t k = 1; k < res.waypoints; k++) {
        assert_int_equal(s.time_ms[s.moves - k], s.time_ms[s.moves - 1]);
    }
    /* too slow for one move */
    put(d, start);
    r.line = false;
    r.speed_dps = 0.01f;
    size_t frames = s.frames;
    assert_int_equal(lsc_device_reach(d, &r, &res), LSC_EINVAL);
    assert_has(lsc_device_error(d), "takes longer than 65535 ms: raise the speed");
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

static void move_time(void **state)
{
    (void)state;
    sent s;
    uint16_t t = 0;
    lsc_servo far[LSC_MOVE_MAX + 1];
    lsc_device *d = open_arm(NULL, &s);
    lsc_servo base = {6, 688}; /* 45.12 degrees on a bus servo */
    assert_int_equal(lsc_device_move_time(d, &base, 1, 90, &t), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 6 is no joint of any arm profile (none is set): a "
                                    "speed in degrees a second needs each servo's degrees");
    lsc_arm *arm = profile(XARM);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    assert_int_equal(lsc_device_move_time(d, NULL, 1, 90, &t), LSC_EINVAL);
    assert_has(lsc_device_error(d), "the time of a move of 0 servos: one move takes 1..83");
    assert_int_equal(lsc_device_move_time(d, &base, 1, 90, NULL), LSC_EINVAL);
    assert_int_equal(lsc_device_move_time(d, &base, 0, 90, &t), LSC_EINVAL);
    memset(far, 0, sizeof far);
    assert_int_equal(lsc_device_move_time(d, far, LSC_MOVE_MAX + 1, 90, &t), LSC_EINVAL);
    assert_int_equal(lsc_device_move_time(d, &base, 1, 0, &t), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a speed of 0 degrees a second: give 0.01..100000");
    assert_int_equal(lsc_device_move_time(d, &base, 1, 200000, &t), LSC_EINVAL);
    assert_int_equal(lsc_device_move_time(d, &base, 1, NAN, &t), LSC_EINVAL);
    lsc_servo other = {9, 500};
    assert_int_equal(lsc_device_move_time(d, &other, 1, 90, &t), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 9 is no joint of the arm profile");
    /* not known yet: read, at 1500 (outside a bus servo's range) */
    at_1500(d, 6);
    size_t frames = s.frames;
    assert_int_equal(lsc_device_move_time(d, &base, 1, 90, &t), LSC_EINVAL);
    assert_int_equal(s.frames, frames + 1); /* the read */
    assert_has(lsc_device_error(d), "servo 6 is at position 1500, outside its joint's range");
    /* known from a move: no read */
    lsc_servo zero[2] = {{6, 500}, {5, 500}};
    assert_int_equal(lsc_device_move(d, 100, zero, 2), 0);
    frames = s.frames;
    lsc_servo both[2] = {{6, 688}, {5, 550}};
    assert_int_equal(lsc_device_move_time(d, both, 2, 90, &t), 0);
    assert_int_equal(s.frames, frames);
    assert_int_equal(t, 502); /* 45.12 degrees: 501.3 ms, up */
    assert_int_equal(lsc_device_move_time(d, both, 2, 100000, &t), 0);
    assert_int_equal(t, 1); /* at least 1 */
    lsc_servo same = {6, 500};
    assert_int_equal(lsc_device_move_time(d, &same, 1, 90, &t), 0);
    assert_int_equal(t, 1);
    lsc_servo beyond[2] = {{6, 1500}, {5, 550}};
    assert_int_equal(lsc_device_move_time(d, beyond, 2, 90, &t), LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 6 is at position 1500, outside");
    lsc_servo back = {6, 313}; /* -44.88 degrees: the travel is the same either way */
    assert_int_equal(lsc_device_move_time(d, &back, 1, 90, &t), 0);
    assert_int_equal(t, 499);
    /* a read (the wrist, 3): known from then on */
    uint8_t id = 3;
    lsc_servo got;
    assert_int_equal(lsc_device_move(d, 0, &(lsc_servo){3, 700}, 1), 0);
    assert_true(lsc_device_poll(d, 10) >= 0);
    assert_int_equal(lsc_device_read(d, &id, 1, &got), 1);
    uint16_t pos = 0;
    assert_int_equal(lsc_device_last_position(d, 3, &pos), 0);
    assert_int_equal(pos, 700);
    lsc_device_close(d);
}

/* A move at a speed: its time from lsc_device_move_time, the move, and with
 * wait the settle; the time is the move frame's and the sim's clock's. */
static void move_speed(void **state)
{
    (void)state;
    sent s;
    uint16_t t = 77;
    lsc_settle_result res = {.size = sizeof res};
    lsc_servo base = {6, 688}; /* 45.12 degrees on a bus servo */
    res.nstopped = 5;
    assert_int_equal(lsc_device_move_speed(NULL, &base, 1, 90, false, 0, 0, &t, &res),
                     LSC_EINVAL);
    assert_int_equal(t, 0);
    assert_int_equal(res.nstopped, 5); /* refused: nothing written */
    lsc_device *d = open_arm(NULL, &s);
    /* no profile: refused by the time's rule, nothing sent */
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, false, 0, 0, &t, NULL),
                     LSC_EINVAL);
    assert_has(lsc_device_error(d), "servo 6 is no joint of any arm profile");
    assert_int_equal(s.frames, 0);
    lsc_arm *arm = profile(XARM);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_arm_free(arm);
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, true, 0, 4u, &t, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "lsc_device_move_speed: unknown flags 0x4; nothing was sent");
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 0, false, 0, 0, &t, NULL), LSC_EINVAL);
    assert_has(lsc_device_error(d), "a speed of 0 degrees a second");
    assert_int_equal(s.frames, 0);
    /* the time: 45.12 degrees from 500 (read first: not known yet) at 90 a second */
    uint64_t before = lsc_sim_now_us(lsc_device_sim(d));
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, false, 0, 0, &t, NULL), 0);
    assert_int_equal(t, 502);
    assert_int_equal(s.frames, 2); /* the read, the move */
    assert_int_equal(s.any_moves, 1);
    assert_int_equal(s.last_move_ms, 502);
    assert_true(lsc_sim_now_us(lsc_device_sim(d)) - before < 502000u); /* no wait */
    /* with the wait: the move's time passes on the sim's clock, all arrive */
    lsc_servo two[2] = {{6, 500}, {5, 625}}; /* back 45.12, and 30 degrees */
    before = lsc_sim_now_us(lsc_device_sim(d));
    assert_int_equal(lsc_device_move_speed(d, two, 2, 60, true, 0, 0, NULL, &res), 0);
    assert_int_equal(s.last_move_ms, 752); /* the base turns the most: 45.12 at 60 */
    assert_true(lsc_sim_now_us(lsc_device_sim(d)) - before >= 752000u);
    assert_int_equal(res.nstopped, 0);
    lsc_servo got[2];
    const uint8_t ids[2] = {6, 5};
    assert_int_equal(lsc_device_read(d, ids, 2, got), 2);
    assert_int_equal(got[0].position, 500);
    assert_int_equal(got[1].position, 625);
    /* a servo held short of its target: listed; strict: an error */
    assert_int_equal(lsc_sim_block(lsc_device_sim(d), 6, 600, LSC_SIM_BLOCK_ABOVE), 0);
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, true, 0, 0, &t, &res),
                     LSC_SETTLE_STOPPED);
    assert_int_equal(t, 502);
    assert_int_equal(res.nstopped, 1);
    assert_int_equal(res.stopped[0].position, 600);
    assert_int_equal(lsc_device_move_speed(d, &base, 1, 90, true, 0, LSC_SETTLE_STRICT, &t, &res),
                     LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_STOPPED_SHORT);
    assert_int_equal(lsc_sim_block(lsc_device_sim(d), 6, 0, LSC_SIM_BLOCK_NONE), 0);
    /* beyond the gripper's limits (0..700) though in its servo's range: the
     * move refuses it, nothing sent, no time */
    assert_int_equal(lsc_device_move(d, 100, &(lsc_servo){1, 500}, 1), 0);
    size_t frames = s.frames;
    t = 77;
    assert_int_equal(lsc_device_move_speed(d, &(lsc_servo){1, 900}, 1, 90, true, 0, 0, &t, &res),
                     LSC_EINVAL);
    assert_int_equal(t, 0);
    assert_int_equal(s.frames, frames);
    lsc_device_close(d);
}

#ifdef LSC_TEST_HID
static char tmpdir[64], node[96];

/* A controller that goes away after its next frame: the read, the move or
 * the wait after it fails. */
static void controller_gone(void **state)
{
    (void)state;
    lsc_kin_pose p;
    lsc_reach_result res = {.size = sizeof res};
    test_options opt = {0, 50, 0, 0};
    lsc_device *d = NULL;
    lsc_arm *arm = profile(XARM GEOMETRY);
    hid_double_reset();
    assert_true(hid_double_add(node, "ARM", HID_DOUBLE_UNPLUG, 0) >= 0);
    assert_int_equal(test_open("hid", &opt, &d), 0);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    assert_true(lsc_device_where(d, NULL, &p) < 0);
    lsc_device_close(d);
    /* reach, positions unknown: the read fails */
    hid_double_reset();
    assert_true(hid_double_add(node, "ARM", HID_DOUBLE_UNPLUG, 0) >= 0);
    assert_int_equal(test_open("hid", &opt, &d), 0);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_reach r = to(200, 0, 100);
    assert_true(lsc_device_reach(d, &r, &res) < 0);
    lsc_device_close(d);
    /* a line, positions known: the first move goes, then the controller is gone */
    hid_double_reset();
    int a = hid_double_add(node, "ARM", 0, 0);
    assert_int_equal(test_open("hid", &opt, &d), 0);
    assert_int_equal(lsc_device_set_arm(d, arm), 0);
    lsc_servo s[LSC_KIN_JOINTS];
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        s[i].id = chain_ids[i];
        s[i].position = bus(i == 1 ? 40.0f : i == 2 ? 50.0f : 0.0f);
    }
    assert_int_equal(lsc_device_move(d, 0, s, LSC_KIN_JOINTS), 0);
    hid_double_set_flags(a, HID_DOUBLE_UNPLUG);
    r.line = true;
    r.time_ms = 100;
    assert_true(lsc_device_reach(d, &r, &res) < 0);
    lsc_device_close(d);
    lsc_arm_free(arm);
}

static int setup(void **state)
{
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/lsc-test-reach-XXXXXX");
    if (mkdtemp(tmpdir) == NULL) {
        return -1;
    }
    snprintf(node, sizeof node, "%s/hidraw0", tmpdir);
    FILE *f = fopen(node, "w");
    if (f == NULL) {
        return -1;
    }
    (void)fclose(f);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    (void)unlink(node);
    return rmdir(tmpdir);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(where_needs_geometry),
        cmocka_unit_test(where_reads_the_angles),
        cmocka_unit_test(reach_points),
        cmocka_unit_test(reach_refused),
        cmocka_unit_test(sizes),
        cmocka_unit_test(reach_held),
        cmocka_unit_test(reach_positions_checked),
        cmocka_unit_test(reach_refused_every_pitch),
        cmocka_unit_test(reach_line),
        cmocka_unit_test(reach_speed),
        cmocka_unit_test(move_time),
        cmocka_unit_test(move_speed),
#ifdef LSC_TEST_HID
        cmocka_unit_test(controller_gone),
#endif
    };
#ifdef LSC_TEST_HID
    return cmocka_run_group_tests(tests, setup, teardown);
#else
    return cmocka_run_group_tests(tests, NULL, NULL);
#endif
}
