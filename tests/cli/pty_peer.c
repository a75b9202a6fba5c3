/* pty_peer: the far end of a pseudo-terminal for lscctl's tests.
 *
 *   pty_peer [-r HEX] [-s HEX] [-d MS] [-x MS] [-t MS] LINK CAPTURE
 *
 * Opens a pty pair, makes LINK a symlink to the terminal side (what lscctl
 * opens), and appends every byte that arrives to the file CAPTURE, so a
 * test can tell exactly what reached the port (nothing, for refused input).
 * -r HEX  answer with these bytes each time a chunk of input arrives
 * -s HEX  send these bytes once, -d MS (default 0) after the port is opened
 * -x MS   hang up (close the pty: the device is gone) MS after the port is opened
 * -t MS   safety limit: exit after MS (default 600000) whatever happens
 *
 * It lives until the test kills it, or until the test's shell (its parent)
 * is gone. "Opened" is when a program that opened the terminal side flushed
 * its input (lscctl's serial transport does, right after claiming the port),
 * seen through the master's packet mode (TIOCPKT_FLUSHREAD): bytes sent
 * before that would be flushed away, and a timer started at our own start
 * would race the program's start-up on a busy machine. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
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
    long hangup_ms = -1, total_ms = 600000, spont_ms = 0;
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
    const pid_t parent = getppid();
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
    int packet = 1;
    if (ioctl(master, TIOCPKT, &packet) != 0) {
        perror("TIOCPKT");
        return 1;
    }
    FILE *out = fopen(capture, "wb");
    unlink(link_path);
    if (out == NULL || symlink(name, link_path) != 0) {
        perror(capture);
        return 1;
    }
    const long start = now_ms();
    long opened = -1; /* when the port was first opened (flushed), since start */
    for (;;) {
        long now = now_ms() - start;
        if (now >= total_ms || getppid() != parent) {
            break;
        }
        if (opened >= 0 && hangup_ms >= 0 && now >= opened + hangup_ms) {
            break;
        }
        if (opened >= 0 && nspont > 0 && now >= opened + spont_ms) {
            if (write(master, spont, nspont) != (ssize_t)nspont) {
                perror("write");
            }
            nspont = 0;
        }
        struct pollfd p = {master, POLLIN | POLLPRI, 0};
        if (poll(&p, 1, 10) <= 0 || !(p.revents & (POLLIN | POLLPRI))) {
            continue;
        }
        /* packet mode: a leading byte, 0 (TIOCPKT_DATA) before data, else
         * a status alone */
        unsigned char buf[513];
        ssize_t got = read(master, buf, sizeof buf);
        if (got <= 0) {
            continue;
        }
        if (buf[0] != TIOCPKT_DATA) {
            if ((buf[0] & TIOCPKT_FLUSHREAD) && opened < 0) {
                opened = now_ms() - start;
            }
            continue;
        }
        size_t n = (size_t)got - 1u;
        if (fwrite(buf + 1, 1, n, out) != n || fflush(out) != 0) {
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
