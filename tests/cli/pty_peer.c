/* pty_peer: the far end of a pseudo-terminal for lscctl's tests.
 *
 *   pty_peer [-r HEX] [-s HEX] [-d MS] [-x MS] [-t MS] LINK CAPTURE
 *
 * Opens a pty pair, makes LINK a symlink to the terminal side (what lscctl
 * opens), and appends every byte that arrives to the file CAPTURE, so a
 * test can tell exactly what reached the port (nothing, for refused input).
 * -r HEX  answer with these bytes each time a chunk of input arrives
 * -s HEX  send these bytes once, -d MS (default 300) after start
 * -x MS   hang up (close the pty: the device is gone) MS after start
 * -t MS   exit after MS (default 10000) */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "../test_hex.h"

static long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

int main(int argc, char **argv)
{
    uint8_t reply[300], spont[300];
    size_t nreply = 0, nspont = 0;
    long hangup_ms = -1, total_ms = 10000, spont_ms = 300;
    int opt;
    while ((opt = getopt(argc, argv, "r:s:d:x:t:")) != -1) {
        if (opt == 'r') {
            nreply = test_hex(optarg, reply, sizeof reply);
        } else if (opt == 's') {
            nspont = test_hex(optarg, spont, sizeof spont);
        } else if (opt == 'd') {
            spont_ms = strtol(optarg, NULL, 10);
        } else if (opt == 'x') {
            hangup_ms = strtol(optarg, NULL, 10);
        } else if (opt == 't') {
            total_ms = strtol(optarg, NULL, 10);
        } else {
            return 2;
        }
    }
    if (argc - optind != 2) {
        fprintf(stderr, "usage: pty_peer [-r HEX] [-s HEX] [-d MS] [-x MS] [-t MS] LINK CAPTURE\n");
        return 2;
    }
    const char *link_path = argv[optind], *capture = argv[optind + 1];
    int master, slave;
    char name[256];
    if (openpty(&master, &slave, name, NULL, NULL) != 0) {
        perror("openpty");
        return 1;
    }
    struct termios t;
    tcgetattr(slave, &t);
    cfmakeraw(&t);
    tcsetattr(slave, TCSANOW, &t);
    FILE *out = fopen(capture, "wb");
    unlink(link_path);
    if (out == NULL || symlink(name, link_path) != 0) {
        perror(capture);
        return 1;
    }
    long start = now_ms();
    for (;;) {
        long now = now_ms() - start;
        if (now >= total_ms || (hangup_ms >= 0 && now >= hangup_ms)) {
            break;
        }
        if (nspont > 0 && now >= spont_ms) {
            if (write(master, spont, nspont) != (ssize_t)nspont) {
                perror("write");
            }
            nspont = 0;
        }
        struct pollfd p = {master, POLLIN, 0};
        if (poll(&p, 1, 10) <= 0 || !(p.revents & POLLIN)) {
            continue;
        }
        unsigned char buf[512];
        ssize_t got = read(master, buf, sizeof buf);
        if (got <= 0) {
            continue;
        }
        if (fwrite(buf, 1, (size_t)got, out) != (size_t)got || fflush(out) != 0) {
            perror(capture);
            return 1;
        }
        if (nreply > 0 && write(master, reply, nreply) != (ssize_t)nreply) {
            perror("write");
        }
    }
    if (fclose(out) != 0) {
        perror(capture);
        return 1;
    }
    unlink(link_path);
    close(slave);
    close(master);
    return 0;
}
