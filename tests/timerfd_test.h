/* Tests of a device on the real clock (its timer descriptor): timerfd_create
 * wrapped by the linker (the test program links with
 * -Wl,--wrap=timerfd_create, tests/CMakeLists.txt) to fail as on a system
 * out of descriptors while timerfd_fails is set, and the monotonic clock in
 * ms to time the waits. Include it in one source of the program only (it
 * defines the wrapper); _POSIX_C_SOURCE comes from tests/CMakeLists.txt. */
#ifndef LSC_TESTS_TIMERFD_TEST_H
#define LSC_TESTS_TIMERFD_TEST_H

#include <errno.h>
#include <stdbool.h>
#include <time.h>

int __real_timerfd_create(int clockid, int flags); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
int __wrap_timerfd_create(int clockid, int flags); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

/* Set: timerfd_create fails (EMFILE). */
static bool timerfd_fails;

int __wrap_timerfd_create(int clockid, int flags) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp,misc-definitions-in-headers)
{
    if (timerfd_fails) {
        errno = EMFILE;
        return -1;
    }
    return __real_timerfd_create(clockid, flags);
}

/* The monotonic clock, in ms. */
static inline long mono_ms(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (long)t.tv_sec * 1000L + t.tv_nsec / 1000000L;
}

#endif
