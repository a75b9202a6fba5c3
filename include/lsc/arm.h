/*
 * lsc arm: arm profiles (docs/arm-profile.md): joint names, servo ids,
 * kinds, directions, zero offsets and limits, read from a small text file;
 * and the JOINT:VALUE arguments that use them ("base:30deg", "gripper:700",
 * "2:-15.5deg"). The conversions themselves are lsc/units.h's.
 *
 * Host only (it allocates and reads files), like lsc/files.h. A profile is an
 * opaque heap object: other languages hold only a pointer, and it can grow
 * without breaking the ABI. A profile is never changed after it is loaded:
 * any number of threads may read one at once.
 *
 * Errors: 0 or a negative LSC_E... code (lsc/core.h). Functions taking
 * (why, whylen) write one line (no newline, truncated to fit, always
 * NUL-terminated when whylen > 0) saying why they failed; why may be NULL.
 * Text from outside repeated in a why (a file's name, an argument, at most
 * 40 bytes of it) has its control characters, backslashes and non-ASCII
 * bytes escaped as \xNN and \\, so that the message stays one line.
 *   LSC_EINVAL  the text, argument or value is refused (why says where and why)
 *   LSC_EIO     the file cannot be read (why names it and the OS's reason)
 *   LSC_ENOSPC  out of memory
 */
#ifndef LSC_ARM_H
#define LSC_ARM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/sim.h"
#include "lsc/kinematics.h"
#include "lsc/units.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_ARM_JOINTS_MAX 32u   /* joints in one profile */
#define LSC_ARM_NAME_MAX 31u     /* bytes in a joint's name */
#define LSC_ARM_FILE_MAX 65536u  /* bytes in a profile file */
#define LSC_ARM_DEGREES_MAX 16u  /* room for an angle as text: "-360.00" and the NUL */
#define LSC_ARM_MESSAGE_MAX 256u /* room for a why (one naming a long file is cut) */

#define LSC_ARM_CHAIN_MAX 6u     /* joints of a chain: lsc_kin_joint's five, the gripper */
#define LSC_ARM_GRIPPER 5        /* the gripper's place in a chain's joints */

typedef struct lsc_arm lsc_arm;

/* Parses a profile from text[0..len) (no NUL needed; a NUL byte in it, or
 * any control byte but a tab and a CR before a newline, even in a comment, is
 * an error; a UTF-8 byte-order mark at the start is skipped). file names the
 * text in messages, "FILE:LINE:COLUMN: reason" (NULL: "profile"); text may be
 * NULL when len is 0. Returns 0 and *out (free it with lsc_arm_free), or an
 * error with *out NULL (out NULL: LSC_EINVAL). A profile whose limits allow
 * no position of a joint's servo is refused, at its limits. Without limits a
 * joint allows every position of its servo. Time: linear in len. */
LSC_API int lsc_arm_parse(const char *text, size_t len, const char *file, lsc_arm **out,
                          char *why, size_t whylen);

/* Reads and parses the profile at path: a regular file of at most
 * LSC_ARM_FILE_MAX bytes. A directory, FIFO or device is refused at once,
 * LSC_EINVAL, without reading or waiting ("cannot read the arm profile PATH:
 * it is a FIFO (...)"); a longer file is LSC_EINVAL after reading
 * LSC_ARM_FILE_MAX + 1 bytes; a path that cannot be opened or read is
 * LSC_EIO with the OS's reason. */
LSC_API int lsc_arm_load(const char *path, lsc_arm **out, char *why, size_t whylen);

/* The profile name names, as every front end's --arm (lscctl, lsc-sim,
 * lsc-panel, Python's lsc.open(..., arm=)) takes it, loaded as lsc_arm_load
 * loads a file. name is
 *  - a file's path when it has a '/' or ends in ".conf" ("./myarm",
 *    "examples/arms/xarm.conf", "xarm.conf" in the working directory): that
 *    file;
 *  - else a profile's name ("xarm"): the file NAME.conf looked for in, in
 *    this order,
 *      1. $XDG_CONFIG_HOME/lsc/arms (an absolute $XDG_CONFIG_HOME, else
 *         $HOME/.config/lsc/arms; neither set: skipped): the user's own;
 *      2. the installed profiles: $LSC_ARMS_DIR when set and not empty (for
 *         tests, or profiles kept elsewhere), else PREFIX/share/lsc/arms of
 *         the prefix the library was built for (cmake --install, the Debian
 *         package liblsc2: /usr/share/lsc/arms);
 *    the first that exists is loaded (an error in it is that error: a later
 *    one is not tried). None there: LSC_EIO, "no arm profile named NAME:
 *    looked for PATH, PATH (a file in this directory: ./NAME)".
 * Returns 0 and *out (free it with lsc_arm_free), or an error with *out NULL:
 * LSC_EINVAL also for name or out NULL, an empty name, or a name too long for
 * a path. Reads the environment (getenv) at each call. */
LSC_API int lsc_arm_open(const char *name, lsc_arm **out, char *why, size_t whylen);

/* The file lsc_arm_open(name) loads, by the same rules, into out[cap]
 * (without reading it: a path is given back as it is): 0, or an error with
 * why: LSC_EIO (a name found nowhere: the places looked), LSC_EINVAL (name
 * or out NULL, cap 0 or too small, an empty name, one too long for a path). */
LSC_API int lsc_arm_path(const char *name, char *out, size_t cap, char *why, size_t whylen);

/* Frees arm (NULL is fine). */
LSC_API void lsc_arm_free(lsc_arm *arm);

/* A copy of arm (NULL when out of memory or arm is NULL). */
LSC_API lsc_arm *lsc_arm_copy(const lsc_arm *arm);

/* The number of joints (0 for NULL), and joint i's name and joint (NULL when
 * i is out of range), in the order of the file. */
LSC_API size_t lsc_arm_count(const lsc_arm *arm);
LSC_API const char *lsc_arm_name(const lsc_arm *arm, size_t i);
LSC_API const lsc_joint *lsc_arm_joint(const lsc_arm *arm, size_t i);

/* The index of the joint named name, else of the joint on the servo id that
 * name spells (decimal or 0x-hex, at most 7 characters), else -1. arm or name
 * may be NULL (-1). */
LSC_API int lsc_arm_find(const lsc_arm *arm, const char *name);

/* A gripper's ends: where joint i is open (LSC_ARM_OPEN, its open= setting)
 * or closed (LSC_ARM_CLOSED, closed=), as a position inside its limits
 * (docs/arm-profile.md; lscctl calibrate writes both). Returns 0 and *pos
 * (pos may be NULL), or LSC_EINVAL: the profile does not say (or arm NULL, i
 * out of range, an unknown end). */
typedef enum lsc_arm_end_kind {
    LSC_ARM_OPEN = 0,
    LSC_ARM_CLOSED = 1
} lsc_arm_end_kind;
LSC_API int lsc_arm_end(const lsc_arm *arm, size_t i, lsc_arm_end_kind end, uint16_t *pos);

/* The index of the joint on servo id, or -1 (arm may be NULL). */
LSC_API int lsc_arm_by_id(const lsc_arm *arm, uint8_t id);

/* Makes the virtual controller sim stand in for the arm (lsc-sim --arm, the
 * device "sim" given a profile): each joint's servo rests at the joint's
 * zero (0 degrees, brought into its servo's range) and its moves end at its
 * servo's range pos_min..pos_max (lsc_sim_set_servo: 0..1000 for the xArm's
 * bus servos, 500..2500 for an LSC board's PWM servos), as the arm's own
 * would stop there. Other servos are left as they are. Returns 0, or
 * LSC_EINVAL (arm or sim NULL). */
LSC_API int lsc_arm_stand_in(const lsc_arm *arm, lsc_sim *sim);

/* A move target "JOINT:VALUE": JOINT a joint's name or a servo id; VALUE a
 * position, or an angle with the unit deg (at most two decimals). An angle
 * becomes the nearest position (lsc_joint_to_pos). Both the angle as written
 * and the position that would be sent must be inside the joint's limits (and
 * its servo's range), else LSC_EINVAL naming the joint, its limits in degrees
 * and the positions they allow ("10deg (position 542) is outside the limits
 * of joint base (servo 6): 0.00deg..10.00deg, positions 500..541"). A servo
 * id that is no joint takes a position 0..65535 only. arm may be NULL: then
 * ID:POSITION only, and a reason that needs a profile says "arm profile"
 * (lsc_arm_needs_profile tells which targets those are).
 * Returns 0 and *out, or LSC_EINVAL (arg or out NULL too; *out untouched). */
LSC_API int lsc_arm_target(const lsc_arm *arm, const char *arg, lsc_servo *out, char *why,
                           size_t whylen);

/* A servo to read or unload: a joint's name, or a servo id 0..255 (decimal
 * or 0x-hex). arm may be NULL: ids only. Returns 0 and *id, or LSC_EINVAL. */
LSC_API int lsc_arm_servo_id(const lsc_arm *arm, const char *arg, uint8_t *id, char *why,
                             size_t whylen);

/* What an argument of lsc_arm_target or lsc_arm_servo_id asks for that
 * only an arm profile gives, by the rules they follow without one: a
 * joint's name (it starts with a letter: "base", "base:30deg"), or an angle
 * ("1:30deg"); LSC_ARM_NEEDS_NONE for anything else (and NULL). For a front
 * end that says how to give a profile when such an argument was refused
 * without one. */
typedef enum lsc_arm_need {
    LSC_ARM_NEEDS_NONE = 0,
    LSC_ARM_NEEDS_JOINT = 1,  /* a joint's name */
    LSC_ARM_NEEDS_DEGREES = 2 /* an angle (VALUE in deg) */
} lsc_arm_need;
LSC_API lsc_arm_need lsc_arm_needs_profile(const char *arg);

/* Checks servos[0..n) against the limits of the joints they are on, position
 * by position (lsc_joint_allows_pos; servos on no joint pass, all of them when
 * arm is NULL): 0, or LSC_EINVAL naming the first joint outside them ("position
 * 2000 is outside the limits of joint base (servo 6): ..."). servos may be
 * NULL when n is 0. */
LSC_API int lsc_arm_check(const lsc_arm *arm, const lsc_servo *servos, size_t n, char *why,
                          size_t whylen);

/* The joint on servo s->id (its index; -1 if none, or arm or s NULL) and, in
 * deg[cap], its angle at s->position as degrees with two decimals ("-15.50"),
 * or "" when there is no joint or the position lies outside its servo's
 * range. cap >= LSC_ARM_DEGREES_MAX always suffices; deg NULL or cap 0:
 * nothing is written. */
LSC_API int lsc_arm_degrees(const lsc_arm *arm, const lsc_servo *s, char *deg, size_t cap);

/* The arm's geometry (its chain: and links: lines, docs/arm-profile.md) for
 * lsc/kinematics.h: the lengths in mm; the limits, in degrees, of its joints
 * in the order of lsc_kin_joint. joints (NULL: not wanted) gets
 * LSC_ARM_CHAIN_MAX indexes of joints of arm: base, shoulder, elbow, wrist,
 * wrist roll, then the gripper's (LSC_ARM_GRIPPER) or -1 when the chain names
 * none. Returns 0, or LSC_EINVAL (arm or chain NULL, or a profile without
 * geometry: why says what to add). */
LSC_API int lsc_arm_chain(const lsc_arm *arm, lsc_kin_chain *chain, int *joints, char *why,
                          size_t whylen);

/* ---- Joints in degrees, as numbers (src/arm/arm_deg.c) ------------------- */

/* The target of joint (a joint's name, or the servo id of a joint, as
 * lsc_arm_target takes it) at deg degrees, taken as given (no rounding to
 * hundredths): the nearest position (halves away from the joint's zero),
 * checked as lsc_arm_target checks an angle: deg must lie within the joint's
 * limits and the position within its servo's range and limits. Returns 0 and
 * *out, or LSC_EINVAL with the reason in why ("base: 30.004deg is outside the
 * limits of joint base (servo 6): -30.00deg..30.00deg"; not finite, no such
 * joint, arm, joint or out NULL; *out untouched). */
LSC_API int lsc_arm_target_deg(const lsc_arm *arm, const char *joint, double deg,
                               lsc_servo *out, char *why, size_t whylen);

/* The angle of the joint on servo s->id at s->position, in degrees, exact
 * (not rounded to hundredths as lsc_arm_degrees writes it). Returns the
 * joint's index and *deg, or -1 (no joint on that servo, a position outside
 * its servo's range, or a NULL argument; *deg untouched). */
LSC_API int lsc_arm_angle(const lsc_arm *arm, const lsc_servo *s, double *deg);

#ifdef __cplusplus
}
#endif

#endif /* LSC_ARM_H */
