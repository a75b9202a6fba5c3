/* The HID transport's node check against the system's sysfs. Alone in its
 * file on purpose (hid_internal.h): a test program linked with the static
 * library may define lsc_hid_node_identify_live itself, and the linker then
 * leaves this file out. Host only, like hid.c. */
#include "lsc/host.h"
#if LSC_HOST

#include "hid_internal.h"

int lsc_hid_node_identify_live(const char *path, lsc_hid_node *node, lsc_port_error *e)
{
    return lsc_hid_node_identify("", path, path, node, e);
}

#endif
