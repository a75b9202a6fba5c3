#include "lsc/core.h"

const char *lsc_strerror(int err)
{
    switch (err) {
    case LSC_OK: return "success";
    case LSC_EINVAL: return "invalid argument";
    case LSC_ENOSPC: return "buffer too small";
    case LSC_ESYNC: return "bytes outside a frame discarded";
    case LSC_EFRAME: return "malformed frame";
    case LSC_ETOOBIG: return "frame longer than the buffer";
    case LSC_ETIMEOUT: return "no reply within the timeout";
    case LSC_EIO: return "I/O error";
    case LSC_EREPLY: return "unexpected reply";
    case LSC_EBUSY: return "port busy";
    case LSC_ENODEV: return "no such device";
    case LSC_EACCES: return "permission denied";
    default: return err > 0 ? "success" : "unknown error";
    }
}
