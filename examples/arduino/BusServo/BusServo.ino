// BusServo: the servos themselves, on their one-wire bus (LX-16A, the xArm's
// LX-15D, LX-224...), at 115200 baud with their own protocol (lsc/lx.h):
// scans the bus for servos, moves the first one found, and reads back its
// position, supply voltage and temperature.
//
// Wiring (half duplex): the bus's signal wire to the board's RX, and the
// board's TX to the same wire through a 1 kOhm resistor (a tri-state buffer
// such as a 74HC126 is the cleaner way); GND to the servos' GND; the servos
// powered from their own supply (6-8.4 V for an LX-16A). The board then hears
// its own bytes before any answer: the bus client (lsc/lxclient.h) skips
// that echo, and believes a reply only when its checksum holds and it comes
// from the servo asked. An Uno's only UART is Serial, so the bus takes
// it; on a board with a second port (Mega, Leonardo, ...) the bus goes on
// Serial1 and Serial prints what the sketch finds.
#include <LSC.h>
#include <lsc/lxclient.h>

#if defined(HAVE_HWSERIAL1)
#define BUS Serial1
#ifndef EXAMPLE_CONSOLE
#define EXAMPLE_CONSOLE Serial
#endif
#else
#define BUS Serial
#endif
#ifndef EXAMPLE_EXIT
#define EXAMPLE_EXIT(code) (void)(code)
#endif

static lsc_lxclient bus;

void say(const char *label, long value, const char *unit);
int busWrite(void *ctx, const uint8_t *data, size_t n);
int busRead(void *ctx, uint8_t *buf, size_t cap, uint32_t timeoutMs);
uint32_t busNow(void *ctx);

void say(const char *label, long value, const char *unit)
{
#ifdef EXAMPLE_CONSOLE
    EXAMPLE_CONSOLE.print(label);
    EXAMPLE_CONSOLE.print(value);
    EXAMPLE_CONSOLE.println(unit);
#else
    (void)label;
    (void)value;
    (void)unit;
#endif
}

// The bus client's transport (lsc/io.h) over the Stream: a frame written
// whole (flush: on a one-wire bus the line must be free before a servo
// answers), bytes read as they come, millis() for the clock.
int busWrite(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    size_t written = BUS.write(data, n);
    BUS.flush();
    return (int)written;
}

int busRead(void *ctx, uint8_t *buf, size_t cap, uint32_t timeoutMs)
{
    (void)ctx;
    unsigned long start = millis();
    while (BUS.available() <= 0) {
        if (millis() - start >= timeoutMs) {
            return 0;
        }
    }
    size_t n = 0;
    while (n < cap && BUS.available() > 0) {
        buf[n++] = (uint8_t)BUS.read();
    }
    return (int)n;
}

uint32_t busNow(void *ctx)
{
    (void)ctx;
    return millis();
}

void setup()
{
#if defined(EXAMPLE_CONSOLE) && defined(HAVE_HWSERIAL1)
    Serial.begin(115200);
#endif
    BUS.begin(115200);
    const lsc_io io = {NULL, busWrite, busRead, busNow};
    lsc_lxclient_init(&bus, &io);
    lsc_lxclient_set_timeout(&bus, 20);

    // Every id, one at a time, LSC_LXCLIENT_SCAN_TIMEOUT_MS (8 ms) each: a
    // servo there answers within a millisecond or two; the whole bus takes
    // about 2.1 s.
    lsc_lx_scan scan;
    if (lsc_lxclient_scan(&bus, NULL, 0, 0, &scan) <= 0) {
        say("servos on the bus: ", 0, "");
        EXAMPLE_EXIT(1);
        return;
    }
    uint8_t first = 0;
    bool none = true;
    for (uint16_t id = 0; id <= LSC_LX_ID_MAX; id++) {
        if (lsc_lx_scan_found(&scan, (uint8_t)id)) {
            say("found servo ", id, "");
            first = none ? (uint8_t)id : first;
            none = false;
        }
    }
    say("servos on the bus: ", scan.count, "");

    // The first one to 700 over 300 ms, then where it is.
    lsc_lxclient_move(&bus, first, 700, 300);
    delay(400);
    int16_t position;
    if (lsc_lxclient_read_position(&bus, first, &position) == 0) {
        say("position ", position, "");
    }
    uint16_t millivolts;
    if (lsc_lxclient_read_vin(&bus, first, &millivolts) == 0) {
        say("supply ", millivolts, " mV");
    }
    uint8_t celsius;
    if (lsc_lxclient_read_temp(&bus, first, &celsius) == 0) {
        say("temperature ", celsius, " C");
    }
    say("echoes dropped: ", (long)(bus.parser.echoes + bus.echoes), "");
    say("bad checksums: ", (long)bus.parser.bad_checksums, "");
    EXAMPLE_EXIT(0);
}

void loop()
{
}
