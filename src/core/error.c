#include "lsc/core.h"

/* The texts of 0, -1, -2, ... in order, then the text for unknown codes, one
 * after the other: a table of pointers would cost 4 bytes a code. */
static const char texts[] = "success\0"
                            "invalid argument\0"
                            "buffer too small\0"
                            "bytes outside a frame\0"
                            "malformed frame\0"
                            "frame too long\0"
                            "timed out\0"
                            "I/O error\0"
                            "unexpected reply\0"
                            "port busy\0"
                            "no such device\0"
                            "permission denied\0"
                            "interrupted\0"
                            "unknown error";

const char *lsc_strerror(int err)
{
    /* positive values are counts: success */
    unsigned skip = err >= 0 ? 0u : err < LSC_EINTR ? (unsigned)-LSC_EINTR + 1u : (unsigned)-err;
    const char *s = texts;
    while (skip-- > 0) {
        while (*s++ != '\0') {
        }
    }
    return s;
}
