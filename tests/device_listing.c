/* The transports' listings replaced through the linker (tests/device_listing.h). */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "device_listing.h"
#include "../src/device/device_internal.h" /* lsc_device_info's fields */
#include "lsc/hid.h"
#include "lsc/serial.h"

int __real_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);
int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);
int __real_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap);
int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap);

int serial_mode = SERIAL_PORTS;
int hid_mode = HID_REAL;

void device_listing_reset(void)
{
    serial_mode = SERIAL_PORTS;
    hid_mode = HID_REAL;
}

int list_into(lsc_device_info *out, size_t cap, char *msg, size_t msgcap)
{
    lsc_device_info **all = (lsc_device_info **)&all;
    int n = lsc_device_list(&all, msg, msgcap);
    if (n < 0) {
        assert_null(all);
        return n;
    }
    size_t i = 0;
    for (; all[i] != NULL; i++) {
        if (i < cap) {
            out[i] = *all[i];
        }
    }
    assert_int_equal(i, n);
    lsc_device_list_free(all);
    return n;
}

static void fake_port(lsc_port_info *p, const char *path, const char *desc, bool usb,
                      uint16_t vid, uint16_t pid, const char *serial)
{
    memset(p, 0, sizeof *p);
    p->size = sizeof *p;
    snprintf(p->path, sizeof p->path, "%s", path);
    snprintf(p->description, sizeof p->description, "%s", desc);
    p->usb = usb;
    p->vid = vid;
    p->pid = pid;
    snprintf(p->serial, sizeof p->serial, "%s", serial);
}

int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap)
{
    lsc_port_info ports[8];
    size_t n = 0;
    assert_true(cap == 0 || out[0].size == sizeof *out); /* the device layer's elements */
    switch (serial_mode) {
    case SERIAL_REAL: return __real_lsc_serial_list_ports(out, cap, message, msgcap);
    case SERIAL_FAIL:
        snprintf(message, msgcap, "no serial listing here");
        return LSC_EIO;
    case SERIAL_FAIL_BARE: return LSC_ENODEV;
    case SERIAL_PORTS:
        fake_port(&ports[n++], "/nonexistent/ttyUSB7", "USB2.0-Serial", true, 0x1a86, 0x7523,
                  "S1");
        fake_port(&ports[n++], "/nonexistent/ttyS0", "", false, 0, 0, "");
        fake_port(&ports[n++], "/nonexistent/ttyACM0", "Arduino Uno", true, 0x2341, 0x0043, "");
        break;
    case SERIAL_TWO:
        fake_port(&ports[n++], "/nonexistent/ttyUSB0", "CP2102", true, 0x10c4, 0xea60, "");
        fake_port(&ports[n++], "/nonexistent/ttyUSB1", "FT232R", true, 0x0403, 0x6001, "F1");
        break;
    case SERIAL_ODD:
        fake_port(&ports[n++], "/nonexistent/ttyUSB0", "CP2102", true, 0x10c4, 0xea60,
                  "S\n\033[2J");
        fake_port(&ports[n++], "/nonexistent/tty\nUSB1", "FT232R", true, 0x0403, 0x6001, "F1");
        break;
    case SERIAL_NEAR:
        fake_port(&ports[n++], "/nonexistent/ttyUSB3", "CH9102", true, 0x1a86, 0x55d4, "");
        break;
    case SERIAL_HUGE:
        for (size_t i = 0; i < cap; i++) {
            fake_port(&out[i], "/nonexistent/ttyUSB9", "CH340", true, 0x1a86, 0x7523, "");
        }
        return 0x7fffffff;
    default:
        for (; n < 8; n++) {
            char path[220];
            memset(path, 'x', sizeof path - 1u);
            path[sizeof path - 1u] = '\0';
            memcpy(path, "/nonexistent/", 13);
            path[13] = (char)('0' + n);
            fake_port(&ports[n], path, "CH340", true, 0x1a86, 0x7523, "");
        }
        break;
    }
    for (size_t i = 0; i < n && i < cap; i++) {
        out[i] = ports[i];
    }
    return (int)n;
}

int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap)
{
    if (hid_mode == HID_FAIL) {
        snprintf(message, msgcap, "no HID listing here");
        return LSC_EINVAL;
    }
    if (hid_mode == HID_FAIL_BARE || (hid_mode == HID_FAIL_OTHER && (vid != 0 || pid != 0))) {
        return LSC_EIO;
    }
    assert_true(cap == 0 || out[0].size == sizeof *out); /* the device layer's elements */
    if (hid_mode == HID_MANY && vid == 0 && pid == 0) {
        for (size_t i = 0; i < cap; i++) {
            memset(&out[i], 0, sizeof out[i]);
            out[i].size = sizeof out[i];
            snprintf(out[i].path, sizeof out[i].path, "/nonexistent/hidraw%zu", i);
            snprintf(out[i].serial, sizeof out[i].serial, "M%zu", i);
            out[i].vid = LSC_HID_VID;
            out[i].pid = LSC_HID_PID;
        }
        return 100;
    }
    return __real_lsc_hid_list(out, cap, vid, pid, message, msgcap);
}
