/* lsc device: the calibrated profile of the arm on a controller, by the
 * controller's stable name (include/lsc/calibrated.h). Host only. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE /* realpath, lstat, gmtime_r */

#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "lsc/calibrated.h"
#include "lsc/files.h"
#include "lsc/lscd.h"
#include "device_internal.h"

#define LIST_MAX 80u /* ports and controllers looked at */

/* prefix + s into key[cap], made a file's name. */
static int put_key(char *key, size_t cap, const char *prefix, const char *s)
{
    size_t n = (size_t)snprintf(key, cap, "%s%s", prefix, s); /* (size_t)-1 on an error */
    if (n >= cap) {
        return LSC_EINVAL;
    }
    for (size_t i = 0; i < n; i++) {
        char c = key[i];
        /* ('.' too: a key starts with its kind, "hid-", "port-" or "sim", never a dot) */
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '_' || c == '-' || c == '.';
        if (!ok) {
            key[i] = '_';
        }
    }
    return LSC_OK;
}

int lsc_dev_port_key(const char *dir, const char *path, char *key, size_t cap)
{
    struct stat st;
    char real[PATH_MAX], other[PATH_MAX], link[PATH_MAX];
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
        const char *slash = strrchr(path, '/');
        return put_key(key, cap, "port-", slash != NULL ? slash + 1 : path);
    }
    DIR *d = realpath(path, real) != NULL ? opendir(dir) : NULL;
    if (d == NULL) {
        return LSC_ENODEV;
    }
    int r = LSC_ENODEV;
    for (struct dirent *e = readdir(d); e != NULL && r == LSC_ENODEV; e = readdir(d)) {
        (void)snprintf(link, sizeof link, "%s/%s", dir, e->d_name);
        if (e->d_name[0] != '.' && realpath(link, other) != NULL && strcmp(real, other) == 0) {
            r = put_key(key, cap, "port-", e->d_name);
        }
    }
    (void)closedir(d);
    return r;
}

/* The name of the one controller present (hid only: the one HID controller
 * with a serial number) into name[cap]: 0, or LSC_ENODEV. */
static int only_one(bool hid, char *name, size_t cap)
{
    lsc_device_info *all = calloc(LIST_MAX, sizeof *all);
    int n = all != NULL ? lsc_dev_list(all, LIST_MAX, NULL, 0, 0, 0) : LSC_ENOSPC;
    size_t found = 0;
    for (size_t i = 0; i < (size_t)(n > 0 ? n : 0) && i < LIST_MAX; i++) {
        bool wanted = hid ? all[i].kind == LSC_DEVICE_HID && all[i].serial[0] != '\0'
                          : all[i].controller;
        if (wanted && found++ == 0) {
            (void)snprintf(name, cap, "%s", all[i].name);
        }
    }
    free(all);
    return found == 1 ? LSC_OK : LSC_ENODEV;
}

int lsc_calibrated_key(const char *name, char *key, size_t cap)
{
    char found[LSC_DEVICE_NAME_MAX], port[LSC_DEVICE_NAME_MAX];
    if (key == NULL || cap == 0) {
        return LSC_EINVAL;
    }
    key[0] = '\0';
    if (name != NULL && strncmp(name, LSC_LSCD_PREFIX, 5) == 0) { /* lscd:NAME: its port's */
        if (strchr(name + 5, '/') != NULL ||
            lsc_lscd_port_of_name(name + 5, port, sizeof port) < 0) {
            return LSC_ENODEV;
        }
        name = port; /* "sim", "hid", "hid:SERIAL" or /dev/NAME */
    }
    if (name == NULL || *name == '\0' || strcmp(name, "hid") == 0) {
        bool hid = name != NULL && *name != '\0';
        if (only_one(hid, found, sizeof found) != 0) {
            return LSC_ENODEV;
        }
        name = found; /* "hid:SERIAL", or a path */
    }
    if (strcmp(name, "sim") == 0) {
        return put_key(key, cap, "", "sim");
    }
    if (strncmp(name, "hid:", 4) == 0) {
        return put_key(key, cap, "hid-", name + 4);
    }
    return lsc_dev_port_key("/dev/serial/by-id", name, key, cap);
}

int lsc_calibrated_path(const char *key, char *path, size_t cap)
{
    const char *xdg = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
    bool own = xdg != NULL && xdg[0] == '/';
    if (key == NULL || *key == '\0' || path == NULL || (!own && (home == NULL || *home == '\0'))) {
        return LSC_EINVAL;
    }
    size_t n = (size_t)snprintf(path, cap, "%s%s/lsc/arms/%s.conf", own ? xdg : home,
                                own ? "" : "/.config", key);
    return n < cap ? LSC_OK : LSC_EINVAL;
}

int lsc_calibrated_find(const char *name, char *path, size_t cap)
{
    char key[LSC_CALIBRATED_KEY_MAX];
    struct stat st;
    int r = lsc_calibrated_key(name, key, sizeof key);
    if (r == 0) {
        r = lsc_calibrated_path(key, path, cap);
    }
    if (r == 0 && (stat(path, &st) != 0 || !S_ISREG(st.st_mode))) {
        r = LSC_ENODEV;
    }
    return r;
}

int lsc_device_calibrate(lsc_device *d, lsc_calib_step step, const char *text, size_t len,
                         const char *file, char **out, size_t *outlen)
{
    char why[LSC_ARM_MESSAGE_MAX], stamp[LSC_CALIB_STAMP_MAX + 1], when[32];
    uint8_t ids[LSC_ARM_CHAIN_MAX];
    lsc_servo at[LSC_ARM_CHAIN_MAX];
    lsc_arm *arm = NULL;
    if (out != NULL) {
        *out = NULL;
    }
    if (d == NULL || out == NULL || outlen == NULL || (text == NULL && len > 0)) {
        return d != NULL ? lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NONE,
                                        "calibrate: a NULL argument")
                         : LSC_EINVAL;
    }
    int r = lsc_arm_parse(text, len, file, &arm, why, sizeof why);
    int n = r == 0 ? lsc_calib_ids(arm, step, ids, sizeof ids, why, sizeof why) : r;
    lsc_arm_free(arm);
    if (n < 0) {
        return lsc_dev_fail(d, n, LSC_DEVICE_CAUSE_NONE, "%s", why);
    }
    r = lsc_device_read(d, ids, (size_t)n, at);
    if (r < 0) {
        return r; /* d says why */
    }
    /* the stamp: when, and from what (printable ASCII only) */
    time_t now = time(NULL);
    struct tm t;
    memset(&t, 0, sizeof t);
    (void)gmtime_r(&now, &t);
    (void)strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", &t);
    size_t k = (size_t)snprintf(stamp, sizeof stamp, "%s, from %.120s", when,
                                file != NULL ? file : "profile");
    for (size_t i = 0; i < k; i++) { /* (k < sizeof stamp: 120 bytes of the name at most) */
        unsigned char b = (unsigned char)stamp[i];
        if (b < 0x20 || b > 0x7e) {
            stamp[i] = '?';
        }
    }
    r = lsc_calib_apply(text, len, file, step, at, (size_t)n, stamp, out, outlen, why,
                        sizeof why);
    return r != 0 ? lsc_dev_fail(d, r, LSC_DEVICE_CAUSE_NONE, "%s", why) : 0;
}

int lsc_calibrated_write(const char *path, const char *text, size_t len, char *why,
                         size_t whylen)
{
    char dir[PATH_MAX];
    lsc_file_error err = {.size = sizeof err};
    if (path == NULL || (text == NULL && len > 0)) {
        return LSC_EINVAL;
    }
    (void)snprintf(dir, sizeof dir, "%s", path);
    for (char *p = strchr(dir + 1, '/'); p != NULL; p = strchr(p + 1, '/')) {
        *p = '\0';
        if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
            int e = errno;
            if (why != NULL && whylen > 0) {
                (void)snprintf(why, whylen, "cannot make the directory %.200s: %s", dir,
                               strerror(e));
            }
            return LSC_EIO;
        }
        *p = '/';
    }
    int r = lsc_file_replace(path, text, len, &err);
    if (r != 0 && why != NULL && whylen > 0) {
        (void)snprintf(why, whylen, "cannot write %.200s: %s", path, err.message);
    }
    return r;
}

#endif
