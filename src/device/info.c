/* lsc device: a listing of the controllers present as opaque infos read
 * through accessors (contract in lsc/discovery.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>

#include "device_internal.h"

int lsc_device_list(lsc_device_info ***out, char *message, size_t msgcap)
{
    if (out == NULL) {
        if (message != NULL && msgcap > 0u) {
            (void)snprintf(message, msgcap, "lsc_device_list: no list to fill");
        }
        return LSC_EINVAL;
    }
    *out = NULL;
    int n = lsc_dev_list(NULL, 0, message, msgcap, 0, 0); /* how many */
    if (n < 0) {
        return n;
    }
    size_t cap = (size_t)n < LSC_DEVICE_LIST_MAX ? (size_t)n : LSC_DEVICE_LIST_MAX;
    /* one block: the NULL-terminated pointers, then the infos they point to */
    size_t head = (cap + 1u) * sizeof(lsc_device_info *);
    char *block = calloc(1, head + cap * sizeof(lsc_device_info));
    if (block == NULL) {
        if (message != NULL && msgcap > 0u) {
            (void)snprintf(message, msgcap, "out of memory");
        }
        return LSC_ENOSPC;
    }
    lsc_device_info *infos = (lsc_device_info *)(void *)(block + head);
    n = lsc_dev_list(infos, cap, message, msgcap, 0, 0);
    if (n < 0) {
        free(block);
        return n;
    }
    /* a controller plugged in between the two listings waits for the next */
    size_t got = (size_t)n > cap ? cap : (size_t)n;
    lsc_device_info **list = (lsc_device_info **)(void *)block;
    for (size_t i = 0; i < got; i++) {
        list[i] = &infos[i];
    }
    list[got] = NULL;
    *out = list;
    return (int)got;
}

void lsc_device_list_free(lsc_device_info **list)
{
    free(list); /* one block (above) */
}

const char *lsc_device_info_name(const lsc_device_info *info)
{
    return info != NULL ? info->name : "";
}

const char *lsc_device_info_path(const lsc_device_info *info)
{
    return info != NULL ? info->path : "";
}

const char *lsc_device_info_description(const lsc_device_info *info)
{
    return info != NULL ? info->description : "";
}

const char *lsc_device_info_serial(const lsc_device_info *info)
{
    return info != NULL ? info->serial : "";
}

const char *lsc_device_info_manufacturer(const lsc_device_info *info)
{
    return info != NULL ? info->manufacturer : "";
}

uint16_t lsc_device_info_vid(const lsc_device_info *info)
{
    return info != NULL ? info->vid : 0u;
}

uint16_t lsc_device_info_pid(const lsc_device_info *info)
{
    return info != NULL ? info->pid : 0u;
}

bool lsc_device_info_usb(const lsc_device_info *info)
{
    return info != NULL && info->usb;
}

lsc_device_kind lsc_device_info_kind(const lsc_device_info *info)
{
    return info != NULL ? info->kind : LSC_DEVICE_SERIAL;
}

bool lsc_device_info_controller(const lsc_device_info *info)
{
    return info != NULL && info->controller;
}

#endif /* LSC_HOST */
