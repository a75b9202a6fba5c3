/* lsc core: the library's version (lsc/version.h). */
#include "lsc/core.h"

const char *lsc_version(void)
{
    return LSC_VERSION_STRING;
}
