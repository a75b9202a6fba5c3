// Running: a test sketch, not an example (run-arduino.sh builds it with the
// simavr console). A sketch that has not asked for notifications (no
// onNotification, poll or waitForCompletion yet) does not link the code that
// hands them out, but a read that takes a notification still keeps the
// running state for isRunning(), and takes no notification for its reply.
#include <LSC.h>

LSC lsc(Serial);
// check() and failures: sketch_check.h (run-arduino.sh includes it)

void setup()
{
    Serial.begin(9600);
    lsc.begin();

    check("run group 100 300 times", lsc.runActionGroup(100, 300), 0);
    // the notification that it started (7 bytes) waits in the Stream
    // (bounded: the harness's time limit); the read below takes it
    while (Serial.available() < 7)
        ;
    uint16_t mv = 0;
    check("read the battery", lsc.getBatteryVoltage(mv), 0);
    check("battery above 0 mV", mv > 0, 1);
    check("running, as the read found", lsc.isRunning(), 1);

    check("stop group", lsc.stopActionGroup(), 0);
    while (Serial.available() < 4) // the notification that it stopped
        ;
    const uint8_t one = 1;
    LSCServo s = {0, 0};
    check("read servo 1", lsc.readPositions(&one, 1, &s), 1);
    check("servo 1 read", s.id, 1);
    check("not running, as the read found", lsc.isRunning(), 0);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
