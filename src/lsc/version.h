/* Forwards to include/lsc/version.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/version.h"
