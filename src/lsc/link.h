/* Forwards to include/lsc/link.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/link.h"
