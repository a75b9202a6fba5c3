/* The HID transport's node check against the system's sysfs. Alone in its
 * file on purpose (hid_internal.h): a test program linked with the static
 * library may define lsc_hid_node_identify_live itself, and the linker then
 * leaves this file out. Host only, like hid.c. */
#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)

#include "hid_internal.h"

int lsc_hid_node_identify_live(const char *path, lsc_hid_node *node, lsc_port_error *e)
{
    return lsc_hid_node_identify("", path, path, node, e);
}

#else
typedef int lsc_hid_live_empty_unit; /* ISO C forbids an empty translation unit */
#endif
