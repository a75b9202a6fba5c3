/* Wall-clock waits in tests, scaled for slow or busy machines.
 *
 * Every test that waits on real time (a peer's patience, a deadline, the slack
 * allowed past a timeout) takes its figure through test_ms(), which multiplies
 * it by LSC_TEST_TIME_SCALE (a positive integer, default 1). The sanitize and
 * valgrind stages raise it; a Debian build daemon or a Raspberry Pi can too.
 * Only waits that bound how long a test may take scale: a figure a test
 * asserts the code under test keeps (a timeout that must not end early) does
 * not. */
#ifndef LSC_TEST_TIME_H
#define LSC_TEST_TIME_H

#include <stdlib.h>

static inline long test_time_scale(void)
{
    const char *s = getenv("LSC_TEST_TIME_SCALE");
    if (s == NULL || *s == '\0') {
        return 1;
    }
    char *end;
    long v = strtol(s, &end, 10);
    return (*end == '\0' && v >= 1 && v <= 1000) ? v : 1;
}

static inline long test_ms(long ms)
{
    return ms * test_time_scale();
}

#endif
