/* Force-included (-include) into a sketch whose delays add up to more than a
 * few seconds: runs them 10 times faster, so the test takes seconds (simavr
 * runs an ATmega328P at about real speed). */
#include <Arduino.h>

#define delay(ms) delay((ms) / 10u)
