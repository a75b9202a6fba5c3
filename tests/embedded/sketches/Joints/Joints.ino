// Joints: a test sketch, not an example (run-arduino.sh builds it with the
// simavr console). LSC::moveJoint and readJoint on an Uno: an angle in
// centidegrees goes out as the joint's position, an angle outside the
// joint's limits is refused with nothing on the wire, and the position read
// back comes back as an angle (expected/arduino-Joints.txt holds the exchange).
#include <LSC.h>

LSC lsc(Serial);
// check() and failures: sketch_check.h (run-arduino.sh includes it)

void setup()
{
    Serial.begin(9600);
    lsc.begin();

    // A PWM servo on id 6 (500..2500 over 180 degrees), limits -45..45 degrees.
    LSCJoint base;
    check("init", lsc_joint_init(&base, 6, LSC_JOINT_PWM), 0);
    base.min_cdeg = -4500;
    base.max_cdeg = 4500;
    // 30 degrees: 1500 + 333.3 -> 1833 (0x0729)
    check("move 30 degrees", lsc.moveJoint(base, 3000, 0), 0);
    delay(50);
    int32_t cdeg = 0;
    check("read", lsc.readJoint(base, cdeg), 0);
    check("angle read back", cdeg, 2997); // 333 units of 9 centidegrees
    // Beyond the limits: refused, nothing sent.
    int beyond = lsc.moveJoint(base, 4501, 0);
    Serial.flush();
    check("move 45.01 degrees", beyond, LSC_EINVAL);
    // A bus servo joint reading the sim's 1500: outside its 0..1000, a bad reply.
    LSCJoint wrist;
    lsc_joint_init(&wrist, 3, LSC_JOINT_BUS);
    check("read a bus joint at 1500", lsc.readJoint(wrist, cdeg), LSC_EREPLY);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
