/*
 * lsc convert: an action (lsc/files.h) recorded on one arm made into the same
 * motion on another, through the arm profiles (lsc/arm.h). No device is used.
 *
 * Host only.
 */
#ifndef LSC_CONVERT_H
#define LSC_CONVERT_H

#include <stddef.h>

#include "lsc/arm.h"
#include "lsc/files.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Converts the positions of in, recorded on arm `from`, for arm `to`,
 * through joint angles: each servo of in is a joint of from (found by its
 * id); the joint of the same name in to (matched by name, never by id) gets
 * the position of the same angle (lsc_joint_to_cdeg, then lsc_joint_to_pos:
 * rounded to the nearest position). out gets to's servo ids, in in's order,
 * and in's times; it is initialised here (lsc_action_free it after success;
 * on error it is empty). Refused, LSC_EINVAL with why[whylen] saying which
 * and why (one line), nothing in out:
 *   - a servo of in on no joint of from ("servo 7 is on no joint of the
 *     source profile: ...");
 *   - a joint of from that to has no joint of that name ("joint wrist (servo
 *     3) has no joint of that name in the target profile");
 *   - a position outside its servo's range in from ("keyframe 2: joint
 *     gripper (servo 1): position 1200 is outside its servo's range 0..1000
 *     in the source profile");
 *   - an angle outside the limits of to's joint, or its servo's range
 *     ("keyframe 3: joint base: 100.08deg (position 917) is outside the
 *     target's limits of joint base (servo 6): -85.00deg..85.00deg"): the
 *     first keyframe, then the first joint, in in's order;
 *   - NULL arguments, or in the same as out.
 * LSC_ENOSPC: out of memory. No device is used. O(keyframes x servos). */
LSC_API int lsc_action_to_arm(const lsc_action *in, const lsc_arm *from, const lsc_arm *to,
                              lsc_action *out, char *why, size_t whylen);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CONVERT_H */
