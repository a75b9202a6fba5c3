/* The stand-in bus of tests/lxbus/lxbus_peer.py as a child process
 * (lx_peer_harness.h). */
#include "lx_peer_harness.h"

#include <poll.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_time.h"

long lx_peer_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

void lx_peer_start(lx_peer *p, const char *python, const char *script, const char *ids, bool echo)
{
    int in[2], out[2];
    memset(p, 0, sizeof *p);
    p->echo = echo;
    snprintf(p->dir, sizeof p->dir, "/tmp/lsc-lx-peer.XXXXXX");
    assert_non_null(mkdtemp(p->dir));
    snprintf(p->link, sizeof p->link, "%s/bus", p->dir);
    snprintf(p->ctl, sizeof p->ctl, "%s/ctl", p->dir);
    assert_int_equal(pipe(in), 0);
    assert_int_equal(pipe(out), 0);
    p->pid = fork();
    assert_true(p->pid >= 0);
    if (p->pid == 0) {
        dup2(in[0], 0);
        dup2(out[1], 1);
        close(in[1]);
        close(out[0]);
        execl(python, python, script, "--link", p->link, "--ids", ids, "--control", p->ctl,
              "--watch-stdin", echo ? "--echo" : (char *)NULL, (char *)NULL);
        _exit(127);
    }
    close(in[0]);
    close(out[1]);
    p->in = in[1];
    /* "ready PATH" */
    char line[256] = {0};
    size_t n = 0;
    long end = lx_peer_now_ms() + test_ms(30000);
    while (n == 0 || line[n - 1] != '\n') {
        struct pollfd pfd = {out[0], POLLIN, 0};
        long left = end - lx_peer_now_ms();
        assert_true(left > 0);
        assert_true(poll(&pfd, 1, (int)left) == 1);
        ssize_t r = read(out[0], &line[n], sizeof line - 1 - n);
        assert_true(r > 0);
        n += (size_t)r;
    }
    close(out[0]);
    assert_int_equal(strncmp(line, "ready ", 6), 0);
}

void lx_peer_stop(lx_peer *p)
{
    int status = 0;
    close(p->in);
    assert_int_equal(waitpid(p->pid, &status, 0), p->pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    unlink(p->ctl);
    rmdir(p->dir);
}

void lx_peer_control_reply(const lx_peer *p, const char *cmd, char *out, size_t cap)
{
    int s = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    snprintf(a.sun_path, sizeof a.sun_path, "%s", p->ctl);
    assert_true(s >= 0);
    assert_int_equal(connect(s, (struct sockaddr *)&a, sizeof a), 0);
    char line[128];
    int n = snprintf(line, sizeof line, "%s\n", cmd);
    assert_int_equal(write(s, line, (size_t)n), n);
    char reply[4096] = {0};
    size_t got = 0;
    while (got == 0 || reply[got - 1] != '\n') {
        struct pollfd pfd = {s, POLLIN, 0};
        assert_true(poll(&pfd, 1, (int)test_ms(10000)) == 1);
        ssize_t r = read(s, &reply[got], sizeof reply - 1 - got);
        assert_true(r > 0);
        got += (size_t)r;
    }
    close(s);
    assert_int_equal(strncmp(reply, "ok", 2), 0);
    if (out != NULL) {
        snprintf(out, cap, "%s", reply);
    }
}

void lx_peer_control(const lx_peer *p, const char *cmd)
{
    lx_peer_control_reply(p, cmd, NULL, 0);
}
