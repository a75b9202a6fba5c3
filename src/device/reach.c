/* lsc device: the hand through the arm profile's geometry (contract in
 * lsc/device.h, the kinematics in lsc/kinematics.h): the last known
 * positions, a move's time from a speed and the move at a speed, where the grasp point is, and reach
 * (a point, or a straight line of waypoints, every one checked before the
 * first is sent). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"

#define SPEED_MIN 0.01f   /* degrees a second */
#define SPEED_MAX 100000.0f
#define STEP_MIN 0.1f     /* mm between waypoints */
#define STEP_MAX 1000.0f
#define TIME_DEFAULT 1000u /* ms: a move's, as lscctl move's */
#define TIME_MAX 65535.0f

/* from[0..n): the last positions of ids[0..n) (n <= LSC_MOVE_MAX), those not
 * known read first. */
static int last_positions(lsc_device *d, const uint8_t *ids, size_t n, uint16_t *from)
{
    uint8_t ask[LSC_MOVE_MAX];
    lsc_servo got[LSC_MOVE_MAX];
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (lsc_device_last_position(d, ids[i], &from[i]) != 0) {
            ask[m++] = ids[i];
        }
    }
    if (m > 0) { /* LSC_MOVE_MAX <= LSC_READ_MAX: one read */
        int r = lsc_dev_read_positions(d, ask, m, got);
        if (r < 0) {
            return r;
        }
        for (size_t i = 0; i < n; i++) {
            (void)lsc_device_last_position(d, ids[i], &from[i]);
        }
    }
    return 0;
}

/* The angle of servo s on joint j (of the profile), or why not. */
static int angle_of(lsc_device *d, const lsc_joint *j, uint16_t pos, int32_t *cdeg)
{
    if (lsc_joint_to_cdeg(j, pos, cdeg) != 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "servo %u is at position %u, outside its joint's range %u..%u: "
                            "move it into the range first; nothing was sent",
                            j->id, pos, j->pos_min, j->pos_max);
    }
    return 0;
}

/* The speed's checks: 0, or why not. */
static int check_speed(lsc_device *d, float speed_dps)
{
    if (!(speed_dps >= SPEED_MIN && speed_dps <= SPEED_MAX)) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "a speed of %g degrees a second: give 0.01..100000; nothing was "
                            "sent",
                            (double)speed_dps);
    }
    return 0;
}

/* ms to turn by deg at speed_dps (checked): 1..65535, or why not. */
static int travel_time(lsc_device *d, float deg, float speed_dps, uint16_t *ms)
{
    float t = ceilf(deg * 1000.0f / speed_dps);
    if (t > TIME_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "turning %.2f degrees at %g degrees a second takes longer than "
                            "65535 ms: raise the speed; nothing was sent",
                            (double)deg, (double)speed_dps);
    }
    *ms = t < 1.0f ? (uint16_t)1u : (uint16_t)t;
    return 0;
}

int lsc_device_move_time(lsc_device *d, const lsc_servo *servos, size_t n, float speed_dps,
                         uint16_t *time_ms)
{
    uint8_t ids[LSC_MOVE_MAX];
    uint16_t from[LSC_MOVE_MAX] = {0};
    const lsc_joint *joints[LSC_MOVE_MAX];
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
    if (servos == NULL || time_ms == NULL || n == 0 || n > LSC_MOVE_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "the time of a move of %lu servos: one move takes 1..%u",
                            servos == NULL ? 0ul : (unsigned long)n, LSC_MOVE_MAX);
    }
    r = check_speed(d, speed_dps);
    if (r != 0) {
        return r;
    }
    for (size_t i = 0; i < n; i++) {
        int k = lsc_arm_by_id(d->arm, servos[i].id);
        if (k < 0) {
            return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                "servo %u is no joint of %s: a speed in degrees a second "
                                "needs each servo's degrees; nothing was sent",
                                servos[i].id, d->arm == NULL ? "any arm profile (none is set)"
                                                             : "the arm profile");
        }
        joints[i] = lsc_arm_joint(d->arm, (size_t)k);
        ids[i] = servos[i].id;
    }
    r = last_positions(d, ids, n, from);
    float most = 0.0f;
    for (size_t i = 0; i < n && r == 0; i++) {
        int32_t a = 0, b = 0;
        r = angle_of(d, joints[i], from[i], &a);
        if (r == 0) {
            r = angle_of(d, joints[i], servos[i].position, &b);
        }
        float deg = (float)(a > b ? a - b : b - a) / 100.0f;
        most = deg > most ? deg : most;
    }
    return r != 0 ? r : travel_time(d, most, speed_dps, time_ms);
}

int lsc_device_move_speed(lsc_device *d, const lsc_servo *servos, size_t n, float speed_dps,
                          bool wait, uint16_t tolerance, unsigned flags, uint16_t *time_ms,
                          lsc_settle_result *settle)
{
    uint16_t t = 0;
    lsc_settle_result none = {0};
    if (time_ms != NULL) {
        *time_ms = 0;
    }
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = lsc_dev_sized(d, settle, LSC_SIZED_MIN(lsc_settle_result, nstopped),
                          "lsc_settle_result");
    if (r != 0) {
        return r;
    }
    none.size = sizeof none;
    lsc_sized_give(settle, &none, sizeof none); /* nstopped 0 until a wait */
    if ((flags & ~LSC_SETTLE_STRICT) != 0u) {
        r = lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                         "lsc_device_move_speed: unknown flags 0x%x; nothing was sent", flags);
    }
    if (r == 0) {
        r = lsc_device_move_time(d, servos, n, speed_dps, &t);
    }
    if (r == 0) {
        r = lsc_device_move(d, t, servos, n);
    }
    if (r != 0) {
        return r;
    }
    if (time_ms != NULL) {
        *time_ms = t;
    }
    return wait ? lsc_device_settle_ex(d, servos, n, t, tolerance, flags, settle) : 0;
}

/* ---- where and reach -------------------------------------------------------- */

/* The device's chain: 0 and *c and the joints' indexes, or why not. */
static int chain_of(lsc_device *d, lsc_kin_chain *c, int *joints)
{
    char why[LSC_ARM_MESSAGE_MAX];
    if (d->arm == NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "no arm profile: the hand's position needs one that states its "
                            "geometry (docs/kinematics.md); nothing was sent");
    }
    if (lsc_arm_chain(d->arm, c, joints, why, sizeof why) != 0) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE, "%s; nothing was sent", why);
    }
    return 0;
}

/* The angles (degrees) of the chain's five joints at positions pos[]. */
static int angles(lsc_device *d, const int *joints, const uint16_t *pos, float *q)
{
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        int32_t cdeg = 0;
        int r = angle_of(d, lsc_arm_joint(d->arm, (size_t)joints[i]), pos[i], &cdeg);
        if (r != 0) {
            return r;
        }
        q[i] = (float)cdeg / 100.0f;
    }
    return 0;
}

static void chain_ids(const lsc_device *d, const int *joints, uint8_t *ids)
{
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        ids[i] = lsc_arm_joint(d->arm, (size_t)joints[i])->id;
    }
}

int lsc_device_where(lsc_device *d, float *q, lsc_kin_pose *pose)
{
    lsc_where w;
    w.size = sizeof w;
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (pose == NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE, "lsc_device_where: no pose");
    }
    int r = lsc_device_where_ex(d, &w);
    if (r != 0) {
        return r;
    }
    *pose = w.pose;
    for (size_t i = 0; q != NULL && i < LSC_KIN_JOINTS; i++) {
        q[i] = w.q[i];
    }
    return 0;
}

int lsc_device_where_ex(lsc_device *d, lsc_where *w)
{
    lsc_where all = {0};
    lsc_kin_chain c;
    int joints[LSC_ARM_CHAIN_MAX] = {0};
    uint8_t ids[LSC_KIN_JOINTS];
    lsc_servo got[LSC_KIN_JOINTS];
    uint16_t pos[LSC_KIN_JOINTS] = {0};
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = w == NULL ? lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                     "lsc_device_where_ex: no result")
                      : lsc_dev_sized(d, w, LSC_SIZED_MIN(lsc_where, q), "lsc_where");
    if (r == 0) {
        r = chain_of(d, &c, joints);
    }
    if (r != 0) {
        return r;
    }
    chain_ids(d, joints, ids);
    r = lsc_dev_read_positions(d, ids, LSC_KIN_JOINTS, got);
    if (r < 0) {
        return r;
    }
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        pos[i] = got[i].position;
    }
    r = angles(d, joints, pos, all.q);
    if (r != 0) {
        return r;
    }
    all.size = sizeof all;
    (void)lsc_kin_forward(&c, all.q, &all.pose); /* a profile's angles: within 360 degrees */
    all.near_end = lsc_kin_near_ends(&c, all.q, LSC_KIN_NEAR_END_DEG);
    all.chain = c;
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        all.joint[i] = joints[i];
    }
    lsc_sized_give(w, &all, sizeof all);
    return 0;
}

/* A reach being planned: the chain, its joints, the waypoints. */
typedef struct plan {
    lsc_kin_chain c;
    int joints[LSC_ARM_CHAIN_MAX];
    uint8_t ids[LSC_KIN_JOINTS];
    float now[LSC_KIN_JOINTS];
    size_t n;
    float q[LSC_REACH_WAYPOINTS_MAX][LSC_KIN_JOINTS];
    lsc_servo servos[LSC_REACH_WAYPOINTS_MAX][LSC_KIN_JOINTS];
    uint16_t time_ms[LSC_REACH_WAYPOINTS_MAX];
} plan;

static const char *const joint_roles[LSC_KIN_JOINTS] = {"base", "shoulder", "elbow", "wrist",
                                                        "wrist roll"};

/* The pitches that reach t's point within the limits, for a message:
 * "; pitches A..B, C..D reach it" (at most 3 arcs, "..." after; through 180
 * when A > B), or "; no pitch reaches it within the joints' limits". */
static void pitches_hint(const plan *p, const lsc_kin_target *t, char *out, size_t cap)
{
    float lo[3], hi[3];
    lsc_kin_target any = *t;
    any.has_pitch = false;
    int n = lsc_kin_pitches(&p->c, &any, p->now, lo, hi, 3);
    /* (cap holds three arcs: no truncation) */
    size_t len = (size_t)snprintf(out, cap, "%s",
                                  n > 0 ? "; pitches" : "; no pitch reaches it within the joints' "
                                                        "limits");
    for (int i = 0; i < n && i < 3; i++) {
        len += (size_t)snprintf(out + len, cap - len, "%s %.1f..%.1f", i > 0 ? "," : "",
                                (double)lo[i], (double)hi[i]);
    }
    if (n > 0) {
        (void)snprintf(out + len, cap - len, "%s reach it", n > 3 ? ", ..." : "");
    }
}

/* Why the inverse of t failed (res: its result), k of n the waypoint. */
static int refused(lsc_device *d, const plan *p, const lsc_kin_target *t,
                   const lsc_kin_result *res, size_t k)
{
    char where[256], which[64] = "", hint[160] = "";
    if (p->n > 1) {
        (void)snprintf(which, sizeof which, "waypoint %lu of %lu, ", (unsigned long)k + 1u,
                       (unsigned long)p->n);
    } else if (t->has_pitch && res->status != LSC_KIN_BAD_INPUT) {
        pitches_hint(p, t, hint, sizeof hint);
    }
    (void)snprintf(where, sizeof where, "%s(%.1f, %.1f, %.1f) mm", which, (double)t->x_mm,
                   (double)t->y_mm, (double)t->z_mm);
    if (res->status == LSC_KIN_OUT_OF_REACH) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "%s is out of reach by %.1f mm%s%s; nothing was sent", where,
                            (double)res->by_mm, t->has_pitch ? " at that pitch" : "", hint);
    }
    if (res->status == LSC_KIN_BEYOND_LIMIT) {
        const int i = res->joint;
        const lsc_joint *j = lsc_arm_joint(d->arm, (size_t)p->joints[i]);
        char at[96] = "";
        if (!t->has_pitch && (i == LSC_KIN_BASE || i == LSC_KIN_ROLL)) {
            (void)snprintf(at, sizeof at, " at every pitch");
        } else if (!t->has_pitch) { /* the reason differs from pitch to pitch */
            (void)snprintf(where + strlen(where), sizeof where - strlen(where),
                           " is within reach but at no pitch within the joints' limits: at "
                           "pitch %.1f (the nearest that reaches it) it",
                           (double)res->pitch_deg);
        }
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "%s needs joint %s (the %s, servo %u) at %.2fdeg, beyond its %s "
                            "limit %.2fdeg%s%s; nothing was sent",
                            where, lsc_arm_name(d->arm, (size_t)p->joints[i]), joint_roles[i],
                            j->id, (double)res->angle_deg, res->high ? "upper" : "lower",
                            (double)(res->high ? p->c.max_deg[i] : p->c.min_deg[i]), at, hint);
    }
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "%s: the target or the profile's geometry is refused (a value not "
                        "finite or too large); nothing was sent",
                        where);
}

/* Waypoint k's positions from its angles: each within its joint's limits. */
static int positions(lsc_device *d, plan *p, size_t k)
{
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        const lsc_joint *j = lsc_arm_joint(d->arm, (size_t)p->joints[i]);
        float a = p->q[k][i] * 100.0f;
        int32_t cdeg = (int32_t)(a >= 0.0f ? a + 0.5f : a - 0.5f);
        uint16_t pos = 0;
        int r = lsc_joint_to_pos(j, cdeg, &pos);
        if (r == 0 && !lsc_joint_allows_pos(j, pos)) {
            /* the angle is within the joint's limits (the chain's are the
             * joint's), its nearest position just beyond one (the pitch
             * chosen often puts an angle on a limit): the next one inside
             * is allowed (a profile's limits hold a position) */
            uint16_t below = (uint16_t)(pos - 1u);
            pos = lsc_joint_allows_pos(j, below) ? below : (uint16_t)(pos + 1u);
        }
        if (r != 0) {
            return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                "joint %s (servo %u) at %.2fdeg: its nearest position is "
                                "outside its limits; nothing was sent",
                                lsc_arm_name(d->arm, (size_t)p->joints[i]), j->id,
                                (double)p->q[k][i]);
        }
        p->servos[k][i].id = j->id;
        p->servos[k][i].position = pos;
    }
    return 0;
}

static float lerp(float a, float b, float f)
{
    return a + (b - a) * f;
}

/* The waypoints of r: one, or the line's. */
static int solve(lsc_device *d, plan *p, const lsc_reach *r, lsc_kin_result *res)
{
    lsc_kin_target end = r->target;
    lsc_kin_pose from;
    p->n = 1;
    if (lsc_kin_inverse(&p->c, &end, p->now, p->q[0], res) != 0) {
        return refused(d, p, &end, res, 0);
    }
    if (!r->line) {
        return 0;
    }
    /* the line: from where the hand is to there, the pitch (the one chosen
     * if none was given) and the roll turning evenly */
    end.has_pitch = true;
    end.pitch_deg = res->pitch_deg;
    (void)lsc_kin_forward(&p->c, p->now, &from);
    float dx = end.x_mm - from.x_mm, dy = end.y_mm - from.y_mm, dz = end.z_mm - from.z_mm;
    float len = sqrtf(dx * dx + dy * dy + dz * dz);
    float step = r->step_mm > 0.0f ? r->step_mm : LSC_REACH_STEP_MM;
    float segments = ceilf(len / step);
    p->n = segments < 1.0f                                ? 1u
           : segments > (float)LSC_REACH_WAYPOINTS_MAX ? LSC_REACH_WAYPOINTS_MAX
                                                         : (size_t)segments;
    float turn = end.pitch_deg - from.pitch_deg;
    const float *near = p->now;
    for (size_t k = 0; k < p->n; k++) {
        float f = (float)(k + 1u) / (float)p->n;
        lsc_kin_target t = {lerp(from.x_mm, end.x_mm, f), lerp(from.y_mm, end.y_mm, f),
                            lerp(from.z_mm, end.z_mm, f), from.pitch_deg + turn * f,
                            lerp(p->now[LSC_KIN_ROLL], end.roll_deg, f), true, end.has_roll};
        if (lsc_kin_inverse(&p->c, &t, near, p->q[k], res) != 0) {
            return refused(d, p, &t, res, k);
        }
        near = p->q[k];
    }
    res->pitch_deg = end.pitch_deg;
    return 0;
}

/* Each move's time: the given time shared evenly, or from the speed. */
static int times(lsc_device *d, plan *p, const lsc_reach *r)
{
    if (r->speed_dps > 0.0f) {
        float most = 0.0f;
        const float *before = p->now;
        for (size_t k = 0; k < p->n; k++) {
            for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
                float deg = fabsf(p->q[k][i] - before[i]);
                most = deg > most ? deg : most;
            }
            before = p->q[k];
        }
        uint16_t ms = 0;
        int e = travel_time(d, most, r->speed_dps, &ms);
        for (size_t k = 0; e == 0 && k < p->n; k++) {
            p->time_ms[k] = ms;
        }
        return e;
    }
    uint32_t total = r->time_ms > 0 ? r->time_ms : TIME_DEFAULT;
    for (size_t k = 0; k < p->n; k++) {
        p->time_ms[k] = (uint16_t)(total * (k + 1u) / p->n - total * k / p->n);
    }
    return 0;
}

/* r's own checks: 0, or why not. */
static int check_reach(lsc_device *d, const lsc_reach *r)
{
    if (r->speed_dps != 0.0f) {
        int e = check_speed(d, r->speed_dps);
        if (e != 0) {
            return e;
        }
    }
    if ((r->flags & ~LSC_SETTLE_STRICT) != 0u) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "lsc_device_reach: unknown flags 0x%x; nothing was sent", r->flags);
    }
    if (r->line && r->step_mm != 0.0f && !(r->step_mm >= STEP_MIN && r->step_mm <= STEP_MAX)) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "a step of %g mm between waypoints: give 0.1..1000; nothing was "
                            "sent",
                            (double)r->step_mm);
    }
    return 0;
}

static int reach_planned(lsc_device *d, plan *p, const lsc_reach *r, lsc_reach_result *res)
{
    uint16_t pos[LSC_KIN_JOINTS] = {0};
    int e = check_reach(d, r);
    if (e == 0) {
        e = chain_of(d, &p->c, p->joints);
    }
    if (e != 0) {
        return e;
    }
    chain_ids(d, p->joints, p->ids);
    /* refused whatever the current angles: before anything is read. Only a
     * target on the base's axis depends on them (the base stays); the roll
     * not given stays too: in the middle of its limits here */
    float mid[LSC_KIN_JOINTS];
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        mid[i] = (p->c.min_deg[i] + p->c.max_deg[i]) / 2.0f;
    }
    if (lsc_kin_inverse(&p->c, &r->target, mid, p->q[0], &res->kin) != 0 &&
        (res->kin.status != LSC_KIN_BEYOND_LIMIT ||
         hypotf(r->target.x_mm, r->target.y_mm) >= LSC_KIN_AXIS_MM)) {
        p->n = 1;
        res->waypoints = 1;
        return refused(d, p, &r->target, &res->kin, 0);
    }
    e = last_positions(d, p->ids, LSC_KIN_JOINTS, pos);
    if (e == 0) {
        e = angles(d, p->joints, pos, p->now);
    }
    if (e == 0) {
        e = solve(d, p, r, &res->kin);
    }
    res->waypoints = p->n;
    for (size_t k = 0; e == 0 && k < p->n; k++) {
        e = positions(d, p, k);
    }
    if (e == 0) {
        e = times(d, p, r);
    }
    if (e != 0) {
        return e;
    }
    for (size_t k = 0; k < p->n; k++) {
        /* each move when the one before has had its time */
        e = k > 0 ? lsc_device_poll(d, p->time_ms[k - 1u]) : 0;
        if (e >= 0) {
            e = lsc_device_move(d, p->time_ms[k], p->servos[k], LSC_KIN_JOINTS);
        }
        if (e < 0) {
            return e;
        }
        res->time_ms += p->time_ms[k];
    }
    size_t last = p->n - 1u;
    return r->wait ? lsc_device_settle_ex(d, p->servos[last], LSC_KIN_JOINTS, p->time_ms[last],
                                          r->tolerance, r->flags, &res->settle)
                   : 0;
}

int lsc_device_reach(lsc_device *d, const lsc_reach *r, lsc_reach_result *res)
{
    lsc_reach in;
    lsc_reach_result all = {0};
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    if (r == NULL) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "lsc_device_reach: no reach; nothing was sent");
    }
    int e = lsc_dev_sized(d, r, LSC_SIZED_MIN(lsc_reach, target), "lsc_reach");
    if (e == 0) {
        e = lsc_dev_sized(d, res, LSC_SIZED_MIN(lsc_reach_result, kin), "lsc_reach_result");
    }
    if (e != 0) {
        return e;
    }
    lsc_sized_take(&in, r, sizeof in); /* beyond the caller's size: as if 0 */
    plan *p = calloc(1, sizeof *p); /* the waypoints: about 12 KiB */
    if (p == NULL) {
        return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE, "out of memory");
    }
    all.size = sizeof all;
    all.settle.size = sizeof all.settle;
    e = reach_planned(d, p, &in, &all);
    free(p);
    lsc_sized_give(res, &all, sizeof all);
    return e;
}

#endif
