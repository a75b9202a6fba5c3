// StaleInput: a test sketch, not an example (run-arduino.sh builds it with the
// simavr console). Input that arrived before a request is all read before the
// request goes out, however much of it there is: here three late replies to
// position reads (8 bytes each) and two notifications (7 and 4 bytes), 35
// bytes in the Stream, more than the wrapper reads at once (16). The third
// late reply carries the servo's old position for the very id read next; if
// it were left behind, readPositions would take it for the fresh reply.
// Then the notifications' fields as the sketch gets them, and a reply for
// another servo that comes while a read waits, which the read must skip.
#include <LSC.h>

LSC lsc(Serial);
// check() and failures: sketch_check.h (run-arduino.sh includes it)

static int notes = 0;
static LSCNotification first = {0, 0, 0};
static void onNote(const LSCNotification &n)
{
    if (notes++ == 0)
        first = n;
}

void setup()
{
    Serial.begin(9600);
    lsc.begin();
    lsc.onNotification(onNote);

    check("move servo 5 to 1000", lsc.moveServo(5, 1000, 0), 0);
    // Three position reads of servo 5 written straight to the port, as a call
    // that gave up before its reply came leaves them: their replies (1000)
    // come late. Then a group starts and stops (two notifications).
    const uint8_t five = 5;
    uint8_t frame[LSC_FRAME_MIN + 2];
    int len = lsc_encode_pos_request(frame, sizeof frame, &five, 1);
    for (uint8_t i = 0; i < 3; i++)
        Serial.write(frame, (size_t)len);
    check("run group 100 300 times", lsc.runActionGroup(100, 300), 0);
    check("stop group", lsc.stopActionGroup(), 0);
    // Everything is waiting in the Stream (bounded: the harness's time limit).
    const int stale = 3 * 8 + 7 + 4;
    while (Serial.available() < stale)
        ;
    check("stale bytes waiting", Serial.available(), stale);
    check("notifications before", notes, 0);

    check("move servo 5 to 2000", lsc.moveServo(5, 2000, 0), 0);
    LSCServo s = {0, 0};
    check("read servo 5", lsc.readPositions(&five, 1, &s), 1);
    check("servo 5 read", s.id, 5);
    check("servo 5 position (the fresh reply)", s.position, 2000);
    check("notifications handed out", notes, 2);
    check("first: command", first.cmd, LSC_CMD_GROUP_RUN);
    check("first: group", first.group, 100);
    check("first: times", first.times, 300);

    // A reply for another servo (1500) that comes while the read waits: its
    // request goes out just before the read's, after the read before it.
    const uint8_t six = 6;
    len = lsc_encode_pos_request(frame, sizeof frame, &six, 1);
    Serial.write(frame, (size_t)len);
    s.position = 0;
    check("read servo 5 again", lsc.readPositions(&five, 1, &s), 1);
    check("servo 5 position (not servo 6's)", s.position, 2000);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
