// PlayKeyframes: plays a sequence of keyframes kept in flash, without a host.
// The keyframes come from an action file (recorded with `lscctl record`, or
// the vendor's .rob / .d6a) turned into a C header:
//
//     lscctl convert wave.rob wave.h
//
// The library's player (lsc/player.h) schedules them: the move to the first
// keyframe over LEAD_MS, then one servo_move per keyframe at its time, the
// servos that did not change left out, times counted from one start (no
// drift). On AVR the arrays are in PROGMEM: the player reads them through
// readFlash().
//
// Wiring as in Basic: the controller on Serial (Serial1 where the board has
// one, with Serial printing what happens).
#include <LSC.h>
#include <lsc/player.h>

#include "wave.h"

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

const uint16_t LEAD_MS = 500; // the move to the first keyframe
const uint16_t SPEED = 100;   // percent: 200 plays twice as fast
const uint16_t TIMES = 2;     // play it twice

LSC lsc(CONTROLLER);

#if defined(__AVR__)
static uint16_t readFlash(const void *data, size_t i)
{
    return pgm_read_word((const uint16_t *)data + i);
}
#else
#define readFlash NULL // the arrays are ordinary memory
#endif

void say(const char *text, long value)
{
#ifdef EXAMPLE_CONSOLE
    EXAMPLE_CONSOLE.print(text);
    EXAMPLE_CONSOLE.println(value);
#else
    (void)text;
    (void)value;
#endif
}

void setup()
{
#if defined(EXAMPLE_CONSOLE) && defined(HAVE_HWSERIAL1)
    Serial.begin(115200);
#endif
    CONTROLLER.begin(9600);
    lsc.begin();

    static const lsc_track track = {wave_ids, WAVE_SERVOS, WAVE_COUNT, wave_keyframes,
                                    readFlash};
    static lsc_player player;
    lsc_player_config config = {SPEED, TIMES, LEAD_MS, 9600};
    int failures = 0;
    if (lsc_player_init(&player, &track, &config) != 0) {
        say("cannot play these keyframes: ", WAVE_COUNT);
        EXAMPLE_EXIT(1);
        return;
    }
    unsigned long start = millis();
    lsc_player_step step;
    long sent = 0;
    int r;
    while ((r = lsc_player_next(&player, (uint32_t)millis(), &step)) != LSC_PLAYER_DONE) {
        if (r == LSC_PLAYER_WAIT) {
            delay(step.wait_ms);
        } else if (lsc.moveServos(step.servos, step.nservos, step.time_ms) == 0) {
            sent++;
        } else {
            failures++;
        }
    }
    unsigned long took = millis() - start;
    say("moves sent: ", sent); // a keyframe where nothing changes sends none
    say("dropped: ", (long)lsc_player_dropped(&player));
    // the schedule's length, give or take the millis() tick
    say("on time: ", took + 2 >= lsc_player_total_ms(&player) &&
                         took <= lsc_player_total_ms(&player) + 20);
    failures += took + 2 < lsc_player_total_ms(&player) ||
                took > lsc_player_total_ms(&player) + 20;
    EXAMPLE_EXIT(failures);
}

void loop()
{
    lsc.poll();
}
