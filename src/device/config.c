/* lsc device: how to open a device, as an opaque object with setters
 * (contract in lsc/device.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdlib.h>

#include "device_internal.h"

lsc_device_config *lsc_device_config_new(void)
{
    return calloc(1, sizeof(lsc_device_config)); /* all 0: the defaults */
}

void lsc_device_config_free(lsc_device_config *cfg)
{
    free(cfg);
}

int lsc_device_config_set_baud(lsc_device_config *cfg, uint32_t baud)
{
    if (cfg == NULL || baud == 0u || baud > LSC_DEVICE_BAUD_MAX) {
        return LSC_EINVAL;
    }
    cfg->baud = baud;
    return 0;
}

int lsc_device_config_set_timeout_ms(lsc_device_config *cfg, uint32_t timeout_ms)
{
    if (cfg == NULL || timeout_ms == 0u || timeout_ms > LSC_DEVICE_TIMEOUT_MAX) {
        return LSC_EINVAL;
    }
    cfg->timeout_ms = timeout_ms;
    return 0;
}

int lsc_device_config_set_hid_id(lsc_device_config *cfg, uint16_t vid, uint16_t pid)
{
    if (cfg == NULL) {
        return LSC_EINVAL;
    }
    cfg->hid_vid = vid;
    cfg->hid_pid = pid;
    return 0;
}

#endif /* LSC_HOST */
