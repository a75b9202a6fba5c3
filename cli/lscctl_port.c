/* lscctl: opening a port (serial device or `sim`), talking through the
 * client, turning every error into one line on stderr and an exit code. */
#include "lscctl_port.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/serial.h"
#include "lsc/sim.h"

/* Action groups of the built-in virtual controller (--port sim). */
static const char sim_groups_text[] =
    "# lscctl --port sim: demo action groups\n"
    "group 1\n"
    "step 500 1:1000 2:2000\n"
    "step 500 1:1500 2:1500\n"
    "group 2\n"
    "step 300 1:1200\n"
    "step 300 1:1800\n"
    "group 8\n"
    "step 1000 1:2000 2:1200 3:1500\n"
    "step 1000 1:1000 2:1800 3:1500\n"
    "step 500 1:1500 2:1500 3:1500\n";

#define SIM_STEPS 16u
#define SIM_TARGETS 32u
#define WAIT_CHUNK_MS 1000u /* wait/monitor without --timeout: read in chunks */

struct lscctl_link {
    const lscctl_opts *o;
    const char *name; /* the port, for messages */
    lsc_client client;
    lsc_io io;
    bool is_sim;
    lsc_serial serial;
    lsc_sim sim;
    lsc_sim_groups groups;
    lsc_sim_step steps[SIM_STEPS];
    lsc_servo targets[SIM_TARGETS];
};

/* -v: every frame on stderr, hex and meaning. */
static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)user;
    lsc_frame f = {frame[3], (uint8_t)(n - 4u), &frame[4]};
    lscctl_msg m;
    char why[96], hex[LSCCTL_HEX_MAX];
    lscctl_hex(hex, sizeof hex, frame, n);
    fputs(dir == LSC_TRACE_TX ? "lscctl: sent " : "lscctl: received ", stderr);
    if (lscctl_msg_decode(&m, &f, dir == LSC_TRACE_TX ? LSCCTL_DIR_HOST : LSCCTL_DIR_CONTROLLER,
                          why, sizeof why) == 0) {
        lscctl_msg_print(stderr, &m, false, false, hex);
    } else {
        fprintf(stderr, "%s (%s)\n", why, hex);
    }
}

/* The one line for an error err of the link. */
static int link_fail(lscctl_link *l, int err)
{
    const lscctl_opts *o = l->o;
    if (err == LSC_ETIMEOUT) {
        return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                           "no reply from the controller on %s within %lu ms: check that it is "
                           "powered and connected, and the port and baud rate (%lu); or raise "
                           "--timeout",
                           l->name, o->timeout_ms, o->baud);
    }
    if (err == LSC_EREPLY) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL,
                           "bad reply from the controller on %s: check the baud rate (%lu) and "
                           "that nothing else talks on the line",
                           l->name, o->baud);
    }
    const char *msg = l->is_sim ? "" : lsc_serial_error_message(&l->serial);
    if (*msg != '\0') {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s", msg);
    }
    return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s: %s", l->name, lsc_strerror(err));
}

/* VID:PID of the USB serial adapters LSC boards use, and the xArm. */
static const struct {
    uint16_t vid, pid;
} controller_ids[] = {
    {0x1a86, 0x7523}, /* CH340 */
    {0x10c4, 0xea60}, /* CP210x */
    {0x0403, 0x6001}, /* FTDI FT232 */
    {0x0483, 0x5750}, /* Hiwonder xArm (LOBOT) */
};

static bool looks_like_controller(const lsc_port_info *p)
{
    for (size_t i = 0; p->usb && i < sizeof controller_ids / sizeof controller_ids[0]; i++) {
        if (p->vid == controller_ids[i].vid && p->pid == controller_ids[i].pid) {
            return true;
        }
    }
    return false;
}

#define PORTS_MAX 64u

/* The serial ports; *n their count. Returns 0, or -1 after printing why. */
static int list(const lscctl_opts *o, lsc_port_info **out, size_t *n)
{
    char msg[256] = "";
    *out = calloc(PORTS_MAX, sizeof **out);
    if (*out == NULL) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
    }
    int r = lsc_serial_list_ports(*out, PORTS_MAX, msg, sizeof msg);
    if (r < 0) {
        free(*out);
        *out = NULL;
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "cannot list serial ports: %s",
                           *msg ? msg : lsc_strerror(r));
    }
    *n = (size_t)r < PORTS_MAX ? (size_t)r : PORTS_MAX;
    return 0;
}

/* Without --port or $LSC_PORT: the one port that looks like a controller. */
static int find_port(const lscctl_opts *o, char *path, size_t cap)
{
    lsc_port_info *ports;
    size_t n, found = 0;
    const char *hint = "choose one with --port PATH (see 'lscctl ports') or set LSC_PORT; "
                       "--port sim is the built-in virtual controller";
    if (list(o, &ports, &n) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "no port given: %s", hint);
    }
    for (size_t i = 0; i < n; i++) {
        if (looks_like_controller(&ports[i])) {
            if (found++ == 0) {
                snprintf(path, cap, "%s", ports[i].path);
            }
        }
    }
    free(ports);
    if (found == 1) {
        return 0;
    }
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s",
                       found == 0 ? "no port given and none looks like a controller"
                                  : "no port given and several look like a controller",
                       hint);
}

int lscctl_link_open(const lscctl_opts *o, lscctl_link **out)
{
    static char found[LSC_SERIAL_PATH_MAX];
    lscctl_link *l = calloc(1, sizeof *l);
    if (l == NULL) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
    }
    l->o = o;
    l->name = o->port;
    lsc_serial_init(&l->serial);
    if (l->name == NULL) {
        int r = find_port(o, found, sizeof found);
        if (r != 0) {
            free(l);
            return r;
        }
        l->name = found;
    }
    if (strcmp(l->name, "sim") == 0) {
        l->is_sim = true;
        lsc_sim_init(&l->sim);
        lsc_sim_groups_init(&l->groups, l->steps, SIM_STEPS, l->targets, SIM_TARGETS);
        lsc_sim_groups_parse(&l->groups, sim_groups_text, sizeof sim_groups_text - 1u, NULL);
        lsc_sim_set_groups(&l->sim, &l->groups);
        lsc_sim_io_init(&l->sim, &l->io);
    } else {
        int r = lsc_serial_open(&l->serial, l->name, (uint32_t)o->baud, LSC_SERIAL_AUTO);
        if (r != 0) {
            int code = r == LSC_EINVAL ? LSCCTL_EXIT_USAGE : LSCCTL_EXIT_FAIL;
            lscctl_fail(o, code, "cannot open %s", lsc_serial_error_message(&l->serial));
            free(l);
            return code;
        }
        lsc_serial_get_io(&l->serial, &l->io);
    }
    lsc_client_init(&l->client, &l->io);
    if (o->verbose) {
        lsc_client_set_trace(&l->client, trace, NULL);
    }
    *out = l;
    return 0;
}

void lscctl_link_close(lscctl_link *l)
{
    lsc_serial_close(&l->serial);
    free(l);
}

int lscctl_link_send(lscctl_link *l, const uint8_t *frame, size_t n)
{
    if (l->o->verbose) {
        trace(NULL, LSC_TRACE_TX, frame, n);
    }
    int r = l->io.write(l->io.ctx, frame, n);
    return r == (int)n ? 0 : link_fail(l, r < 0 ? r : LSC_EIO);
}

int lscctl_link_battery(lscctl_link *l, uint16_t *millivolts)
{
    int r = lsc_client_get_battery(&l->client, millivolts, (uint32_t)l->o->timeout_ms);
    return r == 0 ? 0 : link_fail(l, r);
}

int lscctl_link_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out)
{
    int r = lsc_client_read_positions(&l->client, ids, n, out, (uint32_t)l->o->timeout_ms);
    return r >= 0 ? 0 : link_fail(l, r);
}

/* The built-in virtual controller sends nothing on its own: when nothing is
 * pending there, waiting longer cannot bring anything. */
static int sim_idle(lscctl_link *l)
{
    if (l->is_sim && lsc_sim_next_event_us(&l->sim) == LSC_SIM_TIME_NEVER) {
        return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                           "nothing runs on the virtual controller (--port sim, groups 1, 2 and "
                           "8), so nothing will arrive: start a group in the same command "
                           "(run GROUP --wait), or serve it with lsc-sim");
    }
    return 0;
}

/* How long the next read may take: a chunk, or what is left of --timeout. */
static uint32_t next_wait(const lscctl_link *l, uint32_t start, bool *expired)
{
    uint32_t spent = l->io.now_ms(l->io.ctx) - start;
    *expired = l->o->timeout_set && spent >= l->o->timeout_ms;
    return l->o->timeout_set ? (uint32_t)l->o->timeout_ms - spent : WAIT_CHUNK_MS;
}

int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out)
{
    uint32_t start = l->io.now_ms(l->io.ctx);
    for (;;) {
        bool expired;
        uint32_t t = next_wait(l, start, &expired);
        int r = expired ? LSC_ETIMEOUT : lsc_client_wait_group(&l->client, t, out);
        if (r == 0 && (any || out->cmd == LSC_CMD_GROUP_STOP || out->group == group)) {
            return 0;
        }
        if (r == LSC_ETIMEOUT && l->o->timeout_set && (expired || t == 0)) {
            return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                               "no action group ended within %lu ms; raise --timeout, or leave "
                               "it out to wait without limit",
                               l->o->timeout_ms);
        }
        if (r != 0 && r != LSC_ETIMEOUT) {
            return link_fail(l, r);
        }
        if (r == LSC_ETIMEOUT && sim_idle(l) != 0) {
            return LSCCTL_EXIT_TIMEOUT;
        }
    }
}

typedef struct monitor_state {
    bool (*fn)(void *user, const lsc_notification *n);
    void *user;
    bool done;
} monitor_state;

static void on_notify(void *user, const lsc_notification *n)
{
    monitor_state *m = user;
    if (!m->done) {
        m->done = !m->fn(m->user, n);
    }
}

int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user)
{
    monitor_state m = {fn, user, false};
    uint32_t start = l->io.now_ms(l->io.ctx);
    lsc_client_set_notify(&l->client, on_notify, &m);
    while (!m.done) {
        bool expired;
        uint32_t t = next_wait(l, start, &expired);
        if (expired) {
            return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                               "nothing arrived within %lu ms; raise --timeout, or leave it out "
                               "to wait without limit",
                               l->o->timeout_ms);
        }
        int r = lsc_client_poll(&l->client, t);
        if (r < 0) {
            return link_fail(l, r);
        }
        if (r > 0) {
            start = l->io.now_ms(l->io.ctx);
        } else if (sim_idle(l) != 0) {
            return LSCCTL_EXIT_TIMEOUT;
        }
    }
    return 0;
}

int lscctl_list_ports(const lscctl_opts *o)
{
    lsc_port_info *ports;
    size_t n;
    int r = list(o, &ports, &n);
    if (r != 0) {
        return r;
    }
    for (size_t i = 0; i < n; i++) {
        const lsc_port_info *p = &ports[i];
        bool ctl = looks_like_controller(p);
        if (o->json) {
            fputs("{\"path\":", stdout);
            lscctl_json_string(stdout, p->path);
            fputs(",\"description\":", stdout);
            lscctl_json_string(stdout, p->description);
            if (p->usb) {
                printf(",\"vid\":\"%04x\",\"pid\":\"%04x\",\"serial\":", p->vid, p->pid);
                lscctl_json_string(stdout, p->serial);
            }
            printf(",\"controller\":%s}\n", ctl ? "true" : "false");
        } else {
            printf("%s\t%s", p->path, *p->description ? p->description : "-");
            if (p->usb) {
                printf("\t%04x:%04x\t%s", p->vid, p->pid, *p->serial ? p->serial : "-");
            } else {
                fputs("\t-\t-", stdout);
            }
            puts(ctl ? "\tcontroller" : "");
        }
    }
    if (n == 0 && !o->json) {
        fprintf(stderr, "lscctl: ports: no serial ports found (plug the controller in; "
                        "--port sim is the built-in virtual controller)\n");
    }
    free(ports);
    return LSCCTL_EXIT_OK;
}
