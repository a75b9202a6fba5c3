/* lsc device: every error as one line that names the port, says what failed
 * and what to check (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "device_internal.h"

int lsc_dev_fail(lsc_device *d, int err, lsc_device_cause cause, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(d->message, sizeof d->message, fmt, ap);
    va_end(ap);
    d->cause = cause;
    return err;
}

int lsc_dev_fail_text(lsc_device *d, int err, lsc_device_cause cause, const char *prefix,
                      const char *text)
{
    (void)snprintf(d->message, sizeof d->message, "%s", prefix);
    size_t len = strlen(d->message); /* < sizeof d->message */
    (void)lsc_escape_text(d->message + len, sizeof d->message - len, text, strlen(text));
    d->cause = cause;
    return err;
}

int lsc_dev_sized(lsc_device *d, const void *s, size_t least, const char *what)
{
    if (s == NULL || lsc_sized_size(s) >= least) {
        return 0;
    }
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                        "%s.size is %lu, less than %lu: set it to sizeof(%s); nothing was sent",
                        what, (unsigned long)lsc_sized_size(s), (unsigned long)least, what);
}

void lsc_dev_begin(lsc_device *d)
{
    d->message[0] = '\0';
    d->cause = LSC_DEVICE_CAUSE_NONE;
    d->tx_failed = false;
}

const char *lsc_device_cmd_name(uint8_t cmd)
{
    switch (cmd) {
    case LSC_CMD_SERVO_MOVE: return "servo_move";
    case LSC_CMD_GROUP_RUN: return "action_group_run";
    case LSC_CMD_GROUP_STOP: return "action_group_stop";
    case LSC_CMD_GROUP_COMPLETE: return "action_group_complete";
    case LSC_CMD_GROUP_SPEED: return "action_group_speed";
    case LSC_CMD_BATTERY: return "get_battery_voltage";
    case LSC_CMD_UNLOAD: return "mult_servo_unload";
    case LSC_CMD_POS_READ: return "mult_servo_pos_read";
    case LSC_CMD_OFFSET_READ: return "servo_offset_read";
    case LSC_CMD_OFFSET_ADJUST: return "servo_offset_adjust";
    default: return "unknown";
    }
}

const char *lsc_device_kind_name(lsc_device_kind kind)
{
    switch (kind) {
    case LSC_DEVICE_SERIAL: return "serial";
    case LSC_DEVICE_HID: return "hid";
    case LSC_DEVICE_SIM: return "sim";
    case LSC_DEVICE_LSCD: return "lscd";
    case LSC_DEVICE_LX: return "lx";
    default: return "unknown";
    }
}

/* The timeout message: what did arrive during the request, and what that
 * suggests ("no reply" when plenty arrived would mislead). */
static int timed_out(lsc_device *d)
{
    lsc_client_counts now;
    lsc_client_get_counts(&d->client, &now);
    uint32_t frames = now.frames - d->before.frames;
    uint32_t notes = now.notifications - d->before.notifications;
    uint32_t noise = now.discarded - d->before.discarded + now.pending;
    if (frames > notes) {
        /* an answer came, but to something else: say what, not "no reply" */
        return lsc_dev_fail(
            d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_OTHER_FRAMES,
            "the controller on %s did not answer %s (command %u) within %lu ms: %lu frame(s) "
            "answering something else came instead (the last: %s (command %d)), with %lu "
            "notification(s) and %lu byte(s) that formed no frame; another program or device "
            "may be talking on the line, or the controller does not know this request; or "
            "raise the timeout",
            d->shown, lsc_device_cmd_name(d->asked), d->asked, (unsigned long)d->timeout_ms,
            (unsigned long)(frames - notes), lsc_device_cmd_name((uint8_t)d->rx_other),
            d->rx_other, (unsigned long)notes, (unsigned long)noise);
    }
    if (notes > 0) {
        return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_ONLY_NOTIFICATIONS,
                            "no reply from the controller on %s within %lu ms: only %lu "
                            "notification(s) arrived (and %lu byte(s) that formed no frame): "
                            "the controller is there but did not answer; or raise the timeout",
                            d->shown, (unsigned long)d->timeout_ms, (unsigned long)notes,
                            (unsigned long)noise);
    }
    if (noise > 0) {
        return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_NOISE,
                            "no reply from the controller on %s within %lu ms: only %lu "
                            "byte(s) arrived that formed no frame: likely a wrong baud rate "
                            "(this was %lu, LSC controllers use 9600), noise on the line, or a "
                            "reply whose bytes came more than %u ms apart; or raise the timeout",
                            d->shown, (unsigned long)d->timeout_ms, (unsigned long)noise,
                            (unsigned long)d->baud, LSC_CLIENT_GAP_MS);
    }
    if (d->t->silence != NULL) { /* e.g. lscd opened the port, at its own baud rate */
        return d->t->silence(d);
    }
    return lsc_dev_fail(d, LSC_ETIMEOUT, LSC_DEVICE_CAUSE_NO_REPLY,
                        "no reply from the controller on %s within %lu ms: nothing arrived; "
                        "check that it is powered and connected, and the port and baud rate "
                        "(%lu); or raise the timeout",
                        d->shown, (unsigned long)d->timeout_ms, (unsigned long)d->baud);
}

int lsc_dev_link_fail(lsc_device *d, int err)
{
    int own = d->t->link_fail != NULL ? d->t->link_fail(d, err) : 0;
    if (own != 0) { /* e.g. HID: no baud rate on USB; a closed port: every error */
        return own;
    }
    if (err == LSC_EINTR) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_INTERRUPTED,
                            "interrupted (lsc_device_interrupt) while waiting for the "
                            "controller on %s",
                            d->shown);
    }
    if (err == LSC_ETIMEOUT) {
        return timed_out(d);
    }
    if (err == LSC_EREPLY) {
        return lsc_dev_fail(d, err, LSC_DEVICE_CAUSE_NONE,
                            "bad reply from the controller on %s: check the baud rate (%lu) and "
                            "that nothing else talks on the line",
                            d->shown, (unsigned long)d->baud);
    }
    char sending[160] = "";
    if (d->tx_failed) {
        (void)snprintf(sending, sizeof sending, "sending %s (command %u, %lu bytes): ",
                       lsc_device_cmd_name(d->tx_cmd), d->tx_cmd, (unsigned long)d->tx_len);
    }
    /* the transport's own line: it names the port (or lscd's socket) and says
     * what failed. Every failure of a transport sets one; "sim" fails only
     * by timeouts and bad replies (above), and arguments are refused before
     * this (lsc_device_cmd_name's line). */
    return lsc_dev_fail_text(d, err, LSC_DEVICE_CAUSE_NONE, sending, d->t->message(d));
}

int lsc_dev_refuse(char *why, size_t whylen, const char *fmt, ...)
{
    if (why != NULL && whylen > 0) {
        va_list ap;
        va_start(ap, fmt);
        (void)vsnprintf(why, whylen, fmt, ap);
        va_end(ap);
    }
    return LSC_EINVAL;
}

#endif
