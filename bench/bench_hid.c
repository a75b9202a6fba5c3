/* Time per battery round trip through the HID transport and the client,
 * against the hidapi test double (tests/hid_double.c, linked in place of
 * libhidapi-hidraw): one 65-byte report out, one 64-byte report back from the
 * virtual controller. Also times the double alone (hid_write and
 * hid_read_timeout called directly, the same reports), so the difference is
 * the client's and the transport's own cost. Prints median and p90 in
 * microseconds. No USB is involved: a real arm adds its USB polling interval
 * and its firmware's time (docs/protocol.md: up to ~450 ms for a position read).
 *
 * Usage: bench_hid [ITERATIONS] */
#define _DEFAULT_SOURCE 1
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <hidapi.h>

#include "hid_double.h"
#include "lsc/lsc.h"

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static void report(const char *what, uint64_t *t, long n)
{
    qsort(t, (size_t)n, sizeof *t, cmp);
    long median = n / 2, p90 = n * 9 / 10, p10 = n / 10; /* indices of the sorted times */
    printf("%s, %ld iterations: median %.2f us, p90 %.2f us (p10 %.2f us, max %.2f us)\n", what,
           n, (double)t[median] / 1000.0, (double)t[p90] / 1000.0, (double)t[p10] / 1000.0,
           (double)t[n - 1] / 1000.0);
}

int main(int argc, char **argv)
{
    long iterations = argc > 1 ? strtol(argv[1], NULL, 10) : 100000;
    if (iterations < 10 || iterations > 10000000) {
        fprintf(stderr, "usage: %s [ITERATIONS (10..10000000)]\n", argv[0]);
        return 2;
    }
    char dir[] = "/tmp/lsc-bench-hid-XXXXXX";
    char node[64];
    if (mkdtemp(dir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(node, sizeof node, "%s/hidraw0", dir);
    FILE *f = fopen(node, "w");
    if (f == NULL) {
        perror(node);
        return 1;
    }
    (void)fclose(f);
    hid_double_reset();
    hid_double_add(node, "BENCH", 0, 0);
    uint64_t *t = malloc((size_t)iterations * sizeof *t);
    if (t == NULL) {
        return 1;
    }
    int status = 0;

    /* the double alone: a request report out, the reply report back */
    hid_device *dev = hid_open_path(node);
    uint8_t out[65] = {0x00, 0x55, 0x55, 0x02, 0x0F}, in[64];
    for (long i = 0; i < iterations && dev != NULL; i++) {
        uint64_t start = now_ns();
        int w = hid_write(dev, out, sizeof out);
        int r = hid_read_timeout(dev, in, sizeof in, 1000);
        t[i] = now_ns() - start;
        if (w != 65 || r != 64 || in[3] != 0x0F) {
            fprintf(stderr, "double alone: round trip %ld failed\n", i);
            status = 1;
            break;
        }
    }
    hid_close(dev);
    if (status == 0) {
        report("hidapi test double alone (hid_write + hid_read_timeout)", t, iterations);
    }

    /* the client and the transport over the double */
    lsc_hid *hid = NULL;
    if (status == 0 && lsc_hid_open_path(node, &hid) != 0) {
        fprintf(stderr, "%s\n", lsc_hid_error_message(hid));
        status = 1;
    }
    lsc_io io;
    lsc_client client;
    lsc_hid_get_io(hid, &io);
    lsc_client_init(&client, &io);
    for (long i = 0; i < iterations && status == 0; i++) {
        uint16_t mv = 0;
        uint64_t start = now_ns();
        int r = lsc_client_get_battery(&client, &mv, 1000);
        t[i] = now_ns() - start;
        if (r != 0 || mv != 7500) {
            fprintf(stderr, "round trip %ld failed: %s\n", i, lsc_strerror(r));
            status = 1;
        }
    }
    if (status == 0) {
        report("battery round trip, client + HID transport + test double", t, iterations);
    }
    lsc_hid_close(hid);
    free(t);
    unlink(node);
    rmdir(dir);
    return status;
}
