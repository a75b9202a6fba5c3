/* lsc device: an action file's positions converted from one arm to another
 * through joint angles (lsc_action_to_arm), over lsc/arm.h, lsc/units.h and
 * lsc/files.h. Host only: compiles to nothing elsewhere (the Arduino IDE
 * builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h" /* lsc_dev_refuse */


/* cdeg as degrees with two decimals: "-15.50deg". */
static void degrees(int32_t cdeg, char *buf, size_t cap)
{
    long v = (long)cdeg;
    unsigned long a = (unsigned long)(v < 0 ? -v : v);
    (void)snprintf(buf, cap, "%s%lu.%02ludeg", v < 0 ? "-" : "", a / 100u, a % 100u);
}

/* The index of the joint named name in arm, or -1 (by name only: not an id). */
static int by_name(const lsc_arm *arm, const char *name)
{
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        if (strcmp(lsc_arm_name(arm, i), name) == 0) {
            return (int)i;
        }
    }
    return -1;
}

/* For each servo of in: its joint in from and the joint of the same name in
 * to (indexes into the profiles). */
static int match_joints(const lsc_action *in, const lsc_arm *from, const lsc_arm *to,
                        int *src, int *dst, char *why, size_t whylen)
{
    for (size_t i = 0; i < in->nservos; i++) {
        src[i] = lsc_arm_by_id(from, in->ids[i]);
        if (src[i] < 0) {
            return lsc_dev_refuse(why, whylen,
                          "servo %u is on no joint of the source profile: its angle is not "
                          "known",
                          in->ids[i]);
        }
        const char *name = lsc_arm_name(from, (size_t)src[i]);
        dst[i] = by_name(to, name);
        if (dst[i] < 0) {
            return lsc_dev_refuse(why, whylen, "joint %s (servo %u) has no joint of that name in the "
                                       "target profile",
                          name, in->ids[i]);
        }
    }
    return 0;
}

/* Position pos of servo i of keyframe k, from joint a of from to joint b of
 * to, through its angle: 0 and *out, or LSC_EINVAL saying why. */
static int convert_one(const lsc_arm *from, int a, const lsc_arm *to, int b, uint32_t k,
                       uint16_t pos, uint16_t *out, char *why, size_t whylen)
{
    const lsc_joint *js = lsc_arm_joint(from, (size_t)a);
    const lsc_joint *jd = lsc_arm_joint(to, (size_t)b);
    const char *name = lsc_arm_name(from, (size_t)a);
    int32_t cdeg = 0;
    char deg[24], lo[24], hi[24];
    if (lsc_joint_to_cdeg(js, pos, &cdeg) != 0) {
        return lsc_dev_refuse(why, whylen,
                      "keyframe %lu: joint %s (servo %u): position %u is outside its servo's "
                      "range %u..%u in the source profile",
                      (unsigned long)k + 1u, name, js->id, pos, js->pos_min, js->pos_max);
    }
    /* outside the servo's range, the joint's limits, or (rounded to a
     * position) past them */
    if (lsc_joint_to_pos(jd, cdeg, out) != 0 || !lsc_joint_allows(jd, cdeg) ||
        !lsc_joint_allows_pos(jd, *out)) {
        int32_t min = jd->min_cdeg, max = jd->max_cdeg;
        int32_t e0 = 0, e1 = 0; /* the servo's own range, as angles (a profile's
                                 * joints are valid: their ends convert) */
        (void)lsc_joint_to_cdeg(jd, jd->pos_min, &e0);
        (void)lsc_joint_to_cdeg(jd, jd->pos_max, &e1);
        int32_t rlo = e0 < e1 ? e0 : e1, rhi = e0 < e1 ? e1 : e0;
        min = min > rlo ? min : rlo;
        max = max < rhi ? max : rhi;
        degrees(cdeg, deg, sizeof deg);
        degrees(min, lo, sizeof lo);
        degrees(max, hi, sizeof hi);
        return lsc_dev_refuse(why, whylen,
                      "keyframe %lu: joint %s: %s (position %u) is outside the target's "
                      "limits of joint %s (servo %u): %s..%s",
                      (unsigned long)k + 1u, name, deg, pos, name, jd->id, lo, hi);
    }
    return 0;
}

int lsc_action_to_arm(const lsc_action *in, const lsc_arm *from, const lsc_arm *to,
                      lsc_action *out, char *why, size_t whylen)
{
    if (why != NULL && whylen > 0) {
        why[0] = '\0';
    }
    if (in == NULL || from == NULL || to == NULL || out == NULL || in == out) {
        return lsc_dev_refuse(why, whylen, "no action or no profile to convert with");
    }
    memset(out, 0, sizeof *out);
    if (in->nservos == 0 || in->nservos > LSC_PLAYER_SERVOS_MAX ||
        (in->words == NULL && in->count > 0)) {
        return lsc_dev_refuse(why, whylen, "the action has no servos (lsc_action_init gives them)");
    }
    int src[LSC_PLAYER_SERVOS_MAX] = {0}, dst[LSC_PLAYER_SERVOS_MAX] = {0};
    int r = match_joints(in, from, to, src, dst, why, whylen);
    if (r != 0) {
        return r;
    }
    uint8_t ids[LSC_PLAYER_SERVOS_MAX];
    for (size_t i = 0; i < in->nservos; i++) {
        ids[i] = lsc_arm_joint(to, (size_t)dst[i])->id; /* dst[i] was found */
    }
    /* a profile has one joint per servo and one per name: the target's ids
     * repeat only where the action's do (an action not made by
     * lsc_action_init) */
    if (lsc_action_init(out, ids, in->nservos) != 0) {
        return lsc_dev_refuse(why, whylen, "the action gives a servo twice (lsc_action_init "
                                           "refuses that)");
    }
    uint16_t row[LSC_PLAYER_SERVOS_MAX];
    for (uint32_t k = 0; k < in->count && r == 0; k++) {
        const uint16_t *w = in->words + (size_t)k * (1u + in->nservos);
        for (size_t i = 0; i < in->nservos && r == 0; i++) {
            r = convert_one(from, src[i], to, dst[i], k, w[1 + i], &row[i], why, whylen);
        }
        if (r == 0 && lsc_action_append(out, w[0], row) != 0) {
            r = LSC_ENOSPC;
            (void)lsc_dev_refuse(why, whylen, "out of memory");
        }
    }
    if (r != 0) {
        lsc_action_free(out);
    }
    return r;
}

#endif
