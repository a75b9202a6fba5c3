/* lsc units: joint angle <-> servo position, and limits (include/lsc/units.h).
 * Integer arithmetic only; the bounds lsc_joint_valid checks keep every
 * product below 2^31 (|angle| * range <= 36000 * 10000). */
#include "lsc/units.h"

/* num / den rounded to the nearest integer, halves away from zero; den > 0. */
static int32_t div_round(int32_t num, int32_t den)
{
    return num >= 0 ? (num + den / 2) / den : -((-num + den / 2) / den);
}

static bool within_cdeg(int32_t cdeg)
{
    return cdeg >= -LSC_UNITS_CDEG_MAX && cdeg <= LSC_UNITS_CDEG_MAX;
}

bool lsc_joint_valid(const lsc_joint *j)
{
    return j != NULL && (j->direction == 1 || j->direction == -1) && j->pos_min < j->pos_max &&
           j->pos_max <= LSC_UNITS_POS_MAX && j->span_cdeg >= 1 &&
           j->span_cdeg <= LSC_UNITS_CDEG_MAX && j->zero >= j->pos_min && j->zero <= j->pos_max &&
           within_cdeg(j->min_cdeg) && within_cdeg(j->max_cdeg) && j->min_cdeg <= j->max_cdeg;
}

int lsc_joint_to_cdeg(const lsc_joint *j, uint16_t pos, int32_t *cdeg)
{
    if (!lsc_joint_valid(j) || cdeg == NULL || pos < j->pos_min || pos > j->pos_max) {
        return LSC_EINVAL;
    }
    int32_t steps = ((int32_t)pos - (int32_t)j->zero) * j->direction;
    *cdeg = div_round(steps * j->span_cdeg, (int32_t)j->pos_max - (int32_t)j->pos_min);
    return LSC_OK;
}

int lsc_joint_to_pos(const lsc_joint *j, int32_t cdeg, uint16_t *pos)
{
    if (!lsc_joint_valid(j) || pos == NULL || !within_cdeg(cdeg)) {
        return LSC_EINVAL;
    }
    int32_t range = (int32_t)j->pos_max - (int32_t)j->pos_min;
    int32_t p = (int32_t)j->zero + j->direction * div_round(cdeg * range, j->span_cdeg);
    if (p < (int32_t)j->pos_min || p > (int32_t)j->pos_max) {
        return LSC_EINVAL;
    }
    *pos = (uint16_t)p;
    return LSC_OK;
}

int lsc_joint_init_range(lsc_joint *j, uint8_t id, uint16_t pos_min, uint16_t pos_max,
                         int32_t span_cdeg)
{
    lsc_joint t;
    int32_t a = 0, b = 0;
    if (j == NULL) {
        return LSC_EINVAL;
    }
    t.id = id;
    t.direction = 1;
    t.pos_min = pos_min;
    t.pos_max = pos_max;
    t.span_cdeg = span_cdeg;
    t.zero = (uint16_t)(pos_min + (pos_max > pos_min ? (pos_max - pos_min) / 2 : 0));
    t.min_cdeg = 0;
    t.max_cdeg = 0;
    /* limits: the angles of both ends (valid so far with limits 0..0) */
    if (lsc_joint_to_cdeg(&t, pos_min, &a) != LSC_OK) {
        return LSC_EINVAL;
    }
    (void)lsc_joint_to_cdeg(&t, pos_max, &b);
    t.min_cdeg = a;
    t.max_cdeg = b;
    if (!lsc_joint_valid(&t)) { /* an end beyond LSC_UNITS_CDEG_MAX */
        return LSC_EINVAL;
    }
    *j = t;
    return LSC_OK;
}

int lsc_joint_init(lsc_joint *j, uint8_t id, lsc_joint_kind kind)
{
    switch (kind) {
    case LSC_JOINT_PWM: return lsc_joint_init_range(j, id, 500, 2500, 18000);
    case LSC_JOINT_BUS: return lsc_joint_init_range(j, id, 0, 1000, 24000);
    default: return LSC_EINVAL;
    }
}

bool lsc_joint_allows(const lsc_joint *j, int32_t cdeg)
{
    uint16_t pos;
    return lsc_joint_to_pos(j, cdeg, &pos) == LSC_OK && cdeg >= j->min_cdeg &&
           cdeg <= j->max_cdeg;
}

bool lsc_joint_allows_pos(const lsc_joint *j, uint16_t pos)
{
    if (!lsc_joint_valid(j) || pos < j->pos_min || pos > j->pos_max) {
        return false;
    }
    /* exact: min <= (pos - zero) * dir * span / range <= max, times range */
    int32_t range = (int32_t)j->pos_max - (int32_t)j->pos_min;
    int32_t scaled = ((int32_t)pos - (int32_t)j->zero) * j->direction * j->span_cdeg;
    return scaled >= j->min_cdeg * range && scaled <= j->max_cdeg * range;
}
