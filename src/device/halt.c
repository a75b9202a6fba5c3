/* lsc device: halt and hold (the servos stay where they are) and the ids
 * "all" stands for (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <string.h>

#include "device_internal.h"

int lsc_device_all_ids(const lsc_arm *arm, const char *name, uint8_t *ids, size_t cap)
{
    size_t n;
    if (ids == NULL && cap > 0) {
        return LSC_EINVAL;
    }
    if (arm != NULL) {
        n = lsc_arm_count(arm);
        for (size_t i = 0; i < n && i < cap; i++) {
            ids[i] = lsc_arm_joint(arm, i)->id;
        }
        return (int)n;
    }
    if (name == NULL) {
        name = lsc_dev_env_port();
        if (name == NULL) {
            return LSC_ENODEV; /* discovery decides the kind */
        }
    }
    n = lsc_dev_transport_of(name)->all_ids(name);
    for (size_t i = 0; i < n && i < cap; i++) {
        ids[i] = (uint8_t)(i + 1u);
    }
    return (int)n;
}

int lsc_device_parse_ids_all(const lsc_arm *arm, const char *name, const char *list,
                             uint8_t *ids, size_t cap, char *why, size_t whylen)
{
    if (list == NULL || strcmp(list, "all") != 0 || ids == NULL || cap == 0) {
        return lsc_device_parse_ids(arm, list, ids, cap, why, whylen);
    }
    int n = lsc_device_all_ids(arm, name, ids, cap);
    if (n == LSC_ENODEV) {
        (void)lsc_dev_refuse(why, whylen,
                             "'all' stands for the controller's servos, which its kind tells: "
                             "name the controller or give an arm profile");
        return LSC_ENODEV;
    }
    if ((size_t)n > cap) {
        return lsc_dev_refuse(why, whylen, "'all' is %d servos here: more than %lu", n,
                              (unsigned long)cap);
    }
    return n;
}

/* lsc_device_hold after lsc_dev_begin. */
static int hold(lsc_device *d, const uint8_t *ids, size_t n, lsc_hold_result *res)
{
    char why[LSC_ARM_MESSAGE_MAX], first[LSC_ARM_MESSAGE_MAX];
    if (ids == NULL || n == 0 || n > LSC_MOVE_MAX) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "holding %lu servos: one hold takes 1..%u; nothing was sent",
                            ids == NULL ? 0ul : (unsigned long)n, LSC_MOVE_MAX);
    }
    int r = lsc_dev_bound(d, n, "a hold", "; hold them in parts");
    if (r != 0) {
        return r;
    }
    size_t rep = lsc_ids_first_repeat(ids, 1, n);
    if (rep < n) {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "servo %u is given twice in one hold; nothing was sent", ids[rep]);
    }
    r = lsc_dev_read_positions(d, ids, n, res->held);
    if (r < 0) {
        return r;
    }
    first[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        if (lsc_arm_check(d->arm, &res->held[i], 1, why, sizeof why) != 0) {
            if (res->nbeyond == 0) {
                (void)snprintf(first, sizeof first, "%s", why);
            }
            res->beyond[res->nbeyond++] = res->held[i].id;
        }
    }
    /* the limits are not checked: each servo goes where it already is */
    r = d->t->ops->move(d, LSC_HOLD_MS, res->held, n);
    if (r != 0) {
        return lsc_dev_link_fail(d, r);
    }
    lsc_dev_remember(d, res->held, n);
    res->n = n;
    /* the move's time: when this returns, they hold (a servo that went on
     * during the read is back where it was read) */
    r = lsc_dev_pass(d, LSC_HOLD_MS);
    if (r != 0) {
        return r;
    }
    if (res->nbeyond == 0) {
        return 0;
    }
    return lsc_dev_fail(d, LSC_HOLD_BEYOND, LSC_DEVICE_CAUSE_NONE,
                        "held where it is, beyond its limits: %s; move it back within them "
                        "(moves out of a limit stay refused)",
                        first);
}

int lsc_device_hold(lsc_device *d, const uint8_t *ids, size_t n, lsc_hold_result *res)
{
    lsc_hold_result all = {0};
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r = lsc_dev_sized(d, res, LSC_SIZED_MIN(lsc_hold_result, n), "lsc_hold_result");
    if (r != 0) {
        return r;
    }
    all.size = sizeof all;
    r = hold(d, ids, n, &all);
    lsc_sized_give(res, &all, sizeof all);
    return r;
}

int lsc_device_halt(lsc_device *d)
{
    uint8_t ids[LSC_MOVE_MAX];
    lsc_hold_result res = {0};
    res.size = sizeof res;
    if (d == NULL) {
        return LSC_EINVAL;
    }
    lsc_dev_begin(d);
    int r;
    if (d->t->ops->halt != NULL) { /* e.g. lscd halts its controller, whoever leases it */
        return d->t->ops->halt(d);
    }
    r = d->t->ops->stop != NULL ? d->t->ops->stop(d) : 0; /* a kind without groups: none runs */
    if (r != 0) {
        return lsc_dev_link_fail(d, r);
    }
    /* (d->name is known; a profile of more joints than one move takes is
     * refused by hold before it reads ids) */
    int n = lsc_device_all_ids(d->arm, d->name, ids, sizeof ids);
    r = hold(d, ids, (size_t)n, &res);
    if (r == LSC_ETIMEOUT) {
        char was[DEVICE_MESSAGE_MAX];
        (void)snprintf(was, sizeof was, "%s", d->message);
        return lsc_dev_fail(d, r, d->cause,
                            "halt: the action group was stopped, but the servos' positions "
                            "could not be read, so they go on to their last targets: %s",
                            was);
    }
    return r;
}

#endif
