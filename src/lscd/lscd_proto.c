/* lscd's wire protocol helpers and the names of its sockets (lsc/lscd.h,
 * lscd_proto.h). Host only: compiles to nothing elsewhere (the Arduino IDE
 * builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lscd_proto.h"

int lsc_lscd_encode_ctl(uint8_t *buf, size_t cap, uint8_t op, const uint8_t *args, size_t n)
{
    uint8_t params[LSC_PARAMS_MAX];
    if (n > LSCD_ARGS_MAX || (n > 0u && args == NULL)) {
        return LSC_EINVAL;
    }
    params[0] = op;
    if (n > 0u) {
        memcpy(params + 1, args, n);
    }
    return lsc_encode_frame(buf, cap, LSC_LSCD_CMD, params, n + 1u);
}

/* Writes the text built in a NUL-terminated buffer to out[cap]; returns its
 * length, or LSC_ENOSPC when it does not fit out (or is `limit` or longer). */
static int put_text(char *out, size_t cap, const char *s, size_t limit)
{
    size_t n = strlen(s);
    if (out == NULL || n + 1u > cap || n + 1u > limit) {
        return LSC_ENOSPC;
    }
    memcpy(out, s, n + 1u);
    return (int)n;
}

static bool name_char(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '.' || c == '-';
}

int lsc_lscd_name(const char *port, char *out, size_t cap)
{
    char name[LSC_LSCD_NAME_MAX];
    const char *src;
    size_t n = 0;
    if (port == NULL || port[0] == '\0') {
        return LSC_EINVAL;
    }
    if (strncmp(port, "hid:", 4) == 0) {
        if (port[4] == '\0') {
            return LSC_EINVAL;
        }
        name[n++] = 'h';
        name[n++] = 'i';
        name[n++] = 'd';
        name[n++] = '-';
        src = port + 4;
    } else {
        if (strncmp(port, "lx:", 3) == 0) { /* a bus: "lx-" and its port's name */
            port += 3;
            name[n++] = 'l';
            name[n++] = 'x';
            name[n++] = '-';
        }
        const char *slash = strrchr(port, '/');
        src = slash != NULL ? slash + 1 : port;
        if (*src == '\0') { /* no name: "", "/dev/", "lx:" */
            return LSC_EINVAL;
        }
    }
    for (; *src != '\0'; src++) {
        if (n + 1u >= sizeof name) {
            return LSC_ENOSPC;
        }
        char c = *src;
        if (!name_char(c)) {
            c = '_';
        }
        name[n++] = c;
    }
    name[n] = '\0';
    if (n == 0u || strcmp(name, ".") == 0 || strcmp(name, "..") == 0) {
        return LSC_EINVAL;
    }
    return put_text(out, cap, name, LSC_LSCD_NAME_MAX);
}

int lsc_lscd_port_of_name(const char *name, char *out, size_t cap)
{
    char port[LSC_LSCD_PATH_MAX + 8u];
    int w;
    if (name == NULL || name[0] == '\0' || strchr(name, '/') != NULL) {
        return LSC_EINVAL;
    }
    if (strcmp(name, "sim") == 0 || strcmp(name, "hid") == 0) {
        w = snprintf(port, sizeof port, "%s", name);
    } else if (strncmp(name, "hid-", 4) == 0 && name[4] != '\0') {
        w = snprintf(port, sizeof port, "hid:%s", name + 4);
    } else if (strcmp(name, "lx-sim") == 0) {
        w = snprintf(port, sizeof port, "lx:sim");
    } else if (strncmp(name, "lx-", 3) == 0 && name[3] != '\0') {
        w = snprintf(port, sizeof port, "lx:/dev/%s", name + 3);
    } else {
        w = snprintf(port, sizeof port, "/dev/%s", name);
    }
    if (w < 0 || (size_t)w >= sizeof port) {
        return LSC_ENOSPC;
    }
    return put_text(out, cap, port, sizeof port);
}

int lsc_lscd_socket_path(const char *name, char *out, size_t cap)
{
    char path[LSC_LSCD_PATH_MAX];
    const char *dir;
    size_t dlen;
    int w;
    if (name == NULL) {
        return LSC_EINVAL;
    }
    if (strncmp(name, LSC_LSCD_PREFIX, sizeof LSC_LSCD_PREFIX - 1u) == 0) {
        name += sizeof LSC_LSCD_PREFIX - 1u;
    }
    if (name[0] == '\0') {
        return LSC_EINVAL;
    }
    if (strchr(name, '/') != NULL) {
        w = snprintf(path, sizeof path, "%s", name);
    } else {
        dir = getenv("LSC_LSCD_DIR");
        if (dir == NULL || dir[0] == '\0') {
            dir = LSC_LSCD_DIR;
        }
        dlen = strlen(dir);
        while (dlen > 1u && dir[dlen - 1u] == '/') {
            dlen--;
        }
        w = dlen > (size_t)INT_MAX ? -1 : snprintf(path, sizeof path, "%.*s/%s.sock", (int)dlen, dir, name);
    }
    if (w < 0 || (size_t)w >= sizeof path) {
        return LSC_ENOSPC;
    }
    return put_text(out, cap, path, sizeof path);
}

#endif
