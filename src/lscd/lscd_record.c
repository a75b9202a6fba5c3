/* lscd's records: which socket serves which port (lsc/lscd.h,
 * lsc_lscd_recorded_socket; the daemon's side: lsc_lscd_record_write). Host only:
 * compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1 /* fchmod, kill, O_NOFOLLOW, O_CLOEXEC */
#define _DARWIN_C_SOURCE 1

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "lscd_proto.h"

/* Room for one record: three keys and two paths. */
#define RECORD_MAX (3u * LSC_LSCD_PATH_MAX + 64u)

int lsc_lscd_record_path(const char *port, char *out, size_t cap)
{
    char name[LSC_LSCD_NAME_MAX], sock[LSC_LSCD_PATH_MAX];
    int r = lsc_lscd_name(port, name, sizeof name);
    if (r < 0) {
        return r;
    }
    /* DIR/NAME.sock, then the suffix in place of ".sock" */
    r = lsc_lscd_socket_path(name, sock, sizeof sock);
    if (r < 0) {
        return r;
    }
    sock[(size_t)r - 5u] = '\0';
    int w = snprintf(out, cap, "%s%s", sock, LSC_LSCD_RECORD_SUFFIX);
    return w < 0 || (size_t)w >= cap ? LSC_ENOSPC : w;
}

/* path made absolute (prefixed with the working directory) into out[cap]. */
static int absolute(const char *path, char *out, size_t cap)
{
    char cwd[LSC_LSCD_PATH_MAX * 4u];
    int w;
    if (path[0] == '/') {
        w = snprintf(out, cap, "%s", path);
    } else if (getcwd(cwd, sizeof cwd) == NULL) {
        return LSC_ENOSPC;
    } else {
        w = snprintf(out, cap, "%s/%s", cwd, path);
    }
    return w < 0 || (size_t)w >= cap ? LSC_ENOSPC : 0;
}

int lsc_lscd_record_write(const char *port, const char *socket_path, char *record, size_t cap)
{
    char text[RECORD_MAX], aport[LSC_LSCD_PATH_MAX * 2u], asock[LSC_LSCD_PATH_MAX];
    char tmp[LSC_LSCD_PATH_MAX + 32u];
    int r = lsc_lscd_record_path(port, record, cap);
    if (r < 0) {
        return r;
    }
    if (strchr(port, '\n') != NULL || strchr(socket_path, '\n') != NULL) {
        return LSC_EINVAL; /* a line each: a path with a newline cannot be told */
    }
    if (absolute(port, aport, sizeof aport) != 0 || absolute(socket_path, asock, sizeof asock) != 0) {
        return LSC_ENOSPC;
    }
    int n = snprintf(text, sizeof text, "pid %ld\nport %s\nsocket %s\n", (long)getpid(), aport,
                     asock);
    int w = snprintf(tmp, sizeof tmp, "%s.%ld.tmp", record, (long)getpid());
    if (n < 0 || (size_t)n >= sizeof text || w < 0 || (size_t)w >= sizeof tmp) {
        return LSC_ENOSPC;
    }
    /* its directory: made if missing (its last component only) */
    char *slash = strrchr(record, '/');
    if (slash != NULL && slash != record) {
        *slash = '\0';
        (void)mkdir(record, 0755);
        *slash = '/';
    }
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
        return errno == EACCES || errno == EPERM || errno == EROFS ? LSC_EACCES : LSC_EIO;
    }
    bool ok = write(fd, text, (size_t)n) == (ssize_t)n && fchmod(fd, 0644) == 0;
    ok = close(fd) == 0 && ok;
    if (!ok || rename(tmp, record) != 0) {
        (void)unlink(tmp);
        return LSC_EIO;
    }
    return 0;
}

/* The record at path, read: *pid, port[cap] and sock[cap]. 0, or LSC_ENODEV
 * (none), LSC_EINVAL (not a record). */
static int read_record(const char *path, long *pid, char *port, char *sock, size_t cap)
{
    char text[RECORD_MAX + 1u];
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) {
        return LSC_ENODEV;
    }
    struct stat st;
    ssize_t n = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) ? read(fd, text, RECORD_MAX) : -1;
    (void)close(fd);
    if (n < 0) {
        return LSC_EINVAL;
    }
    text[n] = '\0';
    int got = 0;
    for (char *line = text, *next; *line != '\0'; line = next) {
        char *nl = strchr(line, '\n');
        if (nl == NULL) {
            return LSC_EINVAL; /* cut short */
        }
        *nl = '\0';
        next = nl + 1;
        char *end;
        if (strncmp(line, "pid ", 4) == 0) {
            errno = 0;
            *pid = strtol(line + 4, &end, 10);
            got |= *end == '\0' && errno == 0 && *pid > 0 ? 1 : 0;
        } else if (strncmp(line, "port /", 6) == 0 && strlen(line + 5) < cap) {
            memcpy(port, line + 5, strlen(line + 5) + 1u);
            got |= 2;
        } else if (strncmp(line, "socket /", 8) == 0 && strlen(line + 7) < cap) {
            memcpy(sock, line + 7, strlen(line + 7) + 1u);
            got |= 4;
        }
    }
    return got == 7 ? 0 : LSC_EINVAL;
}

/* Whether a and b name the same file (the same device node, through links). */
static bool same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

int lsc_lscd_recorded_socket(const char *port, char *out, size_t cap, long *pid)
{
    char path[LSC_LSCD_PATH_MAX + 16u], rport[LSC_LSCD_PATH_MAX * 2u], sock[LSC_LSCD_PATH_MAX * 2u];
    long who = 0;
    if (port == NULL || out == NULL) {
        return LSC_EINVAL;
    }
    int r = lsc_lscd_record_path(port, path, sizeof path);
    if (r >= 0) {
        r = read_record(path, &who, rport, sock, sizeof sock);
    }
    if (r < 0) {
        return r;
    }
    if (!same_file(port, rport) || (kill((pid_t)who, 0) != 0 && errno != EPERM)) {
        return LSC_ENODEV; /* another port of the same name, or its lscd is gone */
    }
    if (pid != NULL) {
        *pid = who;
    }
    size_t n = strlen(sock);
    if (n + 1u > cap) {
        return LSC_ENOSPC;
    }
    memcpy(out, sock, n + 1u);
    return (int)n;
}

#endif
