/* The tests' way to open a device with settings written as one initializer
 * ({baud, timeout_ms, hid_vid, hid_pid}, 0 for a default), through an
 * lsc_device_config made, set and freed around the open (lsc/device.h). */
#ifndef LSC_TEST_OPEN_H
#define LSC_TEST_OPEN_H

#include <stdint.h>

#include "lsc/device.h"

typedef struct test_options {
    uint32_t baud;       /* 0: the default */
    uint32_t timeout_ms; /* 0: the default */
    uint16_t hid_vid, hid_pid;
} test_options;

/* lsc_device_open(name, a config of o (NULL: NULL), out); LSC_ENOSPC when
 * the config cannot be made, LSC_EINVAL when a setter refuses a value (then
 * nothing was opened: *out NULL, as a failed open leaves it). */
static inline int test_open(const char *name, const test_options *o, lsc_device **out)
{
    if (o == NULL) {
        return lsc_device_open(name, NULL, out);
    }
    lsc_device_config *cfg = lsc_device_config_new();
    if (cfg == NULL) {
        if (out != NULL) {
            *out = NULL;
        }
        return LSC_ENOSPC;
    }
    int r = lsc_device_config_set_hid_id(cfg, o->hid_vid, o->hid_pid);
    if (r == 0 && o->baud != 0u) {
        r = lsc_device_config_set_baud(cfg, o->baud);
    }
    if (r == 0 && o->timeout_ms != 0u) {
        r = lsc_device_config_set_timeout_ms(cfg, o->timeout_ms);
    }
    if (r == 0) {
        r = lsc_device_open(name, cfg, out);
    } else if (out != NULL) {
        *out = NULL;
    }
    lsc_device_config_free(cfg);
    return r;
}

#endif
