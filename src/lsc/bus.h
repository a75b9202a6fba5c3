/* Forwards to include/lsc/bus.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/bus.h"
