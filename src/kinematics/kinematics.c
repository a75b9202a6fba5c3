/* lsc kinematics: forward and closed-form inverse kinematics of the 5-joint
 * arm chain (include/lsc/kinematics.h, docs/kinematics.md). Float only, no
 * allocation, no mutable static state: builds freestanding for MCUs. */
#include <math.h>

#include "lsc/kinematics.h"

#define RAD_PER_DEG 0.017453292519943f
#define DEG_PER_RAD 57.29577951308232f
#define ANGLE_MAX 3600.0f    /* |angle| accepted, degrees */
#define LIMIT_MAX 360.0f     /* |limit| accepted, degrees */
#define PITCH_LOW (-90)      /* the pitches tried without one given */
#define PITCH_HIGH 90

/* NaN fails both comparisons */
static bool within(float v, float max)
{
    return v >= -max && v <= max;
}

/* a into -180 < a <= 180 (|a| <= 3 * ANGLE_MAX: a few turns at most) */
static float wrap(float a)
{
    while (a > 180.0f) {
        a -= 360.0f;
    }
    while (a <= -180.0f) {
        a += 360.0f;
    }
    return a;
}

bool lsc_kin_chain_valid(const lsc_kin_chain *c)
{
    if (c == NULL || !within(c->base_mm, LSC_KIN_MM_MAX) || !within(c->upper_mm, LSC_KIN_MM_MAX) ||
        !within(c->fore_mm, LSC_KIN_MM_MAX) || !within(c->tool_mm, LSC_KIN_MM_MAX) ||
        c->base_mm < 0.0f || c->upper_mm <= 0.0f || c->fore_mm <= 0.0f || c->tool_mm < 0.0f) {
        return false;
    }
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        if (!within(c->min_deg[i], LIMIT_MAX) || !within(c->max_deg[i], LIMIT_MAX) ||
            c->min_deg[i] > c->max_deg[i]) {
            return false;
        }
    }
    return true;
}

static bool angles_ok(const float *q)
{
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        if (!within(q[i], ANGLE_MAX)) {
            return false;
        }
    }
    return true;
}

int lsc_kin_forward(const lsc_kin_chain *c, const float *q, lsc_kin_pose *out)
{
    if (!lsc_kin_chain_valid(c) || q == NULL || out == NULL || !angles_ok(q)) {
        return LSC_EINVAL;
    }
    float a1 = q[LSC_KIN_SHOULDER] * RAD_PER_DEG;
    float a2 = a1 + q[LSC_KIN_ELBOW] * RAD_PER_DEG;
    float a3 = a2 + q[LSC_KIN_WRIST] * RAD_PER_DEG;
    float b = q[LSC_KIN_BASE] * RAD_PER_DEG;
    float r = c->upper_mm * sinf(a1) + c->fore_mm * sinf(a2) + c->tool_mm * sinf(a3);
    out->x_mm = r * cosf(b);
    out->y_mm = r * sinf(b);
    out->z_mm = c->base_mm + c->upper_mm * cosf(a1) + c->fore_mm * cosf(a2) +
                c->tool_mm * cosf(a3);
    /* the hand's direction (sin a3, cos a3) in the plane, from the horizontal */
    out->pitch_deg = wrap(atan2f(cosf(a3), sinf(a3)) * DEG_PER_RAD);
    out->roll_deg = q[LSC_KIN_ROLL];
    return LSC_OK;
}

/* ---- inverse ------------------------------------------------------------- */

/* One solve's outcome: status, and for BEYOND_LIMIT the excess and the joint. */
typedef struct solve {
    lsc_kin_status status;
    float by_mm;  /* OUT_OF_REACH */
    float excess; /* BEYOND_LIMIT: the sum of the angles beyond the limits */
    int joint;
    bool high;
    float angle_deg;
} solve;

/* Puts angles within the slack of a limit on it; the sum of what lies beyond
 * the limits, and the first joint beyond one in *s. */
static float beyond(const lsc_kin_chain *c, float *q, solve *s)
{
    float sum = 0.0f;
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        bool high = q[i] > c->max_deg[i];
        if (!high && q[i] >= c->min_deg[i]) {
            continue; /* inside: the usual case, two comparisons */
        }
        float limit = high ? c->max_deg[i] : c->min_deg[i];
        float ex = high ? q[i] - limit : limit - q[i];
        if (ex <= LSC_KIN_LIMIT_SLACK_DEG) {
            q[i] = limit;
            continue;
        }
        if (sum == 0.0f) {
            s->joint = i;
            s->high = high;
            s->angle_deg = q[i];
        }
        sum += ex;
    }
    return sum;
}

static float distance(const float *q, const float *near)
{
    float sum = 0.0f;
    for (int i = 0; i < LSC_KIN_ROLL; i++) {
        float d = wrap(q[i] - near[i]);
        sum += d * d;
    }
    return sum;
}

/* The solutions for the target at pitch p (degrees): the best of them into q
 * (status OK), or why none. */
static solve solve_pitch(const lsc_kin_chain *c, const lsc_kin_target *t, float roll, float p,
                         const float *near, float *q)
{
    solve out = {LSC_KIN_OUT_OF_REACH, 0.0f, 0.0f, 0, false, 0.0f};
    float r = sqrtf(t->x_mm * t->x_mm + t->y_mm * t->y_mm);
    float b = r < LSC_KIN_AXIS_MM ? near[LSC_KIN_BASE] : atan2f(t->y_mm, t->x_mm) * DEG_PER_RAD;
    float pr = p * RAD_PER_DEG;
    float l1 = c->upper_mm, l2 = c->fore_mm;
    float zw = t->z_mm - c->base_mm - c->tool_mm * sinf(pr);
    float best = 0.0f;
    bool found = false, known = false;
    for (int side = 0; side < 2; side++) { /* toward the target, then turned half round */
        float base = wrap(side == 0 ? b : b + 180.0f);
        if (side == 1 && found && (base > c->max_deg[LSC_KIN_BASE] + LSC_KIN_LIMIT_SLACK_DEG ||
                                   base < c->min_deg[LSC_KIN_BASE] - LSC_KIN_LIMIT_SLACK_DEG)) {
            break; /* no solution of that side is within the limits: skip its cost */
        }
        float rw = (side == 0 ? r : -r) - c->tool_mm * cosf(pr);
        float d2 = rw * rw + zw * zw, d = sqrtf(d2);
        float far = d - (l1 + l2), close = fabsf(l1 - l2) - d;
        float by = far > close ? far : close;
        if (by > LSC_KIN_EDGE_MM) {
            if (out.status == LSC_KIN_OUT_OF_REACH && (side == 0 || by < out.by_mm)) {
                out.by_mm = by;
            }
            continue;
        }
        /* the elbow's angle from its cosine and its sine (the triangle's
         * area); on the edge of the reach (by within LSC_KIN_EDGE_MM) the arm
         * is straight or folded: one elbow */
        float cos2 = far > close ? 1.0f : -1.0f, sin2 = 0.0f;
        if (by < -LSC_KIN_EDGE_MM) {
            float inv = 0.5f / (l1 * l2);
            cos2 = (d2 - l1 * l1 - l2 * l2) * inv;
            sin2 = sqrtf((d2 - (l1 - l2) * (l1 - l2)) * ((l1 + l2) * (l1 + l2) - d2)) * inv;
        }
        float e = atan2f(sin2, cos2) * DEG_PER_RAD;
        float alpha = atan2f(rw, zw) * DEG_PER_RAD;
        float beta = atan2f(l2 * sin2, l1 + l2 * cos2) * DEG_PER_RAD;
        for (int elbow = 0; elbow < 2; elbow++) {
            float cand[LSC_KIN_JOINTS];
            float e2 = elbow == 0 ? e : -e;
            solve s = {LSC_KIN_BEYOND_LIMIT, 0.0f, 0.0f, 0, false, 0.0f};
            cand[LSC_KIN_BASE] = base;
            cand[LSC_KIN_SHOULDER] = wrap(elbow == 0 ? alpha - beta : alpha + beta);
            cand[LSC_KIN_ELBOW] = wrap(e2);
            cand[LSC_KIN_WRIST] = wrap(90.0f - p - cand[LSC_KIN_SHOULDER] - e2);
            cand[LSC_KIN_ROLL] = roll;
            s.excess = beyond(c, cand, &s);
            if (s.excess > 0.0f) {
                if (out.status == LSC_KIN_OUT_OF_REACH || s.excess < out.excess) {
                    out = s;
                }
                continue;
            }
            if (found) { /* the distances only when there is a choice */
                if (!known) {
                    best = distance(q, near);
                    known = true;
                }
                float dist = distance(cand, near);
                if (!(dist < best)) {
                    continue;
                }
                best = dist;
            }
            found = true;
            for (int i = 0; i < LSC_KIN_JOINTS; i++) {
                q[i] = cand[i];
            }
        }
    }
    if (found) {
        solve ok = {LSC_KIN_OK, 0.0f, 0.0f, 0, false, 0.0f};
        return ok;
    }
    return out;
}

/* The whole degree nearest v (|v| <= 180) */
static int nearest_degree(float v)
{
    return (int)(v >= 0.0f ? v + 0.5f : v - 0.5f);
}

/* s into res (may be NULL); 0 for OK, else LSC_EINVAL */
static int report(lsc_kin_result *res, const solve *s, float p)
{
    if (res != NULL) {
        res->status = s->status;
        res->by_mm = s->by_mm;
        res->joint = s->joint;
        res->high = s->high;
        res->angle_deg = s->angle_deg;
        res->pitch_deg = p;
    }
    return s->status == LSC_KIN_OK ? LSC_OK : LSC_EINVAL;
}

/* Without a pitch: the whole degrees from the current pitch outwards, the
 * lower first; the first that reaches the target within the limits. Else the
 * first that reaches it beyond a limit, else the least distance out of reach. */
static solve free_pitch(const lsc_kin_chain *c, const lsc_kin_target *t, float roll,
                        const float *from, float *sol, float *p)
{
    lsc_kin_pose now = {0.0f, 0.0f, 0.0f, 90.0f, 0.0f};
    solve limit = {LSC_KIN_OUT_OF_REACH, 0.0f, 0.0f, 0, false, 0.0f}, reach = limit;
    float limit_p = 0.0f;
    (void)lsc_kin_forward(c, from, &now); /* the caller checked c and from */
    int p0 = nearest_degree(now.pitch_deg);
    p0 = p0 < PITCH_LOW ? PITCH_LOW : p0 > PITCH_HIGH ? PITCH_HIGH : p0;
    for (int k = 0; k <= PITCH_HIGH - PITCH_LOW; k++) {
        for (int side = -1; side <= 1; side += 2) {
            int pi = p0 + side * k;
            if (pi < PITCH_LOW || pi > PITCH_HIGH || (k == 0 && side > 0)) {
                continue;
            }
            *p = (float)pi;
            solve one = solve_pitch(c, t, roll, *p, from, sol);
            if (one.status == LSC_KIN_OK) {
                return one;
            }
            if (one.status == LSC_KIN_BEYOND_LIMIT) {
                if (limit.status != LSC_KIN_BEYOND_LIMIT) {
                    limit = one;
                    limit_p = *p;
                }
            } else if (reach.by_mm == 0.0f || one.by_mm < reach.by_mm) {
                reach.by_mm = one.by_mm;
            }
        }
    }
    *p = limit_p; /* 0 when out of reach */
    return limit.status == LSC_KIN_BEYOND_LIMIT ? limit : reach;
}

int lsc_kin_inverse(const lsc_kin_chain *c, const lsc_kin_target *t, const float *near,
                    float *q, lsc_kin_result *res)
{
    static const float zeros[LSC_KIN_JOINTS] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    solve s = {LSC_KIN_BAD_INPUT, 0.0f, 0.0f, 0, false, 0.0f};
    const float *from = near != NULL ? near : zeros;
    float sol[LSC_KIN_JOINTS];
    float p = 0.0f;
    if (!lsc_kin_chain_valid(c) || t == NULL || q == NULL || !angles_ok(from) ||
        !within(t->x_mm, LSC_KIN_MM_MAX) || !within(t->y_mm, LSC_KIN_MM_MAX) ||
        !within(t->z_mm, LSC_KIN_MM_MAX) || (t->has_pitch && !within(t->pitch_deg, ANGLE_MAX)) ||
        (t->has_roll && !within(t->roll_deg, ANGLE_MAX))) {
        return report(res, &s, p);
    }
    float roll = t->has_roll ? t->roll_deg : from[LSC_KIN_ROLL];
    if (t->has_pitch) {
        p = t->pitch_deg;
        s = solve_pitch(c, t, roll, p, from, sol);
    } else {
        s = free_pitch(c, t, roll, from, sol, &p);
    }
    if (s.status == LSC_KIN_OK) {
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            q[i] = sol[i];
        }
    }
    return report(res, &s, p);
}
