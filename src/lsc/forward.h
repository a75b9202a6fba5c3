/* Forwards to include/lsc/forward.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/forward.h"
