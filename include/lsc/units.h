/*
 * lsc units: a joint's angle (centidegrees) <-> its servo's position, and the
 * joint's limits. Portable C99, freestanding, integer arithmetic only (no
 * floating point, no malloc, no mutable static state): runs on an MCU.
 *
 * A joint is one servo seen through the arm: the servo's position range
 * pos_min..pos_max covers span_cdeg centidegrees of rotation, linearly. The
 * joint reads 0 at position `zero`; its angle grows with the position when
 * direction is +1 and shrinks when it is -1:
 *
 *     angle = direction * (pos - zero) * span_cdeg / (pos_max - pos_min)
 *
 * Both conversions round to the nearest unit (halves away from zero).
 * Bounds that keep every intermediate inside int32_t (checked by
 * lsc_joint_valid; no conversion overflows on a valid joint):
 *   pos_max <= LSC_UNITS_POS_MAX, 1 <= span_cdeg <= LSC_UNITS_CDEG_MAX,
 *   |angle| <= LSC_UNITS_CDEG_MAX (so |angle * range| <= 3.6e8).
 * Round trip: position -> angle -> position gives the same position back
 * whenever the range has at most one position per centidegree
 * (pos_max - pos_min <= span_cdeg), as on every servo kind below.
 *
 * Kinds: PWM servos on LSC-6/16/32 boards: pulse 500..2500 us over 180
 * degrees (0.09 degree a unit); bus servos (xArm, Bus Servo Controller):
 * 0..1000 over 240 degrees (0.24 degree a unit).
 */
#ifndef LSC_UNITS_H
#define LSC_UNITS_H

#include <stdbool.h>
#include <stdint.h>

#include "lsc/core.h" /* LSC_API, error codes */

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_UNITS_POS_MAX 10000 /* largest position a joint may use */
#define LSC_UNITS_CDEG_MAX 36000 /* largest angle (and span), in centidegrees */

typedef enum lsc_joint_kind {
    LSC_JOINT_PWM = 0, /* 500..2500 over 180 degrees */
    LSC_JOINT_BUS = 1  /* 0..1000 over 240 degrees */
} lsc_joint_kind;

typedef struct lsc_joint {
    uint8_t id;         /* servo id */
    int8_t direction;   /* +1 or -1 */
    uint16_t pos_min;   /* the servo's position range ... */
    uint16_t pos_max;   /* ... pos_min < pos_max <= LSC_UNITS_POS_MAX */
    int32_t span_cdeg;  /* angle the whole range covers */
    uint16_t zero;      /* position where the joint reads 0 (pos_min..pos_max) */
    int32_t min_cdeg;   /* the joint's limits, in its own angle; */
    int32_t max_cdeg;   /* min_cdeg <= max_cdeg, both within +-LSC_UNITS_CDEG_MAX */
} lsc_joint;

/* A joint of the given kind on servo id: direction +1, zero at the middle of
 * the range, limits the whole range. Returns 0, or LSC_EINVAL (j NULL or an
 * unknown kind; *j untouched). */
LSC_API int lsc_joint_init(lsc_joint *j, uint8_t id, lsc_joint_kind kind);

/* A joint over any range: pos_min..pos_max covering span_cdeg; zero at the
 * middle (rounded down), direction +1, limits the whole range. Returns 0, or
 * LSC_EINVAL if the result would not be valid (see lsc_joint_valid). */
LSC_API int lsc_joint_init_range(lsc_joint *j, uint8_t id, uint16_t pos_min, uint16_t pos_max,
                                 int32_t span_cdeg);

/* Whether j (not NULL) keeps every bound above: a conversion refuses a joint
 * that does not. */
LSC_API bool lsc_joint_valid(const lsc_joint *j);

/* The position for angle cdeg. Returns 0 and *pos, or LSC_EINVAL: invalid
 * joint or NULL, |cdeg| > LSC_UNITS_CDEG_MAX, or the position it gives lies
 * outside pos_min..pos_max. Limits are not checked: see lsc_joint_allows. */
LSC_API int lsc_joint_to_pos(const lsc_joint *j, int32_t cdeg, uint16_t *pos);

/* The angle of position pos. Returns 0 and *cdeg, or LSC_EINVAL: invalid
 * joint or NULL, or pos outside pos_min..pos_max. */
LSC_API int lsc_joint_to_cdeg(const lsc_joint *j, uint16_t pos, int32_t *cdeg);

/* Whether the joint may go to angle cdeg: min_cdeg <= cdeg <= max_cdeg and
 * the angle maps into the servo's range. False for an invalid joint. */
LSC_API bool lsc_joint_allows(const lsc_joint *j, int32_t cdeg);

/* Whether the joint may go to position pos: pos in pos_min..pos_max and its
 * exact (unrounded) angle within the limits. False for an invalid joint. */
LSC_API bool lsc_joint_allows_pos(const lsc_joint *j, uint16_t pos);

#ifdef __cplusplus
}
#endif

#endif
