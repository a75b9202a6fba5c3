/* lscctl's number parser (tools-common/lscctl_parse.c) at the edges of unsigned long:
 * the largest value and one past it, for every max up to ULONG_MAX (with a
 * 32-bit unsigned long, as on armhf and i386, lscctl's --count takes
 * 0..ULONG_MAX). */
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "lscctl_parse.h"

/* s plus one, in decimal ("99" -> "100"); s has room for one more digit */
static void increment(char *s)
{
    size_t n = strlen(s);
    for (size_t i = n; i-- > 0;) {
        if (s[i] != '9') {
            s[i]++;
            return;
        }
        s[i] = '0';
    }
    memmove(s + 1, s, n + 1);
    s[0] = '1';
}

static int parse(const char *s, unsigned long max, unsigned long *v)
{
    char why[160];
    *v = 12345;
    int r = lscctl_parse_uint(s, max, "value", v, why, sizeof why);
    if (r != 0) {
        assert_non_null(strstr(why, "out of range"));
    }
    return r;
}

static void check_max(unsigned long max)
{
    char text[64];
    unsigned long v;
    snprintf(text, sizeof text, "%lu", max);
    assert_int_equal(parse(text, max, &v), 0);
    assert_true(v == max);
    increment(text); /* one past */
    assert_int_equal(parse(text, max, &v), -1);
    assert_true(v == 12345); /* untouched */
    snprintf(text, sizeof text, "0x%lx", max);
    assert_int_equal(parse(text, max, &v), 0);
    assert_true(v == max);
    snprintf(text, sizeof text, "0x%lx0", max); /* sixteen times max */
    assert_int_equal(parse(text, max, &v), max == 0 ? 0 : -1);
    if (max < ULONG_MAX) {
        snprintf(text, sizeof text, "0x%lx", max + 1u);
        assert_int_equal(parse(text, max, &v), -1);
    }
}

static void test_largest_and_one_past(void **state)
{
    (void)state;
    check_max(ULONG_MAX);
    check_max(ULONG_MAX - 1u);
    check_max(ULONG_MAX / 10u);
    check_max(ULONG_MAX / 10u + 1u);
    check_max(4294967295ul);
    check_max(65535);
    check_max(255);
    check_max(9);
    check_max(0);
}

/* Values that wrap an unsigned long when multiplied out are out of range,
 * never a small number. */
static void test_wrapping_values(void **state)
{
    (void)state;
    unsigned long v;
    char text[64];
    /* ULONG_MAX + 1 wraps to 0 */
    snprintf(text, sizeof text, "%lu", ULONG_MAX);
    increment(text);
    assert_int_equal(parse(text, ULONG_MAX, &v), -1);
    /* ten times ULONG_MAX, and a value whose digits make it wrap to a small one */
    snprintf(text, sizeof text, "%lu0", ULONG_MAX);
    assert_int_equal(parse(text, ULONG_MAX, &v), -1);
    assert_int_equal(parse("99999999999999999999999999999999", ULONG_MAX, &v), -1);
    assert_int_equal(parse("0x10000000000000000000", ULONG_MAX, &v), -1);
    assert_int_equal(parse("0000000000000000000000000000000000000000001", ULONG_MAX, &v), 0);
    assert_true(v == 1);
}

/* A range with a minimum (-b, -t, --count): below it is refused, and every
 * reason states min..max (never "use 0..N" for a range that starts at 1). */
static void test_range_states_its_minimum(void **state)
{
    (void)state;
    char why[160];
    unsigned long v = 7;
    assert_int_equal(lscctl_parse_range("0", 1, 4000000, "baud rate", &v, why, sizeof why), -1);
    assert_string_equal(why, "baud rate 0 is out of range: use 1..4000000");
    assert_true(v == 7);
    assert_int_equal(lscctl_parse_range("0x0", 1, 9, "n", &v, why, sizeof why), -1);
    assert_string_equal(why, "n 0x0 is out of range: use 1..9");
    assert_int_equal(lscctl_parse_range("10", 1, 9, "n", &v, why, sizeof why), -1);
    assert_string_equal(why, "n 10 is out of range: use 1..9");
    assert_int_equal(lscctl_parse_range("-1", 1, 9, "n", &v, why, sizeof why), -1);
    assert_string_equal(why, "n '-1' is negative: use 1..9");
    assert_int_equal(lscctl_parse_range("1", 1, 9, "n", &v, why, sizeof why), 0);
    assert_true(v == 1);
    assert_int_equal(lscctl_parse_range("9", 1, 9, "n", &v, why, sizeof why), 0);
    assert_true(v == 9);
    /* without a minimum the reason still says 0.. */
    assert_int_equal(lscctl_parse_uint("10", 9, "n", &v, why, sizeof why), -1);
    assert_string_equal(why, "n 10 is out of range: use 0..9");
}

/* Decimals (reach's millimetres and degrees, --speed DEG/S): sign, point,
 * range; no exponent, hex, spaces or suffix. */
static void test_decimals(void **state)
{
    (void)state;
    char why[160];
    double v = 7;
    static const struct {
        const char *s;
        double want;
    } ok[] = {{"0", 0}, {"-15", -15}, {"+2.5", 2.5}, {"100.125", 100.125}, {"-0.000001", -1e-6},
              {"360", 360}, {"-360", -360}, {"123456789", 123456789}};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        assert_int_equal(lscctl_parse_decimal(ok[i].s, -1e9, 1e9, "x", &v, why, sizeof why), 0);
        double d = v - ok[i].want;
        assert_true(d <= 1e-9 && d >= -1e-9);
    }
    static const char *const bad[] = {"", "-", "+", ".5", "5.", "1e3", "0x10", "1 ", " 1",
                                      "1mm", "1.2.3", "1.1234567", "1234567890", "inf", "nan"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        v = 7;
        assert_int_equal(lscctl_parse_decimal(bad[i], -1e9, 1e9, "x", &v, why, sizeof why), -1);
        assert_true(v == 7);
    }
    assert_int_equal(lscctl_parse_decimal("1e3", -10, 10, "pitch", &v, why, sizeof why), -1);
    assert_string_equal(why, "pitch '1e3' is not a number: write it in decimal (-15, 2.5)");
    assert_int_equal(lscctl_parse_decimal("-360.5", -360, 360, "pitch", &v, why, sizeof why), -1);
    assert_string_equal(why, "pitch -360.5 is out of range: use -360..360");
    assert_int_equal(lscctl_parse_decimal("0.001", 0.01, 1e5, "speed", &v, why, sizeof why), -1);
    assert_string_equal(why, "speed 0.001 is out of range: use 0.01..100000");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_largest_and_one_past),
        cmocka_unit_test(test_wrapping_values),
        cmocka_unit_test(test_range_states_its_minimum),
        cmocka_unit_test(test_decimals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
