// Reach: the board itself works out where the xArm's joints must go for the
// grasp point to be 200 mm in front of the base, 100 mm above the table, the
// hand pointing 45 degrees down (inverse kinematics, lsc/kinematics.h, float
// arithmetic, no allocation), and sends the move. A point out of reach is
// refused with nothing sent. docs/kinematics.md has the frame and the angles.
//
// The xArm's figures (examples/arms/xarm.conf, from nuro-arm's URDF): the
// shoulder 64.7 mm above the table, 98.8 mm to the elbow, 94.7 mm to the
// wrist, 158.8 mm to the grasp point, the URDF's joint limits; bus servos 6
// (base) to 2 (wrist roll), position 500 at 0 degrees, 0.24 degree a unit.
//
// Wiring: as the Basic example (the controller on Serial, or Serial1 on a
// board that has it).
#include <LSC.h>
#include <lsc/kinematics.h>

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

// Timer 1 counts the CPU's cycles, divided by 8 (up to 524288 cycles) or by
// 64 (up to 4194304); interrupts are off meanwhile, so that the count is the
// call's alone (and the same on every run).
static uint16_t prescale;

static void startCycles(uint16_t divide)
{
    prescale = divide;
    cli();
    TCCR1A = 0;
    TCCR1B = 0;
    TCNT1 = 0;
    TIFR1 = _BV(TOV1);
    TCCR1B = divide == 8 ? _BV(CS11) : _BV(CS11) | _BV(CS10);
}

// The cycles since startCycles, or -1 when the timer ran over.
static long stopCycles()
{
    uint16_t ticks = TCNT1;
    TCCR1B = 0;
    bool over = (TIFR1 & _BV(TOV1)) != 0;
    sei();
    return over ? -1L : (long)ticks * prescale;
}

// What the measured call reads and writes goes through these, so that the
// compiler cannot move its work out of the measured stretch.
static volatile float given = 100;
static volatile float sink;

void report(const char *label, long value);
void report(const char *label, long value)
{
#ifdef EXAMPLE_CONSOLE
    EXAMPLE_CONSOLE.print(label);
    EXAMPLE_CONSOLE.println(value);
#else
    (void)label;
    (void)value;
#endif
}

static const uint8_t ids[LSC_KIN_JOINTS] = {6, 5, 4, 3, 2}; // base .. wrist roll

void setup()
{
    CONTROLLER.begin(9600);
    lsc.begin();

    lsc_kin_chain xarm = {64.7f, 98.8f, 94.7f, 158.8f,
                          {-114.59f, -90.52f, -114.59f, -103.13f, -114.59f},
                          {114.59f, 90.52f, 114.59f, 114.59f, 114.59f}};
    float now[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0}; // standing straight up
    float q[LSC_KIN_JOINTS];
    lsc_kin_result why;

    lsc_kin_target target = {200, 0, 0, -45, 0, true, false};
    startCycles(8);
    target.z_mm = given;
    int rc = lsc_kin_inverse(&xarm, &target, now, q, &why);
    sink = q[0] + q[1] + q[2] + q[3] + (float)rc;
    report("inverse kinematics, cycles: ", stopCycles());
    if (rc != 0) {
        report("refused: ", why.status);
        EXAMPLE_EXIT(1);
        return;
    }
    LSCServo move[LSC_KIN_JOINTS];
    for (uint8_t i = 0; i < LSC_KIN_JOINTS; i++) {
        LSCJoint j;
        lsc_joint_init(&j, ids[i], LSC_JOINT_BUS);
        int32_t cdeg = (int32_t)lroundf(q[i] * 100);
        report("centidegrees: ", cdeg);
        move[i].id = ids[i];
        lsc_joint_to_pos(&j, cdeg, &move[i].position);
    }
    lsc.moveServos(move, LSC_KIN_JOINTS, 1000);

    // Without a pitch: the one nearest the hand's (straight up: 90) that
    // reaches the point within the limits, found exactly over the whole
    // circle (docs/kinematics.md).
    target.has_pitch = false;
    startCycles(64);
    target.z_mm = given;
    rc = lsc_kin_inverse(&xarm, &target, now, q, &why);
    sink = q[0] + q[1] + q[2] + q[3] + (float)rc;
    report("inverse kinematics, pitch chosen, cycles: ", stopCycles());
    report("pitch chosen: ", (long)why.pitch_deg);

    // Too high: refused, nothing sent.
    target.z_mm = 600;
    target.has_pitch = true;
    rc = lsc_kin_inverse(&xarm, &target, now, q, &why);
    if (rc != 0 && why.status == LSC_KIN_OUT_OF_REACH)
        report("out of reach by mm: ", (long)why.by_mm);
    Serial.flush();
    EXAMPLE_EXIT(0);
}

void loop()
{
}
