/* lsc device: what is plugged in (lsc_device_list), and the controller the
 * name NULL stands for ($LSC_PORT, else the one present). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"

/* VID:PID of the USB serial adapters LSC boards use (the xArm is a HID
 * device, listed by lsc_hid_list: a serial listing never shows it). */
static const struct {
    uint16_t vid, pid;
} adapter_ids[] = {
    {0x1a86, 0x7523}, /* CH340 */
    {0x10c4, 0xea60}, /* CP210x */
    {0x0403, 0x6001}, /* FTDI FT232 */
};

bool lsc_dev_known_adapter(bool usb, uint16_t vid, uint16_t pid)
{
    for (size_t i = 0; usb && i < sizeof adapter_ids / sizeof adapter_ids[0]; i++) {
        if (vid == adapter_ids[i].vid && pid == adapter_ids[i].pid) {
            return true;
        }
    }
    return false;
}

static void copy(char *to, size_t cap, const char *from)
{
    (void)snprintf(to, cap, "%s", from);
}

static void from_serial(lsc_device_info *o, const lsc_port_info *p)
{
    memset(o, 0, sizeof *o);
    copy(o->name, sizeof o->name, p->path);
    copy(o->path, sizeof o->path, p->path);
    copy(o->description, sizeof o->description, p->description);
    copy(o->serial, sizeof o->serial, p->usb ? p->serial : "");
    o->usb = p->usb;
    o->vid = p->usb ? p->vid : 0u;
    o->pid = p->usb ? p->pid : 0u;
    o->kind = LSC_DEVICE_SERIAL;
    o->controller = lsc_dev_known_adapter(p->usb, p->vid, p->pid);
}

static void from_hid(lsc_device_info *o, const lsc_hid_info *h)
{
    memset(o, 0, sizeof *o);
    /* hid:SERIAL opens it; without a serial number, its path */
    (void)snprintf(o->name, sizeof o->name, *h->serial != '\0' ? "hid:%s" : "%s",
                   *h->serial != '\0' ? h->serial : h->path);
    copy(o->path, sizeof o->path, h->path);
    copy(o->description, sizeof o->description, h->product);
    copy(o->serial, sizeof o->serial, h->serial);
    copy(o->manufacturer, sizeof o->manufacturer, h->manufacturer);
    o->usb = true;
    o->vid = h->vid;
    o->pid = h->pid;
    o->kind = LSC_DEVICE_HID;
    o->controller = true;
}

/* The HID controllers with the known ids, then (vid:pid not 0:0 and not a
 * known one) those with vid:pid, into out[0..cap): how many exist, or the
 * first listing's error. */
static int hid_list(lsc_hid_info *out, size_t cap, char *message, size_t msgcap, uint16_t vid,
                    uint16_t pid)
{
    int h = lsc_hid_list(out, cap, 0, 0, message, msgcap);
    if (h < 0 || (vid == 0 && pid == 0) || lsc_hid_is_known(vid, pid)) {
        return h;
    }
    size_t known = (size_t)h;
    if (known < cap) {
        out[known].size = sizeof out[known]; /* the second listing's out[0] */
    }
    int e = lsc_hid_list(known < cap ? out + known : NULL, known < cap ? cap - known : 0, vid,
                         pid, NULL, 0);
    return e < 0 ? h : h + e;
}

int lsc_dev_list(lsc_device_info *out, size_t cap, char *message, size_t msgcap, uint16_t vid,
                 uint16_t pid)
{
    char msg[256] = "", hmsg[256] = "";
    size_t room = cap > 0 ? cap : 1u;
    lsc_port_info *serial = calloc(room, sizeof *serial);
    lsc_hid_info *hid = calloc(room, sizeof *hid);
    if (serial == NULL || hid == NULL) {
        free(serial);
        free(hid);
        if (message != NULL && msgcap > 0) {
            copy(message, msgcap, "out of memory");
        }
        return LSC_ENOSPC;
    }
    serial[0].size = sizeof serial[0]; /* every element's (structs that grow) */
    hid[0].size = sizeof hid[0];
    int r = lsc_serial_list_ports(serial, room, msg, sizeof msg);
    int h = hid_list(hid, room, hmsg, sizeof hmsg, vid, pid);
    if (r < 0 && h < 0) {
        if (message != NULL && msgcap > 0) {
            (void)snprintf(message, msgcap, "cannot list serial ports: %s; nor HID: %s",
                           *msg != '\0' ? msg : lsc_strerror(r),
                           *hmsg != '\0' ? hmsg : lsc_strerror(h));
        }
        free(serial);
        free(hid);
        return r;
    }
    size_t ns = r < 0 ? 0u : (size_t)r, nh = h < 0 ? 0u : (size_t)h, n = 0;
    for (size_t i = 0; i < ns && n < cap; i++) {
        from_serial(&out[n++], &serial[i]);
    }
    for (size_t i = 0; i < nh && i < room && n < cap; i++) {
        from_hid(&out[n++], &hid[i]);
    }
    free(serial);
    free(hid);
    if (message != NULL && msgcap > 0) {
        message[0] = '\0';
    }
    return ns + nh > (size_t)0x7fffffff ? 0x7fffffff : (int)(ns + nh);
}

#define FIND_MAX 80u /* ports and controllers looked at */

int lsc_dev_find(lsc_device *d, char *name, size_t cap)
{
    const char *env = lsc_dev_env_port();
    if (env != NULL) {
        copy(name, cap, env);
        return 0;
    }
    char why[256], candidates[1024] = "";
    size_t found = 0, len = 0;
    lsc_device_info *all = calloc(FIND_MAX, sizeof *all);
    if (all == NULL) {
        return lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE, "out of memory");
    }
    int n = lsc_dev_list(all, FIND_MAX, why, sizeof why, d->hid_vid, d->hid_pid);
    if (n < 0) {
        free(all);
        return lsc_dev_fail(d, n == LSC_ENOSPC ? n : LSC_ENODEV,
                            n == LSC_ENOSPC ? LSC_DEVICE_CAUSE_NONE
                                            : LSC_DEVICE_CAUSE_NO_CONTROLLER,
                            "no device named ($LSC_PORT is not set) and none can be found: %s",
                            why);
    }
    for (size_t i = 0; i < (size_t)n && i < FIND_MAX; i++) {
        if (!all[i].controller) {
            continue;
        }
        if (found++ == 0) {
            copy(name, cap, all[i].name);
        }
        int w = snprintf(candidates + len, sizeof candidates - len, "%s%s (serial number %s)",
                         found == 1 ? "" : ", ", all[i].name,
                         *all[i].serial != '\0' ? all[i].serial : "none");
        /* cut: the rest of the room (a negative w, which "%s" cannot give,
         * would read as cut too) */
        len += (size_t)w < sizeof candidates - len ? (size_t)w : sizeof candidates - 1u - len;
    }
    free(all);
    if (found == 1) {
        return 0;
    }
    if (found == 0) {
        return lsc_dev_fail(d, LSC_ENODEV, LSC_DEVICE_CAUSE_NO_CONTROLLER,
                            "no device named ($LSC_PORT is not set) and none looks like a "
                            "controller: plug one in, name one (a serial port, hid, hid:SERIAL "
                            "or sim) or set LSC_PORT");
    }
    /* names and serial numbers come from the devices: escaped */
    return lsc_dev_fail_text(d, LSC_EINVAL, LSC_DEVICE_CAUSE_SEVERAL,
                             "no device named ($LSC_PORT is not set) and several look like a "
                             "controller: name one or set LSC_PORT; they are: ",
                             candidates);
}

#endif
