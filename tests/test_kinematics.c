/* Tests of the arm chain's kinematics (include/lsc/kinematics.h). The forward
 * kinematics is checked against the chain written as homogeneous transforms
 * (4x4 matrices in double, from the xArm's figures), not the library's
 * formula; the inverse by IK(FK(q)) over a grid of angles inside the limits. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "lsc/lsc.h"

#define PI 3.14159265358979323846

/* |a - b| <= tol, in double (the figures are written in double) */
#define assert_near(a, b, tol) assert_near_at((double)(a), (double)(b), (tol), __LINE__)

static void assert_near_at(double a, double b, double tol, int line)
{
    if (!(fabs(a - b) <= tol)) {
        fail_msg("line %d: %.6f is not %.6f within %g", line, a, b, tol);
    }
}

/* The xArm (nuro-arm's xarm.urdf figures; docs/kinematics.md). */
static lsc_kin_chain xarm(void)
{
    lsc_kin_chain c = {64.7f, 98.8f, 94.7f, 158.8f, {0}, {0}};
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        c.min_deg[i] = -115.0f;
        c.max_deg[i] = 115.0f;
    }
    return c;
}

/* The xArm with examples/arms/xarm.conf's limits (nuro-arm's URDF's, rounded
 * inward to hundredths of a degree). */
static lsc_kin_chain xarm_urdf(void)
{
    lsc_kin_chain c = {64.7f, 98.8f, 94.7f, 158.8f,
                       {-114.59f, -90.52f, -114.59f, -103.13f, -114.59f},
                       {114.59f, 90.52f, 114.59f, 114.59f, 114.59f}};
    return c;
}

/* The LeArm with examples/arms/learm.conf's figures. */
static lsc_kin_chain learm(void)
{
    lsc_kin_chain c = {28.9f, 104.3f, 89.0f, 177.0f, {-85, 0, -85, -85, -90}, {85, 175, 85, 85, 90}};
    return c;
}

/* ---- the independent model: homogeneous transforms ------------------------ */

typedef double mat[4][4];

static void mat_mul(mat a, mat b) /* a = a * b */
{
    mat r;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            r[i][j] = 0;
            for (int k = 0; k < 4; k++) {
                r[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    memcpy(a, r, sizeof r);
}

static void identity(mat m)
{
    memset(m, 0, sizeof(mat));
    for (int i = 0; i < 4; i++) {
        m[i][i] = 1;
    }
}

static void rot_z(mat a, double deg)
{
    mat m;
    double t = deg * PI / 180;
    identity(m);
    m[0][0] = cos(t), m[0][1] = -sin(t), m[1][0] = sin(t), m[1][1] = cos(t);
    mat_mul(a, m);
}

static void rot_y(mat a, double deg)
{
    mat m;
    double t = deg * PI / 180;
    identity(m);
    m[0][0] = cos(t), m[0][2] = sin(t), m[2][0] = -sin(t), m[2][2] = cos(t);
    mat_mul(a, m);
}

static void up(mat a, double mm) /* along the link's own z */
{
    mat m;
    identity(m);
    m[2][3] = mm;
    mat_mul(a, m);
}

/* The grasp point and the hand's axis (the tool frame's z) of angles q. */
static void chain(const lsc_kin_chain *c, const float *q, double p[3], double axis[3])
{
    mat t;
    identity(t);
    rot_z(t, q[LSC_KIN_BASE]);
    up(t, c->base_mm);
    rot_y(t, q[LSC_KIN_SHOULDER]);
    up(t, c->upper_mm);
    rot_y(t, q[LSC_KIN_ELBOW]);
    up(t, c->fore_mm);
    rot_y(t, q[LSC_KIN_WRIST]);
    rot_z(t, q[LSC_KIN_ROLL]);
    up(t, c->tool_mm);
    for (int i = 0; i < 3; i++) {
        p[i] = t[i][3];
        axis[i] = t[i][2];
    }
}

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float uniform(uint32_t *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)(lcg(s) % 100000u) / 100000.0f;
}

static void test_forward_matches_the_transforms(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    uint32_t seed = 1;
    for (int n = 0; n < 2000; n++) {
        float q[LSC_KIN_JOINTS];
        double p[3], axis[3];
        lsc_kin_pose pose;
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            q[i] = uniform(&seed, -180.0f, 180.0f);
        }
        chain(&c, q, p, axis);
        assert_int_equal(lsc_kin_forward(&c, q, &pose), 0);
        assert_true(fabs(pose.x_mm - p[0]) < 0.01);
        assert_true(fabs(pose.y_mm - p[1]) < 0.01);
        assert_true(fabs(pose.z_mm - p[2]) < 0.01);
        /* the pitch: the axis against the base's forward direction */
        double b = q[LSC_KIN_BASE] * PI / 180;
        double fwd = axis[0] * cos(b) + axis[1] * sin(b);
        double pitch = atan2(axis[2], fwd) * 180 / PI;
        double dp = fmod(pose.pitch_deg - pitch + 540.0, 360.0) - 180.0;
        assert_true(fabs(dp) < 0.001);
        assert_true(pose.pitch_deg > -180.0f && pose.pitch_deg <= 180.0f);
        assert_true(pose.roll_deg == q[LSC_KIN_ROLL]);
    }
}

static void test_forward_fixed_poses(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    lsc_kin_pose p;
    float zero[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};
    float forward[LSC_KIN_JOINTS] = {90, 90, 0, 0, 0};  /* base to +y, arm level */
    float down[LSC_KIN_JOINTS] = {0, 90, -90, -90, 0}; /* forearm up, hand back */
    assert_int_equal(lsc_kin_forward(&c, zero, &p), 0);
    assert_near(p.x_mm, 0, 1e-4);
    assert_near(p.z_mm, 64.7 + 98.8 + 94.7 + 158.8, 1e-3);
    assert_near(p.pitch_deg, 90, 1e-4);
    assert_int_equal(lsc_kin_forward(&c, forward, &p), 0);
    assert_near(p.x_mm, 0, 1e-3);
    assert_near(p.y_mm, 98.8 + 94.7 + 158.8, 1e-3);
    assert_near(p.z_mm, 64.7, 1e-3);
    assert_near(p.pitch_deg, 0, 1e-4);
    assert_int_equal(lsc_kin_forward(&c, down, &p), 0);
    assert_near(p.x_mm, 98.8 - 158.8, 1e-3);
    assert_near(p.z_mm, 64.7 + 94.7, 1e-3);
    assert_near(fabsf(p.pitch_deg), 180, 1e-4);
}

static lsc_kin_target at(float x, float y, float z, float pitch)
{
    lsc_kin_target t = {x, y, z, pitch, 0.0f, true, false};
    return t;
}

static float angle_diff(float a, float b)
{
    return (float)fabs(fmod((double)a - b + 540.0, 360.0) - 180.0);
}

/* IK(FK(q)) == q over a grid inside the limits, away from the singular poses
 * (the arm straight; the grasp point on the base's axis); near q, then near q
 * moved by 3 degrees. */
static void test_inverse_of_forward_grid(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    int solved = 0;
    for (int bi = -110; bi <= 110; bi += 20) {
        for (int si = -110; si <= 110; si += 15) {
            for (int ei = -110; ei <= 110; ei += 15) {
                for (int wi = -110; wi <= 110; wi += 20) {
                    float b = (float)bi, s = (float)si, e = (float)ei, w = (float)wi;
                    float q[LSC_KIN_JOINTS] = {b, s, e, w, 10.0f}, got[LSC_KIN_JOINTS];
                    float near[LSC_KIN_JOINTS];
                    lsc_kin_pose p;
                    lsc_kin_result r;
                    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
                    if (fabsf(e) < 5.0f || hypotf(p.x_mm, p.y_mm) < 1.0f) {
                        continue;
                    }
                    lsc_kin_target t = at(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg);
                    for (int k = 0; k < 2; k++) {
                        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
                            near[i] = q[i] + (k == 0 ? 0.0f : (i % 2 ? 3.0f : -3.0f));
                        }
                        assert_int_equal(lsc_kin_inverse(&c, &t, near, got, &r), 0);
                        assert_int_equal(r.status, LSC_KIN_OK);
                        for (int i = 0; i < LSC_KIN_ROLL; i++) {
                            if (angle_diff(got[i], q[i]) > 0.01f) {
                                fail_msg("q %g %g %g %g -> joint %d %g", (double)b, (double)s,
                                         (double)e, (double)w, i, (double)got[i]);
                            }
                        }
                        assert_true(got[LSC_KIN_ROLL] == near[LSC_KIN_ROLL]);
                    }
                    solved++;
                }
            }
        }
    }
    assert_true(solved > 10000);
}

/* Of the two elbows the one nearer the current angles. */
static void test_inverse_nearest_elbow(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float q[LSC_KIN_JOINTS] = {20, 30, 40, 20, 0}, other[LSC_KIN_JOINTS], got[LSC_KIN_JOINTS];
    lsc_kin_pose p;
    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
    lsc_kin_target t = at(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg);
    assert_int_equal(lsc_kin_inverse(&c, &t, q, got, NULL), 0);
    assert_near(got[LSC_KIN_ELBOW], 40, 0.01);
    /* the other elbow: near an elbow of -40 */
    float near[LSC_KIN_JOINTS] = {20, 60, -40, 40, 0};
    assert_int_equal(lsc_kin_inverse(&c, &t, near, other, NULL), 0);
    assert_near(other[LSC_KIN_ELBOW], -40, 0.01);
    lsc_kin_pose back;
    assert_int_equal(lsc_kin_forward(&c, other, &back), 0);
    assert_near(back.x_mm, p.x_mm, 0.01);
    assert_near(back.z_mm, p.z_mm, 0.01);
    assert_near(back.pitch_deg, p.pitch_deg, 0.001);
}

static void test_inverse_singular(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS];
    lsc_kin_result r;
    /* straight up, on the base's axis: the base stays where it is */
    lsc_kin_target t = at(0, 0, 64.7f + 98.8f + 94.7f + 158.8f, 90);
    float near[LSC_KIN_JOINTS] = {30, 1, -1, 0, 5};
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, &r), 0);
    assert_near(got[LSC_KIN_BASE], 30, 1e-4);
    assert_near(got[LSC_KIN_SHOULDER], 0, 0.05);
    assert_near(got[LSC_KIN_ELBOW], 0, 0.05);
    assert_near(got[LSC_KIN_WRIST], 0, 0.05);
    assert_near(got[LSC_KIN_ROLL], 5, 0);
    /* the arm straight and level: one elbow */
    t = at(98.8f + 94.7f + 158.8f, 0, 64.7f, 0);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), 0);
    assert_near(got[LSC_KIN_SHOULDER], 90, 0.05);
    assert_near(got[LSC_KIN_ELBOW], 0, 0.05);
    assert_near(got[LSC_KIN_WRIST], 0, 0.05);
    /* the grasp point on the base's axis, the hand leaning back to it: the
     * base stays where it is, the rest is solved in its plane */
    double a2 = (10 + 30) * PI / 180;
    double a3 = -asin((98.8 * sin(10 * PI / 180) + 94.7 * sin(a2)) / 158.8);
    float q[LSC_KIN_JOINTS] = {-45, 10, 30, (float)((a3 - a2) * 180 / PI), 0};
    lsc_kin_pose p;
    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
    assert_true(hypotf(p.x_mm, p.y_mm) < LSC_KIN_AXIS_MM);
    t = at(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg);
    float from[LSC_KIN_JOINTS] = {20, 10, 30, q[LSC_KIN_WRIST], 0};
    assert_int_equal(lsc_kin_inverse(&c, &t, from, got, &r), 0);
    assert_near(got[LSC_KIN_BASE], 20, 0);
    for (int i = LSC_KIN_SHOULDER; i < LSC_KIN_ROLL; i++) {
        assert_near(got[i], q[i], 0.01);
    }
}

static void test_inverse_roll(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS], near[LSC_KIN_JOINTS] = {0, 0, 0, 0, 12};
    lsc_kin_target t = at(200, 0, 100, -45);
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, NULL), 0);
    assert_near(got[LSC_KIN_ROLL], 12, 0);
    t.has_roll = true;
    t.roll_deg = -30;
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, NULL), 0);
    assert_near(got[LSC_KIN_ROLL], -30, 0);
    t.roll_deg = 120; /* beyond the roll's limit */
    lsc_kin_result r;
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_ROLL);
    assert_true(r.high);
    assert_near(r.angle_deg, 120, 0);
}

static void test_inverse_out_of_reach(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS] = {7, 7, 7, 7, 7};
    lsc_kin_result r;
    /* straight up: the wrist 441.2 above the table, 376.5 from the shoulder */
    lsc_kin_target t = at(0, 0, 600, 90);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_OUT_OF_REACH);
    assert_near(r.by_mm, 600 - 158.8 - 64.7 - 98.8 - 94.7, 0.01);
    assert_near(got[0], 7, 0); /* untouched */
    /* without a pitch: the least over the pitches (straight up again), and
     * the pitch of the least */
    t.has_pitch = false;
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_OUT_OF_REACH);
    assert_near(r.by_mm, 600 - 158.8 - 64.7 - 98.8 - 94.7, 0.01);
    assert_near(r.pitch_deg, 90, 1e-4);
    /* too close: the wrist inside the ring upper - fore can reach (a chain
     * with a short forearm) */
    lsc_kin_chain s = c;
    s.fore_mm = 50;
    t = at(0, 0, 64.7f + 10 + 158.8f, 90);
    assert_int_equal(lsc_kin_inverse(&s, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_OUT_OF_REACH);
    assert_near(r.by_mm, 98.8 - 50 - 10, 0.01);
    /* the arm folded (the wrist 4.1 mm from the shoulder, the hand
     * straight down): on the edge of the reach, beyond the elbow's limit */
    t = at(98.8f - 94.7f, 0, 64.7f - 158.8f, -90);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_ELBOW);
    assert_near(fabsf(r.angle_deg), 180, 0.01);
    /* the hand pointing back: out of reach both ways, the nearer told */
    t = at(500, 0, 64.7f, 180);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_OUT_OF_REACH);
    assert_near(r.by_mm, 500 - 158.8 - 98.8 - 94.7, 0.01);
}

static void test_inverse_beyond_limits(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS];
    lsc_kin_result r;
    /* behind the base, hand level and pointing away: the base would turn 180 */
    lsc_kin_target t = at(-250, 0, 64.7f, 0);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_BASE);
    assert_true(r.high);
    assert_near(r.angle_deg, 180, 0.01);
    assert_near(r.pitch_deg, 0, 0);
    /* the shoulder's low limit: level to the front but shoulder limited */
    c.min_deg[LSC_KIN_SHOULDER] = 0;
    c.max_deg[LSC_KIN_SHOULDER] = 10;
    t = at(300, 0, 64.7f, 0);
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_SHOULDER);
    assert_true(r.high);
    /* without a pitch: none works, the limit of the first pitch that reaches
     * it is told */
    t.has_pitch = false;
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_true(r.pitch_deg < 90);
    t = at(300, 0, 64.7f, r.pitch_deg + 1);
    lsc_kin_result r2;
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r2), LSC_EINVAL);
    assert_int_equal(r2.status, LSC_KIN_OUT_OF_REACH);
    /* under a limit */
    c = xarm();
    c.min_deg[LSC_KIN_WRIST] = 10;
    t = at(200, 0, 100, 90 - 60);
    float near[LSC_KIN_JOINTS] = {0, 30, 30, 0, 0};
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_false(r.high);
}

/* An angle a rounding beyond its limit is put on it. */
static void test_inverse_on_a_limit(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float q[LSC_KIN_JOINTS] = {0, 37.3f, 41.1f, 12.7f, 0}, got[LSC_KIN_JOINTS];
    lsc_kin_pose p;
    c.max_deg[LSC_KIN_SHOULDER] = 37.3f;
    c.min_deg[LSC_KIN_ELBOW] = 41.1f;
    assert_int_equal(lsc_kin_forward(&c, q, &p), 0);
    lsc_kin_target t = at(p.x_mm, p.y_mm, p.z_mm, p.pitch_deg);
    for (int n = 0; n < 50; n++) { /* a few points about it: some round over */
        t.x_mm = p.x_mm + (float)n * 1e-5f;
        assert_int_equal(lsc_kin_inverse(&c, &t, q, got, NULL), 0);
        assert_true(got[LSC_KIN_SHOULDER] <= 37.3f);
        assert_true(got[LSC_KIN_ELBOW] >= 41.1f);
    }
}

/* The base (either way round) and the roll a rounding beyond a limit: put
 * on it. */
static void test_inverse_base_and_roll_on_a_limit(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS], near[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};
    c.min_deg[LSC_KIN_BASE] = -150;
    c.max_deg[LSC_KIN_BASE] = 30;
    for (int k = 0; k < 2; k++) {
        /* toward the target just past 30; or turned round just past -150 */
        double b = (k == 0 ? 30.0005 : 29.9995) * PI / 180;
        lsc_kin_target t = at((float)(250 * cos(b)), (float)(250 * sin(b)), 100, -30);
        near[LSC_KIN_BASE] = k == 0 ? 30.0f : -150.0f;
        t.has_roll = true;
        t.roll_deg = c.max_deg[LSC_KIN_ROLL] + 0.0005f;
        lsc_kin_result r;
        int rc = lsc_kin_inverse(&c, &t, near, got, &r);
        if (k == 0) { /* (turned round, the arm cannot lean back that far) */
            assert_int_equal(rc, 0);
            assert_true(got[LSC_KIN_BASE] == 30.0f);
            assert_true(got[LSC_KIN_ROLL] == c.max_deg[LSC_KIN_ROLL]);
        }
    }
}

/* r's pitch is the one nearest p0 that solves t, ties to the lower: every
 * pitch nearer fails. */
static void assert_nearest_pitch(const lsc_kin_chain *c, lsc_kin_target t, const float *near,
                                 float p0, const lsc_kin_result *r)
{
    float got[LSC_KIN_JOINTS];
    float dist = fabsf(r->pitch_deg - p0);
    t.has_pitch = true;
    for (int p = -90; p <= 90; p++) {
        float dp = fabsf((float)p - p0);
        if (dp < dist || (dp == dist && (float)p < r->pitch_deg)) {
            t.pitch_deg = (float)p;
            assert_int_equal(lsc_kin_inverse(c, &t, near, got, NULL), LSC_EINVAL);
        }
    }
}

/* Without a pitch: the one nearest the current pitch that reaches it. */
static void test_inverse_best_pitch(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm();
    float got[LSC_KIN_JOINTS];
    lsc_kin_result r;
    lsc_kin_target t = at(250, 50, 50, 0);
    t.has_pitch = false;
    /* from the rest pose (pitch 90): the highest that reaches it */
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), 0);
    assert_true(r.pitch_deg < 90);
    assert_nearest_pitch(&c, t, NULL, 90, &r);
    lsc_kin_pose p;
    assert_int_equal(lsc_kin_forward(&c, got, &p), 0);
    assert_near(p.x_mm, 250, 0.01);
    assert_near(p.y_mm, 50, 0.01);
    assert_near(p.z_mm, 50, 0.01);
    assert_near(p.pitch_deg, r.pitch_deg, 0.001);
    /* from a hand pointing down: down it stays */
    float down[LSC_KIN_JOINTS] = {0, 60, 60, 60, 0};
    t = at(150, 0, 30, 0);
    t.has_pitch = false;
    assert_int_equal(lsc_kin_inverse(&c, &t, down, got, &r), 0);
    assert_nearest_pitch(&c, t, down, -90, &r);
    /* from a hand pointing down and back (pitch -120): from -90 */
    float back[LSC_KIN_JOINTS] = {0, 60, 60, 90, 0};
    assert_int_equal(lsc_kin_forward(&c, back, &p), 0);
    assert_near(p.pitch_deg, -120, 0.001);
    assert_int_equal(lsc_kin_inverse(&c, &t, back, got, &r), 0);
    assert_nearest_pitch(&c, t, back, -90, &r);
    /* from pitch -20: below first, then above */
    float level[LSC_KIN_JOINTS] = {0, 50, 30, 30, 0};
    assert_int_equal(lsc_kin_forward(&c, level, &p), 0);
    assert_near(p.pitch_deg, -20, 0.001);
    t = at(p.x_mm, p.y_mm, p.z_mm, 0);
    t.has_pitch = false;
    assert_int_equal(lsc_kin_inverse(&c, &t, level, got, &r), 0);
    assert_near(r.pitch_deg, -20, 0);
    /* a pitch the search reaches from above only: the lower ones cannot */
    c.min_deg[LSC_KIN_WRIST] = -5;
    c.max_deg[LSC_KIN_WRIST] = 5;
    t = at(300, 0, 200, 0);
    t.has_pitch = false;
    assert_int_equal(lsc_kin_inverse(&c, &t, down, got, &r), 0);
    assert_nearest_pitch(&c, t, down, -90, &r);
    assert_int_equal(lsc_kin_forward(&c, got, &p), 0);
    assert_near(p.z_mm, 200, 0.01);
}

/* a into -180 < a <= 180 */
static double wrapped(double a)
{
    a = fmod(a, 360.0);
    return a > 180.0 ? a - 360.0 : a <= -180.0 ? a + 360.0 : a;
}

/* Whether t is reached within the limits at pitch p (near: the angles). */
static bool reaches_at(const lsc_kin_chain *c, lsc_kin_target t, const float *near, double p)
{
    float got[LSC_KIN_JOINTS];
    t.has_pitch = true;
    t.pitch_deg = (float)p;
    return lsc_kin_inverse(c, &t, near, got, NULL) == 0;
}

#define GRID 0.1 /* degrees between the pitches the oracle tries */

/* Targets made from random angles within c's limits, solved without a
 * pitch from other random angles: every one solved, within 0.01 mm, within
 * the limits; its pitch the present one when that reaches it, else none on
 * a grid over the whole circle nearer (than the chosen less 0.1 degree: a
 * grid point within the slack of the edge reaches a little further); and
 * lsc_kin_pitches agrees with the grid (0.1 degree from the arcs' ends). */
static void check_whole_circle(const lsc_kin_chain *c, int n, uint32_t seed)
{
    for (int k = 0; k < n; k++) {
        float q[LSC_KIN_JOINTS], near[LSC_KIN_JOINTS], got[LSC_KIN_JOINTS];
        lsc_kin_pose p, back, from;
        lsc_kin_result r;
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            q[i] = uniform(&seed, c->min_deg[i], c->max_deg[i]);
            near[i] = uniform(&seed, c->min_deg[i], c->max_deg[i]);
        }
        assert_int_equal(lsc_kin_forward(c, q, &p), 0);
        assert_int_equal(lsc_kin_forward(c, near, &from), 0);
        lsc_kin_target t = {p.x_mm, p.y_mm, p.z_mm, 0.0f, 0.0f, false, false};
        assert_int_equal(lsc_kin_inverse(c, &t, near, got, &r), 0);
        assert_int_equal(lsc_kin_forward(c, got, &back), 0);
        assert_near(back.x_mm, p.x_mm, 0.01);
        assert_near(back.y_mm, p.y_mm, 0.01);
        assert_near(back.z_mm, p.z_mm, 0.01);
        assert_near(wrapped(back.pitch_deg - r.pitch_deg), 0, 0.001);
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            assert_true(got[i] >= c->min_deg[i] && got[i] <= c->max_deg[i]);
        }
        double p0 = from.pitch_deg, chosen = fabs(wrapped(r.pitch_deg - p0));
        if (reaches_at(c, t, near, p0)) {
            assert_near(r.pitch_deg, p0, 1e-4);
        }
        float lo[8], hi[8];
        int arcs = lsc_kin_pitches(c, &t, near, lo, hi, 8);
        assert_true(arcs >= 1 && arcs <= 8);
        for (int step = 1; step <= (int)(360 / GRID + 0.5); step++) {
            double g = -180 + step * GRID;
            bool ok = reaches_at(c, t, near, g);
            if (ok && fabs(wrapped(g - p0)) < chosen - 0.1) {
                fail_msg("target %d: pitch %.2f reaches it, nearer %.2f than %.3f", k, g, p0,
                         (double)r.pitch_deg);
            }
            bool in = false, edge = false;
            for (int a = 0; a < arcs; a++) {
                double from_lo = wrapped(g - lo[a]), span = wrapped(hi[a] - lo[a]);
                span = span < 0 || (lo[a] == -180.0f && hi[a] == 180.0f) ? span + 360 : span;
                from_lo = from_lo < 0 ? from_lo + 360 : from_lo;
                in = in || from_lo <= span;
                edge = edge || fabs(wrapped(g - lo[a])) < 0.1 || fabs(wrapped(g - hi[a])) < 0.1;
            }
            if (ok != in && !edge) {
                fail_msg("target %d: pitch %.2f %s, the arcs say otherwise", k, g,
                         ok ? "reaches it" : "does not");
            }
        }
    }
}

static void test_inverse_whole_circle(void **state)
{
    (void)state;
    lsc_kin_chain x = xarm_urdf(), l = learm();
    check_whole_circle(&x, 150, 7);
    check_whole_circle(&l, 100, 11);
}

/* Chains with odd limits: an elbow bent one way only (or up to 0), limits
 * at 180 (a wrapped angle passes it), equal upper arm and forearm that fold
 * onto the shoulder's axis. */
static void test_inverse_odd_chains(void **state)
{
    (void)state;
    lsc_kin_chain one_way = {50, 100, 80, 60, {-120, -100, 10, -120, -90}, {120, 100, 150, 120, 90}};
    lsc_kin_chain other = {50, 100, 80, 60, {-120, -180, -150, -170, -90}, {120, 170, 0, 180, 90}};
    lsc_kin_chain folds = {50, 90, 90, 40, {-180, -180, -180, -180, -180}, {180, 180, 180, 180, 180}};
    check_whole_circle(&one_way, 40, 3);
    check_whole_circle(&other, 40, 5);
    check_whole_circle(&folds, 40, 9);
}

/* A point whose nearest pitch puts a joint on its limit where the arm is
 * nearly straight: there a joint turns fast with the pitch, the rounding
 * of the point's pitch leaves it beyond the limit, and a pitch a little
 * further in is taken. */
static void test_inverse_nudged(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm_urdf();
    float got[LSC_KIN_JOINTS];
    const float near[LSC_KIN_JOINTS] = {76.3585663f, 43.0070114f, 4.90119171f, 53.0858688f,
                                        -67.3805695f};
    lsc_kin_target t = {-178.150421f, -72.4002609f, 171.746307f, 0, 0, false, false};
    lsc_kin_result r;
    assert_int_equal(lsc_kin_inverse(&c, &t, near, got, &r), 0);
    assert_near(r.pitch_deg, -150.307, 0.02);
    lsc_kin_pose p;
    assert_int_equal(lsc_kin_forward(&c, got, &p), 0);
    assert_near(p.x_mm, t.x_mm, 0.01);
    assert_near(p.z_mm, t.z_mm, 0.01);
}

/* Points the pitches -90..90 in whole degrees missed: behind the base,
 * reached leaning back (pitch about -130). */
static void test_inverse_behind(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm_urdf();
    float got[LSC_KIN_JOINTS];
    lsc_kin_result r;
    lsc_kin_target t = {-200, -60, 100, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), 0);
    assert_true(r.pitch_deg < -90 || r.pitch_deg > 90);
    lsc_kin_pose p;
    assert_int_equal(lsc_kin_forward(&c, got, &p), 0);
    assert_near(p.x_mm, -200, 0.01);
    assert_near(p.y_mm, -60, 0.01);
    assert_near(p.z_mm, 100, 0.01);
    t.has_pitch = true;
    t.pitch_deg = -130;
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), 0);
}

/* Refused without a pitch: the reason that holds for every pitch. */
static void test_inverse_no_pitch_refusals(void **state)
{
    (void)state;
    lsc_kin_chain c = learm();
    float got[LSC_KIN_JOINTS];
    lsc_kin_result r;
    /* to the side (base 90 or -90): beyond the base's +-85 either way */
    lsc_kin_target t = {0, 200, 100, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_BASE);
    assert_true(r.high);
    assert_near(r.angle_deg, 90, 1e-3);
    /* the roll beyond its limit: at every pitch */
    t = (lsc_kin_target){200, 0, 100, 0, 120, false, true};
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(r.joint, LSC_KIN_ROLL);
    float lo[2], hi[2];
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, lo, hi, 2), 0);
    /* too close at every pitch: the wrist nearer the shoulder than the
     * folded arm reaches (a long upper arm, short forearm and hand) */
    lsc_kin_chain s = {10, 100, 20, 10, {-180, -180, -180, -180, -180}, {180, 180, 180, 180, 180}};
    t = (lsc_kin_target){0, 0, 15, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&s, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_OUT_OF_REACH);
    assert_near(r.by_mm, 80 - 5 - 10, 1e-3);
    assert_near(r.pitch_deg, -90, 1e-3);
    /* within reach, at no pitch within the limits: the shoulder held near
     * upright, the point level and far: the joint of the pitch nearest the
     * present one that reaches it, never the base */
    c = xarm_urdf();
    c.min_deg[LSC_KIN_SHOULDER] = -5;
    c.max_deg[LSC_KIN_SHOULDER] = 5;
    t = (lsc_kin_target){-330, 0, 64.7f, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_true(r.joint != LSC_KIN_BASE);
    t.has_pitch = true;
    t.pitch_deg = r.pitch_deg;
    lsc_kin_result there;
    assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, &there), LSC_EINVAL);
    assert_int_equal(there.status, LSC_KIN_BEYOND_LIMIT);
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, lo, hi, 2), 0);
    /* to the side: both bases within their limits; the pitch told is the
     * one nearest the present (from above, from below) */
    t = (lsc_kin_target){0, 330, 64.7f, 0, 0, false, false};
    const float above[LSC_KIN_JOINTS] = {0, -3, 0, -60, 0}, below[LSC_KIN_JOINTS] = {0, 3, 0, 60, 0};
    assert_int_equal(lsc_kin_inverse(&c, &t, above, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    float from_above = r.pitch_deg;
    assert_int_equal(lsc_kin_inverse(&c, &t, below, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_true(r.pitch_deg != from_above);
    /* no hand (the pitch moves nothing but the wrist), and a point on the
     * shoulder's axis (the pitch turns the wrist about it): the present
     * pitch is told */
    lsc_kin_chain bare = c;
    bare.tool_mm = 0;
    t = (lsc_kin_target){150, 0, 64.7f, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&bare, &t, above, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_near(r.pitch_deg, 90 - (-3 - 60), 1e-3);
    t = (lsc_kin_target){0, 0, 64.7f, 0, 0, false, false};
    assert_int_equal(lsc_kin_inverse(&c, &t, above, got, &r), LSC_EINVAL);
    assert_int_equal(r.status, LSC_KIN_BEYOND_LIMIT);
    assert_near(r.pitch_deg, 90 - (-3 - 60), 1e-3);
}

/* lsc_kin_pitches: the whole circle, a lone tool-less wrist, caps, NULLs. */
static void test_pitches(void **state)
{
    (void)state;
    lsc_kin_chain c = {10, 100, 80, 0, {-180, -180, -180, -180, -180}, {180, 180, 180, 180, 180}};
    lsc_kin_target t = {100, 0, 50, 0, 0, false, false};
    float lo[4] = {7, 7, 7, 7}, hi[4] = {7, 7, 7, 7};
    /* no hand: the pitch is the wrist's alone, every one reaches it */
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, lo, hi, 2), 1);
    assert_near(lo[0], -180, 0);
    assert_near(hi[0], 180, 0);
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, NULL, NULL, 0), 1);
    /* the wrist limited to 0..0: one pitch per elbow and side */
    c.min_deg[LSC_KIN_WRIST] = 0;
    c.max_deg[LSC_KIN_WRIST] = 0;
    int n = lsc_kin_pitches(&c, &t, NULL, lo, hi, 4);
    assert_int_equal(n, 4);
    for (int i = 0; i < n; i++) {
        assert_near(lo[i], hi[i], 0.01);
        t.has_pitch = true;
        t.pitch_deg = lo[i];
        float got[LSC_KIN_JOINTS];
        assert_int_equal(lsc_kin_inverse(&c, &t, NULL, got, NULL), 0);
        t.has_pitch = false;
    }
    /* the count past the cap; bad input */
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, lo, hi, 1), 4);
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, NULL, hi, 1), LSC_EINVAL);
    assert_int_equal(lsc_kin_pitches(&c, &t, NULL, lo, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_kin_pitches(&c, NULL, NULL, lo, hi, 1), LSC_EINVAL);
    assert_int_equal(lsc_kin_pitches(NULL, &t, NULL, lo, hi, 1), LSC_EINVAL);
}

static void test_near_ends(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm_urdf();
    float q[LSC_KIN_JOINTS] = {0, 88, -110, 0, 0};
    unsigned m = lsc_kin_near_ends(&c, q, LSC_KIN_NEAR_END_DEG);
    assert_int_equal(m, LSC_KIN_NEAR_HIGH(LSC_KIN_SHOULDER) | LSC_KIN_NEAR_LOW(LSC_KIN_ELBOW));
    assert_int_equal(lsc_kin_near_ends(&c, q, 1.0f), 0u);
    c.min_deg[LSC_KIN_BASE] = -1; /* a range narrower than twice the margin */
    c.max_deg[LSC_KIN_BASE] = 1;
    m = lsc_kin_near_ends(&c, q, LSC_KIN_NEAR_END_DEG);
    assert_true((m & LSC_KIN_NEAR_LOW(LSC_KIN_BASE)) && (m & LSC_KIN_NEAR_HIGH(LSC_KIN_BASE)));
    assert_int_equal(lsc_kin_near_ends(NULL, q, 5.0f), 0u);
    assert_int_equal(lsc_kin_near_ends(&c, NULL, 5.0f), 0u);
    assert_int_equal(lsc_kin_near_ends(&c, q, NAN), 0u);
    q[0] = INFINITY;
    assert_int_equal(lsc_kin_near_ends(&c, q, 5.0f), 0u);
}

static void test_bad_input(void **state)
{
    (void)state;
    lsc_kin_chain c = xarm(), bad = c;
    float q[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0}, got[LSC_KIN_JOINTS];
    lsc_kin_pose p;
    lsc_kin_result r;
    lsc_kin_target t = at(300, 0, 100, 0);
    assert_true(lsc_kin_chain_valid(&c));
    assert_false(lsc_kin_chain_valid(NULL));
    float *fields[] = {&bad.base_mm, &bad.upper_mm, &bad.fore_mm, &bad.tool_mm};
    for (int i = 0; i < 4; i++) {
        bad = c;
        *fields[i] = NAN;
        assert_false(lsc_kin_chain_valid(&bad));
        *fields[i] = -1;
        assert_false(lsc_kin_chain_valid(&bad));
        *fields[i] = 0;
        assert_true(lsc_kin_chain_valid(&bad) == (i == 0 || i == 3));
        *fields[i] = 2e5f;
        assert_false(lsc_kin_chain_valid(&bad));
    }
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        bad = c;
        bad.min_deg[i] = NAN;
        assert_false(lsc_kin_chain_valid(&bad));
        bad = c;
        bad.max_deg[i] = 400;
        assert_false(lsc_kin_chain_valid(&bad));
        bad = c;
        bad.min_deg[i] = 116;
        assert_false(lsc_kin_chain_valid(&bad));
    }
    bad = c;
    bad.upper_mm = 0;
    assert_int_equal(lsc_kin_forward(&bad, q, &p), LSC_EINVAL);
    assert_int_equal(lsc_kin_forward(&c, NULL, &p), LSC_EINVAL);
    assert_int_equal(lsc_kin_forward(&c, q, NULL), LSC_EINVAL);
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        float odd[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0};
        odd[i] = INFINITY;
        assert_int_equal(lsc_kin_forward(&c, odd, &p), LSC_EINVAL);
        assert_int_equal(lsc_kin_inverse(&c, &t, odd, got, &r), LSC_EINVAL);
        assert_int_equal(r.status, LSC_KIN_BAD_INPUT);
    }
    assert_int_equal(lsc_kin_inverse(&bad, &t, q, got, &r), LSC_EINVAL);
    assert_int_equal(lsc_kin_inverse(&c, NULL, q, got, &r), LSC_EINVAL);
    assert_int_equal(lsc_kin_inverse(&c, &t, q, NULL, &r), LSC_EINVAL);
    assert_int_equal(lsc_kin_inverse(&c, &t, q, got, NULL), 0);
    float *tfields[] = {&t.x_mm, &t.y_mm, &t.z_mm, &t.pitch_deg, &t.roll_deg};
    for (int i = 0; i < 5; i++) {
        lsc_kin_target keep = t;
        t.has_roll = true;
        *tfields[i] = NAN;
        r.status = LSC_KIN_OK;
        assert_int_equal(lsc_kin_inverse(&c, &t, q, got, &r), LSC_EINVAL);
        assert_int_equal(r.status, LSC_KIN_BAD_INPUT);
        t.has_pitch = false; /* a pitch or roll not given is not looked at */
        t.has_roll = false;
        assert_int_equal(lsc_kin_inverse(&c, &t, q, got, &r) == 0, i >= 3);
        t = keep;
    }
    /* angles beyond a turn are fine for the forward kinematics */
    float turns[LSC_KIN_JOINTS] = {720, -720, 360, -360, 0};
    assert_int_equal(lsc_kin_forward(&c, turns, &p), 0);
    assert_near(p.pitch_deg, 90, 0.01);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_forward_matches_the_transforms),
        cmocka_unit_test(test_forward_fixed_poses),
        cmocka_unit_test(test_inverse_of_forward_grid),
        cmocka_unit_test(test_inverse_nearest_elbow),
        cmocka_unit_test(test_inverse_singular),
        cmocka_unit_test(test_inverse_roll),
        cmocka_unit_test(test_inverse_out_of_reach),
        cmocka_unit_test(test_inverse_beyond_limits),
        cmocka_unit_test(test_inverse_on_a_limit),
        cmocka_unit_test(test_inverse_base_and_roll_on_a_limit),
        cmocka_unit_test(test_inverse_best_pitch),
        cmocka_unit_test(test_inverse_whole_circle),
        cmocka_unit_test(test_inverse_odd_chains),
        cmocka_unit_test(test_inverse_nudged),
        cmocka_unit_test(test_inverse_behind),
        cmocka_unit_test(test_inverse_no_pitch_refusals),
        cmocka_unit_test(test_pitches),
        cmocka_unit_test(test_near_ends),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
