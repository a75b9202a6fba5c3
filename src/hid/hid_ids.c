/* HID transport: the known controllers' USB ids, the one table (contract in
 * lsc/hid.h), in a file of its own so that the node checks (hid_node.c) and
 * the transport (hid.c) both use it and neither needs the other. Host only:
 * compiles to nothing elsewhere (the Arduino IDE builds every .c under
 * src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>

#include "lsc/hid.h"
#include "hid_internal.h"

/* The known controllers' USB ids: the one list (docs/protocol.md, "The USB HID
 * link"). Listing, opening and lsc_hid_is_known read it. */
static const lsc_hid_id known_ids[] = {
    {LSC_HID_VID, LSC_HID_PID, "xArm, LeArm, Bus Servo Controller (LOBOT)"},
};
#define KNOWN_COUNT (sizeof known_ids / sizeof known_ids[0])

const lsc_hid_id *lsc_hid_known_ids(size_t *count)
{
    if (count != NULL) {
        *count = KNOWN_COUNT;
    }
    return known_ids;
}

bool lsc_hid_is_known(uint16_t vid, uint16_t pid)
{
    for (size_t i = 0; i < KNOWN_COUNT; i++) {
        if (known_ids[i].vid == vid && known_ids[i].pid == pid) {
            return true;
        }
    }
    return false;
}

bool lsc_hid_is_extra(uint16_t vid, uint16_t pid)
{
    return (vid != 0u || pid != 0u) && !lsc_hid_is_known(vid, pid);
}

void lsc_hid_known_text(char *out, size_t cap, uint16_t extra_vid, uint16_t extra_pid)
{
    size_t len = 0;
    if (cap == 0u) {
        return;
    }
    out[0] = '\0';
    for (size_t i = 0; i <= KNOWN_COUNT; i++) {
        uint16_t vid = i < KNOWN_COUNT ? known_ids[i].vid : extra_vid;
        uint16_t pid = i < KNOWN_COUNT ? known_ids[i].pid : extra_pid;
        if (i == KNOWN_COUNT && !lsc_hid_is_extra(vid, pid)) {
            break;
        }
        int w = snprintf(out + len, cap - len, "%s%04x:%04x", i == 0 ? "" : " or ",
                         (unsigned)vid, (unsigned)pid);
        if (w < 0 || (size_t)w >= cap - len) {
            break;
        }
        len += (size_t)w;
    }
}

#endif
