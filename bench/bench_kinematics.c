/* Benchmark (not a test): the time of one inverse kinematics solve on this
 * host (lsc_kin_inverse, include/lsc/kinematics.h) with the xArm's chain
 * (examples/arms/xarm.conf's lengths and limits): targets made by the
 * forward kinematics of angles spread over the limits, each solved
 *   - with its pitch given;
 *   - without, from the angles that made it (the present pitch reaches it);
 *   - without, from the arm straight up (pitch 90: mostly the whole search);
 *   - without, from other angles spread over the limits.
 * Prints ns per solve of each (the best of several passes), how many were
 * solved, and the forward kinematics' time for comparison.
 * Usage: bench_kinematics [PASSES] (default 5). The Uno's cycle counts:
 * tests/embedded/sketches/KinBench (ctest -R arduino_kinbench). */
#define _POSIX_C_SOURCE 199309L

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lsc/kinematics.h"

#define TARGETS 4096
#define MODES 5

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static float spread(unsigned *seed, float lo, float hi)
{
    *seed = *seed * 1103515245u + 12345u;
    return lo + (hi - lo) * (float)((*seed >> 8) % 10000u) / 10000.0f;
}

int main(int argc, char **argv)
{
    static const char *const names[MODES] = {
        "inverse, pitch given", "inverse, pitch chosen, the present one reaches",
        "inverse, pitch chosen, from straight up", "inverse, pitch chosen, from other angles",
        "forward"};
    static lsc_kin_target targets[TARGETS];
    static float made[TARGETS][LSC_KIN_JOINTS], other[TARGETS][LSC_KIN_JOINTS];
    static const float up[LSC_KIN_JOINTS] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    lsc_kin_chain c = {64.7f, 98.8f, 94.7f, 158.8f,
                       {-114.59f, -90.52f, -114.59f, -103.13f, -114.59f},
                       {114.59f, 90.52f, 114.59f, 114.59f, 114.59f}};
    int passes = argc > 1 ? (int)strtol(argv[1], NULL, 10) : 5;
    unsigned seed = 1;
    for (int i = 0; i < TARGETS; i++) {
        lsc_kin_pose p;
        for (int k = 0; k < LSC_KIN_JOINTS; k++) {
            made[i][k] = spread(&seed, c.min_deg[k], c.max_deg[k]);
            other[i][k] = spread(&seed, c.min_deg[k], c.max_deg[k]);
        }
        (void)lsc_kin_forward(&c, made[i], &p);
        targets[i] = (lsc_kin_target){p.x_mm, p.y_mm, p.z_mm, p.pitch_deg, 0.0f, true, false};
    }
    double best[MODES];
    int solved[MODES] = {0};
    for (int m = 0; m < MODES; m++) {
        best[m] = 1e30;
    }
    volatile float sink = 0.0f;
    for (int pass = 0; pass < (passes > 0 ? passes : 1); pass++) {
        for (int mode = 0; mode < MODES; mode++) {
            double t0 = now_ns();
            int ok = 0;
            for (int i = 0; i < TARGETS; i++) {
                float q[LSC_KIN_JOINTS] = {0};
                lsc_kin_pose p;
                lsc_kin_target t = targets[i];
                const float *near = mode == 2 ? up : mode == 3 ? other[i] : made[i];
                if (mode == 4) {
                    ok += lsc_kin_forward(&c, made[i], &p) == 0;
                    sink += p.x_mm;
                    continue;
                }
                t.has_pitch = mode == 0;
                ok += lsc_kin_inverse(&c, &t, near, q, NULL) == 0;
                sink += q[0];
            }
            double ns = (now_ns() - t0) / TARGETS;
            best[mode] = ns < best[mode] ? ns : best[mode];
            solved[mode] = ok;
        }
    }
    for (int m = 0; m < MODES; m++) {
        printf("%s: %.0f ns (%d of %d solved)\n", names[m], best[m], solved[m], TARGETS);
    }
    if (sink != sink) { /* keeps the results from being optimised away */
        return 1;
    }
    return 0;
}
