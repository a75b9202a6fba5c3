/* lsc device: the entry of a HID controller (lsc/hid.h): "hid" (the only
 * one), "hid:SERIAL" or a hidraw node; its one bound (a move in one 64-byte
 * report), the retry of the first request, and its lines (no baud rate on
 * USB) (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <string.h>

#include "device_internal.h"

static lsc_hid *st(const lsc_device *d)
{
    return d->state;
}

static bool claims(const char *name)
{
    const char *base = strrchr(name, '/');
    return strcmp(name, "hid") == 0 || strncmp(name, "hid:", 4) == 0 ||
           (base != NULL && strncmp(base + 1, "hidraw", 6) == 0);
}

/* Opens the HID controller name: hid (the only one), hid:SERIAL or a path. */
static int open_hid(lsc_device *d, const char *name)
{
    if (strncmp(name, "hid:", 4) == 0 && name[4] == '\0') {
        return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                            "hid: needs a serial number after the colon (hid:SERIAL), or "
                            "name hid for the only controller present");
    }
    lsc_hid *h = NULL;
    int r;
    if (strcmp(name, "hid") == 0) {
        r = lsc_hid_open_serial_extra(NULL, d->hid_vid, d->hid_pid, &h);
    } else if (strncmp(name, "hid:", 4) == 0) {
        r = lsc_hid_open_serial_extra(name + 4, d->hid_vid, d->hid_pid, &h);
    } else {
        r = lsc_hid_open_path_extra(name, d->hid_vid, d->hid_pid, &h);
    }
    d->state = h;
    if (r != 0) {
        /* the HID layer's message names the device and what failed (or, for
         * several controllers and none chosen, their serial numbers) */
        bool several = r == LSC_EINVAL && strcmp(name, "hid") == 0 && lsc_hid_available();
        return lsc_dev_fail_text(d, r, several ? LSC_DEVICE_CAUSE_SEVERAL : lsc_dev_open_cause(r),
                                 "", lsc_hid_error_message(NULL));
    }
    lsc_hid_get_io(h, &d->port);
    return 0;
}

static void close_hid(lsc_device *d)
{
    lsc_hid_close(st(d));
    d->state = NULL;
}

static int hid_fileno(const lsc_device *d)
{
    return lsc_hid_fileno(st(d));
}

static const char *message(const lsc_device *d)
{
    return lsc_hid_error_message(st(d));
}

static bool held(const lsc_device *d)
{
    return lsc_hid_input_pending(st(d));
}

/* The copies on the descriptor go first, so that a report that comes after
 * the last read finds it readable again. */
static void before_ready(lsc_device *d)
{
    (void)lsc_hid_fileno_drain(st(d));
}

/* LSC_DEVICE_HID_MOVE_MAX servos in one move: a 64-byte report. */
static int bound(lsc_device *d, size_t n, const char *what, const char *advice)
{
    if (n <= LSC_DEVICE_HID_MOVE_MAX) {
        return 0;
    }
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "%s of %lu servos on %s: at most %u servos in one move over HID (a "
                        "64-byte report)%s; nothing was sent",
                        what, (unsigned long)n, d->shown, LSC_DEVICE_HID_MOVE_MAX, advice);
}

/* No baud rate on USB: only power, cable and time are left to check. */
static int link_fail(lsc_device *d, int err)
{
    if (err == LSC_ETIMEOUT) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NO_REPLY,
                            "no reply from the controller on %s within %lu ms: check that "
                            "it is switched on and connected; or raise the timeout",
                            d->shown, (unsigned long)d->timeout_ms);
    }
    if (err == LSC_EREPLY) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NONE,
                            "bad reply from the controller on %s (timeout %lu ms): check "
                            "that no other program talks to it",
                            d->shown, (unsigned long)d->timeout_ms);
    }
    return 0;
}

static size_t all_ids(const char *name)
{
    (void)name;
    return DEVICE_HID_IDS;
}

const lsc_dev_transport lsc_dev_transport_hid = {
    .kind = LSC_DEVICE_HID,
    .claims = claims,
    .open = open_hid,
    .close = close_hid,
    .fileno = hid_fileno,
    .message = message,
    .held = held,
    .before_ready = before_ready,
    .bound = bound,
    .link_fail = link_fail,
    .all_ids = all_ids,
    .ops = &lsc_dev_board_ops,
    /* a real arm may leave the first request after the open unanswered
     * (docs/hid.md): that one is sent again when it timed out */
    .first_retries = LSC_HID_FIRST_RETRIES,
    .restart_grace_ms = DEVICE_RESTART_GRACE_MS,
    .name = "a HID controller",
};

#endif
