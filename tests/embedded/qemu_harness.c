/* Runs firmware in QEMU with its first serial port wired to the virtual
 * controller (lsc/sim.h), and logs the exchange (wire.h).
 *
 *   lsc_qemu_harness [--groups FILE] [--seconds S] QEMU MACHINE firmware.elf
 *
 * QEMU runs as a child process with the serial port on its stdin/stdout
 * (pipes to this process) and semihosting on, so the firmware's exit code
 * becomes QEMU's. The controller's clock follows the host's monotonic clock
 * (QEMU runs the firmware in real time). Exit status: the firmware's code;
 * 124 if it did not finish within S seconds (default 20) of real time; 125 if
 * QEMU died of a signal; 2 for a bad command line or a failure to start. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "wire.h"

static uint64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

static int usage(void)
{
    fputs("usage: lsc_qemu_harness [--groups FILE] [--seconds S] QEMU MACHINE firmware.elf\n",
          stderr);
    return 2;
}

/* Starts qemu with its serial port on the pipes; returns its pid or -1. */
static pid_t start_qemu(char **argv, int *to_qemu, int *from_qemu)
{
    int in[2], out[2];
    if (pipe(in) != 0)
        return -1;
    if (pipe(out) != 0) {
        close(in[0]);
        close(in[1]);
        return -1;
    }
    pid_t pid = fork();
    if (pid == 0) {
        dup2(in[0], STDIN_FILENO);
        dup2(out[1], STDOUT_FILENO);
        close(in[0]);
        close(in[1]);
        close(out[0]);
        close(out[1]);
        execvp(argv[0], argv);
        perror(argv[0]);
        _exit(127);
    }
    close(in[0]);
    close(out[1]);
    if (pid < 0) {
        close(in[1]);
        close(out[0]);
        return -1;
    }
    *to_qemu = in[1];
    *from_qemu = out[0];
    return pid;
}

int main(int argc, char **argv)
{
    static lsc_sim sim;
    static wire_groups groups;
    const char *groups_path = NULL;
    unsigned long seconds = 20;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (!strcmp(argv[i], "--groups") && i + 1 < argc)
            groups_path = argv[++i];
        else if (!strcmp(argv[i], "--seconds") && i + 1 < argc)
            seconds = strtoul(argv[++i], NULL, 10);
        else
            return usage();
    }
    if (argc - i != 3 || seconds == 0 || seconds > 3600)
        return usage();

    if (wire_init(&sim) != 0)
        return 2;
    if (groups_path && wire_load_groups(&sim, &groups, groups_path) != 0)
        return 2;

    char *qemu_argv[] = {argv[i],
                         "-M",
                         argv[i + 1],
                         "-display",
                         "none",
                         "-monitor",
                         "none",
                         "-serial",
                         "stdio",
                         "-semihosting-config",
                         "enable=on,target=native",
                         "-kernel",
                         argv[i + 2],
                         NULL};
    if (signal(SIGPIPE, SIG_IGN) == SIG_ERR) { /* a closed pipe is an error to report, not a death */
        perror("signal");
        return 1;
    }
    int to_qemu = -1, from_qemu = -1;
    pid_t pid = start_qemu(qemu_argv, &to_qemu, &from_qemu);
    if (pid < 0) {
        perror("starting qemu");
        return 2;
    }

    const uint64_t start = now_us();
    const uint64_t limit = start + (uint64_t)seconds * 1000000u;
    int timed_out = 0;
    for (;;) {
        uint64_t t = now_us();
        if (t >= limit) {
            timed_out = 1;
            break;
        }
        if (t - start > lsc_sim_now_us(&sim))
            lsc_sim_advance_us(&sim, t - start - lsc_sim_now_us(&sim));
        uint8_t buf[256];
        size_t n;
        while ((n = lsc_sim_read(&sim, buf, sizeof buf)) > 0) {
            if (write(to_qemu, buf, n) != (ssize_t)n) {
                perror("writing to qemu");
                break;
            }
        }
        uint64_t wait_us = lsc_sim_next_event_us(&sim);
        if (wait_us > 10000u)
            wait_us = 10000u; /* 10 ms: the clock keeps up */
        struct pollfd p = {from_qemu, POLLIN, 0};
        int r = poll(&p, 1, (int)((wait_us + 999u) / 1000u));
        if (r < 0 && errno != EINTR) {
            perror("poll");
            break;
        }
        if (r > 0) {
            ssize_t got = read(from_qemu, buf, sizeof buf);
            if (got <= 0)
                break; /* qemu has exited */
            t = now_us();
            if (t - start > lsc_sim_now_us(&sim))
                lsc_sim_advance_us(&sim, t - start - lsc_sim_now_us(&sim));
            lsc_sim_feed(&sim, buf, (size_t)got);
        }
    }
    if (timed_out)
        kill(pid, SIGKILL);
    close(to_qemu);
    close(from_qemu);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (timed_out) {
        printf("still running after %lu s\n", seconds);
        return 124;
    }
    if (WIFEXITED(status)) {
        printf("exit %d\n", WEXITSTATUS(status));
        return WEXITSTATUS(status);
    }
    printf("qemu ended by signal %d\n", WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return 125;
}
