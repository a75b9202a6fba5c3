/* lscctl: opening a port (serial device, HID controller or `sim`), talking
 * through the client, turning every error into one line on stderr and an
 * exit code. */
#include "lscctl_port.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lsc/hid.h"
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
    lsc_io io;        /* what the client talks through: port with guarded writes */
    lsc_io port;      /* the serial port's or the virtual controller's own */
    uint8_t tx_cmd;   /* the frame the last failed write was sending */
    size_t tx_len;
    bool tx_failed;   /* the last error came from a write */
    int rx_other;     /* command of the last frame that answered nothing, or -1 */
    uint8_t asked;    /* command of the last frame sent (the request a timeout is about) */
    lsc_client_counts before; /* the counts when the request began */
    bool is_sim;
    bool is_hid;
    bool answered; /* HID: a request was answered since the open */
    lsc_serial serial;
    lsc_hid hid;
    lsc_sim sim;
    lsc_sim_groups groups;
    lsc_sim_step steps[SIM_STEPS];
    lsc_servo targets[SIM_TARGETS];
    bool ran;          /* lscctl_link_run sent run_group */
    uint8_t run_group;
    bool run_forever;  /* ... with times 0 */
};

/* Every frame through the client: the command of the last one that was not a
 * notification is kept for the timeout message; with -v each is printed on
 * stderr, hex and meaning. */
static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    lscctl_link *l = user;
    if (dir == LSC_TRACE_RX &&
        (frame[3] < LSC_CMD_GROUP_RUN || frame[3] > LSC_CMD_GROUP_COMPLETE)) {
        l->rx_other = frame[3]; /* for the timeout message (a reply ends the wait first) */
    }
    if (dir == LSC_TRACE_TX) {
        l->asked = frame[3];
    }
    if (!l->o->verbose) {
        return;
    }
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

/* "name (command N, LEN bytes)" for the frame the last failed write sent. */
static void describe_tx(const lscctl_link *l, char *out, size_t cap)
{
    snprintf(out, cap, "%s (command %u, %zu bytes)", lscctl_cmd_name(l->tx_cmd),
             l->tx_cmd, l->tx_len);
}

/* The timeout message: what did arrive during the request, and what that
 * suggests (issue 12: "no reply" when plenty arrived). */
static int timed_out(lscctl_link *l)
{
    const lscctl_opts *o = l->o;
    lsc_client_counts now;
    lsc_client_get_counts(&l->client, &now);
    uint32_t frames = now.frames - l->before.frames;
    uint32_t notes = now.notifications - l->before.notifications;
    uint32_t noise = now.discarded - l->before.discarded + now.pending;
    if (frames > notes) {
        /* an answer came, but to something else: say what, not "no reply" */
        return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                           "the controller on %s did not answer %s (command %u) within %lu ms: "
                           "%u frame(s) answering something else came instead (the last: %s "
                           "(command %d)), with %u notification(s) and %u byte(s) that formed "
                           "no frame; another program or device may be talking on the line, or "
                           "the controller does not know this request; or raise --timeout",
                           l->name, lscctl_cmd_name(l->asked), l->asked, o->timeout_ms,
                           frames - notes, lscctl_cmd_name((uint8_t)l->rx_other),
                           l->rx_other, notes, noise);
    }
    char what[320] = "";
    if (notes > 0) {
        snprintf(what, sizeof what,
                 "only %u notification(s) arrived (and %u byte(s) that formed no frame): the "
                 "controller is there but did not answer",
                 notes, noise);
    } else if (noise > 0) {
        snprintf(what, sizeof what,
                 "only %u byte(s) arrived that formed no frame: likely a wrong baud rate "
                 "(--baud; this was %lu, LSC controllers use 9600), noise on the line, or a "
                 "reply whose bytes came more than %u ms apart",
                 noise, o->baud, LSC_CLIENT_GAP_MS);
    }
    if (what[0] != '\0') {
        return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                           "no reply from the controller on %s within %lu ms: %s; or raise "
                           "--timeout",
                           l->name, o->timeout_ms, what);
    }
    return lscctl_fail(o, LSCCTL_EXIT_TIMEOUT,
                       "no reply from the controller on %s within %lu ms: nothing arrived; check "
                       "that it is powered and connected, and the port and baud rate (%lu); or "
                       "raise --timeout",
                       l->name, o->timeout_ms, o->baud);
}

/* The one line for an error err of the link. */
static int link_fail(lscctl_link *l, int err)
{
    const lscctl_opts *o = l->o;
    if (l->is_hid && (err == LSC_ETIMEOUT || err == LSC_EREPLY)) {
        /* no baud rate on USB: only power, cable and time are left to check */
        return lscctl_fail(o, err == LSC_ETIMEOUT ? LSCCTL_EXIT_TIMEOUT : LSCCTL_EXIT_FAIL,
                           err == LSC_ETIMEOUT
                               ? "no reply from the controller on %s within %lu ms: check that "
                                 "it is switched on and connected; or raise --timeout"
                               : "bad reply from the controller on %s (--timeout %lu ms): check "
                                 "that no other program talks to it",
                           l->name, o->timeout_ms);
    }
    if (err == LSC_ETIMEOUT) {
        return timed_out(l);
    }
    if (err == LSC_EREPLY) {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL,
                           "bad reply from the controller on %s: check the baud rate (%lu) and "
                           "that nothing else talks on the line",
                           l->name, o->baud);
    }
    char sending[160] = "";
    if (l->tx_failed) {
        char frame[96];
        describe_tx(l, frame, sizeof frame);
        snprintf(sending, sizeof sending, "sending %s: ", frame);
    }
    const char *msg = l->is_sim   ? ""
                      : l->is_hid ? lsc_hid_error_message(&l->hid)
                                  : lsc_serial_error_message(&l->serial);
    if (*msg != '\0') {
        return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s%s", sending, msg);
    }
    return lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s%s: %s", sending, l->name, lsc_strerror(err));
}

/* The signals that end lscctl (Ctrl-C, kill, a closed terminal). */
static void stop_signals(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGINT);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGHUP);
}

/* True if sig is pending and will end the process when unblocked (its
 * default action; play and record catch SIGINT to stop cleanly, and then say
 * the failed write's message themselves, once). */
static bool ends_us(const sigset_t *pending, int sig)
{
    struct sigaction sa;
    return sigismember(pending, sig) == 1 && sigaction(sig, NULL, &sa) == 0 &&
           sa.sa_handler == SIG_DFL;
}

/* The client's write: the port's, with the stop signals held back until the
 * frame is out (or the write gave up, bounded by the port's write timeout),
 * so that Ctrl-C or kill never leaves part of a frame on the line for the
 * controller to glue to the next one. A signal that came meanwhile then
 * takes effect as usual, after saying what a failed write sent. */
static int guarded_write(void *ctx, const uint8_t *data, size_t n)
{
    lscctl_link *l = ctx;
    sigset_t stop, old, pending;
    stop_signals(&stop);
    bool held = sigprocmask(SIG_BLOCK, &stop, &old) == 0;
    int r = l->port.write(l->port.ctx, data, n);
    l->tx_failed = r != (int)n;
    if (l->tx_failed) {
        l->tx_cmd = n > 3 ? data[3] : 0;
        l->tx_len = n;
    }
    if (held) {
        if (l->tx_failed && sigpending(&pending) == 0 &&
            (ends_us(&pending, SIGINT) || ends_us(&pending, SIGTERM) ||
             ends_us(&pending, SIGHUP))) {
            (void)link_fail(l, r < 0 ? r : LSC_EIO); /* the last word before the signal */
        }
        (void)sigprocmask(SIG_SETMASK, &old, NULL);
    }
    return r;
}

static int guarded_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    lscctl_link *l = ctx;
    return l->port.read(l->port.ctx, buf, cap, timeout_ms);
}

static uint32_t guarded_now(void *ctx)
{
    lscctl_link *l = ctx;
    return l->port.now_ms(l->port.ctx);
}

/* VID:PID of the USB serial adapters LSC boards use (the xArm is a HID
 * device, listed by lsc_hid_list: libserialport never opens it). */
static const struct {
    uint16_t vid, pid;
} controller_ids[] = {
    {0x1a86, 0x7523}, /* CH340 */
    {0x10c4, 0xea60}, /* CP210x */
    {0x0403, 0x6001}, /* FTDI FT232 */
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
#define HID_MAX 16u

/* What is plugged in: serial ports and HID controllers. */
typedef struct ports {
    lsc_port_info serial[PORTS_MAX];
    size_t nserial;
    lsc_hid_info hid[HID_MAX];
    size_t nhid;
} ports;

/* Lists both kinds into *out (allocated; free it). A build without one of
 * them, or a listing that fails, gives none of that kind; if both fail,
 * returns the exit code after printing why, else 0. */
static int list(const lscctl_opts *o, ports **out)
{
    char msg[256] = "", hmsg[256] = "";
    *out = calloc(1, sizeof **out);
    if (*out == NULL) {
        (void)lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
        return LSCCTL_EXIT_FAIL;
    }
    int r = lsc_serial_list_ports((*out)->serial, PORTS_MAX, msg, sizeof msg);
    int h = lsc_hid_list((*out)->hid, HID_MAX, 0, 0, hmsg, sizeof hmsg);
    if (r < 0 && h < 0) {
        free(*out);
        *out = NULL;
        (void)lscctl_fail(o, LSCCTL_EXIT_FAIL, "cannot list serial ports: %s; nor HID: %s",
                          *msg ? msg : lsc_strerror(r), *hmsg ? hmsg : lsc_strerror(h));
        return LSCCTL_EXIT_FAIL; /* not 0 whatever lscctl_fail returned: *out is NULL */
    }
    (*out)->nserial = r < 0 ? 0u : (size_t)r < PORTS_MAX ? (size_t)r : PORTS_MAX;
    (*out)->nhid = h < 0 ? 0u : (size_t)h < HID_MAX ? (size_t)h : HID_MAX;
    return 0;
}

/* How --port names HID controller i: hid:SERIAL, or its path without one. */
static void hid_name(const lsc_hid_info *i, char *out, size_t cap)
{
    snprintf(out, cap, *i->serial ? "hid:%s" : "%s", *i->serial ? i->serial : i->path);
}

/* Without --port or $LSC_PORT: the one controller present, a serial port
 * that looks like one or a HID controller. Two or more: refuse, listing
 * each candidate with its serial number. */
static int find_port(const lscctl_opts *o, char *path, size_t cap)
{
    ports *p;
    size_t found = 0, len = 0;
    char candidates[1024] = "";
    const char *hint = "choose one with --port PATH (see 'lscctl ports') or set LSC_PORT "
                       "(a HID controller: --port hid:SERIAL); --port sim is the built-in "
                       "virtual controller";
    if (list(o, &p) != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "no port given: %s", hint);
    }
    for (size_t i = 0; i < p->nserial + p->nhid; i++) {
        char name[LSC_HID_PATH_MAX + 8], entry[2 * LSC_HID_PATH_MAX];
        const char *serial;
        if (i < p->nserial) {
            if (!looks_like_controller(&p->serial[i])) {
                continue;
            }
            snprintf(name, sizeof name, "%s", p->serial[i].path);
            serial = p->serial[i].serial;
        } else {
            hid_name(&p->hid[i - p->nserial], name, sizeof name);
            serial = p->hid[i - p->nserial].serial;
        }
        if (found++ == 0) {
            snprintf(path, cap, "%s", name);
        }
        int w = snprintf(entry, sizeof entry, "%s%s (serial number %s)", found == 1 ? "" : ", ",
                         name, *serial ? serial : "none");
        if (w > 0 && len + (size_t)w < sizeof candidates) {
            memcpy(candidates + len, entry, (size_t)w + 1u);
            len += (size_t)w;
        }
    }
    free(p);
    if (found == 1) {
        return 0;
    }
    if (found == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "no port given and none looks like a controller: %s", hint);
    }
    return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                       "no port given and several look like a controller: %s; they are: %s",
                       hint, candidates);
}

/* True if name is a HID port: hid, hid:SERIAL, or a path to a hidraw node. */
static bool is_hid_port(const char *name)
{
    const char *base = strrchr(name, '/');
    return strcmp(name, "hid") == 0 || strncmp(name, "hid:", 4) == 0 ||
           (base != NULL && strncmp(base + 1, "hidraw", 6) == 0);
}

/* Opens the HID controller name: hid (the only one), hid:SERIAL or a path. */
static int open_hid(lscctl_link *l, const char *name)
{
    const lscctl_opts *o = l->o;
    int r;
    l->is_hid = true;
    lsc_hid_init(&l->hid);
    if (strcmp(name, "hid") == 0) {
        r = lsc_hid_open_serial(&l->hid, NULL);
    } else if (strncmp(name, "hid:", 4) == 0) {
        if (name[4] == '\0') {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                               "--port hid: needs a serial number after the colon (see "
                               "'lscctl ports'), or use --port hid for the only arm present");
        }
        r = lsc_hid_open_serial(&l->hid, name + 4);
    } else {
        r = lsc_hid_open_path(&l->hid, name);
    }
    if (r == 0) {
        lsc_hid_get_io(&l->hid, &l->port);
        return 0;
    }
    /* several arms and none chosen, or no HID support: nothing was sent */
    int code = r == LSC_EINVAL  ? LSCCTL_EXIT_USAGE
               : r == LSC_EBUSY ? LSCCTL_EXIT_BUSY
                                : LSCCTL_EXIT_FAIL;
    const char *hint =
        r == LSC_EINVAL && lsc_hid_available()
            ? ": --port hid:SERIAL (see 'lscctl ports')"
        : r == LSC_ENODEV ? " ('lscctl ports' lists the controllers; --port sim is the built-in "
                            "virtual controller)"
                          : "";
    return lscctl_fail(o, code, "%s%s", lsc_hid_error_message(&l->hid), hint);
}

int lscctl_link_open(const lscctl_opts *o, lscctl_link **out)
{
    static char found[LSC_SERIAL_PATH_MAX + 8];
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
        lsc_sim_io_init(&l->sim, &l->port);
    } else if (is_hid_port(l->name)) {
        int r = open_hid(l, l->name);
        if (r != 0) {
            free(l);
            return r;
        }
    } else {
        int r = lsc_serial_open(&l->serial, l->name, (uint32_t)o->baud, LSC_SERIAL_AUTO);
        if (r != 0) {
            int code = r == LSC_EINVAL ? LSCCTL_EXIT_USAGE
                       : r == LSC_EBUSY ? LSCCTL_EXIT_BUSY
                                        : LSCCTL_EXIT_FAIL;
            const char *hint =
                r == LSC_ENODEV ? " ('lscctl ports' lists the serial ports; --port sim is the "
                                  "built-in virtual controller)"
                : r == LSC_EINVAL ? " (check --port, and use a standard --baud such as 9600)"
                                  : "";
            /* the serial layer's message names the path and what failed */
            const char *msg = lsc_serial_error_message(&l->serial);
            if (*msg != '\0') {
                lscctl_fail(o, code, "%s%s", msg, hint);
            } else {
                lscctl_fail(o, code, "cannot open %s: %s%s", l->name, lsc_strerror(r), hint);
            }
            free(l);
            return code;
        }
        lsc_serial_get_io(&l->serial, &l->port);
    }
    l->io.ctx = l;
    l->io.write = guarded_write;
    l->io.read = guarded_read;
    l->io.now_ms = guarded_now;
    l->rx_other = -1;
    lsc_client_init(&l->client, &l->io);
    lsc_client_set_trace(&l->client, trace, l);
    *out = l;
    return 0;
}

void lscctl_link_close(lscctl_link *l)
{
    lsc_serial_close(&l->serial);
    if (l->is_hid) {
        lsc_hid_close(&l->hid);
    }
    free(l);
}

/* A send-only client call's result: 0, or the exit code after its message. */
static int sent(lscctl_link *l, int r)
{
    return r == 0 ? 0 : link_fail(l, r);
}

int lscctl_link_move(lscctl_link *l, uint16_t time_ms, const lsc_servo *servos, size_t n)
{
    return sent(l, lsc_client_move(&l->client, time_ms, servos, n));
}

int lscctl_link_run(lscctl_link *l, uint8_t group, uint16_t times)
{
    l->run_group = group;
    l->run_forever = times == 0;
    l->ran = true;
    return sent(l, lsc_client_run_group(&l->client, group, times));
}

int lscctl_link_stop(lscctl_link *l)
{
    return sent(l, lsc_client_stop_group(&l->client));
}

int lscctl_link_speed(lscctl_link *l, uint8_t group, uint16_t percent)
{
    return sent(l, lsc_client_set_group_speed(&l->client, group, percent));
}

int lscctl_link_unload(lscctl_link *l, const uint8_t *ids, size_t n)
{
    return sent(l, lsc_client_unload(&l->client, ids, n));
}

int lscctl_link_send(lscctl_link *l, uint8_t cmd, const uint8_t *params, size_t n)
{
    if (cmd != LSC_CMD_GROUP_COMPLETE) {
        return sent(l, lsc_client_send_raw(&l->client, cmd, params, n));
    }
    /* send 8 --force: the client refuses command 8 by design (it erases the
     * action groups on xArm firmware), so this one frame goes out directly */
    uint8_t frame[LSC_FRAME_MAX];
    int len = lsc_encode_frame(frame, sizeof frame, cmd, params, n);
    if (len < 0) {
        return link_fail(l, len);
    }
    trace(l, LSC_TRACE_TX, frame, (size_t)len);
    int r = l->io.write(l->io.ctx, frame, (size_t)len);
    return r == len ? 0 : link_fail(l, r < 0 ? r : LSC_EIO);
}

/* Over HID, a real arm may leave the first request after the open
 * unanswered (PROTOCOL.md): that one is sent again, LSC_HID_FIRST_RETRIES
 * times, when it timed out. Returns how many more tries r allows. */
static unsigned retries(lscctl_link *l, int r, unsigned tried)
{
    if (r != LSC_ETIMEOUT) {
        l->answered = true;
    }
    return r == LSC_ETIMEOUT && l->is_hid && !l->answered && tried < LSC_HID_FIRST_RETRIES ? 1u
                                                                                          : 0u;
}

/* A request's arguments, for ask and its callers. */
typedef struct request {
    const uint8_t *ids;
    size_t n;
    void *out;
} request;

static int ask_battery(lsc_client *c, const request *q, uint32_t timeout_ms)
{
    return lsc_client_get_battery(c, q->out, timeout_ms);
}

static int ask_positions(lsc_client *c, const request *q, uint32_t timeout_ms)
{
    return lsc_client_read_positions(c, q->ids, q->n, q->out, timeout_ms);
}

static int ask_offsets(lsc_client *c, const request *q, uint32_t timeout_ms)
{
    return lsc_client_read_offsets(c, q->ids, q->n, q->out, timeout_ms);
}

/* A request and its reply (fn, o->timeout_ms), sent again as retries says;
 * the counts at the start of each try are kept for the timeout message.
 * Returns fn's result. */
static int ask(lscctl_link *l, int (*fn)(lsc_client *c, const request *q, uint32_t timeout_ms),
               const request *q)
{
    int r;
    unsigned tried = 0;
    do {
        lsc_client_get_counts(&l->client, &l->before);
        r = fn(&l->client, q, (uint32_t)l->o->timeout_ms);
    } while (retries(l, r, tried++) != 0);
    return r;
}

int lscctl_link_battery(lscctl_link *l, uint16_t *millivolts)
{
    request q = {NULL, 0, millivolts};
    int r = ask(l, ask_battery, &q);
    return r == 0 ? 0 : link_fail(l, r);
}

int lscctl_link_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out)
{
    request q = {ids, n, out};
    int r = ask(l, ask_positions, &q);
    return r >= 0 ? 0 : link_fail(l, r);
}

uint32_t lscctl_link_now(lscctl_link *l)
{
    return l->io.now_ms(l->io.ctx);
}

int lscctl_link_idle(lscctl_link *l, uint32_t ms)
{
    int r = lsc_client_poll(&l->client, ms);
    return r >= 0 ? 0 : link_fail(l, r);
}

int lscctl_link_try_read(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo *out)
{
    int r = lsc_client_read_positions(&l->client, ids, n, out, (uint32_t)l->o->timeout_ms);
    return r >= 0 ? 0 : r == LSC_ETIMEOUT ? r : link_fail(l, r);
}

/* The groups of the built-in virtual controller, as "1, 2 and 8". */
static void sim_group_list(const lscctl_link *l, char *out, size_t cap)
{
    size_t len = 0, n = 0, total = 0;
    for (size_t g = 0; g < LSC_SIM_GROUPS; g++) {
        total += l->groups.group_steps[g] != 0;
    }
    out[0] = '\0';
    for (size_t g = 0; g < LSC_SIM_GROUPS && len < cap; g++) {
        if (l->groups.group_steps[g] != 0) {
            n++;
            int w = snprintf(out + len, cap - len, "%s%zu",
                             n == 1 ? "" : n == total ? " and " : ", ", g);
            len += w > 0 ? (size_t)w : 0u;
        }
    }
}

/* The built-in virtual controller does nothing on its own: only what this
 * command started can make it send anything. Exit 3 at once (after saying
 * why) when waiting longer cannot bring what we wait for; else 0. */
static int sim_hopeless(lscctl_link *l, bool want_end)
{
    char groups[64];
    if (!l->is_sim) {
        return 0;
    }
    sim_group_list(l, groups, sizeof groups);
    if (want_end && l->run_forever && !l->o->timeout_set &&
        lsc_sim_group_running(&l->sim) == (int)l->run_group) {
        return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                           "group %u loops forever (--times 0) and nothing else on the virtual "
                           "controller (--port sim) can stop it, so the wait would never end: "
                           "give --times N, or --timeout MS",
                           l->run_group);
    }
    if (lsc_sim_next_event_us(&l->sim) != LSC_SIM_TIME_NEVER) {
        return 0;
    }
    if (l->ran && (l->run_group >= LSC_SIM_GROUPS || l->groups.group_steps[l->run_group] == 0)) {
        return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                           "the virtual controller (--port sim) has no group %u, so it never "
                           "starts: its groups are %s",
                           l->run_group, groups);
    }
    return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                       "nothing runs on the virtual controller (--port sim, groups %s), so "
                       "nothing will arrive: start a group in the same command (run GROUP "
                       "--wait), or serve it with lsc-sim",
                       groups);
}

typedef struct listener {
    bool (*fn)(void *user, const lsc_notification *n);
    void *user;
    bool done;
    bool heard; /* a notification arrived since the last check */
} listener;

static void on_notify(void *user, const lsc_notification *n)
{
    listener *m = user;
    m->heard = true;
    if (!m->done) {
        m->done = !m->fn(m->user, n);
    }
}

typedef struct group_end {
    bool any;
    uint8_t group;
    bool started; /* any, or the 6 of `group` arrived: ends count from now */
    lsc_notification *out;
} group_end;

/* run --wait on a real port: if the controller has not reported that the
 * group started after this long, it may have no such group (a board ignores
 * a run of a group it does not have, in silence). */
#define START_NOTICE_MS 3000u

/* run --wait (g waits for its group's start), on a real port, with stderr on
 * a terminal (someone is watching; a script gets the exit status instead):
 * the notice that the group has not started is still to be said. */
static bool start_notice_due(const lscctl_link *l, const group_end *g)
{
    return g != NULL && !g->started && !l->is_sim && isatty(STDERR_FILENO) == 1;
}

/* Reads and hands every notification to fn until it returns false. With
 * --timeout: exit 3 when that long passed since the start (or, if
 * restart, since the last notification). g: the group end run --wait waits
 * for (its start notice, start_notice_due), or NULL. */
static int listen(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n), void *user,
                  bool restart, const group_end *g, const char *what)
{
    listener m = {fn, user, false, false};
    uint32_t start = l->io.now_ms(l->io.ctx);
    bool notice = start_notice_due(l, g);
    lsc_client_set_notify(&l->client, on_notify, &m);
    while (!m.done) {
        uint32_t spent = l->io.now_ms(l->io.ctx) - start;
        if (l->o->timeout_set && spent >= l->o->timeout_ms) {
            return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                               "%s within %lu ms; raise --timeout, or leave it out to wait "
                               "without limit",
                               what, l->o->timeout_ms);
        }
        notice = notice && !g->started;
        if (notice && spent >= START_NOTICE_MS) {
            fflush(stdout);
            fprintf(stderr,
                    "lscctl: %s: the controller on %s has not reported that group %u started "
                    "(%u s since it was sent): the board may have no group %u; still waiting "
                    "(Ctrl-C to stop)\n",
                    l->o->cmd != NULL ? l->o->cmd : "wait", l->name, g->group,
                    START_NOTICE_MS / 1000u, g->group);
            notice = false;
        }
        uint32_t t = l->o->timeout_set ? (uint32_t)l->o->timeout_ms - spent : WAIT_CHUNK_MS;
        if (notice && START_NOTICE_MS - spent < t) {
            t = START_NOTICE_MS - spent; /* wake up for the notice */
        }
        m.heard = false;
        int r = lsc_client_poll(&l->client, t);
        if (r < 0) {
            return link_fail(l, r);
        }
        if (m.heard && restart) {
            start = l->io.now_ms(l->io.ctx);
        } else if (!m.heard && !m.done && sim_hopeless(l, g != NULL) != 0) {
            return LSCCTL_EXIT_TIMEOUT;
        }
    }
    return 0;
}

/* Starting a group while another runs makes the controller send 7 (the old
 * one stopped) before 6 (ours started): ends before our 6 are not ours. */
static bool is_end(void *user, const lsc_notification *n)
{
    group_end *g = user;
    if (!g->started) {
        g->started = n->cmd == LSC_CMD_GROUP_RUN && n->group == g->group;
        return true;
    }
    bool end = n->cmd == LSC_CMD_GROUP_STOP ||
               (n->cmd == LSC_CMD_GROUP_COMPLETE && (g->any || n->group == g->group));
    if (end) {
        *g->out = *n;
    }
    return !end;
}

int lscctl_link_wait_group(lscctl_link *l, bool any, uint8_t group, lsc_notification *out)
{
    group_end g = {any, group, any, out};
    return listen(l, is_end, &g, false, &g, "no action group ended");
}

int lscctl_link_monitor(lscctl_link *l, bool (*fn)(void *user, const lsc_notification *n),
                        void *user)
{
    return listen(l, fn, user, true, NULL, "nothing arrived");
}

static void print_hid(const lscctl_opts *o, const lsc_hid_info *h)
{
    char name[LSC_HID_PATH_MAX + 8];
    hid_name(h, name, sizeof name);
    if (o->json) {
        fputs("{\"path\":", stdout);
        lscctl_json_string(stdout, h->path);
        fputs(",\"description\":", stdout);
        lscctl_json_string(stdout, h->product);
        printf(",\"vid\":\"%04x\",\"pid\":\"%04x\",\"serial\":", h->vid, h->pid);
        lscctl_json_string(stdout, h->serial);
        fputs(",\"manufacturer\":", stdout);
        lscctl_json_string(stdout, h->manufacturer);
        fputs(",\"hid\":true,\"port\":", stdout);
        lscctl_json_string(stdout, name);
        puts(",\"controller\":true}");
    } else {
        printf("%s\t%s (USB HID)\t%04x:%04x\t%s\tcontroller (--port %s)\n", h->path,
               *h->product ? h->product : "-", h->vid, h->pid, *h->serial ? h->serial : "-",
               name);
    }
}

int lscctl_list_ports(const lscctl_opts *o)
{
    ports *all;
    int r = list(o, &all);
    if (r != 0) {
        return r;
    }
    for (size_t i = 0; i < all->nserial; i++) {
        const lsc_port_info *p = &all->serial[i];
        bool ctl = looks_like_controller(p);
        if (o->json) {
            fputs("{\"path\":", stdout);
            lscctl_json_string(stdout, p->path);
            fputs(",\"description\":", stdout);
            lscctl_json_string(stdout, p->description);
            if (p->usb) {
                printf(",\"vid\":\"%04x\",\"pid\":\"%04x\",\"serial\":", p->vid, p->pid);
                lscctl_json_string(stdout, p->serial);
            } else { /* the same keys on every line: none of them known */
                fputs(",\"vid\":null,\"pid\":null,\"serial\":null", stdout);
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
    for (size_t i = 0; i < all->nhid; i++) {
        print_hid(o, &all->hid[i]);
    }
    if (all->nserial + all->nhid == 0 && !o->json) {
        fprintf(stderr, "lscctl: ports: no serial ports or HID controllers found (plug the "
                        "controller in; --port sim is the built-in virtual controller)\n");
    }
    free(all);
    return LSCCTL_EXIT_OK;
}

#define SETTLE_POLL_MS 20u /* between position reads while servos settle */

int lscctl_link_settle(lscctl_link *l, const lsc_servo *targets, size_t n, uint16_t time_ms,
                       uint16_t tolerance)
{
    uint8_t ids[LSC_MOVE_MAX];
    lsc_servo got[LSC_MOVE_MAX];
    uint32_t start = l->io.now_ms(l->io.ctx), spent;
    /* the move's time (notifications that arrive meanwhile are read) */
    while ((spent = l->io.now_ms(l->io.ctx) - start) < time_ms) {
        int r = lsc_client_poll(&l->client, time_ms - spent);
        if (r < 0) {
            return link_fail(l, r);
        }
    }
    for (size_t i = 0; i < n; i++) {
        ids[i] = targets[i].id;
    }
    start = l->io.now_ms(l->io.ctx);
    for (;;) {
        int r = lsc_client_read_positions(&l->client, ids, n, got, (uint32_t)l->o->timeout_ms);
        if (r == LSC_ETIMEOUT) { /* LSC boards' PWM servos may not report */
            if (l->o->verbose) {
                fprintf(stderr, "lscctl: move: the controller on %s does not answer position "
                                "reads: the move's time has passed\n",
                        l->name);
            }
            return 0;
        }
        if (r < 0) {
            return link_fail(l, r);
        }
        size_t off = n;
        for (size_t i = 0; i < n && off == n; i++) {
            int d = (int)got[i].position - (int)targets[i].position;
            off = d > (int)tolerance || d < -(int)tolerance ? i : n;
        }
        if (off == n) {
            return 0;
        }
        spent = l->io.now_ms(l->io.ctx) - start;
        if (spent >= l->o->timeout_ms) {
            return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                               "servo %u is at %u, not within %u of its target %u, %lu ms after "
                               "the move's time; raise --timeout or --tolerance",
                               got[off].id, got[off].position, tolerance, targets[off].position,
                               l->o->timeout_ms);
        }
        r = lsc_client_poll(&l->client, (uint32_t)l->o->timeout_ms - spent < SETTLE_POLL_MS
                                            ? (uint32_t)l->o->timeout_ms - spent
                                            : SETTLE_POLL_MS);
        if (r < 0) {
            return link_fail(l, r);
        }
    }
}

int lscctl_link_read_offsets(lscctl_link *l, const uint8_t *ids, size_t n, lsc_servo_offset *out)
{
    request q = {ids, n, out};
    int r = ask(l, ask_offsets, &q);
    if (r == LSC_ETIMEOUT) {
        return lscctl_fail(l->o, LSCCTL_EXIT_TIMEOUT,
                           "no reply from the controller on %s within %lu ms: servo offsets "
                           "(command 23) are the xArm firmware's, LSC-6/16/32 boards may not "
                           "answer; else check the port, power and --timeout",
                           l->name, l->o->timeout_ms);
    }
    return r >= 0 ? 0 : link_fail(l, r);
}

int lscctl_link_adjust_offset(lscctl_link *l, uint8_t id, int8_t offset)
{
    return sent(l, lsc_client_adjust_offset(&l->client, id, offset));
}
