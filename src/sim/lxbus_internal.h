/* Shared by the virtual bus's files (not part of the API). */
#ifndef LSC_LXBUS_INTERNAL_H
#define LSC_LXBUS_INTERNAL_H

#include <stdint.h>

#include "lsc/lxbus.h"

/* Servo s's shaft position at time now (interpolated, with its offset; in
 * motor mode turning). */
int32_t lsc_lxbus_shaft(const lsc_lxbus_servo *s, uint64_t now);

/* Makes s a servo fresh from the box with this id, at rest at the default
 * position. */
void lsc_lxbus_servo_fresh(lsc_lxbus_servo *s, uint8_t id);

/* Power comes back to s, its shaft at `shaft`: what is lost at power-off
 * takes its power-on value (start_us is the caller's to set). */
void lsc_lxbus_servo_power_on(lsc_lxbus_servo *s, int32_t shaft);

#endif
