/* Forwards to include/lsc/lxclient.h, for builds that put only src/ on the
 * include path (the Arduino IDE compiles a library that way). */
#include "../../include/lsc/lxclient.h"
