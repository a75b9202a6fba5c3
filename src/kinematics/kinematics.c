/* lsc kinematics: forward and closed-form inverse kinematics of the 5-joint
 * arm chain (include/lsc/kinematics.h, docs/kinematics.md). Float only, no
 * allocation, no mutable static state: builds freestanding for MCUs.
 *
 * Angles are degrees throughout. In the vertical plane of the base (R
 * horizontal, away from the base's axis; Z up from the shoulder's axis) a
 * direction "a" is the unit vector (sin a, cos a): measured from the
 * vertical toward +R, as the joints measure it. A1 = shoulder, A2 = A1 +
 * elbow and A3 = A2 + wrist are the links' directions; the pitch is 90 - A3.
 *
 * Without a pitch the pitch is chosen over the whole circle: the pitches at
 * which a joint meets one of its limits, or the arm is straight or folded,
 * are found in closed form (each is the intersection of two circles); the
 * feasible pitches are arcs between such points, so the one nearest the
 * present pitch is the present pitch itself or the nearest of those points
 * that is within every limit. */
#include <math.h>
#include <stdint.h>

#include "lsc/kinematics.h"

#define RAD_PER_DEG 0.017453292519943f
#define DEG_PER_RAD 57.29577951308232f
#define ANGLE_MAX 3600.0f /* |angle| accepted, degrees */
#define LIMIT_MAX 360.0f  /* |limit| accepted, degrees */
#define TINY_MM 0.001f    /* a side shorter than this: no triangle to solve */
#define NUDGE_DEG 0.001f  /* free_pitch: the pitch moved by this times 1, 4, 9 */
#define NUDGES 4
#define COS_SLACK 1e-5f   /* a cosine this far beyond +-1 is rounding: taken as +-1 */

/* ---- checks without float comparisons (each costs ~60 cycles on an AVR) -- */

static uint32_t bits(float v)
{
    union {
        float f;
        uint32_t u;
    } x;
    x.f = v;
    return x.u;
}

#define ABS_BITS 0x7FFFFFFFu

/* |v| <= max (max > 0 finite); false for NaN and infinities */
static bool within(float v, float max)
{
    return (bits(v) & ABS_BITS) <= bits(max);
}

/* 0 <= v <= max (positive: 0 < v); false for -0, NaN, infinities */
static bool length_ok(float v, bool positive)
{
    uint32_t u = bits(v);
    return positive ? u - 1u < bits(LSC_KIN_MM_MAX) : u <= bits(LSC_KIN_MM_MAX);
}

/* a into -180 < a <= 180 (|a| a few turns at most); one comparison when it
 * is inside already */
static float wrap(float a)
{
    if ((bits(a) & ABS_BITS) < bits(180.0f)) {
        return a; /* |a| < 180 (the bits of positive floats sort as they do) */
    }
    while (a > 180.0f) {
        a -= 360.0f;
    }
    while (a <= -180.0f) {
        a += 360.0f;
    }
    return a;
}

/* sin and cos of a (degrees, -180 < a <= 180): one sinf and one sqrtf, the
 * sine taken of whichever of the two is the smaller (no cancellation) */
static void sin_cos(float a, float *s, float *c)
{
    float m = fabsf(a);
    uint32_t mb = bits(m); /* m's bits: they sort as m does */
    if (mb <= bits(45.0f) || mb >= bits(135.0f)) {
        *s = sinf(a * RAD_PER_DEG);
        float k = sqrtf(1.0f - *s * *s);
        *c = mb <= bits(90.0f) ? k : -k;
    } else {
        *c = sinf((90.0f - m) * RAD_PER_DEG);
        float k = sqrtf(1.0f - *c * *c);
        *s = a > 0.0f ? k : -k;
    }
}

/* acos in degrees of a cosine clamped into -1..1 */
static float acos_deg(float v)
{
    return acosf(fmaxf(-1.0f, fminf(1.0f, v))) * DEG_PER_RAD;
}

static float atan2_deg(float y, float x)
{
    return atan2f(y, x) * DEG_PER_RAD;
}

/* acos (degrees) of a cosine, or -1 when it is beyond -1..1 by more than
 * rounding (COS_SLACK): no such angle */
static float arc(float v)
{
    return within(v, 1.0f + COS_SLACK) ? acos_deg(v) : -1.0f;
}

bool lsc_kin_chain_valid(const lsc_kin_chain *c)
{
    if (c == NULL || !length_ok(c->base_mm, false) || !length_ok(c->upper_mm, true) ||
        !length_ok(c->fore_mm, true) || !length_ok(c->tool_mm, false)) {
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
    float s1, c1, s2, c2, s3, c3, sb, cb;
    float a1 = wrap(q[LSC_KIN_SHOULDER]);
    float a2 = wrap(a1 + q[LSC_KIN_ELBOW]);
    float a3 = wrap(a2 + q[LSC_KIN_WRIST]);
    sin_cos(a1, &s1, &c1);
    sin_cos(a2, &s2, &c2);
    sin_cos(a3, &s3, &c3);
    sin_cos(wrap(q[LSC_KIN_BASE]), &sb, &cb);
    float r = c->upper_mm * s1 + c->fore_mm * s2 + c->tool_mm * s3;
    out->x_mm = r * cb;
    out->y_mm = r * sb;
    out->z_mm = c->base_mm + c->upper_mm * c1 + c->fore_mm * c2 + c->tool_mm * c3;
    out->pitch_deg = wrap(90.0f - a3);
    out->roll_deg = q[LSC_KIN_ROLL];
    return LSC_OK;
}

/* ---- inverse ------------------------------------------------------------- */

/* angle within joint i's limits, or beyond by at most the slack */
static bool inside(const lsc_kin_chain *c, int i, float angle)
{
    return angle >= c->min_deg[i] - LSC_KIN_LIMIT_SLACK_DEG &&
           angle <= c->max_deg[i] + LSC_KIN_LIMIT_SLACK_DEG;
}

/* The target in the base's vertical plane, the same for every pitch. */
typedef struct plane {
    float r;    /* the grasp point's horizontal distance from the base's axis */
    float b;    /* the base's angle toward it (near's base on the axis) */
    float z;    /* its height above the shoulder's axis */
    float roll; /* the wrist roll's angle */
    unsigned sides; /* bit 0: the base toward the target; bit 1: turned half round */
} plane;

/* One solve's outcome: status, and for BEYOND_LIMIT the excess and the joint. */
typedef struct solve {
    lsc_kin_status status;
    float by_mm;  /* OUT_OF_REACH */
    float excess; /* BEYOND_LIMIT: the sum of the angles beyond the limits */
    int joint;
    bool high;
    float angle_deg;
} solve;

/* Joint i at v within its limits (the usual case: two comparisons, no call),
 * else fits(). */
#define FITS(c, i, v) (((v) <= (c)->max_deg[i] && (v) >= (c)->min_deg[i]) || fits(c, i, &(v)))

/* Joint i at *v within its limits, or beyond one by at most the slack (a
 * rounding: then put on it). Two comparisons when inside. */
static bool fits(const lsc_kin_chain *c, int i, float *v)
{
    float lo = c->min_deg[i], hi = c->max_deg[i];
    if (*v <= hi) {
        if (*v >= lo) {
            return true;
        }
        *v = *v >= lo - LSC_KIN_LIMIT_SLACK_DEG ? lo : *v;
        return *v == lo;
    }
    *v = *v <= hi + LSC_KIN_LIMIT_SLACK_DEG ? hi : *v;
    return *v == hi;
}

/* Why the solution q is refused: the sum of what lies beyond the limits
 * (into s->excess) and the first joint beyond one. */
static void beyond(const lsc_kin_chain *c, const float *q, solve *s)
{
    s->status = LSC_KIN_BEYOND_LIMIT;
    s->excess = 0.0f;
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        float v = q[i];
        if (fits(c, i, &v)) {
            continue;
        }
        bool high = v > c->max_deg[i];
        if (s->excess == 0.0f) {
            s->joint = i;
            s->high = high;
            s->angle_deg = v;
        }
        s->excess += high ? v - c->max_deg[i] : c->min_deg[i] - v;
    }
}

/* The base's angle on side (0 toward the target, 1 turned half round). */
static float side_base(const plane *pl, int side)
{
    return side == 0 ? pl->b : pl->b > 0.0f ? pl->b - 180.0f : pl->b + 180.0f;
}

/* The solutions for the target at pitch p (degrees, -180 < p <= 180) on the
 * sides pl->sides, in the order of preference: the side whose base is within
 * its limits and nearer near's, then the elbow bent as near's (its sign; 0
 * counts as +); the first within the limits into q (status OK). Else why
 * none: out of reach, or the solution least beyond the limits. */
static solve solve_pitch(const lsc_kin_chain *c, const plane *pl, float p, const float *near,
                         float *q, bool why, int hint)
{
    solve out = {LSC_KIN_OUT_OF_REACH, 0.0f, 0.0f, 0, false, 0.0f};
    float roll = pl->roll;
    bool roll_ok = FITS(c, LSC_KIN_ROLL, roll); /* the same for every solution */
    float sp, cp;
    sin_cos(p, &sp, &cp);
    float l1 = c->upper_mm, l2 = c->fore_mm;
    float zw = pl->z - c->tool_mm * sp, tc = c->tool_mm * cp;
    float sum = l1 + l2, dif = fabsf(l1 - l2), sum2 = sum * sum, dif2 = dif * dif;
    float base[2] = {side_base(pl, 0), side_base(pl, 1)};
    const bool base_ok[2] = {FITS(c, LSC_KIN_BASE, base[0]), FITS(c, LSC_KIN_BASE, base[1])};
    int first = base_ok[1] && (!base_ok[0] || fabsf(base[1] - near[LSC_KIN_BASE]) <
                                                  fabsf(base[0] - near[LSC_KIN_BASE]));
    int bent = near[LSC_KIN_ELBOW] < 0.0f;
    if (hint >= 0) { /* the side and elbow of the point the search chose first */
        first = hint >> 1;
        bent = hint & 1;
    }
    for (int n = 0; n < 2; n++) {
        int side = first ^ n;
        if ((pl->sides & (1u << side)) == 0u) {
            continue;
        }
        float rw = (side == 0 ? pl->r : -pl->r) - tc, d2 = rw * rw + zw * zw;
        /* the wrist's distance d from the shoulder against the reach: u =
         * d^2 - (l1 - l2)^2 and v = (l1 + l2)^2 - d^2 are both positive
         * inside it, and 2 l1 l2 times the elbow's sine and cosine are
         * sqrt(u v) and (u - v) / 2 */
        float u = d2 - dif2, v = sum2 - d2, se, ce, bx;
        if (u > dif * (2.0f * LSC_KIN_EDGE_MM) && v > sum * (2.0f * LSC_KIN_EDGE_MM)) {
            se = 2.0f * sqrtf(u * v);
            ce = u - v;
            bx = 4.0f * l1 * l1 + ce; /* the shoulder's angle off the wrist,
                                      * atan2(l2 sin, l1 + l2 cos), scaled alike */
        } else { /* on the edge (the arm straight or folded), or out of reach */
            float d = sqrtf(d2), far = d - sum, close = dif - d;
            float by = far > close ? far : close;
            if (by > LSC_KIN_EDGE_MM) {
                if (out.status == LSC_KIN_OUT_OF_REACH && (out.by_mm == 0.0f || by < out.by_mm)) {
                    out.by_mm = by;
                }
                continue;
            }
            se = 0.0f;
            ce = far > close ? 1.0f : -1.0f;
            bx = l1 + l2 * ce;
        }
        float e = atan2_deg(se, ce); /* both scaled alike: no division */
        for (int m = 0; m < 2; m++) {
            float x[LSC_KIN_JOINTS];
            /* the shoulder: the wrist's direction less (or plus) the angle
             * off it, in one atan2 (a complex product) */
            float sg = (bent ^ m) == 0 ? 1.0f : -1.0f, sb = sg * se;
            x[LSC_KIN_BASE] = base[side];
            x[LSC_KIN_SHOULDER] = atan2_deg(rw * bx - zw * sb, zw * bx + rw * sb);
            x[LSC_KIN_ELBOW] = sg * e;
            x[LSC_KIN_WRIST] = wrap(90.0f - p - x[LSC_KIN_SHOULDER] - x[LSC_KIN_ELBOW]);
            x[LSC_KIN_ROLL] = roll;
            if (base_ok[side] && roll_ok && FITS(c, LSC_KIN_SHOULDER, x[LSC_KIN_SHOULDER]) &&
                FITS(c, LSC_KIN_ELBOW, x[LSC_KIN_ELBOW]) && FITS(c, LSC_KIN_WRIST, x[LSC_KIN_WRIST])) {
                for (int i = 0; i < LSC_KIN_JOINTS; i++) {
                    q[i] = x[i];
                }
                solve ok = {LSC_KIN_OK, 0.0f, 0.0f, 0, false, 0.0f};
                return ok;
            }
            if (why) { /* (only a refusal needs to know how far beyond) */
                solve s = out;
                beyond(c, x, &s);
                out = out.status == LSC_KIN_OUT_OF_REACH || s.excess < out.excess ? s : out;
            } else {
                out.status = LSC_KIN_BEYOND_LIMIT;
            }
        }
    }
    return out;
}

/* ---- the pitch chosen ------------------------------------------------------ */

/* The points where feasibility can change go to offer(): the pitch there and
 * the angles of shoulder, elbow and wrist (not yet wrapped) on a side. */
typedef struct search {
    const lsc_kin_chain *c;
    float lo[LSC_KIN_ROLL], hi[LSC_KIN_ROLL]; /* the limits, the slack added */
    float mid[LSC_KIN_ROLL];                  /* their middles */
    float p0;        /* the present pitch */
    unsigned sides;  /* the sides whose base is within its limit */
    bool found;      /* a feasible point: */
    float best_p;    /* ... its pitch */
    float best_dist; /* ... its distance from p0 */
    int best_hint;   /* ... its side * 2 + 1 if its elbow is bent below 0 */
    float *list;     /* lsc_kin_pitches: every point's pitch instead */
    size_t n;
} search;

/* Joint i at v (within 180 of its limits' middle: a point on a limit at 180
 * is not turned into -180 by a rounding) within its limits, the slack
 * added. */
static bool allows(const search *s, int i, float v)
{
    float mid = s->mid[i];
    v = (bits(mid) << 1) == 0u ? wrap(v) : wrap(v - mid) + mid; /* (limits -x..x: no sums) */
    return v >= s->lo[i] && v <= s->hi[i];
}

/* fixed: the joint the point puts on a limit (or the elbow straight or
 * folded, within its limits): not checked again. */
static void offer(search *s, int side, float a3, float a1, float e, int fixed)
{
    if ((s->sides & (1u << side)) == 0u) {
        return;
    }
    if (s->list != NULL) { /* (POINTS_MAX holds them all) */
        s->list[s->n++] = wrap(90.0f - a3);
        return;
    }
    float dist = fabsf(wrap(90.0f - a3 - s->p0));
    if (s->found && !(dist < s->best_dist)) {
        return; /* no nearer (of two as near, the first offered) */
    }
    if ((fixed == LSC_KIN_SHOULDER || allows(s, LSC_KIN_SHOULDER, a1)) &&
        (fixed == LSC_KIN_ELBOW || allows(s, LSC_KIN_ELBOW, e)) &&
        (fixed == LSC_KIN_WRIST || allows(s, LSC_KIN_WRIST, a3 - a1 - e))) {
        s->found = true;
        s->best_p = wrap(90.0f - a3);
        s->best_dist = dist;
        s->best_hint = side * 2 + (e < 0.0f);
    }
}

/* The geometry every family of points shares. */
typedef struct circ {
    float d2, d;  /* the target's squared distance and distance from the shoulder */
    float inv;    /* 1 / (2 d) */
    float inv_t;  /* 1 / tool, 1 / upper, 1 / (2 fore tool): divisions made once */
    float inv_l1;
    float inv_2l2t;
    float phi[2]; /* its direction on each side */
    float r;      /* its horizontal distance */
    float z;
} circ;

/* The angles at which joint i's limits can be met (a wrapped angle passes
 * +-180 too): its limits inside the circle, and 180 when only one side of it
 * is allowed. At most 3 into v. */
static int ends(const lsc_kin_chain *c, int i, float *v)
{
    int n = 0;
    float lo = c->min_deg[i], hi = c->max_deg[i];
    if (lo > -180.0f) {
        v[n++] = lo;
    }
    if (hi < 180.0f) {
        v[n++] = hi;
    }
    if ((hi >= 180.0f) != (lo <= -180.0f)) {
        v[n++] = 180.0f;
    }
    return n;
}

/* The elbow at +-eps (cos ce, sin se; signs: bit 0 +, bit 1 -): the wrist
 * on the circle of radius d about the shoulder and of radius tool about the
 * target: nu the angle at the target, mu at the shoulder. */
static void elbow_points(search *s, const circ *g, float eps, float ce, float se, unsigned signs)
{
    const lsc_kin_chain *c = s->c;
    float l1 = c->upper_mm, l2 = c->fore_mm, t = c->tool_mm;
    float d2 = l1 * l1 + l2 * l2 + 2.0f * l1 * l2 * ce;
    float d = eps == 0.0f ? l1 + l2 : sqrtf(d2);
    if (d < TINY_MM) {
        return; /* the wrist on the shoulder's axis */
    }
    float nu = arc((g->d2 + t * t - d2) * g->inv * g->inv_t);
    if (nu < 0.0f) {
        return; /* the circles do not meet */
    }
    float mu = acos_deg((g->d2 + d2 - t * t) * g->inv / d);
    float beta = eps == 0.0f ? 0.0f : atan2_deg(l2 * se, l1 + l2 * ce);
    for (int k = 0; k < 2; k++) {
        float sg = k == 0 ? 1.0f : -1.0f;
        if ((signs & (1u << k)) == 0u) {
            continue;
        }
        for (int side = 0; side < 2; side++) {
            for (int rho = -1; rho <= 1; rho += 2) {
                float a3 = g->phi[side] - (float)rho * nu;
                offer(s, side, a3, g->phi[side] + (float)rho * mu - sg * beta, sg * eps,
                      LSC_KIN_ELBOW);
            }
        }
    }
}

/* The shoulder at lim (sin sl, cos cl): the elbow fixed, the forearm and the
 * hand reach the target from it (omega the wrist's angle, kappa the angle at
 * the elbow between the forearm and the target). mirror: the shoulder's
 * limits are -x..x, and each point on side 0 at lim is, mirrored, a point on
 * side 1 at -lim: side 1 is not solved again. */
static void shoulder_points(search *s, const circ *g, float lim, float sl, float cl, bool mirror)
{
    const lsc_kin_chain *c = s->c;
    float l1 = c->upper_mm, l2 = c->fore_mm, t = c->tool_mm;
    for (int side = 0; side < (mirror ? 1 : 2); side++) {
        if ((s->sides & (mirror ? 3u : 1u << side)) == 0u) {
            continue; /* not asked for */
        }
        float vr = (side == 0 ? g->r : -g->r) - l1 * sl, vz = g->z - l1 * cl;
        float m2 = vr * vr + vz * vz;
        float omega = arc((m2 - l2 * l2 - t * t) * g->inv_2l2t);
        if (omega < 0.0f) {
            continue; /* out of the forearm and hand's reach */
        }
        /* (m 0: the target on the elbow, the hand folded back on the
         * forearm: any direction, acos_deg's clamp takes one) */
        float kappa = acos_deg((l2 * l2 + m2 - t * t) / (2.0f * l2 * sqrtf(m2)));
        float gamma = atan2_deg(vr, vz);
        for (int rho = -1; rho <= 1; rho += 2) {
            float a2 = gamma - (float)rho * kappa, a3 = a2 + (float)rho * omega;
            offer(s, side, a3, lim, a2 - lim, LSC_KIN_SHOULDER);
            if (mirror) {
                offer(s, 1, -a3, -lim, lim - a2, LSC_KIN_SHOULDER);
            }
        }
    }
}

/* The wrist at lim: forearm and hand one rigid body, its far end on the
 * target, its near end (the elbow) on the upper arm's circle: mu the angle
 * at the shoulder, nu at the target. */
static void wrist_points(search *s, const circ *g, float lim)
{
    const lsc_kin_chain *c = s->c;
    float l1 = c->upper_mm, l2 = c->fore_mm, t = c->tool_mm;
    float sl, cl;
    sin_cos(lim, &sl, &cl);
    float k2 = l2 * l2 + t * t + 2.0f * l2 * t * cl, k = sqrtf(k2);
    float mu = arc((g->d2 + l1 * l1 - k2) * g->inv * g->inv_l1);
    if (mu < 0.0f) {
        return; /* the circles do not meet (k 0 is a point: they do not either) */
    }
    float nu = acos_deg((g->d2 + k2 - l1 * l1) * g->inv / k);
    float off = atan2_deg(t * sl, l2 + t * cl); /* elbow->target from the forearm */
    for (int side = 0; side < 2; side++) {
        for (int rho = -1; rho <= 1; rho += 2) {
            float a1 = g->phi[side] + (float)rho * mu;
            float a2 = g->phi[side] - (float)rho * nu - off;
            offer(s, side, a2 + lim, a1, a2 - a1, LSC_KIN_WRIST);
        }
    }
}

/* Every point where a joint meets a limit or the arm is straight or folded,
 * on the sides s->sides, to offer(). */
static void points(search *s, const plane *pl)
{
    const lsc_kin_chain *c = s->c;
    float v[3];
    circ g;
    g.r = pl->r;
    g.z = pl->z;
    g.d2 = pl->r * pl->r + pl->z * pl->z;
    g.d = sqrtf(g.d2);
    g.inv = 0.5f / g.d;
    g.inv_t = 1.0f / fmaxf(c->tool_mm, TINY_MM); /* (no hand: only the wrist's points) */
    g.inv_l1 = 1.0f / c->upper_mm;
    g.inv_2l2t = g.inv_t * 0.5f / c->fore_mm;
    g.phi[0] = atan2_deg(pl->r, pl->z);
    g.phi[1] = -g.phi[0];
    int n = c->tool_mm < TINY_MM ? 0 : ends(c, LSC_KIN_SHOULDER, v);
    bool mirror = c->min_deg[LSC_KIN_SHOULDER] == -c->max_deg[LSC_KIN_SHOULDER];
    float sl = 0.0f, cl = 0.0f;
    for (int i = 0; i < n; i++) {
        if (i == 0 || !mirror) {
            sin_cos(v[i], &sl, &cl);
        } else {
            sl = -sl; /* -x: the same cosine, the sine turned */
        }
        shoulder_points(s, &g, v[i], sl, cl, mirror);
    }
    if (g.d < TINY_MM) {
        return; /* the pitch turns the wrist about the shoulder: only the
                 * shoulder's angle changes with it */
    }
    n = ends(c, LSC_KIN_WRIST, v);
    for (int i = 0; i < n; i++) {
        wrist_points(s, &g, v[i]);
    }
    if (c->tool_mm < TINY_MM) {
        return; /* the pitch does not move the wrist: the elbow stays */
    }
    float lo = c->min_deg[LSC_KIN_ELBOW], hi = c->max_deg[LSC_KIN_ELBOW];
    if (inside(c, LSC_KIN_ELBOW, 0.0f)) {
        elbow_points(s, &g, 0.0f, 1.0f, 0.0f, 1u); /* straight */
    }
    if (hi >= 180.0f) {
        elbow_points(s, &g, 180.0f, -1.0f, 0.0f, 1u); /* folded */
    }
    bool both = lo == -hi;
    for (int k = 0; k < 2; k++) {
        float lim = k == 0 ? hi : lo;
        if (lim == 0.0f || !within(lim, 179.999f) || (both && k == 1)) {
            continue;
        }
        float eps = fabsf(lim), se, ce;
        sin_cos(eps, &se, &ce);
        elbow_points(s, &g, eps, ce, se, both ? 3u : lim > 0.0f ? 1u : 2u);
    }
}

/* Why no pitch reaches the target within the limits (none does): out of
 * reach at every pitch; or the base beyond its limit on both sides; or the
 * joint beyond its limit at the pitch nearest p0 that reaches it. *p: the
 * pitch the reason is told for. */
static solve refusal(const lsc_kin_chain *c, plane *pl, const float *near, float p0, float *p)
{
    float l1 = c->upper_mm, l2 = c->fore_mm, t = c->tool_mm;
    float d = sqrtf(pl->r * pl->r + pl->z * pl->z);
    float phi = atan2_deg(pl->r, pl->z);
    float far = fabsf(d - t) - (l1 + l2), close = fabsf(l1 - l2) - (d + t);
    float sol[LSC_KIN_JOINTS];
    if (far > LSC_KIN_EDGE_MM || close > LSC_KIN_EDGE_MM) {
        solve s = {LSC_KIN_OUT_OF_REACH, far > close ? far : close, 0.0f, 0, false, 0.0f};
        /* the hand along the line from the shoulder: outward, or inward */
        *p = wrap(far > close ? 90.0f - phi : -90.0f - phi);
        return s;
    }
    unsigned ok = 0u;
    for (int side = 0; side < 2; side++) {
        ok |= inside(c, LSC_KIN_BASE, side_base(pl, side)) ? 1u << side : 0u;
    }
    *p = p0;
    if (ok == 0u) {
        solve s = {LSC_KIN_BEYOND_LIMIT, 0.0f, 0.0f, LSC_KIN_BASE, pl->b > c->max_deg[LSC_KIN_BASE],
                   pl->b};
        return s;
    }
    /* the reachable pitches: 90 - phi +- nu, nu between the arm straight
     * (the wrist farthest) and folded */
    float lo = 0.0f, hi = 180.0f;
    if (d >= TINY_MM && t >= TINY_MM) {
        lo = acos_deg((d * d + t * t - (l1 - l2) * (l1 - l2)) / (2.0f * d * t));
        hi = acos_deg((d * d + t * t - (l1 + l2) * (l1 + l2)) / (2.0f * d * t));
    }
    float best = 360.0f;
    for (int side = 0; side < 2; side++) {
        float mid = side == 0 ? 90.0f - phi : 90.0f + phi;
        float x = wrap(p0 - mid), ax = fabsf(x);
        ax = fminf(fmaxf(ax, lo), hi);
        float at = wrap(mid + (x >= 0.0f ? ax : -ax));
        float dist = fabsf(wrap(at - p0));
        if ((ok & (1u << side)) != 0u && dist < best) {
            best = dist;
            *p = at;
        }
    }
    pl->sides = ok;
    return solve_pitch(c, pl, *p, near, sol, true, -1);
}

/* Without a pitch: the present one if it reaches the target within the
 * limits, else the nearest point where a limit is met (or the arm straight
 * or folded) that is within every limit; of two as near, the lower pitch. */
static solve free_pitch(const lsc_kin_chain *c, plane *pl, const float *near, float *q, float *p)
{
    float p0 = wrap(90.0f - wrap(wrap(near[LSC_KIN_SHOULDER] + near[LSC_KIN_ELBOW]) +
                                 near[LSC_KIN_WRIST]));
    *p = p0;
    float roll = pl->roll;
    if (!fits(c, LSC_KIN_ROLL, &roll)) { /* the same at every pitch */
        solve s = {LSC_KIN_BEYOND_LIMIT, 0.0f, 0.0f, LSC_KIN_ROLL,
                   roll > c->max_deg[LSC_KIN_ROLL], roll};
        return s;
    }
    search x = {c, {0.0f}, {0.0f}, {0.0f}, p0, 0u, false, 0.0f, 0.0f, 0, NULL, 0};
    for (int side = 0; side < 2; side++) {
        x.sides |= inside(c, LSC_KIN_BASE, side_base(pl, side)) ? 1u << side : 0u;
    }
    pl->sides = x.sides; /* a side whose base is beyond its limit: none of its solutions */
    solve s = solve_pitch(c, pl, p0, near, q, false, -1);
    if (s.status == LSC_KIN_OK) {
        return s;
    }
    for (int i = 0; i < LSC_KIN_ROLL; i++) {
        x.lo[i] = c->min_deg[i] - LSC_KIN_LIMIT_SLACK_DEG;
        x.hi[i] = c->max_deg[i] + LSC_KIN_LIMIT_SLACK_DEG;
        x.mid[i] = (c->min_deg[i] + c->max_deg[i]) / 2.0f;
    }
    points(&x, pl);
    /* the point's pitch; a rounding may put a joint there beyond its limit
     * by more than the slack (where the arm is nearly straight a joint turns
     * fast with the pitch): then a little further into the arc, away from p0 */
    float step = wrap(x.best_p - p0) >= 0.0f ? NUDGE_DEG : -NUDGE_DEG;
    for (int k = 0; k < (x.found ? NUDGES : 0); k++) {
        *p = wrap(x.best_p + step * (float)k * (float)k);
        s = solve_pitch(c, pl, *p, near, q, false, x.best_hint);
        if (s.status == LSC_KIN_OK) {
            return s;
        }
    }
    return refusal(c, pl, near, p0, p);
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

/* The checks every inverse makes, and the target's plane: true if fine. */
static bool setup(const lsc_kin_chain *c, const lsc_kin_target *t, const float *from, plane *pl)
{
    if (!lsc_kin_chain_valid(c) || t == NULL || !angles_ok(from) ||
        !within(t->x_mm, LSC_KIN_MM_MAX) || !within(t->y_mm, LSC_KIN_MM_MAX) ||
        !within(t->z_mm, LSC_KIN_MM_MAX) || (t->has_pitch && !within(t->pitch_deg, ANGLE_MAX)) ||
        (t->has_roll && !within(t->roll_deg, ANGLE_MAX))) {
        return false;
    }
    pl->r = sqrtf(t->x_mm * t->x_mm + t->y_mm * t->y_mm);
    pl->b = pl->r < LSC_KIN_AXIS_MM ? wrap(from[LSC_KIN_BASE]) : atan2_deg(t->y_mm, t->x_mm);
    pl->z = t->z_mm - c->base_mm;
    pl->roll = t->has_roll ? t->roll_deg : from[LSC_KIN_ROLL];
    pl->sides = 3u;
    return true;
}

static const float zeros[LSC_KIN_JOINTS] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};

int lsc_kin_inverse(const lsc_kin_chain *c, const lsc_kin_target *t, const float *near,
                    float *q, lsc_kin_result *res)
{
    solve s = {LSC_KIN_BAD_INPUT, 0.0f, 0.0f, 0, false, 0.0f};
    const float *from = near != NULL ? near : zeros;
    float sol[LSC_KIN_JOINTS] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    float p = 0.0f;
    plane pl;
    if (q == NULL || !setup(c, t, from, &pl)) {
        return report(res, &s, p);
    }
    if (t->has_pitch) {
        p = wrap(t->pitch_deg);
        s = solve_pitch(c, &pl, p, from, sol, true, -1);
    } else {
        s = free_pitch(c, &pl, from, sol, &p);
    }
    if (s.status == LSC_KIN_OK) {
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            q[i] = sol[i];
        }
    }
    return report(res, &s, p);
}

/* Sorts v[0..n) up (n small: insertion). */
static void sort(float *v, size_t n)
{
    for (size_t i = 1; i < n; i++) {
        float x = v[i];
        size_t j = i;
        for (; j > 0 && v[j - 1] > x; j--) {
            v[j] = v[j - 1];
        }
        v[j] = x;
    }
}

/* points(): the shoulder's and the wrist's 3 angles at most x 2 sides x 2
 * (the two circles meet twice), the elbow's straight, folded and 2 limits */
#define POINTS_MAX 40

int lsc_kin_pitches(const lsc_kin_chain *c, const lsc_kin_target *t, const float *near, float *lo,
                    float *hi, size_t cap)
{
    const float *from = near != NULL ? near : zeros;
    float at[POINTS_MAX], sol[LSC_KIN_JOINTS];
    bool point[POINTS_MAX], arc_ok[POINTS_MAX];
    plane pl;
    if (!setup(c, t, from, &pl) || (cap > 0 && (lo == NULL || hi == NULL))) {
        return LSC_EINVAL;
    }
    if (!inside(c, LSC_KIN_ROLL, pl.roll)) {
        return 0; /* the roll's limit holds for every pitch */
    }
    search x = {c, {0.0f}, {0.0f}, {0.0f}, 0.0f, 0u, false, 0.0f, 0.0f, 0, at, 0};
    for (int side = 0; side < 2; side++) {
        x.sides |= inside(c, LSC_KIN_BASE, side_base(&pl, side)) ? 1u << side : 0u;
    }
    points(&x, &pl);
    size_t n = x.n, k = 0;
    if (n == 0) {
        at[n++] = 0.0f; /* no point: every pitch alike */
    }
    sort(at, n);
    /* the points and the arcs between them (the last past 180 to the
     * first): each feasible or not as its middle is */
    bool all = true;
    for (size_t i = 0; i < n; i++) {
        float b = i + 1 < n ? at[i + 1] : at[0] + 360.0f;
        point[i] = solve_pitch(c, &pl, at[i], from, sol, false, -1).status == LSC_KIN_OK;
        arc_ok[i] = solve_pitch(c, &pl, wrap((at[i] + b) / 2.0f), from, sol, false, -1).status ==
                 LSC_KIN_OK;
        all = all && arc_ok[i];
        k = arc_ok[i] ? k : (i + 1) % n; /* a point after an arc not feasible */
    }
    if (all) {
        if (cap > 0) {
            lo[0] = -180.0f;
            hi[0] = 180.0f;
        }
        return 1;
    }
    /* the runs of feasible points and arcs, from a point after one that is
     * not: each from a point to a point */
    int arcs = 0;
    bool open = false;
    for (size_t m = 0; m < n; m++) {
        size_t i = (k + m) % n;
        if (!open && (point[i] || arc_ok[i])) {
            open = true;
            if ((size_t)arcs < cap) {
                lo[arcs] = at[i];
            }
        }
        if (open && !arc_ok[i]) {
            open = false;
            if ((size_t)arcs < cap) {
                hi[arcs] = at[i];
            }
            arcs++;
        }
    }
    return arcs;
}

/* ---- near an end ---------------------------------------------------------- */

unsigned lsc_kin_near_ends(const lsc_kin_chain *c, const float *q, float margin_deg)
{
    unsigned out = 0u;
    if (!lsc_kin_chain_valid(c) || q == NULL || !angles_ok(q) || !within(margin_deg, LIMIT_MAX)) {
        return 0u;
    }
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        out |= q[i] <= c->min_deg[i] + margin_deg ? LSC_KIN_NEAR_LOW(i) : 0u;
        out |= q[i] >= c->max_deg[i] - margin_deg ? LSC_KIN_NEAR_HIGH(i) : 0u;
    }
    return out;
}
