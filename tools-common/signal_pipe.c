/* Signals as bytes on a pipe (signal_pipe.h). tools-common's build defines
 * _DEFAULT_SOURCE (sigaction, fcntl). */
#include "signal_pipe.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

/* The write end, for the handler. */
static int write_end = -1;

static void on_signal(int sig)
{
    int saved = errno;
    unsigned char c = (unsigned char)sig;
    if (write(write_end, &c, 1) < 0) {
        /* the pipe is full: a signal is already pending */
    }
    errno = saved;
}

int signal_pipe_open(const int *sigs, size_t n)
{
    int fds[2];
    struct sigaction sa;
    if (pipe(fds) != 0) {
        return -1;
    }
    for (int i = 0; i < 2; i++) {
        (void)fcntl(fds[i], F_SETFD, FD_CLOEXEC);
        (void)fcntl(fds[i], F_SETFL, fcntl(fds[i], F_GETFL) | O_NONBLOCK);
    }
    write_end = fds[1];
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    (void)sigemptyset(&sa.sa_mask);
    int r = 0;
    for (size_t i = 0; i < n && r == 0; i++) {
        r = sigaction(sigs[i], &sa, NULL);
    }
    sa.sa_handler = SIG_IGN;
    if (r != 0 || sigaction(SIGPIPE, &sa, NULL) != 0) {
        int saved = errno;
        write_end = -1; /* a handler set already writes nowhere */
        (void)close(fds[0]);
        (void)close(fds[1]);
        errno = saved;
        return -1;
    }
    return fds[0];
}
