/*
 * lsc kinematics: joint angles <-> the position of the hand, for the 5-joint
 * chain of the xArm and the LeArm (docs/kinematics.md has the drawing).
 * Portable C99 with float arithmetic only (sinf, cosf, atan2f, sqrtf from
 * <math.h>), no allocation, no mutable static state: builds for AVR and
 * Cortex-M and runs on an Arduino Uno.
 *
 * Conventions (millimetres and degrees):
 * - the origin is on the table under the base's axis; z points up, x forward
 *   when the base is at 0, y to the left (right-handed);
 * - the angles are the arm profile's joint angles (lsc/arm.h); with every
 *   joint at 0 the arm stands straight up;
 * - the base turns about z: a positive angle turns +x toward +y;
 * - shoulder, elbow and wrist pitch turn about axes parallel to y (after the
 *   base's turn): a positive angle leans the arm toward +x;
 * - the wrist roll turns the hand about its own axis (the grasp point does
 *   not move);
 * - the tool point is the grasp point between the fingers; the pitch is the
 *   angle of the hand's axis from the horizontal: 0 forward, -90 straight
 *   down, +90 straight up.
 *
 * So, in the vertical plane of the base (r horizontal, z up), with
 * a1 = shoulder, a2 = a1 + elbow, a3 = a2 + wrist (each from the vertical):
 *   r = upper sin a1 + fore sin a2 + tool sin a3
 *   z = base + upper cos a1 + fore cos a2 + tool cos a3
 *   pitch = 90 - a3
 * and x = r cos(base angle), y = r sin(base angle).
 *
 * Errors: 0, or LSC_EINVAL with the reason in the result (lsc_kin_result).
 */
#ifndef LSC_KINEMATICS_H
#define LSC_KINEMATICS_H

#include <stdbool.h>
#include <stddef.h>

#include "lsc/core.h" /* LSC_API, error codes */

#ifdef __cplusplus
extern "C" {
#endif

/* The joints of the chain, the index of each in angle arrays. */
typedef enum lsc_kin_joint {
    LSC_KIN_BASE = 0,     /* base yaw, about z */
    LSC_KIN_SHOULDER = 1, /* about y */
    LSC_KIN_ELBOW = 2,    /* about y */
    LSC_KIN_WRIST = 3,    /* wrist pitch, about y */
    LSC_KIN_ROLL = 4      /* wrist roll, about the hand's axis */
} lsc_kin_joint;
#define LSC_KIN_JOINTS 5

/* Largest length and coordinate accepted, in mm (|value|). */
#define LSC_KIN_MM_MAX 100000.0f
/* An angle may exceed a limit by this much (rounding) and is then put on it. */
#define LSC_KIN_LIMIT_SLACK_DEG 0.001f
/* A target closer than this to the base's axis keeps the base where it is. */
#define LSC_KIN_AXIS_MM 0.001f
/* A target out of reach by at most this much is taken as on its edge. */
#define LSC_KIN_EDGE_MM 0.001f

/* The chain: lengths in mm and the joints' limits in degrees. */
typedef struct lsc_kin_chain {
    float base_mm;  /* shoulder axis above the table (>= 0) */
    float upper_mm; /* shoulder axis to elbow axis (> 0) */
    float fore_mm;  /* elbow axis to wrist pitch axis (> 0) */
    float tool_mm;  /* wrist pitch axis to the grasp point (>= 0) */
    float min_deg[LSC_KIN_JOINTS]; /* limits, min_deg[i] <= max_deg[i] */
    float max_deg[LSC_KIN_JOINTS];
} lsc_kin_chain;

/* Where the grasp point is and how the hand points. */
typedef struct lsc_kin_pose {
    float x_mm, y_mm, z_mm;
    float pitch_deg; /* -180 < pitch <= 180 */
    float roll_deg;  /* the wrist roll joint's angle */
} lsc_kin_pose;

/* Where the grasp point should go: x, y, z; the pitch and the roll when
 * has_pitch / has_roll (else the pitch is chosen, and the roll stays). */
typedef struct lsc_kin_target {
    float x_mm, y_mm, z_mm;
    float pitch_deg, roll_deg;
    bool has_pitch, has_roll;
} lsc_kin_target;

typedef enum lsc_kin_status {
    LSC_KIN_OK = 0,
    LSC_KIN_BAD_INPUT = 1,    /* NULL, a length or limit refused, a value not finite */
    LSC_KIN_OUT_OF_REACH = 2, /* no joint angles reach it: by_mm says by how much */
    LSC_KIN_BEYOND_LIMIT = 3  /* reachable only beyond joint's limit (high: its max) */
} lsc_kin_status;

/* Why an inverse failed, and the pitch it used. */
typedef struct lsc_kin_result {
    lsc_kin_status status;
    float by_mm;     /* OUT_OF_REACH: how far the target is beyond the reach */
    int joint;       /* BEYOND_LIMIT: the first joint (lsc_kin_joint) beyond ... */
    bool high;       /* ... its max_deg (true) or its min_deg (false) */
    float angle_deg; /* ... the angle it would need */
    float pitch_deg; /* the pitch solved for (given, or chosen; OK and BEYOND_LIMIT) */
} lsc_kin_result;

/* Whether c is a chain the functions accept: lengths finite within
 * 0..LSC_KIN_MM_MAX, upper and fore above 0, limits finite within
 * -360..360 with min <= max. */
LSC_API bool lsc_kin_chain_valid(const lsc_kin_chain *c);

/* Forward kinematics: the pose of joint angles q[LSC_KIN_JOINTS] (degrees,
 * finite, |q| <= 3600; limits are not checked). Returns 0 and *out, or
 * LSC_EINVAL (an argument NULL, c not valid, an angle refused). Time:
 * constant (four sines and cosines, one atan2). */
LSC_API int lsc_kin_forward(const lsc_kin_chain *c, const float *q, lsc_kin_pose *out);

/* Inverse kinematics in closed form. near[LSC_KIN_JOINTS] are the current
 * angles (NULL: all 0); of the solutions (the base toward the target or
 * turned half round and leaning back; elbow bent one way or the other) the
 * first within the limits in this order goes to q[LSC_KIN_JOINTS], every
 * angle within -180..180 and within its limits: the side whose base is
 * within its limits and nearer near's base, then the elbow bent as near's
 * (its sign; 0 counts as +). The roll is t->roll_deg, or near's.
 * Singular targets: on the base's axis (closer than LSC_KIN_AXIS_MM) the base
 * keeps near's angle; with the arm straight the two elbow solutions are one.
 * Without a pitch (t->has_pitch false) the pitch is chosen over the whole
 * circle: the present one (the pose of near) if it reaches the target within
 * the limits, else the nearest pitch that does (of two as near, the lower).
 * That pitch is exact, not searched on a grid: the pitches that reach a
 * target within the limits are arcs whose ends are where a joint meets a
 * limit or the arm is straight or folded, each found in closed form (two
 * circles' intersection); lsc_kin_pitches lists the arcs.
 * Returns 0 (res->status LSC_KIN_OK, res->pitch_deg), or LSC_EINVAL with
 * res->status (res may be NULL; q is written only on success):
 *   LSC_KIN_BAD_INPUT     an argument NULL, c not valid, a value not finite
 *                         or beyond LSC_KIN_MM_MAX / 3600 degrees;
 *   LSC_KIN_OUT_OF_REACH  res->by_mm: how far the wrist would have to be
 *                         beyond (or inside) the reach of upper and fore.
 *                         Without a pitch: at every pitch, by_mm the least
 *                         (res->pitch_deg the pitch of the least);
 *   LSC_KIN_BEYOND_LIMIT  of the solutions, the one least beyond its limits
 *                         (the sum of the excesses): its first joint beyond
 *                         one (res->joint, res->high, res->angle_deg).
 *                         Without a pitch no pitch reaches the target within
 *                         the limits: the base or the roll (beyond at every
 *                         pitch: the base on both sides), else the joint of
 *                         the pitch nearest the present one that reaches it
 *                         (res->pitch_deg), of the solutions whose base is
 *                         within its limits.
 * Time: with a pitch constant (1 sin, 3 sqrt and 4 atan2 when the first
 * solution tried is within the limits, at most 7 atan2); without one that
 * solve at the present pitch, and when it fails a bounded number of
 * closed-form points (about 20 acos/atan2 for the xArm) and one more solve
 * (docs/kinematics.md has the figures on a PC and on an Uno). */
LSC_API int lsc_kin_inverse(const lsc_kin_chain *c, const lsc_kin_target *t, const float *near,
                            float *q, lsc_kin_result *res);

/* The pitches at which t's point (its pitch is ignored; its roll and near as
 * lsc_kin_inverse takes them) is reached within the limits: arcs of the
 * circle, the i-th from lo[i] up to hi[i] (degrees in -180..180; through 180
 * when lo[i] > hi[i]; the whole circle is -180..180, a single pitch lo ==
 * hi), in order, up to cap of them written. Returns how many arcs there are
 * (0: no pitch; may exceed cap), or LSC_EINVAL (c, t, near refused as
 * lsc_kin_inverse refuses them; lo or hi NULL with cap > 0). Time: about 80
 * solves at a given pitch at most. */
LSC_API int lsc_kin_pitches(const lsc_kin_chain *c, const lsc_kin_target *t, const float *near,
                            float *lo, float *hi, size_t cap);

/* A joint within this many degrees of an end of its limits is near its end
 * (lscctl where says so). */
#define LSC_KIN_NEAR_END_DEG 5.0f
/* The bits of lsc_kin_near_ends: joint i (lsc_kin_joint) near its lower
 * limit, near its upper limit. */
#define LSC_KIN_NEAR_LOW(i) (1u << (i))
#define LSC_KIN_NEAR_HIGH(i) (1u << ((i) + 8))

/* Which joints at angles q[LSC_KIN_JOINTS] are within margin_deg of an end
 * of their limits, or beyond it: LSC_KIN_NEAR_LOW(i) when q[i] <=
 * min_deg[i] + margin_deg, LSC_KIN_NEAR_HIGH(i) when q[i] >= max_deg[i] -
 * margin_deg (both for a range narrower than twice the margin). 0 when c is
 * not valid, q NULL or an angle or the margin not finite (|margin| <= 360). */
LSC_API unsigned lsc_kin_near_ends(const lsc_kin_chain *c, const float *q, float margin_deg);

#ifdef __cplusplus
}
#endif

#endif /* LSC_KINEMATICS_H */
