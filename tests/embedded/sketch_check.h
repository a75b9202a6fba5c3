/* check() for the test-only sketches (sketches/): prints "what: got" on the
 * simavr console and counts a failure when got is not want. run-arduino.sh
 * force-includes it (after simavr_console.h) into those sketches. */
#ifndef LSC_SKETCH_CHECK_H
#define LSC_SKETCH_CHECK_H

static int failures = 0;

static void check(const char *what, long got, long want)
{
    EXAMPLE_CONSOLE.print(what);
    EXAMPLE_CONSOLE.print(": ");
    EXAMPLE_CONSOLE.print(got);
    if (got != want) {
        EXAMPLE_CONSOLE.print(" FAIL, want ");
        EXAMPLE_CONSOLE.print(want);
        failures++;
    }
    EXAMPLE_CONSOLE.println();
}

#endif
