/* Benchmark (not a test): the time of one inverse kinematics solve on this
 * host (lsc_kin_inverse, include/lsc/kinematics.h), with the xArm's chain
 * (examples/arms/xarm.conf's figures): targets made by the forward
 * kinematics of angles spread over the limits, each solved with its pitch
 * given, then again without (the pitch searched from the current one).
 * Prints ns per solve of each (the best of several passes) and the forward
 * kinematics' for comparison. Usage: bench_kinematics [PASSES] (default 5).
 * The Uno's cycle count: tests/embedded (the IK example in simavr). */
#define _POSIX_C_SOURCE 199309L

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lsc/kinematics.h"

#define TARGETS 4096

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    static lsc_kin_target targets[TARGETS];
    static float near[TARGETS][LSC_KIN_JOINTS];
    lsc_kin_chain c = {64.7f, 98.8f, 94.7f, 158.8f, {0}, {0}};
    int passes = argc > 1 ? (int)strtol(argv[1], NULL, 10) : 5;
    unsigned seed = 1;
    for (int i = 0; i < LSC_KIN_JOINTS; i++) {
        c.min_deg[i] = -115.0f;
        c.max_deg[i] = 115.0f;
    }
    for (int i = 0; i < TARGETS; i++) {
        lsc_kin_pose p;
        for (int k = 0; k < LSC_KIN_JOINTS; k++) {
            seed = seed * 1103515245u + 12345u;
            near[i][k] = (float)((seed >> 8) % 2000u) / 10.0f - 100.0f;
        }
        (void)lsc_kin_forward(&c, near[i], &p);
        targets[i] = (lsc_kin_target){p.x_mm, p.y_mm, p.z_mm, p.pitch_deg, 0.0f, true, false};
    }
    double best[3] = {1e30, 1e30, 1e30};
    int solved[2] = {0, 0};
    volatile float sink = 0.0f;
    for (int pass = 0; pass < (passes > 0 ? passes : 1); pass++) {
        for (int mode = 0; mode < 3; mode++) {
            double t0 = now_ns();
            int ok = 0;
            for (int i = 0; i < TARGETS; i++) {
                float q[LSC_KIN_JOINTS];
                lsc_kin_pose p;
                lsc_kin_target t = targets[i];
                if (mode == 2) {
                    ok += lsc_kin_forward(&c, near[i], &p) == 0;
                    sink += p.x_mm;
                    continue;
                }
                t.has_pitch = mode == 0;
                ok += lsc_kin_inverse(&c, &t, near[i], q, NULL) == 0;
                sink += q[0];
            }
            double ns = (now_ns() - t0) / TARGETS;
            best[mode] = ns < best[mode] ? ns : best[mode];
            if (mode < 2) {
                solved[mode] = ok;
            }
        }
    }
    printf("inverse, pitch given: %.0f ns per solve (%d of %d targets solved)\n", best[0],
           solved[0], TARGETS);
    printf("inverse, pitch chosen: %.0f ns per solve (%d of %d solved)\n", best[1], solved[1],
           TARGETS);
    printf("forward: %.0f ns\n", best[2]);
    if (sink != sink) { /* keeps the results from being optimised away */
        return 1;
    }
    return 0;
}
