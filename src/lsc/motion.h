/* Forwards to include/lsc/motion.h, for builds that put only src/ on the include
 * path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/motion.h"
