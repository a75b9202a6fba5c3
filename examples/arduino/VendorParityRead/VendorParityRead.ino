// VendorParityRead: VendorParity's calls (those of the vendor's own Arduino
// example, LobotServoController), then a battery read and a read of six
// servos' positions: the reads a sketch of the vendor's library makes with
// getBatteryVolt and its position read, so that the two builds can be
// compared with reading included.
#include <LSC.h>

#ifndef EXAMPLE_EXIT
#define EXAMPLE_EXIT(code) (void)(code)
#endif

LSC lsc(Serial);

void setup()
{
    pinMode(13, OUTPUT);
    Serial.begin(9600);
    while (!Serial)
        ;
    digitalWrite(13, HIGH);

    lsc.runActionGroup(100, 0); // group 100, over and over
    delay(5000);
    lsc.stopActionGroup();
    delay(2000);
    lsc.setActionGroupSpeed(100, 200); // twice as fast
    delay(2000);
    lsc.runActionGroup(100, 5); // five times
    delay(5000);
    lsc.stopActionGroup();
    delay(2000);
    lsc.moveServo(0, 1500, 1000); // servo 0 to 1500 over 1 s
    delay(2000);
    lsc.moveServo(2, 800, 1000);
    delay(2000);
    const LSCServo five[] = {{0, 1300}, {2, 700}, {4, 600}, {6, 900}, {8, 790}};
    lsc.moveServos(five, 5, 1000);
    delay(2000);
    LSCServo servos[2];
    servos[0].id = 2;
    servos[0].position = 1400;
    servos[1].id = 4;
    servos[1].position = 700;
    lsc.moveServos(servos, 2, 1000);
    delay(2000);

    uint16_t mv = 0;
    int battery = lsc.getBatteryVoltage(mv); // millivolts
    // six servos the moves above left alone (a servo still moving would be
    // read wherever it is on its way)
    const uint8_t ids[] = {1, 3, 5, 7, 9, 11};
    LSCServo where[6];
    int read = lsc.readPositions(ids, 6, where); // where[i]: ids[i] and its position
    EXAMPLE_EXIT(battery == 0 && mv > 0 && read == 6 && where[5].id == 11 ? 0 : 1);
}

void loop()
{
}
