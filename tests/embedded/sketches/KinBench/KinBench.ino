// KinBench: a bench sketch, not an example (run-arduino.sh builds it with the
// simavr console). On an Uno (simavr counts its cycles exactly) it prints:
// - what avr-libc's float functions cost (the kinematics' building blocks);
// - lsc_kin_forward, and lsc_kin_inverse for the xArm (examples/arms/
//   xarm.conf's lengths and limits) with the pitch given, on nine targets at
//   pitches -40..60;
// - lsc_kin_inverse on the same targets with the pitch chosen, from the arm
//   standing straight up (pitch 90: none of them is reached at it, so the
//   whole search runs), and from a pose at the target's own pitch.
// It fails (exit 1) when a solve fails or costs more than its bound: 24,000
// cycles with the pitch given, 160,000 with it chosen. Timer 1 counts the
// cycles with interrupts off (by 1 up to 65,535; by 8 up to 524,280).
// expected/arduino-KinBench.txt holds the figures; docs/kinematics.md quotes
// them.
#include <LSC.h>
#include <lsc/kinematics.h>
#include <math.h>

static const long GIVEN_MAX = 24000L;
static const long CHOSEN_MAX = 160000L;

static uint8_t divide;

static void start(uint8_t by)
{
    divide = by;
    cli();
    TCCR1A = 0;
    TCCR1B = 0;
    TCNT1 = 0;
    TIFR1 = _BV(TOV1);
    TCCR1B = by == 1 ? _BV(CS10) : _BV(CS11);
}

static long stop()
{
    uint16_t ticks = TCNT1;
    TCCR1B = 0;
    bool over = (TIFR1 & _BV(TOV1)) != 0;
    sei();
    return over ? -1L : (long)ticks * divide;
}

static volatile float va = 0.7f, vb = -0.3f, sink;
static int failures = 0;

static void line(const char *what, long v)
{
    EXAMPLE_CONSOLE.print(what);
    EXAMPLE_CONSOLE.println(v);
}

// Cycles of one float operation, less those of moving the operands.
#define COST(label, expr)                                                                          \
    do {                                                                                           \
        start(1);                                                                                  \
        sink = va;                                                                                 \
        long base_ = stop();                                                                       \
        start(1);                                                                                  \
        sink = (expr);                                                                             \
        line(label, stop() - base_);                                                               \
    } while (0)

struct Target {
    float x, y, z, pitch;
};

// Points made by the forward kinematics of angles within the limits (base
// 0, 20, -15, 30, 0, -25; then 90, -75 and 100, where the base may also turn
// half round: both sides are searched), hand pitches -40..60.
static const Target targets[] = {
    {279.9f, 0.0f, 38.3f, -40},   {274.3f, 99.8f, 112.4f, -20}, {265.2f, -71.1f, 204.9f, 0},
    {206.9f, 119.5f, 277.2f, 20}, {169.0f, 0.0f, 347.6f, 40},   {85.8f, -40.0f, 388.5f, 60},
    {0.0f, 274.6f, 204.9f, 0},    {61.8f, -230.8f, 277.2f, 20}, {-48.6f, 275.6f, 38.3f, -40},
};
static const uint8_t TARGETS = sizeof targets / sizeof targets[0];

void setup()
{
    COST("avr-libc cycles, a + b: ", va + vb);
    COST("avr-libc cycles, a * b: ", va * vb);
    COST("avr-libc cycles, a / b: ", va / vb);
    COST("avr-libc cycles, a < b: ", (float)(va < vb));
    COST("avr-libc cycles, sqrtf: ", sqrtf(va));
    COST("avr-libc cycles, sinf: ", sinf(va));
    COST("avr-libc cycles, cosf: ", cosf(va));
    COST("avr-libc cycles, atan2f: ", atan2f(va, vb));
    COST("avr-libc cycles, acosf: ", acosf(va));

    lsc_kin_chain xarm = {64.7f, 98.8f, 94.7f, 158.8f,
                          {-114.59f, -90.52f, -114.59f, -103.13f, -114.59f},
                          {114.59f, 90.52f, 114.59f, 114.59f, 114.59f}};
    float up[LSC_KIN_JOINTS] = {0, 0, 0, 0, 0}; // straight up: pitch 90
    float q[LSC_KIN_JOINTS];
    lsc_kin_pose pose;
    lsc_kin_result why;

    start(1);
    int rc = lsc_kin_forward(&xarm, up, &pose);
    long cycles = stop();
    sink = pose.z_mm + (float)rc;
    line("lsc_kin_forward cycles: ", cycles);

    long given = 0, chosen = 0, same = 0;
    for (uint8_t i = 0; i < TARGETS; i++) {
        const Target &g = targets[i];
        lsc_kin_target t = {g.x, g.y, g.z, g.pitch, 0, true, false};
        start(1);
        rc = lsc_kin_inverse(&xarm, &t, up, q, &why);
        cycles = stop();
        if (rc != 0 || cycles < 0) {
            line("pitch given: refused, target ", i);
            failures++;
        }
        given = cycles > given ? cycles : given;
        EXAMPLE_CONSOLE.print("pitch ");
        EXAMPLE_CONSOLE.print((int)g.pitch);
        EXAMPLE_CONSOLE.print(" given, cycles: ");
        EXAMPLE_CONSOLE.print(cycles);

        // the pitch chosen from straight up: the whole search
        t.has_pitch = false;
        start(8);
        rc = lsc_kin_inverse(&xarm, &t, up, q, &why);
        cycles = stop();
        if (rc != 0 || cycles < 0) {
            failures++;
        }
        chosen = cycles > chosen ? cycles : chosen;
        EXAMPLE_CONSOLE.print("; chosen from 90: ");
        EXAMPLE_CONSOLE.print(cycles);
        EXAMPLE_CONSOLE.print(" (pitch ");
        EXAMPLE_CONSOLE.print(why.pitch_deg, 2);

        // from a pose at the target's pitch: reached at once
        float at[LSC_KIN_JOINTS] = {0, 0, 0, 90 - g.pitch, 0};
        start(8);
        rc = lsc_kin_inverse(&xarm, &t, at, q, &why);
        cycles = stop();
        if (rc != 0 || cycles < 0) {
            failures++;
        }
        same = cycles > same ? cycles : same;
        EXAMPLE_CONSOLE.print("); from ");
        EXAMPLE_CONSOLE.print((int)g.pitch);
        EXAMPLE_CONSOLE.print(": ");
        EXAMPLE_CONSOLE.println(cycles);
    }
    line("most, pitch given: ", given);
    line("most, pitch chosen (the whole search): ", chosen);
    line("most, pitch chosen (the present one reaches): ", same);
    if (given > GIVEN_MAX || chosen > CHOSEN_MAX) {
        failures++;
    }
    line("failures: ", failures);
    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
