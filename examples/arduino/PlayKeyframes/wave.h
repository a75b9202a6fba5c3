/* 4 keyframes for 6 servos, written by lscctl convert. Each row: the
 * time since the previous keyframe (ms), then the position of each id.
 * Play them with lsc_player (lsc/player.h): see
 * examples/arduino/PlayKeyframes. */
#ifndef WAVE_KEYFRAMES_H
#define WAVE_KEYFRAMES_H

#include <stdint.h>

#if defined(__AVR__)
#include <avr/pgmspace.h>
#define WAVE_STORAGE PROGMEM /* in flash: read with pgm_read_word */
#else
#define WAVE_STORAGE
#endif

#define WAVE_SERVOS 6u
#define WAVE_COUNT 4u

static const uint8_t wave_ids[WAVE_SERVOS] = {1, 2, 3, 4, 5, 6};

static const uint16_t wave_keyframes[WAVE_COUNT * (1u + WAVE_SERVOS)] WAVE_STORAGE = {
    500, 500, 500, 500, 500, 500, 500,
    300, 500, 300, 500, 700, 500, 500,
    300, 500, 700, 500, 300, 500, 500,
    400, 500, 500, 500, 500, 500, 500,
};

#endif
