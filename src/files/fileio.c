/* Files on the host (files_internal.h): regular files read whole, files
 * replaced atomically. Below the formats; it calls only action.c's messages. */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#define _DEFAULT_SOURCE 1 /* fchown, fchmod, O_NOFOLLOW, O_DIRECTORY, O_CLOEXEC */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h> /* rename */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "files_internal.h"

#define TMP_BASE_MAX 200u /* bytes of the target's name kept in the temporary one */
#define TMP_ATTEMPTS 100  /* names tried before giving up */

/* What a file that is not a regular one is, for a message. */
static const char *kind(mode_t m)
{
    if (S_ISDIR(m)) {
        return "a directory";
    }
    if (S_ISFIFO(m)) {
        return "a FIFO";
    }
    if (S_ISCHR(m)) {
        return "a character device";
    }
    if (S_ISBLK(m)) {
        return "a block device";
    }
    if (S_ISSOCK(m)) {
        return "a socket";
    }
    if (S_ISLNK(m)) {
        return "a symbolic link";
    }
    return "not a file";
}

static int io_fail(lsc_file_error *err, const char *what, int e)
{
    return lsc_files_fail_code(err, LSC_EIO, "%s%s", what, strerror(e));
}

int lsc_files_check_regular(const char *path, size_t max, lsc_file_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        return io_fail(err, "", errno);
    }
    if (!S_ISREG(st.st_mode)) {
        return lsc_files_fail_code(err, LSC_EIO, "not a regular file (%s)", kind(st.st_mode));
    }
    if ((uintmax_t)st.st_size > max) {
        return lsc_files_fail(err, 0, "larger than %zu bytes", max);
    }
    return 0;
}

int lsc_file_load(const char *path, size_t max, uint8_t **data, size_t *len,
                  lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || data == NULL || len == NULL) {
        return LSC_EINVAL;
    }
    *data = NULL;
    *len = 0;
    lsc_files_err_clear(err);
    if (max > SIZE_MAX / 2u) {
        max = SIZE_MAX / 2u;
    }
    /* stat first: a device is never opened (opening a tty can reset a board) */
    int r = lsc_files_check_regular(path, max, err);
    if (r != 0) {
        return r;
    }
    struct stat st;
    /* O_NONBLOCK: should it have become a FIFO since, the open does not wait */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        return io_fail(err, "", errno);
    }
    if (fstat(fd, &st) != 0) {
        int e = errno;
        (void)close(fd);
        return io_fail(err, "", e);
    }
    if (!S_ISREG(st.st_mode)) {
        (void)close(fd);
        return lsc_files_fail_code(err, LSC_EIO, "not a regular file (%s)", kind(st.st_mode));
    }
    /* reading max + 1 bytes proves the file too large, whatever it said */
    size_t limit = max + 1u;
    size_t cap = (size_t)st.st_size + 1u;
    cap = cap < 4096u ? 4096u : cap;
    cap = cap > limit ? limit : cap;
    size_t n = 0;
    uint8_t *buf = malloc(cap + 1u);
    if (buf == NULL) {
        (void)close(fd);
        return lsc_files_oom(err);
    }
    while (r == 0) {
        if (n == cap) {
            if (cap == limit) {
                r = lsc_files_fail(err, 0, "larger than %zu bytes", max);
                break;
            }
            cap = cap > limit / 2u ? limit : cap * 2u;
            uint8_t *bigger = realloc(buf, cap + 1u);
            if (bigger == NULL) {
                r = lsc_files_oom(err);
                break;
            }
            buf = bigger;
        }
        ssize_t got = read(fd, buf + n, cap - n);
        if (got < 0 && errno == EINTR) {
            continue;
        }
        if (got < 0) {
            r = io_fail(err, "read error: ", errno);
        } else if (got == 0) {
            break;
        } else {
            n += (size_t)got;
        }
    }
    (void)close(fd);
    if (r != 0) {
        free(buf);
        return r;
    }
    buf[n] = 0;
    *data = buf;
    *len = n;
    return 0;
}

/* lstat's verdict on a target: 0 with *exists (and *st), or the refusal. */
static int check_target(const char *path, struct stat *st, bool *exists, lsc_file_error *err)
{
    *exists = false;
    if (lstat(path, st) != 0) {
        return errno == ENOENT ? 0 : io_fail(err, "", errno);
    }
    if (S_ISLNK(st->st_mode)) {
        return lsc_files_fail(err, 0, "a symbolic link: lsc replaces files, not links (name "
                                      "the file it points to)");
    }
    if (!S_ISREG(st->st_mode)) {
        return lsc_files_fail(err, 0, "not a regular file (%s): lsc writes regular files only",
                              kind(st->st_mode));
    }
    if (access(path, W_OK) != 0) {
        return io_fail(err, "", errno);
    }
    *exists = true;
    return 0;
}

int lsc_files_replaceable(const char *path, lsc_file_error *err)
{
    struct stat st;
    bool exists;
    return check_target(path, &st, &exists, err);
}

/* The directory part of path ("." for none) in a new string, or NULL. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash == NULL ? 0 : slash == path ? 1u : (size_t)(slash - path);
    char *d = malloc(n + 2u);
    if (d != NULL) {
        if (n == 0) {
            memcpy(d, ".", 2);
        } else {
            memcpy(d, path, n);
            d[n] = '\0';
        }
    }
    return d;
}

int lsc_files_sync_dir(const char *path, lsc_file_error *err)
{
    char *d = dir_of(path);
    if (d == NULL) {
        return lsc_files_oom(err);
    }
    int fd = open(d, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(d);
    int e = 0;
    if (fd < 0) {
        e = errno;
    } else {
        if (fsync(fd) != 0 && errno != EINVAL) { /* EINVAL: a file system without it */
            e = errno;
        }
        (void)close(fd);
    }
    return e == 0 ? 0 : io_fail(err, "cannot flush the directory: ", e);
}

/* Creates ".BASE.XXXXXX.tmp" beside path (exclusively, `mode` less the umask)
 * into tmp[size]; the descriptor or -1 (errno). */
static int create_temporary(const char *path, char *tmp, size_t size, mode_t mode)
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    const char *slash = strrchr(path, '/');
    int dirlen = slash != NULL ? (int)(slash - path) + 1 : 0;
    const char *base = path + dirlen;
    size_t blen = strlen(base);
    blen = blen > TMP_BASE_MAX ? TMP_BASE_MAX : blen;
    struct timespec now;
    if (clock_gettime(CLOCK_REALTIME, &now) != 0) {
        now.tv_nsec = 0;
    }
    uint32_t x = (uint32_t)now.tv_nsec ^ ((uint32_t)getpid() << 16) ^
                 (uint32_t)(uintptr_t)&now;
    for (int attempt = 0; attempt < TMP_ATTEMPTS; attempt++) {
        char rnd[7];
        for (size_t i = 0; i < 6; i++) {
            x = x * 1664525u + 1013904223u; /* any spread will do: O_EXCL decides */
            rnd[i] = letters[(x >> 16) % (sizeof letters - 1u)];
        }
        rnd[6] = '\0';
        (void)snprintf(tmp, size, "%.*s.%.*s.%s.tmp", dirlen, path, (int)blen, base, rnd);
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
        if (fd >= 0 || errno != EEXIST) {
            return fd;
        }
    }
    return -1; /* errno EEXIST */
}

int lsc_files_replace(const char *path, const uint8_t *bytes, size_t len, lsc_file_error *err)
{
    struct stat st;
    bool exists;
    int r = check_target(path, &st, &exists, err);
    if (r != 0) {
        return r;
    }
    size_t size = strlen(path) + TMP_BASE_MAX + 20u;
    char *tmp = malloc(size);
    if (tmp == NULL) {
        return lsc_files_oom(err);
    }
    int fd = create_temporary(path, tmp, size, exists ? (mode_t)0600 : (mode_t)0666);
    if (fd < 0) {
        r = io_fail(err, "", errno);
        free(tmp);
        return r;
    }
    if (exists) {
        /* the owner and group when this process may set them (root; a
         * group it is in), then the permissions (chown clears set-id bits) */
        (void)fchown(fd, st.st_uid, st.st_gid);
        if (fchmod(fd, st.st_mode & 07777) != 0) {
            r = io_fail(err, "cannot keep the file's permissions: ", errno);
        }
    }
    for (size_t done = 0; r == 0 && done < len;) {
        ssize_t n = write(fd, bytes + done, len - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            r = io_fail(err, "write error: ", n < 0 ? errno : ENOSPC);
        } else {
            done += (size_t)n;
        }
    }
    if (r == 0 && fsync(fd) != 0) {
        r = io_fail(err, "write error: ", errno);
    }
    if (close(fd) != 0 && r == 0) {
        r = io_fail(err, "write error: ", errno);
    }
    if (r == 0 && rename(tmp, path) != 0) {
        r = io_fail(err, "cannot replace the file: ", errno);
    }
    if (r != 0) {
        (void)unlink(tmp);
    }
    free(tmp);
    return r != 0 ? r : lsc_files_sync_dir(path, err);
}
int lsc_file_replace(const char *path, const void *bytes, size_t len, lsc_file_error *err)
{
    if (lsc_files_err_refused(err)) {
        return LSC_EINVAL;
    }
    if (path == NULL || (bytes == NULL && len > 0)) {
        return LSC_EINVAL;
    }
    return lsc_files_replace(path, (const uint8_t *)bytes, len, err);
}
#endif
