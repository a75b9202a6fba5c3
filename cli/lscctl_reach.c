/* lscctl: the hand through the arm profile's geometry: where, reach, and
 * move --speed. The planning (angles, limits, waypoints, times) is the
 * library's (lsc_device_where, lsc_device_reach, lsc_device_move_speed in
 * lsc/device.h): this file checks the command line, opens the port, prints. */
#include <stdio.h>
#include <string.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/motion.h"
#include "lsc/kinematics.h"
#include "lscctl.h"
#include "lscctl_parse.h"
#include "lscctl_port.h"

static int usage(const lscctl_opts *o, const char *why)
{
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s (see 'lscctl help %s')", why, o->cmd);
}

/* The arm profile of --arm or $LSC_ARM, which must state its geometry when
 * geometry is true: 0 and *out, or the exit code after saying why. */
static int need_arm(const lscctl_opts *o, bool geometry, lsc_arm **out)
{
    char why[LSC_ARM_MESSAGE_MAX];
    lsc_kin_chain c;
    *out = NULL;
    if (o->arm == NULL) {
        return usage(o, geometry ? "the hand's position needs an arm profile that states its "
                                   "geometry: --arm FILE (docs/kinematics.md)"
                                 : "--speed in degrees a second needs an arm profile: --arm "
                                   "FILE");
    }
    if (lsc_arm_open(o->arm, out, why, sizeof why) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    if (geometry && lsc_arm_chain(*out, &c, NULL, why, sizeof why) != 0) {
        lsc_arm_free(*out);
        *out = NULL;
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
    }
    return 0;
}

/* v for printing with `decimals` decimals: never "-0.0" */
static double shown(float v, int decimals)
{
    double half = decimals == 1 ? 0.05 : 0.005;
    return (double)v > -half && (double)v < half ? 0.0 : (double)v;
}

/* -n: these commands read the arm's angles first, which a dry run cannot. */
static int no_dry_run(const lscctl_opts *o)
{
    return o->dry_run ? usage(o, "-n: this command reads where the servos are before it "
                                 "sends anything, so it has no dry run")
                      : 0;
}

/* Opens the port with the profile set on the device: 0 and *l, or an exit code. */
static int open_with(const lscctl_opts *o, const lsc_arm *arm, lscctl_link **l)
{
    int r = lscctl_link_open(o, l);
    if (r == 0) {
        r = lscctl_link_check(*l, lsc_device_set_arm(lscctl_link_device(*l), arm));
        if (r != 0) {
            lscctl_link_close(*l);
        }
    }
    return r;
}

int lscctl_cmd_where(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    static const char *const ends[2] = {"lower", "upper"};
    lsc_arm *arm;
    lscctl_link *l;
    lsc_where w = {.size = sizeof w};
    int r = need_arm(o, true, &arm);
    if (r == 0) {
        r = no_dry_run(o);
    }
    if (r == 0) {
        r = open_with(o, arm, &l);
    }
    if (r != 0) {
        lsc_arm_free(arm);
        return r;
    }
    r = lscctl_link_check(l, lsc_device_where_ex(lscctl_link_device(l), &w));
    lscctl_link_close(l);
    const lsc_kin_pose *p = &w.pose;
    if (r == 0 && o->json) {
        printf("{\"x_mm\":%.2f,\"y_mm\":%.2f,\"z_mm\":%.2f,\"pitch_deg\":%.2f,\"joints\":{",
               shown(p->x_mm, 2), shown(p->y_mm, 2), shown(p->z_mm, 2), shown(p->pitch_deg, 2));
        for (size_t i = 0; i < LSC_KIN_JOINTS; i++) {
            printf("%s", i > 0 ? "," : "");
            lscctl_json_string(stdout, lsc_arm_name(arm, (size_t)w.joint[i]));
            printf(":%.2f", shown(w.q[i], 2));
        }
        printf("},\"near_end\":{");
        for (int i = 0, n = 0; i < LSC_KIN_JOINTS; i++) {
            for (int high = 0; high < 2; high++) {
                if ((w.near_end & (high ? LSC_KIN_NEAR_HIGH(i) : LSC_KIN_NEAR_LOW(i))) != 0u) {
                    printf("%s", n++ > 0 ? "," : "");
                    lscctl_json_string(stdout, lsc_arm_name(arm, (size_t)w.joint[i]));
                    printf(":\"%s\"", ends[high]);
                }
            }
        }
        printf("}}\n");
    } else if (r == 0) {
        printf("x %.1f y %.1f z %.1f mm, pitch %.1f deg\n", shown(p->x_mm, 1), shown(p->y_mm, 1),
               shown(p->z_mm, 1), shown(p->pitch_deg, 1));
        /* a joint near an end: which, and how near */
        for (int i = 0; i < LSC_KIN_JOINTS; i++) {
            for (int high = 0; high < 2; high++) {
                if ((w.near_end & (high ? LSC_KIN_NEAR_HIGH(i) : LSC_KIN_NEAR_LOW(i))) != 0u) {
                    printf("%s at %.2f deg: within %g deg of its %s limit %.2f deg\n",
                           lsc_arm_name(arm, (size_t)w.joint[i]), shown(w.q[i], 2),
                           (double)LSC_KIN_NEAR_END_DEG, ends[high],
                           (double)(high ? w.chain.max_deg[i] : w.chain.min_deg[i]));
                }
            }
        }
    }
    lsc_arm_free(arm);
    return r;
}

int lscctl_cmd_reach(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    static const char *const axes[3] = {"X", "Y", "Z"};
    char why[160];
    double v[3];
    lsc_reach req = {.size = sizeof req};
    lsc_reach_result res = {.size = sizeof res};
    lsc_arm *arm;
    lscctl_link *l;
    for (int i = 0; i < 3; i++) {
        if (lscctl_parse_decimal(argv[i], -10000, 10000, axes[i], &v[i], why, sizeof why) != 0) {
            (void)snprintf(why + strlen(why), sizeof why - strlen(why), " (millimetres)");
            return usage(o, why);
        }
    }
    if (o->time_set && o->deg_speed > 0) {
        return usage(o, "give --time or --speed, not both");
    }
    if (o->time_set && o->time_ms == 0) {
        return usage(o, "--time 0: give 1..65535 ms");
    }
    if (o->step > 0 && !o->line) {
        return usage(o, "--step is the distance between the waypoints of --line");
    }
    int r = need_arm(o, true, &arm);
    if (r == 0) {
        r = no_dry_run(o);
    }
    if (r != 0) {
        lsc_arm_free(arm);
        return r;
    }
    req.target = (lsc_kin_target){(float)v[0], (float)v[1], (float)v[2], (float)o->pitch,
                                  (float)o->roll, o->pitch_set, o->roll_set};
    req.time_ms = (uint16_t)o->time_ms;
    req.speed_dps = (float)o->deg_speed;
    req.line = o->line;
    req.step_mm = (float)o->step;
    req.wait = o->wait;
    req.tolerance = (uint16_t)o->tolerance;
    req.flags = o->strict ? LSC_SETTLE_STRICT : 0u;
    r = open_with(o, arm, &l);
    lsc_arm_free(arm);
    if (r != 0) {
        return r;
    }
    r = lscctl_link_settled(l, lsc_device_reach(lscctl_link_device(l), &req, &res),
                            &res.settle);
    lscctl_link_close(l);
    if (r == 0 && o->json) {
        printf("{\"x_mm\":%.2f,\"y_mm\":%.2f,\"z_mm\":%.2f,\"pitch_deg\":%.2f,"
               "\"waypoints\":%lu,\"time_ms\":%lu}\n",
               v[0], v[1], v[2], shown(res.kin.pitch_deg, 2), (unsigned long)res.waypoints,
               (unsigned long)res.time_ms);
    }
    return r;
}

int lscctl_move_at_speed(const lscctl_opts *o, const lsc_servo *servos, size_t n)
{
    lsc_arm *arm;
    lscctl_link *l;
    uint16_t t = 0;
    if (o->time_set) {
        return usage(o, "give --time or --speed, not both");
    }
    int r = need_arm(o, false, &arm);
    if (r == 0) {
        r = no_dry_run(o);
    }
    if (r == 0) {
        r = open_with(o, arm, &l);
    }
    lsc_arm_free(arm);
    if (r != 0) {
        return r;
    }
    lsc_settle_result res = {.size = sizeof res};
    int e = lsc_device_move_speed(lscctl_link_device(l), servos, n, (float)o->deg_speed, o->wait,
                                  (uint16_t)o->tolerance, o->strict ? LSC_SETTLE_STRICT : 0u,
                                  &t, &res);
    if (t > 0 && o->verbose) { /* sent: before what the wait says */
        (void)lscctl_fail(o, 0, "the move takes %u ms", t);
    }
    r = lscctl_link_settled(l, e, &res);
    lscctl_link_close(l);
    return r;
}
