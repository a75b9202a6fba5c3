/* The cmocka shim must fail a test whenever cmocka would: each test of
 * `failing` breaks one assertion and must be counted failed; each test of
 * `passing` must pass. Exit status 0 only if the runner counted exactly so. */
#include <stdint.h>
#include <stdio.h>

#include "cmocka.h"

static int setup_fails(void **state)
{
    (void)state;
    return -1;
}

static void never_run(void **state)
{
    (void)state;
    fail_msg("a test whose setup failed must not run");
}

static void bad_true(void **state) { (void)state; assert_true(0); }
static void bad_false(void **state) { (void)state; assert_false(1); }
static void bad_int(void **state) { (void)state; assert_int_equal(-1, 1); }
static void bad_int_not(void **state) { (void)state; assert_int_not_equal(7, 7); }
static void bad_range(void **state) { (void)state; assert_in_range(11, 1, 10); }
static void bad_ptr(void **state) { (void)state; assert_null(state); }
static void bad_non_null(void **state) { (void)state; assert_non_null(NULL); }
static void bad_memory(void **state)
{
    (void)state;
    assert_memory_equal("abc", "abd", 3);
}
static void bad_string(void **state) { (void)state; assert_string_equal("x", "y"); }
static void bad_string_not(void **state) { (void)state; assert_string_not_equal("x", "x"); }
static void bad_return_code(void **state) { (void)state; assert_return_code(-5, 0); }
static void bad_fail(void **state) { (void)state; fail(); }

static void good(void **state)
{
    (void)state;
    assert_true(1);
    assert_false(0);
    assert_int_equal(-1, -1);
    assert_int_not_equal(1, 2);
    assert_in_range(5, 1, 10);
    assert_not_in_range(11, 1, 10);
    assert_non_null(state);
    assert_memory_equal("abc", "abc", 3);
    assert_memory_not_equal("abc", "abd", 3);
    assert_string_equal("x", "x");
    assert_string_not_equal("x", "y");
    assert_return_code(0, 0);
}

static void skipped(void **state)
{
    (void)state;
    skip();
}

int main(void)
{
    const struct CMUnitTest failing[] = {
        cmocka_unit_test(bad_true),       cmocka_unit_test(bad_false),
        cmocka_unit_test(bad_int),        cmocka_unit_test(bad_int_not),
        cmocka_unit_test(bad_range),      cmocka_unit_test(bad_ptr),
        cmocka_unit_test(bad_non_null),   cmocka_unit_test(bad_memory),
        cmocka_unit_test(bad_string),     cmocka_unit_test(bad_string_not),
        cmocka_unit_test(bad_return_code), cmocka_unit_test(bad_fail),
        cmocka_unit_test_setup(never_run, setup_fails),
    };
    const struct CMUnitTest passing[] = {cmocka_unit_test(good), cmocka_unit_test(skipped)};
    int failed = cmocka_run_group_tests(failing, NULL, NULL);
    int passed = cmocka_run_group_tests(passing, NULL, NULL);
    int want = (int)(sizeof failing / sizeof failing[0]);
    printf("shim selftest: %d of %d failing tests failed, %d passing tests failed\n", failed,
           want, passed);
    return failed == want && passed == 0 ? 0 : 1;
}
