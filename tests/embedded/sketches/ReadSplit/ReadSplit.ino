// ReadSplit: a test sketch, not an example (run-arduino.sh builds it with the
// simavr console). LSC::readPositions on an Uno: a read of 20 servos goes out
// as requests of 9, 9 and 2 (the client's 32-byte receive buffer holds a reply
// for 9), and a list that cannot be read (an id twice, count 0, NULL) is
// refused before anything is sent. expected/arduino-ReadSplit.txt holds the
// exchange: the three requests and, between the two console lines around the
// refused calls, nothing on the wire.
#include <LSC.h>
#include <LSCReadSplit.h>

LSC lsc(Serial);
// check() and failures: sketch_check.h (run-arduino.sh includes it)

void setup()
{
    Serial.begin(9600);
    lsc.begin();

    // The split rule at this board's buffer size: 9 per request.
    const uint8_t per = lsc_read_per(LSC_CLIENT_RX_MAX);
    check("servos per request", per, 9);
    check("first request of 20", lsc_read_chunk(20, per), 9);
    check("last request of 20", lsc_read_chunk(2, per), 2);

    // Three servos, one in each request of the read below, somewhere else
    // than the power-on 1500.
    const LSCServo moved[] = {{1, 1001}, {10, 1010}, {20, 1020}};
    check("move", lsc.moveServos(moved, 3, 0), 0);
    delay(100);

    uint8_t ids[20];
    LSCServo out[20];
    for (uint8_t i = 0; i < 20; i++)
        ids[i] = (uint8_t)(i + 1);
    check("read 20 servos", lsc.readPositions(ids, 20, out), 20);
    int wrong = 0;
    for (uint8_t i = 0; i < 20; i++) {
        uint16_t want = ids[i] == 1 ? 1001 : ids[i] == 10 ? 1010 : ids[i] == 20 ? 1020 : 1500;
        if (out[i].id != ids[i] || out[i].position != want)
            wrong++;
    }
    check("servos read wrong", wrong, 0);

    // Servo 5 again in the second request (ids 1..9, then 10, 11, 5): the
    // first request alone would be valid, but nothing may go out. (The read
    // above had its replies: all it sent is on the wire already.)
    uint8_t twice[12];
    for (uint8_t i = 0; i < 11; i++)
        twice[i] = (uint8_t)(i + 1);
    twice[11] = 5;
    int rc = lsc.readPositions(twice, 12, out);
    int none = lsc.readPositions(ids, 0, out);
    int noIds = lsc.readPositions(NULL, 3, out);
    int noOut = lsc.readPositions(ids, 3, NULL);
    Serial.flush(); // anything those calls sent is on the wire before the next line
    check("servo 5 twice", rc, LSC_EINVAL);
    check("no servos", none, LSC_EINVAL);
    check("no ids", noIds, LSC_EINVAL);
    check("nowhere to put them", noOut, LSC_EINVAL);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
