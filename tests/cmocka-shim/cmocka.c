/* The cmocka-compatible runner of cmocka.h (s390x cross build only). */
#include "cmocka.h"

#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

enum { SHIM_PASS, SHIM_FAIL, SHIM_SKIP };

static jmp_buf shim_env;

#ifdef __GNUC__
__attribute__((noreturn))
#endif
static void stop(const char *file, int line, int how)
{
    (void)fprintf(stderr, "%s:%d: %s\n", file, line, how == SHIM_SKIP ? "skipped" : "failure");
    longjmp(shim_env, how);
}

void print_message(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vprintf(fmt, ap);
    va_end(ap);
}

void print_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vfprintf(stderr, fmt, ap);
    va_end(ap);
}

void lsc_shim_true(int ok, const char *expr, const char *file, int line)
{
    if (!ok) {
        (void)fprintf(stderr, "%s is not true\n", expr);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_int(uintmax_t a, uintmax_t b, int equal, const char *file, int line)
{
    if ((a == b) != (equal != 0)) {
        (void)fprintf(stderr, "%#" PRIxMAX " %s %#" PRIxMAX "\n", a, equal ? "!=" : "==", b);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_range(uintmax_t v, uintmax_t lo, uintmax_t hi, int inside, const char *file, int line)
{
    if ((v >= lo && v <= hi) != (inside != 0)) {
        (void)fprintf(stderr, "%#" PRIxMAX " is %s range %#" PRIxMAX "-%#" PRIxMAX "\n", v,
                      inside ? "not within" : "within", lo, hi);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_ptr(const void *a, const void *b, int equal, const char *file, int line)
{
    if ((a == b) != (equal != 0)) {
        (void)fprintf(stderr, "%p %s %p\n", a, equal ? "!=" : "==", b);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_memory(const void *a, const void *b, size_t n, int equal, const char *file, int line)
{
    if ((memcmp(a, b, n) == 0) != (equal != 0)) {
        (void)fprintf(stderr, "%zu bytes of %p and %p %s\n", n, a, b,
                      equal ? "differ" : "are the same");
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_string(const char *a, const char *b, int equal, const char *file, int line)
{
    if ((strcmp(a, b) == 0) != (equal != 0)) {
        (void)fprintf(stderr, "\"%s\" %s \"%s\"\n", a, equal ? "!=" : "==", b);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_return_code(intmax_t rc, const char *expr, const char *file, int line)
{
    if (rc < 0) {
        (void)fprintf(stderr, "%s < 0 (%" PRIdMAX ")\n", expr, rc);
        stop(file, line, SHIM_FAIL);
    }
}

void lsc_shim_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vfprintf(stderr, fmt, ap);
    va_end(ap);
    (void)fputc('\n', stderr);
    stop(file, line, SHIM_FAIL);
}

void lsc_shim_skip(const char *file, int line)
{
    stop(file, line, SHIM_SKIP);
}

/* Runs f(state) unless it longjmps: returns SHIM_PASS, SHIM_FAIL or SHIM_SKIP. */
static int guarded_test(CMUnitTestFunction f, void **state)
{
    int how = setjmp(shim_env);
    if (how == 0) {
        f(state);
        return SHIM_PASS;
    }
    return how;
}

static int guarded_fixture(CMFixtureFunction f, void **state)
{
    int how = setjmp(shim_env);
    if (how == 0) {
        return f(state) == 0 ? SHIM_PASS : SHIM_FAIL;
    }
    return how;
}

int lsc_shim_run_group(const char *group_name, const struct CMUnitTest *tests, size_t n,
                            CMFixtureFunction group_setup, CMFixtureFunction group_teardown)
{
    void *group_state = NULL;
    size_t failed = 0, skipped = 0;
    (void)printf("[==========] Running %zu test(s) of %s (cmocka shim).\n", n, group_name);
    if (group_setup != NULL && guarded_fixture(group_setup, &group_state) != SHIM_PASS) {
        (void)printf("[  ERROR   ] group setup of %s failed\n", group_name);
        return (int)n;
    }
    for (size_t i = 0; i < n; i++) {
        const struct CMUnitTest *t = &tests[i];
        void *state = t->initial_state != NULL ? t->initial_state : group_state;
        (void)printf("[ RUN      ] %s\n", t->name);
        int how = SHIM_PASS;
        if (t->setup_func != NULL) {
            how = guarded_fixture(t->setup_func, &state);
        }
        if (how == SHIM_PASS) {
            how = guarded_test(t->test_func, &state);
        }
        if (t->teardown_func != NULL && guarded_fixture(t->teardown_func, &state) == SHIM_FAIL) {
            how = SHIM_FAIL;
        }
        (void)printf("%s %s\n",
                     how == SHIM_PASS ? "[       OK ]" : how == SHIM_SKIP ? "[  SKIPPED ]" : "[  FAILED  ]",
                     t->name);
        failed += how == SHIM_FAIL;
        skipped += how == SHIM_SKIP;
    }
    if (group_teardown != NULL && guarded_fixture(group_teardown, &group_state) != SHIM_PASS) {
        (void)printf("[  ERROR   ] group teardown of %s failed\n", group_name);
        failed++;
    }
    (void)printf("[==========] %zu test(s) run: %zu passed, %zu failed, %zu skipped.\n", n,
                 n - failed - skipped, failed, skipped);
    (void)fflush(stdout);
    return (int)failed;
}
