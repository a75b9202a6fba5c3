/* The main() that runs a libFuzzer-style harness without libFuzzer.
 *
 *   fuzz_X [-n N] [-s SEED] PATH...   runs every file (or every file of every
 *                                     directory) given, then N deterministic
 *                                     mutations of each (ctest uses this)
 *   fuzz_X < FILE                     runs one input read from stdin (replaying
 *                                     a crash, or under AFL++)
 *
 * A failed check inside the harness aborts, so any non-zero exit is a finding.
 * The mutations come from a fixed-seed xorshift generator: the same command
 * runs the same inputs on every machine. When an input crashes, it is written
 * to fuzz-crash-NAME in the current directory (replay it from stdin; keep it
 * in regress/NAME once fixed). */
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz.h"

#define MAX_INPUT 4096u
#define MAX_SEEDS 8192u

typedef struct seed {
    uint8_t *data;
    size_t size;
} seed;

static seed seeds[MAX_SEEDS];
static size_t nseeds;
static uint64_t rng_state = 0x9E3779B97F4A7C15u;

static uint32_t rnd(uint32_t below)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return below ? (uint32_t)(rng_state % below) : 0;
}

/* The input being run, for the crash handler. */
static const uint8_t *volatile current;
static volatile size_t current_size;
static char crash_path[256];

/* write(2) from a signal handler; nothing better to do if it fails. */
static void put(int fd, const void *p, size_t n)
{
    ssize_t w = write(fd, p, n);
    (void)w;
}

static void on_crash(int sig)
{
    int fd = open(crash_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        put(fd, current, current_size);
        (void)close(fd);
        static const char msg[] = "fuzz driver: input written to ";
        put(STDERR_FILENO, msg, sizeof msg - 1u);
        put(STDERR_FILENO, crash_path, strlen(crash_path));
        put(STDERR_FILENO, "\n", 1);
    }
    (void)signal(sig, SIG_DFL);
    (void)raise(sig);
}


static void die(const char *what, const char *path)
{
    (void)fprintf(stderr, "fuzz driver: %s: %s\n", what, path);
    exit(2);
}

/* Runs the harness on a copy of exactly size bytes (so that ASan sees any
 * read past the input), remembered for the crash handler. */
static void run(const uint8_t *data, size_t size)
{
    uint8_t *exact = malloc(size ? size : 1);
    if (exact == NULL) {
        die("out of memory", "input");
    }
    memcpy(exact, data, size);
    current = exact;
    current_size = size;
    LLVMFuzzerTestOneInput(exact, size);
    free(exact);
}

static size_t read_all(FILE *f, uint8_t *buf, size_t cap)
{
    size_t n = 0;
    size_t got;
    while (n < cap && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
    }
    return n;
}

static void add_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        die("cannot open", path);
    }
    if (nseeds == MAX_SEEDS) {
        die("too many inputs", path);
    }
    uint8_t *buf = malloc(MAX_INPUT);
    if (buf == NULL) {
        die("out of memory", path);
    }
    seeds[nseeds].data = buf;
    seeds[nseeds].size = read_all(f, buf, MAX_INPUT);
    nseeds++;
    (void)fclose(f);
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Adds path, or the regular files of the directory path in name order. */
static void add_path(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        die("cannot stat", path);
    }
    if (!S_ISDIR(st.st_mode)) {
        add_file(path);
        return;
    }
    DIR *d = opendir(path);
    if (d == NULL) {
        die("cannot open directory", path);
    }
    static char *names[MAX_SEEDS];
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' || strcmp(e->d_name, "README") == 0) {
            continue;
        }
        if (n == MAX_SEEDS) {
            die("too many inputs in", path);
        }
        size_t len = strlen(path) + strlen(e->d_name) + 2;
        names[n] = malloc(len);
        if (names[n] == NULL) {
            die("out of memory", path);
        }
        (void)snprintf(names[n], len, "%s/%s", path, e->d_name);
        n++;
    }
    (void)closedir(d);
    qsort(names, n, sizeof names[0], by_name);
    for (size_t i = 0; i < n; i++) {
        add_file(names[i]);
        free(names[i]);
    }
}

/* One random edit of buf[0..*size): flip, set, insert, delete, copy a chunk,
 * or splice in part of another seed. */
static void mutate(uint8_t *buf, size_t *size)
{
    static const uint8_t interesting[] = {0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x55, 0x7F,
                                          0x80, 0xFE, 0xFF, 0x52, 0x53, 0x54, 0x56};
    size_t n = *size;
    uint32_t op = rnd(7);
    if (n == 0) {
        op = 2;
    }
    switch (op) {
    case 0: buf[rnd((uint32_t)n)] ^= (uint8_t)(1u << rnd(8)); break;
    case 1: buf[rnd((uint32_t)n)] = interesting[rnd(sizeof interesting)]; break;
    case 2:
        if (n < MAX_INPUT) {
            size_t at = rnd((uint32_t)n + 1);
            memmove(buf + at + 1, buf + at, n - at);
            buf[at] = (uint8_t)rnd(256);
            n++;
        }
        break;
    case 3: {
        size_t at = rnd((uint32_t)n);
        size_t len = 1 + rnd((uint32_t)(n - at));
        memmove(buf + at, buf + at + len, n - at - len);
        n -= len;
        break;
    }
    case 4: buf[rnd((uint32_t)n)] = (uint8_t)rnd(256); break;
    case 5: { /* duplicate a chunk in place */
        size_t at = rnd((uint32_t)n);
        size_t len = 1 + rnd((uint32_t)(n - at));
        if (n + len <= MAX_INPUT) {
            memmove(buf + at + len, buf + at, n - at);
            n += len;
        }
        break;
    }
    default: { /* splice: append part of another seed */
        const seed *s = &seeds[rnd((uint32_t)nseeds)];
        if (s->size > 0) {
            size_t from = rnd((uint32_t)s->size);
            size_t len = 1 + rnd((uint32_t)(s->size - from));
            if (n + len > MAX_INPUT) {
                len = MAX_INPUT - n;
            }
            memcpy(buf + n, s->data + from, len);
            n += len;
        }
        break;
    }
    }
    *size = n;
}

int main(int argc, char **argv)
{
    const char *base = strrchr(argv[0], '/');
    (void)snprintf(crash_path, sizeof crash_path, "fuzz-crash-%s", base ? base + 1 : argv[0]);
    (void)signal(SIGABRT, on_crash);
    (void)signal(SIGSEGV, on_crash);
    unsigned long mutations = 0;
    int i = 1;
    for (; i < argc && argv[i][0] == '-' && argv[i][1] != '\0'; i += 2) {
        if (i + 1 >= argc) {
            die("missing value for", argv[i]);
        }
        char *end;
        unsigned long v = strtoul(argv[i + 1], &end, 0);
        if (*end != '\0') {
            die("not a number", argv[i + 1]);
        }
        if (strcmp(argv[i], "-n") == 0) {
            mutations = v;
        } else if (strcmp(argv[i], "-s") == 0) {
            rng_state = v ? v : 1;
        } else {
            die("unknown option", argv[i]);
        }
    }
    if (i == argc || strcmp(argv[i], "-") == 0) {
        static uint8_t in[1u << 16];
        run(in, read_all(stdin, in, sizeof in));
        return 0;
    }
    for (; i < argc; i++) {
        add_path(argv[i]);
    }
    if (nseeds == 0) {
        die("no inputs", "(empty corpus)");
    }
    uint8_t *work = malloc(MAX_INPUT);
    if (work == NULL) {
        die("out of memory", "work buffer");
    }
    unsigned long runs = 0;
    for (size_t s = 0; s < nseeds; s++) {
        run(seeds[s].data, seeds[s].size);
        runs++;
    }
    for (unsigned long m = 0; m < mutations; m++) {
        const seed *s = &seeds[m % nseeds];
        size_t size = s->size;
        memcpy(work, s->data, size);
        for (uint32_t k = 1 + rnd(4); k > 0; k--) {
            mutate(work, &size);
        }
        run(work, size);
        runs++;
    }
    (void)printf("%s: %zu inputs, %lu runs, no finding\n", argv[0], nseeds, runs);
    free(work);
    for (size_t s = 0; s < nseeds; s++) {
        free(seeds[s].data);
    }
    return 0;
}
