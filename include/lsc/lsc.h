/* lsc: the LSC servo controller protocol. Include this one header. */
#ifndef LSC_LSC_H
#define LSC_LSC_H

#include "lsc/core.h"
#include "lsc/io.h"
#include "lsc/sim.h"

#endif
