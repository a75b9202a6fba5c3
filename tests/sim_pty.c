/* lsc-sim as a child process on its pseudo-terminal (see sim_pty.h).
 * _POSIX_C_SOURCE comes from tests/CMakeLists.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sim_pty.h"

void sim_pty_start(const char *path, const char *const *extra, pid_t *pid, char *tty,
                   size_t size)
{
    const char *argv[8] = {path};
    size_t argc = 1;
    int out[2];
    while (extra != NULL && *extra != NULL && argc < 7) {
        argv[argc++] = *extra++;
    }
    argv[argc] = NULL;
    assert_true(size > 0);
    assert_int_equal(pipe(out), 0);
    *pid = fork();
    assert_true(*pid >= 0);
    if (*pid == 0) {
        dup2(out[1], STDOUT_FILENO);
        close(out[0]);
        close(out[1]);
        execv(path, (char *const *)argv);
        _exit(127);
    }
    close(out[1]);
    size_t len = 0;
    while (len + 1 < size) {
        ssize_t n = read(out[0], tty + len, 1);
        assert_true(n == 1);
        if (tty[len] == '\n') {
            break;
        }
        len++;
    }
    tty[len] = '\0';
    close(out[0]);
}

void sim_pty_stop(pid_t *pid)
{
    int status = 0;
    assert_int_equal(kill(*pid, SIGTERM), 0);
    assert_int_equal(waitpid(*pid, &status, 0), *pid);
    *pid = -1;
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
}
