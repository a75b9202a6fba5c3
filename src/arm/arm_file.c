/* Arm profiles on disk (include/lsc/arm.h): a profile's file read whole and
 * parsed (lsc_arm_load), a profile's name looked up where profiles are
 * installed or configured (lsc_arm_path, lsc_arm_open). Host only: compiles
 * to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _POSIX_C_SOURCE 200809L /* O_CLOEXEC */

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "arm_internal.h"

/* ---- a profile's file ------------------------------------------------------- */

static const char *kind_of(mode_t mode)
{
    return S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO" : "a device";
}

int lsc_arm_load(const char *path, lsc_arm **out, char *why, size_t whylen)
{
    static const char cannot[] = "cannot read the arm profile ";
    struct stat st;
    if (out != NULL) {
        *out = NULL;
    }
    if (path == NULL || out == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_load: no path or no out");
    }
    /* O_NONBLOCK: opening a FIFO must not wait for a writer */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        return lsc_armi_file_fail(LSC_EIO, why, whylen, cannot, path, ": %s", strerror(errno));
    }
    memset(&st, 0, sizeof st);
    (void)fstat(fd, &st); /* cannot fail on an open fd; if it did: mode 0, refused */
    if (!S_ISREG(st.st_mode)) {
        (void)close(fd);
        return lsc_armi_file_fail(LSC_EINVAL, why, whylen, cannot, path,
                                  ": it is %s (an arm profile is a regular file)",
                                  kind_of(st.st_mode));
    }
    char *text = malloc(LSC_ARM_FILE_MAX + 1u);
    size_t n = 0;
    int err = 0;
    while (text != NULL && n <= LSC_ARM_FILE_MAX) {
        ssize_t r = read(fd, text + n, LSC_ARM_FILE_MAX + 1u - n);
        if (r > 0) {
            n += (size_t)r;
        } else if (r == 0) {
            break;
        } else if (errno != EINTR) {
            err = errno;
            break;
        }
    }
    (void)close(fd);
    int r;
    if (text == NULL) {
        r = lsc_armi_oom(why, whylen);
    } else if (err != 0) {
        r = lsc_armi_file_fail(LSC_EIO, why, whylen, cannot, path, ": %s", strerror(err));
    } else if (n > LSC_ARM_FILE_MAX) {
        r = lsc_armi_file_fail(LSC_EINVAL, why, whylen, "", path,
                               ": longer than %u bytes: not an arm profile", LSC_ARM_FILE_MAX);
    } else {
        r = lsc_arm_parse(text, n, path, out, why, whylen);
    }
    free(text);
    return r;
}

/* ---- profiles by name ------------------------------------------------------- */

/* The installed profiles (PREFIX/share/lsc/arms: CMake defines it from the
 * install prefix; this is its default prefix's). */
#ifndef LSC_ARMS_INSTALL_DIR
#define LSC_ARMS_INSTALL_DIR "/usr/local/share/lsc/arms"
#endif
#define PATH_CAP 4096u /* bytes of a profile's path looked for, with the NUL */
#define LOOKS 2u       /* places a name is looked for */

/* A variable's value when it is set and not empty, else NULL. */
static const char *env_value(const char *name)
{
    const char *v = getenv(name);
    return v != NULL && *v != '\0' ? v : NULL;
}

/* Whether name is a file's path rather than a profile's name: a '/' in it, or
 * the ending ".conf". */
static bool is_path(const char *name)
{
    static const char conf[] = ".conf";
    size_t n = strlen(name);
    return strchr(name, '/') != NULL ||
           (n >= sizeof conf - 1u && strcmp(name + n - (sizeof conf - 1u), conf) == 0);
}

/* DIR SUB/NAME.conf into out[PATH_CAP]: false when it does not fit. */
static bool join(char *out, const char *dir, const char *sub, const char *name)
{
    int n = snprintf(out, PATH_CAP, "%s%s/%s.conf", dir, sub, name);
    return (size_t)n < PATH_CAP; /* (negative: an error, as large) */
}

int lsc_arm_path(const char *name, char *out, size_t cap, char *why, size_t whylen)
{
    char path[LOOKS][PATH_CAP];
    size_t n = 0;
    bool fits = true;
    if (name == NULL || out == NULL || cap == 0) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_path: no name or no room");
    }
    if (*name == '\0') {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "no arm profile given: a profile's name (xarm) or a file's path");
    }
    if (is_path(name)) {
        fits = strlen(name) < PATH_CAP;
        (void)snprintf(path[n++], PATH_CAP, "%s", name);
    } else {
        /* $XDG_CONFIG_HOME (an absolute path, else unset: the XDG rule), else ~/.config */
        const char *config = env_value("XDG_CONFIG_HOME");
        const char *home = env_value("HOME");
        if (config != NULL && config[0] == '/') {
            fits = join(path[n++], config, "/lsc/arms", name);
        } else if (home != NULL) {
            fits = join(path[n++], home, "/.config/lsc/arms", name);
        }
        const char *installed = env_value("LSC_ARMS_DIR");
        fits = fits &&
               join(path[n++], installed != NULL ? installed : LSC_ARMS_INSTALL_DIR, "", name);
    }
    if (!fits) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen,
                             "the arm profile's name is too long (%zu bytes): a name such as "
                             "xarm, or a file's path",
                             strlen(name));
    }
    for (size_t i = 0; i < n; i++) {
        struct stat st;
        /* there (or there but not for us: lsc_arm_load says why), or a path as given */
        if (is_path(name) || stat(path[i], &st) == 0 || (errno != ENOENT && errno != ENOTDIR)) {
            if (strlen(path[i]) >= cap) {
                return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_path: no room for the path");
            }
            memcpy(out, path[i], strlen(path[i]) + 1u);
            return LSC_OK;
        }
    }
    lsc_armi_msg m = lsc_armi_msg_start(why, whylen);
    lsc_armi_msg_str(&m, "no arm profile named ");
    lsc_armi_msg_str(&m, name);
    lsc_armi_msg_str(&m, ": looked for ");
    for (size_t i = 0; i < n; i++) {
        lsc_armi_msg_str(&m, i > 0 ? ", " : "");
        lsc_armi_msg_str(&m, path[i]);
    }
    lsc_armi_msg_str(&m, " (a file in this directory: ./");
    lsc_armi_msg_str(&m, name);
    lsc_armi_msg_str(&m, ")");
    return LSC_EIO;
}

int lsc_arm_open(const char *name, lsc_arm **out, char *why, size_t whylen)
{
    char path[PATH_CAP];
    if (out != NULL) {
        *out = NULL;
    }
    if (name == NULL || out == NULL) {
        return lsc_armi_fail(LSC_EINVAL, why, whylen, "lsc_arm_open: no name or no out");
    }
    int r = lsc_arm_path(name, path, sizeof path, why, whylen);
    return r != 0 ? r : lsc_arm_load(path, out, why, whylen);
}

#endif
