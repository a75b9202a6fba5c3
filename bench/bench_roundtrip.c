/* Round-trip time of a battery request through the serial transport and the
 * client, over a pseudo-terminal, against a peer thread that answers at once.
 * Prints the median (and spread) of many round trips, in microseconds.
 *
 * Usage: bench_roundtrip [ITERATIONS] [termios|libserialport|auto]
 *
 * A pty moves bytes at memory speed whatever the baud rate, so this measures
 * the software path (client, transport, kernel tty layer, thread wake-ups),
 * not the wire: on a real 9600-baud line the same exchange adds 10.4 ms of
 * wire time (4 bytes out, 6 back). The libserialport backend cannot open a
 * pty (libserialport 0.1.1), so it fails here; tests/sp_pty_shim.c shows how
 * the tests get around that. */
#define _DEFAULT_SOURCE 1
#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "lsc/lsc.h"

static int master = -1;

/* Answers every 4-byte battery request with a 7500 mV reply, until EOF. */
static void *peer(void *arg)
{
    (void)arg;
    uint8_t reply[8];
    int n = lsc_encode_battery_reply(reply, sizeof reply, 7500);
    uint8_t req[64];
    size_t have = 0;
    for (;;) {
        ssize_t r = read(master, req + have, sizeof req - have);
        if (r < 0 && errno == EINTR) {
            continue;
        }
        if (r <= 0) {
            return NULL;
        }
        have += (size_t)r;
        while (have >= 4) {
            if (write(master, reply, (size_t)n) != n) {
                return NULL;
            }
            memmove(req, req + 4, have - 4);
            have -= 4;
        }
    }
}

static uint64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

static int cmp(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    long iterations = argc > 1 ? strtol(argv[1], NULL, 10) : 5000;
    lsc_serial_backend backend = LSC_SERIAL_TERMIOS;
    if (argc > 2) {
        backend = strcmp(argv[2], "libserialport") == 0 ? LSC_SERIAL_LIBSERIALPORT
                  : strcmp(argv[2], "auto") == 0        ? LSC_SERIAL_AUTO
                                                        : LSC_SERIAL_TERMIOS;
    }
    if (iterations < 1 || iterations > 10000000) {
        fprintf(stderr, "usage: %s [ITERATIONS] [termios|libserialport|auto]\n", argv[0]);
        return 2;
    }
    int slave;
    char path[128];
    if (openpty(&master, &slave, path, NULL, NULL) != 0) {
        perror("openpty");
        return 1;
    }
    close(slave);
    lsc_serial *port = NULL;
    int r = lsc_serial_open(path, 9600, backend, &port);
    if (r != 0) {
        fprintf(stderr, "%s\n", lsc_serial_error_message(port));
        return 1;
    }
    lsc_io io;
    lsc_serial_get_io(port, &io);
    lsc_client client;
    lsc_client_init(&client, &io);
    pthread_t thread;
    pthread_create(&thread, NULL, peer, NULL);
    uint64_t *t = malloc((size_t)iterations * sizeof *t);
    if (t == NULL) {
        return 1;
    }
    for (long i = 0; i < iterations; i++) {
        uint16_t mv = 0;
        uint64_t start = now_us();
        r = lsc_client_get_battery(&client, &mv, 1000);
        t[i] = now_us() - start;
        if (r != 0 || mv != 7500) {
            fprintf(stderr, "round trip %ld failed: %s\n", i, lsc_strerror(r));
            free(t);
            return 1;
        }
    }
    qsort(t, (size_t)iterations, sizeof *t, cmp);
    printf("battery round trip over a pty (%s backend), %ld iterations: median %llu us"
           " (p10 %llu us, p90 %llu us, max %llu us)\n",
           lsc_serial_backend_in_use(port) == LSC_SERIAL_LIBSERIALPORT ? "libserialport"
                                                                          : "termios",
           iterations, (unsigned long long)t[iterations / 2],
           (unsigned long long)t[iterations / 10], (unsigned long long)t[iterations * 9 / 10],
           (unsigned long long)t[iterations - 1]);
    lsc_serial_close(port);
    close(master);
    pthread_join(thread, NULL);
    free(t);
    return 0;
}
