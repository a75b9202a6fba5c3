/*
 * lsc motion: what a device (lsc/device.h) does with servos beyond one frame:
 * a move's wait (settle), a move timed by a speed, where the hand is and a
 * move of the grasp point through the arm profile's geometry
 * (lsc/kinematics.h), and holding or halting everything where it is.
 *
 * Host only. Errors as lsc/device.h says: 0 (or a positive outcome named
 * here) or a negative LSC_E... code, lsc_device_error(d) its line.
 */
#ifndef LSC_MOTION_H
#define LSC_MOTION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/device.h"
#include "lsc/kinematics.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_DEVICE_TOLERANCE_DEFAULT 10u /* positions, for lsc_device_settle */

/* ---- A move's wait ------------------------------------------------------------ */

/* A move's wait: lets time_ms pass (queueing what arrives), then reads the
 * positions of targets[0..n) (n 1..LSC_READ_MAX), every 20 ms, until each is
 * within tolerance of its target, or has stopped short of it (see
 * lsc_device_settle_ex, of which this is the strict form). Returns 0 when they are; 1 when the
 * controller does not answer position reads (some LSC boards: the move's
 * time has passed, which is all there is to wait for; lsc_device_error then
 * says so); LSC_ETIMEOUT (the message names the first servo outside, where
 * it is and its target) when they are not within the device's timeout after
 * time_ms, or at once when one stopped short (cause
 * LSC_DEVICE_CAUSE_STOPPED_SHORT); or a request's error. */
LSC_API int lsc_device_settle(lsc_device *d, const lsc_servo *targets, size_t n,
                              uint16_t time_ms, uint16_t tolerance);

/* A servo stops short of its target when, outside the tolerance, its
 * position reads stay within LSC_SETTLE_STILL of each other for
 * LSC_SETTLE_STILL_MS (a gripper closed on an object, a joint against an
 * obstacle): waiting longer cannot bring it there. */
#define LSC_SETTLE_STILL_MS 200u
#define LSC_SETTLE_STILL 3u /* positions */
#define LSC_SETTLE_STRICT 1u /* lsc_device_settle_ex flag: a servo stopping short is an error */
/* lsc_device_settle_ex's positive outcomes (0: every servo arrived). */
#define LSC_SETTLE_NO_READS 1 /* the controller does not answer position reads */
#define LSC_SETTLE_STOPPED 2  /* some servos stopped short (listed in the result) */

/* A servo that stopped short: where, and its target. */
typedef struct lsc_settle_stop {
    uint8_t id;
    uint16_t position;
    uint16_t target;
} lsc_settle_stop;

/* What lsc_device_settle_ex saw: the servos that stopped short, in the
 * order of targets. The caller sets size to sizeof(lsc_settle_result) of its
 * headers: fields are only ever added at the end, and those beyond size are
 * not written (a size smaller than the size field and nstopped is
 * LSC_EINVAL, nothing sent). */
typedef struct lsc_settle_result {
    size_t size;
    size_t nstopped;
    lsc_settle_stop stopped[LSC_READ_MAX];
} lsc_settle_result;

/* lsc_device_settle that understands a servo held short of its target: the
 * wait ends as soon as every servo is within tolerance or has stopped short
 * (LSC_SETTLE_STILL_MS after it stopped), not after the timeout. Returns 0
 * (all arrived), LSC_SETTLE_NO_READS (as lsc_device_settle's 1),
 * LSC_SETTLE_STOPPED (some stopped short: *out lists them, and
 * lsc_device_error says "servo 1 stopped at 600, 100 short of its target
 * 700"); with flags LSC_SETTLE_STRICT a stop short is LSC_ETIMEOUT (cause
 * LSC_DEVICE_CAUSE_STOPPED_SHORT, the same message) instead; LSC_ETIMEOUT
 * (cause LSC_DEVICE_CAUSE_NOT_SETTLED) when a servo still moving is not
 * there within the device's timeout after time_ms; LSC_EINVAL (n not 1..LSC_READ_MAX, an unknown flag,
 * out->size too small); or a request's error. out may be NULL; it is filled
 * (up to out->size bytes) on every return after the reads began (nstopped 0
 * otherwise; nothing is written when d is NULL or out->size too small). lsc_device_settle is this with
 * LSC_SETTLE_STRICT. */
LSC_API int lsc_device_settle_ex(lsc_device *d, const lsc_servo *targets, size_t n,
                                 uint16_t time_ms, uint16_t tolerance, unsigned flags,
                                 lsc_settle_result *out);

/* ---- The hand: the arm profile's geometry (lsc/kinematics.h) ------------------- */

#define LSC_REACH_STEP_MM 5.0f     /* reach's line: waypoints at most this far apart */
#define LSC_REACH_WAYPOINTS_MAX 256u /* ... and at most this many (longer: wider apart) */

/* The position of servo id that d last commanded (lsc_device_move) or read
 * (lsc_device_read, lsc_device_settle): 0 and *pos, or LSC_EINVAL when there
 * is none yet (or d or pos NULL). */
LSC_API int lsc_device_last_position(const lsc_device *d, uint8_t id, uint16_t *pos);

/* The time of a move of servos[0..n) (n 1..LSC_MOVE_MAX) at speed_dps
 * degrees a second for the joint that turns the most: each servo's travel
 * from its last position (lsc_device_last_position; those not known are read
 * first), in degrees of its joint of the device's arm profile. Rounded up to
 * a whole ms, at least 1, at most 65535 (a longer one is LSC_EINVAL: "lower
 * the speed's travel..."). LSC_EINVAL (nothing sent): speed_dps not within
 * 0.01..100000, no arm profile, a servo that is no joint of it, n or servos
 * refused; or a read's error. */
LSC_API int lsc_device_move_time(lsc_device *d, const lsc_servo *servos, size_t n,
                                 float speed_dps, uint16_t *time_ms);

/* A move of servos[0..n) at speed_dps degrees a second for the joint that
 * turns the most: its time from lsc_device_move_time (the same rule and
 * checks), then lsc_device_move over that time; with wait, then the wait of
 * lsc_device_settle_ex with tolerance and flags (0 or LSC_SETTLE_STRICT).
 * *time_ms (may be NULL) is the move's time once it was sent, else 0;
 * settle (may be NULL) is filled as lsc_device_settle_ex fills it (nstopped
 * 0 without a wait). Returns 0, or with wait lsc_device_settle_ex's positive
 * outcomes (LSC_SETTLE_NO_READS, LSC_SETTLE_STOPPED); LSC_EINVAL with nothing
 * sent (lsc_device_move_time's refusals, lsc_device_move's, flags unknown,
 * settle->size too small);
 * or a read's, the move's or the wait's error. What lscctl move --speed
 * does. */
LSC_API int lsc_device_move_speed(lsc_device *d, const lsc_servo *servos, size_t n,
                                  float speed_dps, bool wait, uint16_t tolerance,
                                  unsigned flags, uint16_t *time_ms,
                                  lsc_settle_result *settle);

/* Where the hand is: reads the joints of the arm profile's chain (five, base
 * to wrist roll) and gives their angles q[LSC_KIN_JOINTS] (q may be NULL)
 * and the pose they put the grasp point in (lsc_kin_forward). LSC_EINVAL
 * without an arm profile or without its geometry (the message says what to
 * add); a read's error. */
LSC_API int lsc_device_where(lsc_device *d, float *q, lsc_kin_pose *pose);

/* Where the hand is, and which joints are near an end of their limits. The
 * caller sets size to sizeof(lsc_where) of its headers: fields are only ever
 * added at the end, and those beyond size are not written (a size smaller
 * than the size field and q is LSC_EINVAL). */
typedef struct lsc_where {
    size_t size;
    float q[LSC_KIN_JOINTS]; /* the chain's angles, base to wrist roll (degrees) */
    lsc_kin_pose pose;       /* where they put the grasp point (lsc_kin_forward) */
    unsigned near_end;       /* lsc_kin_near_ends(&chain, q, LSC_KIN_NEAR_END_DEG):
                              * LSC_KIN_NEAR_LOW(i) / LSC_KIN_NEAR_HIGH(i) bits */
    lsc_kin_chain chain;     /* the profile's chain: lengths and limits */
    int joint[LSC_KIN_JOINTS]; /* each chain joint's index in the profile (lsc_arm_name) */
} lsc_where;

/* lsc_device_where with the joints near an end of their limits (within
 * LSC_KIN_NEAR_END_DEG, 5 degrees) and the chain they are judged by: what
 * lscctl where prints, and a front end can show. Returns as
 * lsc_device_where does (w NULL, w->size too small: LSC_EINVAL). */
LSC_API int lsc_device_where_ex(lsc_device *d, lsc_where *w);

/* A move of the grasp point (lsc_device_reach). The caller sets size to
 * sizeof(lsc_reach) of its headers: fields are only ever added at the end,
 * and those beyond size take their default, as if 0 (a size smaller than the
 * size field and target is LSC_EINVAL). In C99:
 *     lsc_reach r = { .size = sizeof r, .target = { 150.0f, 0.0f, 100.0f } }; */
typedef struct lsc_reach {
    size_t size;
    lsc_kin_target target; /* where, and the pitch and roll if given */
    uint16_t time_ms;      /* the whole move's time when speed_dps is 0 (0: 1000) */
    float speed_dps;       /* > 0: timed by the joint that turns the most, at this speed */
    bool line;             /* keep the grasp point on the straight segment */
    float step_mm;         /* line: waypoints at most this far apart (0: LSC_REACH_STEP_MM) */
    bool wait;             /* then wait as lsc_device_settle_ex does */
    uint16_t tolerance;    /* ... positions off target accepted */
    unsigned flags;        /* ... its flags: 0 or LSC_SETTLE_STRICT */
} lsc_reach;

/* What lsc_device_reach did, or why it did not. The caller sets size to
 * sizeof(lsc_reach_result) of its headers: fields are only ever added at the
 * end, and those beyond size are not written (a size smaller than the size
 * field and kin is LSC_EINVAL). The library sets settle.size. */
typedef struct lsc_reach_result {
    size_t size;
    lsc_kin_result kin;  /* the inverse's outcome (kin.status: why refused) */
    size_t waypoints;    /* moves sent (planned, when refused by a limit) */
    uint32_t time_ms;    /* their times, together */
    lsc_settle_result settle; /* r->wait: the servos that stopped short */
} lsc_reach_result;

/* Moves the grasp point to r->target through the device's arm profile: the
 * current angles of its chain (last commanded or read; read when unknown)
 * choose the solution (lsc_kin_inverse: the base and the elbow as they are
 * first; the pitch chosen when none is given, over the whole circle); the joints' positions are checked against the limits.
 * With r->line, the grasp point moves along the straight segment from where
 * it is (lsc_kin_forward of the current angles): waypoints at most step_mm
 * apart (at most LSC_REACH_WAYPOINTS_MAX), the pitch and roll turning evenly
 * from the current ones, every one solved (each nearest the one before) and
 * checked before the first is sent, each sent when the one before has had
 * its time; equal times, so the grasp point moves at one speed. With
 * speed_dps, each move's time is that of the largest joint travel of any
 * waypoint at that speed (lsc_device_move_time's rule). With r->wait, the
 * last move is waited for as lsc_device_settle_ex does with r->flags (its
 * returns: LSC_SETTLE_NO_READS when the controller does not report
 * positions, LSC_SETTLE_STOPPED when a joint stopped short of its target,
 * res->settle listing them; with LSC_SETTLE_STRICT that is LSC_ETIMEOUT).
 * A target that no current angles could reach within the limits (any off
 * the base's axis) is refused before anything is sent, the read too.
 * Returns 0 (or settle_ex's LSC_SETTLE_NO_READS or LSC_SETTLE_STOPPED), res
 * (may be NULL) filled up to res->size bytes; LSC_EINVAL with
 * nothing sent: r NULL, r->size or res->size too small, no arm profile or no geometry, a value refused (r->flags
 * not 0 or LSC_SETTLE_STRICT among them), the target
 * out of reach or reachable only beyond a joint's limit (res->kin says which,
 * the message too: "(x, y, z) is out of reach by N mm", "... needs joint
 * elbow (servo 4) at 131.2deg, beyond its limit 115.00deg"; at a given pitch
 * followed by the pitches that do reach it, "; pitches A..B reach it"; without
 * one the reason that holds at every pitch); an angle on a limit whose nearest
 * position lies beyond it is sent as the next position inside; or a read's,
 * move's or settle's error. */
LSC_API int lsc_device_reach(lsc_device *d, const lsc_reach *r, lsc_reach_result *res);

/* ---- Halt and hold ---------------------------------------------------------------- */

/* lsc_device_hold and lsc_device_halt: some servo was held where it is,
 * beyond its joint's limits in the arm profile (positive, not an error). */
#define LSC_HOLD_BEYOND 1
/* The time of the move that holds a servo where it was read (ms). */
#define LSC_HOLD_MS 20u

/* What lsc_device_hold did. The caller sets size to sizeof(lsc_hold_result)
 * of its headers: fields are only ever added at the end, and those beyond
 * size are not written (a size smaller than the size field and n is
 * LSC_EINVAL, nothing sent). */
typedef struct lsc_hold_result {
    size_t size;
    size_t n;                      /* servos held: held[0..n), in the order of ids */
    lsc_servo held[LSC_READ_MAX];  /* each one's position as read, now its target */
    size_t nbeyond;                /* of them, beyond their joints' limits: */
    uint8_t beyond[LSC_READ_MAX];  /* their ids, in the order of ids */
} lsc_hold_result;

/* Holds servos ids[0..n) where they are: reads their positions, then moves
 * each to its own (LSC_HOLD_MS, which it lets pass: when it returns they
 * hold), which powers a servo that was unloaded and stops one that moves. A servo beyond its joint's limits in the arm profile
 * (opened by hand past a limit while limp) is held there too: holding where a
 * servo already is cannot break a limit (moving it anywhere but back within
 * its limits stays refused: lsc_device_move). Returns 0 (all within their
 * limits), LSC_HOLD_BEYOND (some beyond: res lists them, lsc_device_error
 * names the first: "joint gripper (servo 1) is held at 900, beyond its
 * limits ...: move it back within them"), LSC_EINVAL with nothing sent (ids
 * NULL, n not 1..LSC_READ_MAX, a repeated id, more than
 * LSC_DEVICE_HID_MOVE_MAX over HID, res->size too small), or the read's or move's error (nothing
 * was moved when the read failed). res may be NULL. */
LSC_API int lsc_device_hold(lsc_device *d, const uint8_t *ids, size_t n, lsc_hold_result *res);

/* Stops everything, promptly: sends action_group_stop (7) and then holds
 * every servo where it is (lsc_device_hold of lsc_device_all_ids: the arm
 * profile's joints, else every id of the board kind), so that a move under
 * way or a group's ends where the servos are. It takes the stop's frame, one
 * position read and its reply, and the hold's move and its LSC_HOLD_MS.
 * Returns as lsc_device_hold (LSC_HOLD_BEYOND: some joint beyond its limits,
 * held there); when the positions cannot be read (a board that does not
 * answer position reads) the stop was sent and the read's error is
 * returned, its message saying that the servos go on to their last targets.
 * Through lscd (kind LSC_DEVICE_LSCD) it is lsc_lscd_halt: lscd halts its
 * controller whoever holds the lease (every id of its controller's kind:
 * d's arm profile is not lscd's), and its result and message are d's. */
LSC_API int lsc_device_halt(lsc_device *d);

#ifdef __cplusplus
}
#endif

#endif /* LSC_MOTION_H */
