/* lsc arm: joint angles as numbers, in degrees (lsc/arm.h's
 * lsc_arm_target_deg and lsc_arm_angle), for front ends that hold angles as
 * floating point (Python): built only on lsc/arm.h's and lsc/units.h's
 * public calls. Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>

#include "lsc/arm.h"
#include "lsc/units.h"

#include "arm_internal.h"

/* x rounded to the nearest integer, halves away from zero (as lsc/units.h
 * rounds); |x| <= LSC_UNITS_CDEG_MAX * LSC_UNITS_POS_MAX. */
static long nearest(double x)
{
    return x >= 0 ? (long)(x + 0.5) : -(long)(-x + 0.5);
}

int lsc_arm_target_deg(const lsc_arm *arm, const char *joint, double deg, lsc_servo *out,
                       char *why, size_t whylen)
{
    int i = joint != NULL ? lsc_arm_find(arm, joint) : -1;
    if (i < 0 || out == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "'%s' is not a joint of the arm profile",
                       joint != NULL ? joint : "(none)");
    }
    const lsc_joint *j = lsc_arm_joint(arm, (size_t)i);
    const char *name = lsc_arm_name(arm, (size_t)i);
    double cdeg = deg * 100.0;
    /* (written so that a NaN fails it too) */
    if (!(cdeg >= (double)j->min_cdeg && cdeg <= (double)j->max_cdeg)) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                       "%s: %gdeg is outside the limits of joint %s (servo %u): "
                       "%.2fdeg..%.2fdeg",
                       joint, deg, name, j->id, j->min_cdeg / 100.0, j->max_cdeg / 100.0);
    }
    double range = (double)j->pos_max - (double)j->pos_min;
    long pos = (long)j->zero + (long)j->direction * nearest(cdeg * range / (double)j->span_cdeg);
    /* |pos| < 2^31 (|cdeg| <= LSC_UNITS_CDEG_MAX, range <= LSC_UNITS_POS_MAX);
     * lsc_joint_allows_pos checks the servo's range too */
    uint16_t p16 = (uint16_t)((unsigned long)pos & 0xFFFFu);
    int fits = (long)p16 == pos;
    if ((fits & (int)lsc_joint_allows_pos(j, p16)) == 0) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                       "%s: %gdeg (position %ld) is outside the limits of joint %s (servo %u): "
                       "%.2fdeg..%.2fdeg",
                       joint, deg, pos, name, j->id, j->min_cdeg / 100.0, j->max_cdeg / 100.0);
    }
    out->id = j->id;
    out->position = p16;
    return LSC_OK;
}

int lsc_arm_angle(const lsc_arm *arm, const lsc_servo *s, double *deg)
{
    int i = s != NULL && deg != NULL ? lsc_arm_by_id(arm, s->id) : -1;
    const lsc_joint *j = i >= 0 ? lsc_arm_joint(arm, (size_t)i) : NULL;
    if (j == NULL || s->position < j->pos_min || s->position > j->pos_max) {
        return -1;
    }
    double steps = ((double)s->position - (double)j->zero) * (double)j->direction;
    *deg = steps * (double)j->span_cdeg / (((double)j->pos_max - (double)j->pos_min) * 100.0);
    return i;
}

#endif
