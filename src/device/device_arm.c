/* lsc device: the arm profile a device carries (lsc/arm.h), and the limit
 * check of moves against it (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include "device_internal.h"

int lsc_device_set_arm(lsc_device *d, const lsc_arm *arm)
{
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_arm *copy = NULL;
    if (arm != NULL) {
        copy = lsc_arm_copy(arm);
        if (copy == NULL) {
            return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE,
                                "out of memory for the arm profile");
        }
    }
    lsc_arm_free(d->arm);
    d->arm = copy;
    if (d->t->arm_set != NULL) { /* e.g. the virtual controller becomes that arm */
        d->t->arm_set(d, copy);
    }
    return 0;
}

const lsc_arm *lsc_device_arm(const lsc_device *d)
{
    return d == NULL ? NULL : d->arm;
}

void lsc_dev_arm_free(lsc_device *d)
{
    lsc_arm_free(d->arm);
    d->arm = NULL;
}

int lsc_dev_arm_check(lsc_device *d, const lsc_servo *servos, size_t n)
{
    char why[LSC_ARM_MESSAGE_MAX];
    if (d->arm == NULL) {
        return 0;
    }
    int r = lsc_arm_check(d->arm, servos, n, why, sizeof why);
    return r == 0 ? 0 : lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NONE, "%s; nothing was sent", why);
}

#endif
