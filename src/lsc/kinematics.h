/* Forwards to include/lsc/kinematics.h, for builds that put only src/ on the
 * include path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/kinematics.h"
