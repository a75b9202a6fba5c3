// BusServo: the servos themselves, on their one-wire bus (LX-16A, the xArm's
// LX-15D, LX-224...), at 115200 baud with their own protocol (lsc/lx.h):
// scans the bus for servos, moves the first one found, and reads back its
// position, supply voltage and temperature.
//
// Wiring (half duplex): the bus's signal wire to the board's RX, and the
// board's TX to the same wire through a 1 kOhm resistor (a tri-state buffer
// such as a 74HC126 is the cleaner way); GND to the servos' GND; the servos
// powered from their own supply (6-8.4 V for an LX-16A). The board then hears
// its own bytes before any answer: the parser drops that echo
// (lsc_lx_parser_expect_echo). An Uno's only UART is Serial, so the bus takes
// it; on a board with a second port (Mega, Leonardo, ...) the bus goes on
// Serial1 and Serial prints what the sketch finds.
#include <LSC.h>
#include <lsc/lx.h>

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

static lsc_lx_parser parser;

void say(const char *label, long value, const char *unit);
bool ask(uint8_t id, uint8_t cmd, uint16_t timeoutMs, lsc_lx_frame *reply);
bool sendFrame(const uint8_t *frame, int n);

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

// Sends a frame an encoder made (n > 0), and tells the parser its echo comes.
bool sendFrame(const uint8_t *frame, int n)
{
    if (n <= 0) {
        return false;
    }
    // what came before (the echo of a frame nobody waited for, noise) is no
    // answer to this one
    while (BUS.available() > 0) {
        BUS.read();
    }
    lsc_lx_parser_reset(&parser);
    BUS.write(frame, (size_t)n);
    BUS.flush();
    lsc_lx_parser_expect_echo(&parser, frame, (size_t)n);
    return true;
}

// Sends the read cmd to servo id and waits up to timeoutMs for its reply,
// which is only believed when its checksum holds. The reply's values are
// the parser's until the next byte is fed: decode them at once.
bool ask(uint8_t id, uint8_t cmd, uint16_t timeoutMs, lsc_lx_frame *reply)
{
    uint8_t frame[LSC_LX_FRAME_MAX];
    if (!sendFrame(frame, lsc_lx_encode_request(frame, sizeof frame, id, cmd))) {
        return false;
    }
    unsigned long start = millis();
    while (millis() - start < timeoutMs) {
        while (BUS.available() > 0) {
            int r = lsc_lx_parser_feed(&parser, (uint8_t)BUS.read(), reply);
            if (r == 1 && reply->reply && reply->cmd == cmd && reply->id == id) {
                return true;
            }
        }
    }
    return false;
}

void setup()
{
#if defined(EXAMPLE_CONSOLE) && defined(HAVE_HWSERIAL1)
    Serial.begin(115200);
#endif
    BUS.begin(115200);
    lsc_lx_parser_init(&parser);
    lsc_lx_frame reply;

    // Every id, one at a time: a servo there answers within a millisecond
    // or two; 5 ms each, the whole bus takes about 1.3 s.
    uint8_t first = 0;
    uint8_t found = 0;
    for (uint16_t id = 0; id <= LSC_LX_ID_MAX; id++) {
        uint8_t got;
        if (ask((uint8_t)id, LSC_LX_ID_READ, 5, &reply) && lsc_lx_decode_id(&reply, &got) == 0) {
            say("found servo ", got, "");
            if (found++ == 0) {
                first = got;
            }
        }
    }
    say("servos on the bus: ", found, "");
    if (found == 0) {
        EXAMPLE_EXIT(1);
        return;
    }

    // The first one to 700 over 300 ms, then where it is.
    uint8_t frame[LSC_LX_FRAME_MAX];
    sendFrame(frame, lsc_lx_encode_move_time(frame, sizeof frame, first,
                                             LSC_LX_MOVE_TIME_WRITE, 700, 300));
    delay(400);
    int16_t position;
    if (ask(first, LSC_LX_POS_READ, 20, &reply) &&
        lsc_lx_decode_position(&reply, &position) == 0) {
        say("position ", position, "");
    }
    uint16_t millivolts;
    if (ask(first, LSC_LX_VIN_READ, 20, &reply) && lsc_lx_decode_vin(&reply, &millivolts) == 0) {
        say("supply ", millivolts, " mV");
    }
    uint8_t celsius;
    if (ask(first, LSC_LX_TEMP_READ, 20, &reply) && lsc_lx_decode_temp(&reply, &celsius) == 0) {
        say("temperature ", celsius, " C");
    }
    say("echoes dropped: ", (long)parser.echoes, "");
    say("bad checksums: ", (long)parser.bad_checksums, "");
    EXAMPLE_EXIT(0);
}

void loop()
{
}
