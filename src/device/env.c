/* lsc device: the environment every front end reads the same way
 * ($LSC_PORT, $LSC_ARM, $LSC_HID_ID; contract in lsc/env.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdlib.h>

#include "device_internal.h"

/* A variable's value when it is set and not empty, else NULL. */
static const char *env(const char *name)
{
    const char *v = getenv(name);
    return v != NULL && *v != '\0' ? v : NULL;
}

const char *lsc_dev_env_port(void)
{
    return env("LSC_PORT");
}

const char *lsc_device_env_port(void)
{
    return lsc_dev_env_port();
}

const char *lsc_device_env_arm(void)
{
    return env("LSC_ARM");
}

/* The value of hex digit c, or -1. */
static int hex(char c)
{
    return c >= '0' && c <= '9'   ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
}

int lsc_device_parse_hid_id(const char *s, uint16_t *vid, uint16_t *pid)
{
    unsigned v[2] = {0, 0};
    if (s == NULL || vid == NULL || pid == NULL) {
        return LSC_EINVAL;
    }
    for (int k = 0; k < 2; k++) {
        size_t n = 0;
        for (; hex(*s) >= 0 && n <= 4u; s++, n++) {
            v[k] = v[k] * 16u + (unsigned)hex(*s);
        }
        if (n == 0u || n > 4u || *s != (k == 0 ? ':' : '\0')) {
            return LSC_EINVAL;
        }
        s++;
    }
    if (v[0] == 0u && v[1] == 0u) {
        return LSC_EINVAL;
    }
    *vid = (uint16_t)v[0];
    *pid = (uint16_t)v[1];
    return 0;
}

int lsc_device_config_from_env(lsc_device_config *cfg, char *why, size_t whylen)
{
    if (cfg == NULL) {
        return lsc_dev_refuse(why, whylen, "lsc_device_config_from_env: no config");
    }
    const char *id = env("LSC_HID_ID");
    uint16_t vid = 0, pid = 0;
    if (id != NULL && cfg->hid_vid == 0u && cfg->hid_pid == 0u) {
        if (lsc_device_parse_hid_id(id, &vid, &pid) != 0) {
            return lsc_dev_refuse(why, whylen,
                                  "$LSC_HID_ID needs a USB VID:PID in hex, as 'lscctl ports' or "
                                  "lsusb shows it (e.g. 0483:5750), or nothing");
        }
        cfg->hid_vid = vid;
        cfg->hid_pid = pid;
    }
    if (why != NULL && whylen > 0u) {
        why[0] = '\0';
    }
    return 0;
}

#endif
