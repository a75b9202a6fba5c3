/* A small cmocka-compatible test runner, used ONLY where the real cmocka is
 * not available: the s390x (big-endian) cross build run under qemu-user
 * (cmake/s390x-linux-gnu.cmake sets LSC_CMOCKA_SHIM). Debian ships no
 * cross-built libcmocka and the CI machine has no network to build it.
 *
 * It implements the part of the cmocka 1.1 API the project's tests use:
 * cmocka_unit_test[_setup|_teardown|_setup_teardown|_prestate],
 * cmocka_run_group_tests[_name], assert_true/false, assert_int_[not_]equal,
 * assert_[not_]in_range, assert_ptr_[not_]equal, assert_[non_]null,
 * assert_memory_[not_]equal, assert_string_[not_]equal, assert_return_code,
 * fail, fail_msg, skip, print_message, print_error. Mocking (will_return,
 * mock, expect_*) is not implemented: a test that uses it does not compile
 * here, rather than pass by accident.
 *
 * Like cmocka, a failed assertion ends the test (longjmp back to the runner)
 * and the group's result is the number of failed tests. */
#ifndef LSC_CMOCKA_SHIM_H
#define LSC_CMOCKA_SHIM_H

#include <stddef.h>
#include <stdint.h>

typedef void (*CMUnitTestFunction)(void **state);
typedef int (*CMFixtureFunction)(void **state);

struct CMUnitTest {
    const char *name;
    CMUnitTestFunction test_func;
    CMFixtureFunction setup_func;
    CMFixtureFunction teardown_func;
    void *initial_state;
};

#define cmocka_unit_test(f) {#f, f, NULL, NULL, NULL}
#define cmocka_unit_test_setup(f, setup) {#f, f, setup, NULL, NULL}
#define cmocka_unit_test_teardown(f, teardown) {#f, f, NULL, teardown, NULL}
#define cmocka_unit_test_setup_teardown(f, setup, teardown) {#f, f, setup, teardown, NULL}
#define cmocka_unit_test_prestate(f, state) {#f, f, NULL, NULL, state}

int lsc_shim_run_group(const char *group_name, const struct CMUnitTest *tests, size_t n,
                            CMFixtureFunction group_setup, CMFixtureFunction group_teardown);
#define cmocka_run_group_tests(group, setup, teardown)                                       \
    lsc_shim_run_group(#group, group, sizeof(group) / sizeof((group)[0]), setup, teardown)
#define cmocka_run_group_tests_name(name, group, setup, teardown)                            \
    lsc_shim_run_group(name, group, sizeof(group) / sizeof((group)[0]), setup, teardown)

/* Each check calls one of these with the values and where it is. */
void lsc_shim_true(int ok, const char *expr, const char *file, int line);
void lsc_shim_int(uintmax_t a, uintmax_t b, int equal, const char *file, int line);
void lsc_shim_range(uintmax_t v, uintmax_t lo, uintmax_t hi, int inside, const char *file,
                 int line);
void lsc_shim_ptr(const void *a, const void *b, int equal, const char *file, int line);
void lsc_shim_memory(const void *a, const void *b, size_t n, int equal, const char *file, int line);
void lsc_shim_string(const char *a, const char *b, int equal, const char *file, int line);
void lsc_shim_return_code(intmax_t rc, const char *expr, const char *file, int line);
void lsc_shim_fail(const char *file, int line, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4), noreturn))
#endif
    ;
void lsc_shim_skip(const char *file, int line)
#ifdef __GNUC__
    __attribute__((noreturn))
#endif
    ;
void print_message(const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 1, 2)))
#endif
    ;
void print_error(const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 1, 2)))
#endif
    ;

#define assert_true(c) lsc_shim_true(!!(c), #c, __FILE__, __LINE__)
#define assert_false(c) lsc_shim_true(!(c), "!(" #c ")", __FILE__, __LINE__)
#define assert_int_equal(a, b) lsc_shim_int((uintmax_t)(a), (uintmax_t)(b), 1, __FILE__, __LINE__)
#define assert_int_not_equal(a, b)                                                            \
    lsc_shim_int((uintmax_t)(a), (uintmax_t)(b), 0, __FILE__, __LINE__)
#define assert_uint_equal(a, b) assert_int_equal(a, b)
#define assert_uint_not_equal(a, b) assert_int_not_equal(a, b)
#define assert_in_range(v, lo, hi)                                                            \
    lsc_shim_range((uintmax_t)(v), (uintmax_t)(lo), (uintmax_t)(hi), 1, __FILE__, __LINE__)
#define assert_not_in_range(v, lo, hi)                                                        \
    lsc_shim_range((uintmax_t)(v), (uintmax_t)(lo), (uintmax_t)(hi), 0, __FILE__, __LINE__)
#define assert_ptr_equal(a, b) lsc_shim_ptr((const void *)(a), (const void *)(b), 1, __FILE__, __LINE__)
#define assert_ptr_not_equal(a, b)                                                            \
    lsc_shim_ptr((const void *)(a), (const void *)(b), 0, __FILE__, __LINE__)
#define assert_null(p) lsc_shim_ptr((const void *)(p), NULL, 1, __FILE__, __LINE__)
#define assert_non_null(p) lsc_shim_ptr((const void *)(p), NULL, 0, __FILE__, __LINE__)
#define assert_memory_equal(a, b, n) lsc_shim_memory(a, b, n, 1, __FILE__, __LINE__)
#define assert_memory_not_equal(a, b, n) lsc_shim_memory(a, b, n, 0, __FILE__, __LINE__)
#define assert_string_equal(a, b) lsc_shim_string(a, b, 1, __FILE__, __LINE__)
#define assert_string_not_equal(a, b) lsc_shim_string(a, b, 0, __FILE__, __LINE__)
#define assert_return_code(rc, error) lsc_shim_return_code((intmax_t)(rc), #rc, __FILE__, __LINE__)
#define fail() lsc_shim_fail(__FILE__, __LINE__, "%s", "fail()")
#define fail_msg(...) lsc_shim_fail(__FILE__, __LINE__, __VA_ARGS__)
#define skip() lsc_shim_skip(__FILE__, __LINE__)

#endif
