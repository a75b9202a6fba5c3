/* Force-included (-include) into the example sketches when the tests build
 * them for simavr: gives the sketch a console and an exit code through the
 * general-purpose I/O registers the host harness watches (avr_harness.c). */
#include <Arduino.h>

/* A Print whose bytes go to GPIOR1: the harness prints them as console lines. */
class SimavrConsole : public Print {
public:
    size_t write(uint8_t b) override
    {
        GPIOR1 = b;
        return 1;
    }
};
static SimavrConsole simavrConsole;

#define EXAMPLE_CONSOLE simavrConsole
/* Ends the run with this exit code. */
#define EXAMPLE_EXIT(code)                                                                         \
    do {                                                                                           \
        Serial.flush();                                                                            \
        GPIOR0 = (uint8_t)(code);                                                                  \
        cli();                                                                                     \
        for (;;)                                                                                   \
            ;                                                                                      \
    } while (0)
