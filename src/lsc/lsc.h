/* Forwards to include/lsc/lsc.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/lsc.h"
