/*
 * lsc calibrate: an arm profile made right for the arm in hand, from what its
 * servos read in poses the owner holds it in (docs/arm-profile.md,
 * "Calibration"). A kit is assembled by its owner: a servo horn goes on a
 * spline off by a tooth, a servo is mounted the other way round, a replaced
 * servo has another zero. Four steps, each one reading of the servos:
 *
 *   home            every joint of the chain at 0 degrees (the arm straight up,
 *                   docs/kinematics.md): each joint's zero, offset=
 *   lean            every joint leaned its positive way by a good amount: each
 *                   joint's direction, dir= (a joint that moved less than
 *                   LSC_CALIB_LEAN_MIN_CDEG is refused, never guessed)
 *   gripper-closed  the gripper closed: closed=
 *   gripper-open    the gripper open: open=, and the limits between the two
 *
 * The result is a profile: the text of the one given, with those settings
 * written on the joints' lines (other lines, comments and settings kept as
 * they were) and a comment line per step saying when and from what it was
 * made. Each step starts from the result of the ones before (or from a
 * shipped profile), so the steps can run one by one, in separate programs.
 * Nothing is written into the servos: offsets stay in the profile, on the
 * host, so nothing jumps at power-up.
 *
 * Host only (it allocates). Errors: 0 or a negative LSC_E... code, with why
 * (whylen bytes, may be NULL) one line saying what to do, as lsc/arm.h.
 */
#ifndef LSC_CALIBRATE_H
#define LSC_CALIBRATE_H

#include <stddef.h>
#include <stdint.h>

#include "lsc/arm.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lsc_calib_step {
    LSC_CALIB_HOME = 0,
    LSC_CALIB_LEAN = 1,
    LSC_CALIB_GRIPPER_CLOSED = 2,
    LSC_CALIB_GRIPPER_OPEN = 3
} lsc_calib_step;

#define LSC_CALIB_STEPS 4u
/* The least a joint must be leaned (lean) or the gripper opened
 * (gripper-open after gripper-closed, or the other way), in centidegrees. */
#define LSC_CALIB_LEAN_MIN_CDEG 500
/* Room for a stamp (lsc_calib_apply), without its NUL. */
#define LSC_CALIB_STAMP_MAX 200u

/* A step's name ("home", "lean", "gripper-closed", "gripper-open"), or NULL
 * for a value that is no step. */
LSC_API const char *lsc_calib_step_name(lsc_calib_step step);

/* The step named name: 0 and *step, or LSC_EINVAL (name or step NULL too). */
LSC_API int lsc_calib_step_parse(const char *name, lsc_calib_step *step);

/* The servos step reads, in the order of the chain (home, lean: base,
 * shoulder, elbow, wrist, wrist roll; the gripper steps: the gripper), into
 * ids[0..cap). Returns their number, or LSC_EINVAL: arm NULL, a profile
 * without geometry (why says what to add: lsc_arm_chain), a gripper step
 * on a chain without a gripper, an unknown step, cap too small. */
LSC_API int lsc_calib_ids(const lsc_arm *arm, lsc_calib_step step, uint8_t *ids, size_t cap,
                          char *why, size_t whylen);

/* Applies one step's readings, readings[0..n) (at least the servos of
 * lsc_calib_ids, in any order; others are ignored), to the profile text[0..len)
 * (file names it in messages, NULL: "profile"). stamp (one line of at most
 * LSC_CALIB_STAMP_MAX printable bytes: when and from what, e.g. "2026-11-29
 * 10:04 UTC, from xarm.conf") becomes the comment "# calibrate STEP: STAMP"
 * at the top, replacing an earlier one of the same step.
 *   home: offset= of each chain joint becomes its reading less the middle of
 *     its servo's range (in positions: the servo's own direction);
 *   lean: dir= of each chain joint is +1 when its reading is above its zero,
 *     -1 below; a joint less than LSC_CALIB_LEAN_MIN_CDEG from its zero is
 *     refused (why names every such joint and how far each moved);
 *   gripper-closed, gripper-open: closed= or open= becomes the reading; with
 *     both known the limits become the positions between them (the two
 *     readings must be LSC_CALIB_LEAN_MIN_CDEG apart), else they are widened
 *     to hold the reading.
 * Limits written in degrees stay the joint's degrees (from its new zero);
 * limits written as positions stay those positions.
 * Returns 0 and *out (a NUL-terminated text of *outlen bytes: free() it; a
 * profile lsc_arm_parse accepts), or an error with *out NULL: LSC_EINVAL (the
 * text is no profile, the step's servos are not all read, a reading is
 * outside its servo's range, a lean too small, a bad stamp, NULL arguments;
 * why says which), LSC_ENOSPC (out of memory). Time: linear in len. */
LSC_API int lsc_calib_apply(const char *text, size_t len, const char *file, lsc_calib_step step,
                            const lsc_servo *readings, size_t n, const char *stamp, char **out,
                            size_t *outlen, char *why, size_t whylen);

#ifdef __cplusplus
}
#endif

#endif /* LSC_CALIBRATE_H */
