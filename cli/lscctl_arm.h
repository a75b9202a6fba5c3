/* lscctl: arm profiles (docs/arm-profile.md): joint names, kinds,
 * directions, zero offsets and limits, read from a text file; and the
 * NAME:VALUE arguments of move and read that use them. Host-only, used only
 * by lscctl (the conversions themselves are the library's: lsc/units.h).
 * Every function returning int gives 0, or -1 after writing a one-line
 * reason into why[whylen]. */
#ifndef LSCCTL_ARM_H
#define LSCCTL_ARM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/units.h"

#define LSCCTL_ARM_JOINTS_MAX 32u /* joints in one profile */
#define LSCCTL_ARM_NAME_MAX 31u   /* characters in a joint's name */
#define LSCCTL_ARM_FILE_MAX 65536u /* bytes in a profile file */

typedef struct lscctl_arm_joint {
    char name[LSCCTL_ARM_NAME_MAX + 1u];
    lsc_joint joint;
} lscctl_arm_joint;

typedef struct lscctl_arm {
    lscctl_arm_joint joints[LSCCTL_ARM_JOINTS_MAX];
    size_t n;
} lscctl_arm;

/* Parses a profile from text[0..len) (no NUL needed; a NUL byte in it is an
 * error). Errors read "FILE:LINE:COLUMN: reason" with file as given. */
int lscctl_arm_parse(lscctl_arm *arm, const char *text, size_t len, const char *file,
                     char *why, size_t whylen);

/* Reads and parses the profile at path (at most LSCCTL_ARM_FILE_MAX bytes). */
int lscctl_arm_load(lscctl_arm *arm, const char *path, char *why, size_t whylen);

/* The joint named name[0..len), else the joint on servo id (when name is an
 * id: decimal or 0x-hex), else NULL. */
const lscctl_arm_joint *lscctl_arm_find(const lscctl_arm *arm, const char *name, size_t len);

/* The joint on servo id, or NULL (arm may be NULL). */
const lscctl_arm_joint *lscctl_arm_by_id(const lscctl_arm *arm, uint8_t id);

/* A move target "JOINT:VALUE" (JOINT a name of arm, or a servo id; VALUE a
 * position, or an angle with the unit deg: "base:30deg", "2:-15.5deg",
 * "gripper:700"). Refuses a value outside the joint's limits, naming the
 * joint and its limits. arm may be NULL: then only ID:POSITION. */
int lscctl_arm_target(const lscctl_arm *arm, const char *arg, lsc_servo *out, char *why,
                      size_t whylen);

/* A servo to read: a joint name of arm, or an id (arm may be NULL). */
int lscctl_arm_id(const lscctl_arm *arm, const char *arg, uint8_t *id, char *why, size_t whylen);

/* Room for an angle written as degrees with two decimals ("-360.00"). */
#define LSCCTL_ARM_DEGREES_MAX 16u

/* The joint on servo s->id (NULL: none, or arm NULL) and, in deg[cap], its
 * angle at s->position as degrees with two decimals ("-15.50"), or "" when
 * it has none (no joint, or a position outside the servo's range). */
const lscctl_arm_joint *lscctl_arm_angle(const lscctl_arm *arm, const lsc_servo *s, char *deg,
                                         size_t cap);

#endif
