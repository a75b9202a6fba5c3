/* lscctl: what record, play and convert share (lscctl_teach.h). */
#include <signal.h>
#include <stdbool.h>
#include <string.h>

#include "lsc/files.h"
#include "lscctl.h"
#include "lscctl_teach.h"

volatile sig_atomic_t lscctl_interrupted;

static void on_signal(int sig)
{
    lscctl_interrupted = sig;
}

void lscctl_catch_signal(int sig)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(sig, &sa, NULL);
}

int lscctl_load_action(const lscctl_opts *o, const char *path, lsc_action *a)
{
    lsc_file_error err = {.size = sizeof err};
    lscctl_shown name;
    int r = lsc_action_read_group(path, o->group, a, &err);
    if (r == LSC_ENOSPC) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: out of memory", lscctl_show(&name, path));
    }
    if (r != 0) {
        /* a group file of several: say how to choose one */
        lsc_file_error ignored = {.size = sizeof ignored};
        bool several = r == LSC_EINVAL && o->group < 0 &&
                       lsc_action_groups(path, NULL, 0, &ignored) > 1;
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s%s%s%s", lscctl_show(&name, path),
                           err.message, several ? ": " : "", several ? o->cmd : "",
                           several ? " --group N" : "");
    }
    return 0;
}
