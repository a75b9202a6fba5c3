/* The C side of bench/bench_python.py: the time of one lsc_device_battery and
 * one lsc_device_read of six servos on the virtual controller ("sim"), through
 * the shared library (the one the Python bindings load). Prints, for each, the
 * best of ROUNDS rounds of CALLS calls, in microseconds per call:
 *   battery 1.234
 *   read6 2.345
 * Usage: bench_device [CALLS] [ROUNDS] */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lsc/device.h"

static double now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

int main(int argc, char **argv)
{
    long calls = argc > 1 ? strtol(argv[1], NULL, 10) : 20000;
    long rounds = argc > 2 ? strtol(argv[2], NULL, 10) : 5;
    if (calls < 1 || rounds < 1) {
        fprintf(stderr, "usage: bench_device [CALLS] [ROUNDS]\n");
        return 2;
    }
    lsc_device *d;
    if (lsc_device_open("sim", NULL, &d) != 0) {
        fprintf(stderr, "bench_device: %s\n", lsc_device_error(d));
        lsc_device_close(d);
        return 1;
    }
    /* the library's own cost: the model answers on its virtual clock (on the
     * real one each reply would take its time on a 9600 baud line) */
    (void)lsc_device_set_virtual_clock(d, true);
    static const uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    lsc_servo out[6];
    uint16_t mv = 0;
    double best_battery = 1e30, best_read = 1e30;
    int r = 0;
    for (long k = 0; k < rounds && r >= 0; k++) {
        double t0 = now_us();
        for (long i = 0; i < calls && r >= 0; i++) {
            r = lsc_device_battery(d, &mv);
        }
        double t1 = now_us();
        for (long i = 0; i < calls && r >= 0; i++) {
            r = lsc_device_read(d, ids, 6, out);
        }
        double t2 = now_us();
        if ((t1 - t0) / (double)calls < best_battery) {
            best_battery = (t1 - t0) / (double)calls;
        }
        if ((t2 - t1) / (double)calls < best_read) {
            best_read = (t2 - t1) / (double)calls;
        }
    }
    if (r < 0 || mv != 7500) {
        fprintf(stderr, "bench_device: %s\n", lsc_device_error(d));
        lsc_device_close(d);
        return 1;
    }
    lsc_device_close(d);
    printf("battery %.3f\nread6 %.3f\n", best_battery, best_read);
    return 0;
}
