// Basic: moves servos and reads the battery voltage and the positions back.
//
// Wiring: the controller's TX/RX/GND to the board's RX/TX/GND. An Uno's only
// UART is Serial, so the controller takes it; on a board with a second port
// (Mega, Leonardo, ...) the controller goes on Serial1 and Serial prints what
// the sketch reads.
#include <LSC.h>

#if defined(HAVE_HWSERIAL1)
#define CONTROLLER Serial1
#ifndef EXAMPLE_CONSOLE
#define EXAMPLE_CONSOLE Serial
#endif
#else
#define CONTROLLER Serial
#endif
#ifndef EXAMPLE_EXIT
#define EXAMPLE_EXIT(code) (void)(code)
#endif

LSC lsc(CONTROLLER);

void report(const char *label, long value, const char *unit);
void showServo(const LSCServo &servo);

void report(const char *label, long value, const char *unit)
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

void showServo(const LSCServo &servo)
{
#ifdef EXAMPLE_CONSOLE
    EXAMPLE_CONSOLE.print("servo ");
    EXAMPLE_CONSOLE.print(servo.id);
    EXAMPLE_CONSOLE.print(" at ");
    EXAMPLE_CONSOLE.println(servo.position);
#else
    (void)servo;
#endif
}

void setup()
{
#if defined(EXAMPLE_CONSOLE) && defined(HAVE_HWSERIAL1)
    Serial.begin(115200);
#endif
    CONTROLLER.begin(9600);
    lsc.begin();

    // One servo, then two together, each over one second.
    lsc.moveServo(1, 2000, 1000);
    const LSCServo pair[] = {{2, 1200}, {9, 2300}};
    lsc.moveServos(pair, 2, 800);
    delay(1000);

    uint16_t mv = 0;
    int rc = lsc.getBatteryVoltage(mv);
    if (rc == 0)
        report("battery ", mv, " mV");
    else
        report("battery read failed: ", rc, "");

    // Where servos 1 to 12 are (an Uno reads 9 at a time: two requests).
    uint8_t ids[12];
    for (uint8_t i = 0; i < 12; i++)
        ids[i] = i + 1;
    LSCServo where[12];
    rc = lsc.readPositions(ids, 12, where);
    for (int i = 0; i < rc; i++)
        showServo(where[i]);
    if (rc < 0)
        report("position read failed: ", rc, "");

    // Let servo 9 turn freely.
    const uint8_t loose[] = {9};
    lsc.unloadServos(loose, 1);
    EXAMPLE_EXIT(rc == 12 && mv > 0 ? 0 : 1);
}

void loop()
{
}
