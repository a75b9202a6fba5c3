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
#include "lsc/units.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_ARM_JOINTS_MAX 32u   /* joints in one profile */
#define LSC_ARM_NAME_MAX 31u     /* bytes in a joint's name */
#define LSC_ARM_FILE_MAX 65536u  /* bytes in a profile file */
#define LSC_ARM_DEGREES_MAX 16u  /* room for an angle as text: "-360.00" and the NUL */
#define LSC_ARM_MESSAGE_MAX 256u /* room that is always enough for a why */

typedef struct lsc_arm lsc_arm;

/* Parses a profile from text[0..len) (no NUL needed; a NUL byte in it is an
 * error). file names the text in messages: "FILE:LINE:COLUMN: reason".
 * Returns 0 and *out (free it with lsc_arm_free), or an error with *out NULL.
 * A profile whose limits allow no position of a joint's servo is refused. */
LSC_API int lsc_arm_parse(const char *text, size_t len, const char *file, lsc_arm **out,
                          char *why, size_t whylen);

/* Reads and parses the profile at path: a regular file of at most
 * LSC_ARM_FILE_MAX bytes (a directory, FIFO or device is refused at once,
 * LSC_EINVAL, without reading). */
LSC_API int lsc_arm_load(const char *path, lsc_arm **out, char *why, size_t whylen);

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
 * name spells (decimal or 0x-hex), else -1. arm may be NULL (-1). */
LSC_API int lsc_arm_find(const lsc_arm *arm, const char *name);

/* The index of the joint on servo id, or -1 (arm may be NULL). */
LSC_API int lsc_arm_by_id(const lsc_arm *arm, uint8_t id);

/* A move target "JOINT:VALUE": JOINT a joint's name or a servo id; VALUE a
 * position, or an angle with the unit deg (at most two decimals). An angle
 * becomes the nearest position. The position that would be sent is what is
 * checked: outside the joint's limits or its servo's range is LSC_EINVAL,
 * naming the joint, its limits in degrees and the positions they allow. A
 * servo id that is no joint takes a position 0..65535 only. arm may be NULL:
 * then only ID:POSITION. */
LSC_API int lsc_arm_target(const lsc_arm *arm, const char *arg, lsc_servo *out, char *why,
                           size_t whylen);

/* A servo to read or unload: a joint's name, or a servo id 0..255. */
LSC_API int lsc_arm_servo_id(const lsc_arm *arm, const char *arg, uint8_t *id, char *why,
                             size_t whylen);

/* Checks servos[0..n) against the limits of the joints they are on (servos on
 * no joint pass): 0, or LSC_EINVAL naming the first joint outside them. */
LSC_API int lsc_arm_check(const lsc_arm *arm, const lsc_servo *servos, size_t n, char *why,
                          size_t whylen);

/* The joint on servo s->id (its index; -1 if none or arm NULL) and, in
 * deg[cap], its angle at s->position as degrees with two decimals ("-15.50"),
 * or "" when there is no joint or the position lies outside its servo's
 * range. cap >= LSC_ARM_DEGREES_MAX always suffices. */
LSC_API int lsc_arm_degrees(const lsc_arm *arm, const lsc_servo *s, char *deg, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* LSC_ARM_H */
