/* The C side of bench/bench_play.py: a play through lsc_device_play (the call
 * lscctl play makes) with a callback, and reads of six servos, on a port
 * (lsc-sim's pty), through the shared library the Python bindings load.
 *
 *   bench_device_play play PORT FILE LEAD_MS
 *     plays FILE (speed 100, once, the port's baud); prints one line per
 *     frame sent: "step DUE_MS ELAPSED_MS US", where ELAPSED_MS is what the
 *     callback was given and US the microseconds (CLOCK_MONOTONIC) from just
 *     before the play to the callback.
 *   bench_device_play read PORT COUNT
 *     COUNT reads of servos 1..6; prints one line per read: "read US".
 * Exit 0, 1 on an error (said on stderr), 2 for a usage error. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/play.h"
#include "lsc/player.h"

static double now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

typedef struct steps {
    double start_us;
    size_t n, cap;
    unsigned long *due, *elapsed;
    double *at_us;
} steps;

static bool on_step(void *user, const lsc_player_step *s, uint32_t elapsed_ms)
{
    steps *st = user;
    double t = now_us();
    if (s != NULL && st->n < st->cap) {
        st->due[st->n] = s->due_ms;
        st->elapsed[st->n] = elapsed_ms;
        st->at_us[st->n] = t - st->start_us;
        st->n++;
    }
    return true;
}

static int play(lsc_device *d, const char *file, long lead)
{
    lsc_action a;
    lsc_file_error err = {.size = sizeof err};
    if (lsc_action_read(file, &a, &err) != 0) {
        fprintf(stderr, "bench_device_play: %s: %s\n", file, err.message);
        return 1;
    }
    steps st;
    memset(&st, 0, sizeof st);
    st.cap = (size_t)a.count + 1u;
    st.due = calloc(st.cap, sizeof *st.due);
    st.elapsed = calloc(st.cap, sizeof *st.elapsed);
    st.at_us = calloc(st.cap, sizeof *st.at_us);
    lsc_player_config cfg = {100, 1, (uint16_t)lead, 0};
    lsc_play_result res = {.size = sizeof res};
    int r = -1;
    if (st.due != NULL && st.elapsed != NULL && st.at_us != NULL) {
        st.start_us = now_us();
        r = lsc_device_play(d, &a, &cfg, on_step, &st, &res);
    }
    if (r != 0) {
        fprintf(stderr, "bench_device_play: play: %s\n", lsc_device_error(d));
    }
    for (size_t i = 0; r == 0 && i < st.n; i++) {
        printf("step %lu %lu %.1f\n", st.due[i], st.elapsed[i], st.at_us[i]);
    }
    free(st.due);
    free(st.elapsed);
    free(st.at_us);
    lsc_action_free(&a);
    return r == 0 ? 0 : 1;
}

static int reads(lsc_device *d, long count)
{
    static const uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    lsc_servo out[6];
    for (long i = 0; i < count; i++) {
        double t0 = now_us();
        if (lsc_device_read(d, ids, 6, out) != 6) {
            fprintf(stderr, "bench_device_play: read: %s\n", lsc_device_error(d));
            return 1;
        }
        printf("read %.1f\n", now_us() - t0);
    }
    return 0;
}

int main(int argc, char **argv)
{
    bool is_play = argc == 5 && strcmp(argv[1], "play") == 0;
    bool is_read = argc == 4 && strcmp(argv[1], "read") == 0;
    long n = is_play ? strtol(argv[4], NULL, 10) : is_read ? strtol(argv[3], NULL, 10) : -1;
    if (!(is_play || is_read) || n < 0 || n > 65535) {
        fprintf(stderr, "usage: bench_device_play play PORT FILE LEAD_MS\n"
                        "       bench_device_play read PORT COUNT\n");
        return 2;
    }
    lsc_device *d;
    if (lsc_device_open(argv[2], NULL, &d) != 0) {
        fprintf(stderr, "bench_device_play: %s\n", lsc_device_error(d));
        lsc_device_close(d);
        return 1;
    }
    int code = is_play ? play(d, argv[3], n) : reads(d, n);
    lsc_device_close(d);
    return code;
}
