/* Arm profiles at run time (include/lsc/arm.h): a profile's joints by index,
 * name or servo id, JOINT:VALUE arguments, the limits checked, degrees, the
 * geometry as a kinematic chain, the stand-in for the virtual controller.
 * What is checked is always the position that would be sent (lsc/units.h's
 * conversions and limits). Profiles are read by arm_parse.c and arm_file.c.
 * Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c
 * under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arm_internal.h"

void lsc_arm_free(lsc_arm *arm)
{
    free(arm);
}

lsc_arm *lsc_arm_copy(const lsc_arm *arm)
{
    lsc_arm *copy = arm != NULL ? malloc(sizeof *copy) : NULL;
    if (copy != NULL) {
        memcpy(copy, arm, sizeof *copy);
    }
    return copy;
}

size_t lsc_arm_count(const lsc_arm *arm)
{
    return arm != NULL ? arm->n : 0;
}

const char *lsc_arm_name(const lsc_arm *arm, size_t i)
{
    return i < lsc_arm_count(arm) ? arm->joints[i].name : NULL;
}

const lsc_joint *lsc_arm_joint(const lsc_arm *arm, size_t i)
{
    return i < lsc_arm_count(arm) ? &arm->joints[i].joint : NULL;
}

int lsc_arm_stand_in(const lsc_arm *arm, lsc_sim *sim)
{
    if (arm == NULL || sim == NULL) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < arm->n; i++) {
        const lsc_joint *j = &arm->joints[i].joint;
        (void)lsc_sim_set_servo(sim, j->id, j->zero, j->pos_min, j->pos_max);
    }
    return 0;
}

/* The joint on servo id, or NULL (arm may be NULL). */
static const arm_joint *joint_on(const lsc_arm *arm, uint8_t id)
{
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        if (arm->joints[i].joint.id == id) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

/* The joint named s[0..n), else the joint on the servo id s[0..n) spells,
 * else NULL (arm may be NULL). */
static const arm_joint *joint_named(const lsc_arm *arm, const char *s, size_t n)
{
    long id = lsc_armi_as_id(s, n);
    if (id >= 0) {
        return joint_on(arm, (uint8_t)id);
    }
    for (size_t i = 0; i < lsc_arm_count(arm); i++) {
        if (strlen(arm->joints[i].name) == n && memcmp(arm->joints[i].name, s, n) == 0) {
            return &arm->joints[i];
        }
    }
    return NULL;
}

/* aj's index in arm (aj one of its joints), or -1 for NULL */
static int index_of(const lsc_arm *arm, const arm_joint *aj)
{
    return aj != NULL ? (int)(aj - arm->joints) : -1;
}

int lsc_arm_end(const lsc_arm *arm, size_t i, lsc_arm_end_kind end, uint16_t *pos)
{
    if (arm == NULL || i >= arm->n || (end != LSC_ARM_OPEN && end != LSC_ARM_CLOSED) ||
        !arm->joints[i].has_end[end]) {
        return LSC_EINVAL;
    }
    if (pos != NULL) {
        *pos = arm->joints[i].end[end];
    }
    return LSC_OK;
}

int lsc_arm_by_id(const lsc_arm *arm, uint8_t id)
{
    return index_of(arm, joint_on(arm, id));
}

int lsc_arm_find(const lsc_arm *arm, const char *name)
{
    return name != NULL ? index_of(arm, joint_named(arm, name, strlen(name))) : -1;
}

/* "WHAT is outside the limits of joint base (servo 6): -90.00deg..90.00deg,
 * positions 125..875" */
static int refuse(const arm_joint *aj, const char *what, char *why, size_t whylen)
{
    const lsc_joint *j = &aj->joint;
    char lo[LSC_ARM_DEGREES_MAX], hi[LSC_ARM_DEGREES_MAX];
    long plo, phi;
    lsc_armi_degrees(lo, sizeof lo, j->min_cdeg);
    lsc_armi_degrees(hi, sizeof hi, j->max_cdeg);
    (void)lsc_armi_positions(j, &plo, &phi); /* a profile's joints always keep one */
    return lsc_armi_fail(LSC_EINVAL, why, whylen,
                         "%s is outside the limits of joint %s (servo %u): %sdeg..%sdeg, "
                         "positions %ld..%ld",
                         what, aj->name, j->id, lo, hi, plo, phi);
}

/* "ID:POSITION" (either decimal or 0x-hex): without a profile. */
static int parse_servo(const char *s, lsc_servo *out, char *why, size_t whylen)
{
    const char *colon = strchr(s, ':');
    char idtext[32], text[SHOWN_CAP];
    unsigned long id = 0, pos = 0;
    size_t idlen = colon != NULL ? (size_t)(colon - s) : 0;
    if (colon == NULL || idlen >= sizeof idtext) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "'%s' is not ID:POS (for example 1:1500)",
                             lsc_armi_shown(text, s, strlen(s)));
    }
    memcpy(idtext, s, idlen);
    idtext[idlen] = '\0';
    if (lsc_armi_parse_uint(idtext, 255, "id", &id, why, whylen) != 0 ||
        lsc_armi_parse_uint(colon + 1, 65535, "position", &pos, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    out->id = (uint8_t)id;
    out->position = (uint16_t)pos;
    return LSC_OK;
}

static bool is_letter(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

lsc_arm_need lsc_arm_needs_profile(const char *arg)
{
    size_t len = arg != NULL ? strlen(arg) : 0u;
    if (len == 0u) {
        return LSC_ARM_NEEDS_NONE;
    }
    if (is_letter(arg[0])) {
        return LSC_ARM_NEEDS_JOINT;
    }
    return strchr(arg, ':') != NULL && len >= 3 && memcmp(arg + len - 3, "deg", 3) == 0
               ? LSC_ARM_NEEDS_DEGREES
               : LSC_ARM_NEEDS_NONE;
}

int lsc_arm_target(const lsc_arm *arm, const char *arg, lsc_servo *out, char *why,
                   size_t whylen)
{
    char text[SHOWN_CAP], what[48];
    lsc_armi_value v;
    if (arg == NULL || out == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_target: no argument or no out");
    }
    const char *colon = strchr(arg, ':');
    size_t len = strlen(arg);
    if (arm == NULL && lsc_arm_needs_profile(arg) == LSC_ARM_NEEDS_NONE) {
        return parse_servo(arg, out, why, whylen); /* ID:POSITION */
    }
    if (colon == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "'%s' is not JOINT:VALUE (base:30deg, 2:-15.5deg, 1:700)",
                             lsc_armi_shown(text, arg, len));
    }
    size_t n = (size_t)(colon - arg);
    const arm_joint *aj = joint_named(arm, arg, n);
    long id = lsc_armi_as_id(arg, n);
    const char *bad = lsc_armi_parse_value(colon + 1, len - n - 1u, &v);
    if (aj == NULL && id < 0) {
        return lsc_armi_fail(
            LSC_EINVAL, why, whylen,
            arm == NULL ? "'%s' is not a servo id: a joint name needs an arm profile"
                        : "'%s' is neither a joint of the arm profile nor a servo id",
            lsc_armi_shown(text, arg, n));
    }
    if (bad != NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "'%s': %s", lsc_armi_shown(text, arg, len),
                             bad);
    }
    if (aj == NULL && v.deg) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             arm == NULL ? "'%s': servo %ld is not a joint of any arm profile, "
                                           "so it has no degrees: give a position"
                                         : "'%s': servo %ld is not a joint of the arm profile, "
                                           "so it has no degrees: give a position",
                             lsc_armi_shown(text, arg, len), id);
    }
    if (!v.deg && (v.v < 0 || v.v > 65535)) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "'%s': a position is 0..65535",
                             lsc_armi_shown(text, arg, len));
    }
    if (aj == NULL) {
        out->id = (uint8_t)id;
        out->position = (uint16_t)v.v;
        return LSC_OK;
    }
    uint16_t pos = v.deg ? 0u : (uint16_t)v.v;
    /* colon + 1 parsed as a value: at most 13 plain characters */
    (void)snprintf(what, sizeof what, "%s%s", v.deg ? "" : "position ", colon + 1);
    if (v.deg) {
        int32_t cdeg = (int32_t)v.v; /* |v.v| < 10^8: DIGITS_MAX */
        if (lsc_joint_to_pos(&aj->joint, cdeg, &pos) != 0 || cdeg < aj->joint.min_cdeg ||
            cdeg > aj->joint.max_cdeg) {
            return refuse(aj, what, why, whylen);
        }
        /* the angle is inside; the position it rounds to must be too */
        (void)snprintf(what, sizeof what, "%s (position %u)", colon + 1, pos);
    }
    if (!lsc_joint_allows_pos(&aj->joint, pos)) {
        return refuse(aj, what, why, whylen);
    }
    out->id = aj->joint.id;
    out->position = pos;
    return LSC_OK;
}

int lsc_arm_servo_id(const lsc_arm *arm, const char *arg, uint8_t *id, char *why,
                     size_t whylen)
{
    char text[SHOWN_CAP];
    unsigned long v = 0;
    if (arg == NULL || id == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_servo_id: no argument or no id");
    }
    const arm_joint *aj = joint_named(arm, arg, strlen(arg));
    if (aj != NULL) {
        *id = aj->joint.id;
        return LSC_OK;
    }
    if (arm != NULL && arg[0] != '\0' && !lsc_armi_is_digit(arg[0])) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "'%s' is neither a joint of the arm profile nor a servo id",
                             lsc_armi_shown(text, arg, strlen(arg)));
    }

    if (lsc_armi_parse_uint(arg, 255, "id", &v, why, whylen) != 0) {
        return LSC_EINVAL;
    }
    *id = (uint8_t)v;
    return LSC_OK;
}

int lsc_arm_check(const lsc_arm *arm, const lsc_servo *servos, size_t n, char *why,
                  size_t whylen)
{
    char what[24];
    if (servos == NULL && n > 0) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_check: no servos");
    }
    for (size_t k = 0; k < n; k++) {
        const arm_joint *aj = joint_on(arm, servos[k].id);
        if (aj != NULL && !lsc_joint_allows_pos(&aj->joint, servos[k].position)) {
            (void)snprintf(what, sizeof what, "position %u", servos[k].position);
            return refuse(aj, what, why, whylen);
        }
    }
    return LSC_OK;
}

int lsc_arm_chain(const lsc_arm *arm, lsc_kin_chain *chain, int *joints, char *why,
                  size_t whylen)
{
    if (arm == NULL || chain == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_chain: no arm profile or no chain");
    }
    const arm_chain *c = &arm->chain;
    if (c->chain_line == 0) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "the arm profile states no geometry: add its chain: and links: lines "
                             "(docs/arm-profile.md, docs/kinematics.md)");
    }
    chain->base_mm = (float)c->length[0] / 100.0f;
    chain->upper_mm = (float)c->length[1] / 100.0f;
    chain->fore_mm = (float)c->length[2] / 100.0f;
    chain->tool_mm = (float)c->length[3] / 100.0f;
    for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
        const lsc_joint *j = &arm->joints[c->joint[i]].joint;
        chain->min_deg[i] = (float)j->min_cdeg / 100.0f;
        chain->max_deg[i] = (float)j->max_cdeg / 100.0f;
    }
    for (size_t i = 0; joints != NULL && i < LSC_ARM_CHAIN_MAX; i++) {
        joints[i] = i < c->n ? (int)c->joint[i] : -1;
    }
    return LSC_OK;
}

int lsc_arm_degrees(const lsc_arm *arm, const lsc_servo *s, char *deg, size_t cap)
{
    const arm_joint *aj = s != NULL ? joint_on(arm, s->id) : NULL;
    int32_t cdeg;
    if (deg != NULL && cap > 0) {
        deg[0] = '\0';
        if (aj != NULL && lsc_joint_to_cdeg(&aj->joint, s->position, &cdeg) == 0) {
            lsc_armi_degrees(deg, cap, cdeg);
        }
    }
    return index_of(arm, aj);
}

#endif
