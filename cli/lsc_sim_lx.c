/* lsc-sim --lx: the virtual bus on the pseudo-terminal (lsc_sim_lx.h). */

#include "lsc_sim_lx.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "lsc/lsc.h"

/* ---- The state file -------------------------------------------------------------- */

/* Writes bus's state to path atomically (lsc_file_replace: a temporary file
 * beside it, flushed, renamed over it, the directory flushed; only ever a
 * regular file). 0, or -1 after saying why. */
static int save_state(const lsc_lxbus *bus, const char *prog, const char *path)
{
    char text[LSC_LXBUS_STATE_MAX];
    int n = lsc_lxbus_save(bus, text, sizeof text);
    lsc_file_error err = {.size = sizeof err};
    if (n < 0 || lsc_file_replace(path, text, (size_t)n, &err) != 0) {
        (void)fprintf(stderr, "%s: --state %s: cannot write it: %s\n", prog, path,
                      n < 0 ? "the state does not fit" : err.message);
        return -1;
    }
    return 0;
}

/* Loads the state file path into bus. Returns the number of servos, or -1
 * (the file does not exist), or -2 - status after saying why. */
static int load_state(lsc_lxbus *bus, const char *prog, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) {
        return -1;
    }
    uint8_t *data = NULL;
    size_t len = 0;
    lsc_file_error ferr = {.size = sizeof ferr};
    int r = lsc_file_load(path, (size_t)64u * 1024u, &data, &len, &ferr);
    if (r != 0) {
        (void)fprintf(stderr, "%s: --state %s: %s\n", prog, path, ferr.message);
        return -2 - (r == LSC_EINVAL ? 2 : 1);
    }
    lsc_sim_parse_error err;
    r = lsc_lxbus_load(bus, (const char *)data, len, &err);
    free(data);
    if (r < 0) {
        (void)fprintf(stderr, "%s: --state %s:%u:%u: %s\n", prog, path, (unsigned)err.line,
                      (unsigned)err.column, err.message);
        return -2 - 2;
    }
    return r;
}

int lsc_sim_lx_setup(lsc_lxbus *bus, const char *prog, const char *ids, const char *state)
{
    uint8_t list[LSC_LXBUS_SERVOS];
    char why[256];
    int n = lsc_device_parse_ids(NULL, ids, list, LSC_LXBUS_SERVOS, why, sizeof why);
    if (n < 0) {
        (void)fprintf(stderr, "%s: invalid --lx '%s': %s\nTry '%s --help' for more information.\n",
                      prog, ids, why, prog);
        return 2;
    }
    for (int i = 0; i < n; i++) {
        if (list[i] > LSC_LX_ID_MAX) {
            (void)fprintf(stderr,
                          "%s: invalid --lx '%s': id %u is not a servo's: use 0..253 (254 "
                          "is the broadcast id)\n",
                          prog, ids, (unsigned)list[i]);
            return 2;
        }
        (void)lsc_lxbus_add(bus, list[i]);
    }
    if (state == NULL) {
        return -1;
    }
    int kept = load_state(bus, prog, state);
    if (kept == -1) {
        return save_state(bus, prog, state) == 0 ? -1 : 1;
    }
    if (kept < -1) {
        return -2 - kept;
    }
    if (kept != n) {
        (void)fprintf(stderr,
                      "%s: --state %s keeps %d servos but --lx '%s' names %d: give --lx as "
                      "many ids, or remove the file to start afresh\n",
                      prog, state, kept, ids, n);
        return 2;
    }
    return -1;
}

/* ---- Serving --------------------------------------------------------------------- */

static uint64_t mono_us(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* Moves the bus's clock to the real time since start. */
static void catch_up(lsc_lxbus *bus, uint64_t start)
{
    uint64_t now = mono_us() - start;
    if (now > lsc_lxbus_now_us(bus)) {
        lsc_lxbus_advance_us(bus, now - lsc_lxbus_now_us(bus));
    }
}

int lsc_sim_lx_serve(lsc_lxbus *bus, const char *prog, int master, int sig_fd,
                     const char *state)
{
    uint8_t out[LSC_LXBUS_OUT_BYTES];
    size_t out_len = 0, out_off = 0;
    uint64_t start = mono_us();
    uint32_t saved = bus->changes;

    for (;;) {
        catch_up(bus, start);
        if (out_off == out_len) {
            out_off = 0;
            out_len = lsc_lxbus_read(bus, out, sizeof out);
        }
        while (out_off < out_len) {
            ssize_t n = write(master, out + out_off, out_len - out_off);
            if (n < 0) {
                if (errno == EINTR) {
                    continue;
                }
                if (errno != EAGAIN && errno != EIO) {
                    (void)fprintf(stderr, "%s: write to the pseudo-terminal: %s\n", prog,
                                  strerror(errno));
                    return 1;
                }
                break; /* nobody reads: try again later */
            }
            out_off += (size_t)n;
        }
        if (state != NULL && bus->changes != saved) {
            /* what survives power-off changed: on the disk at once */
            saved = bus->changes;
            if (save_state(bus, prog, state) != 0) {
                return 1;
            }
        }

        int timeout = -1;
        uint64_t next = lsc_lxbus_next_event_us(bus);
        if (out_off < out_len) {
            timeout = 10; /* output is stuck: retry soon */
        } else if (next != LSC_LXBUS_TIME_NEVER) {
            uint64_t ms = (next + 999u) / 1000u;
            timeout = ms > 60000u ? 60000 : (int)ms;
        }
        struct pollfd fds[2] = {{master, POLLIN, 0}, {sig_fd, POLLIN, 0}};
        int r = poll(fds, 2, timeout);
        if (r < 0 && errno != EINTR) {
            (void)fprintf(stderr, "%s: poll: %s\n", prog, strerror(errno));
            return 1;
        }
        if (r > 0 && (fds[1].revents & POLLIN) != 0) {
            unsigned char sig = 0;
            if (read(sig_fd, &sig, 1) == 1 && sig == SIGUSR2) {
                catch_up(bus, start);
                lsc_lxbus_power_cycle(bus);
                out_len = out_off = 0;
                continue;
            }
            catch_up(bus, start);
            /* where the shafts rest goes with the rest */
            return state != NULL && save_state(bus, prog, state) != 0 ? 1 : 0;
        }
        if (r > 0 && (fds[0].revents & POLLIN) != 0) {
            uint8_t in[512];
            ssize_t n = read(master, in, sizeof in);
            if (n > 0) {
                catch_up(bus, start);
                (void)lsc_lxbus_feed(bus, in, (size_t)n);
            }
        }
    }
}
