/* lsc: the LSC servo controller protocol. Include this one header. */
#ifndef LSC_LSC_H
#define LSC_LSC_H

#include "lsc/core.h"
#include "lsc/lx.h"
#include "lsc/io.h"
#include "lsc/client.h"
#include "lsc/lxclient.h"
#include "lsc/sim.h"
#include "lsc/lxbus.h"
#include "lsc/player.h"
#include "lsc/units.h"
#include "lsc/kinematics.h"

/* The serial and HID transports, the action files, arm profiles and the
 * device layer exist only on hosts (not on Arduino, STM32, ...). */
#include "lsc/host.h"
#if LSC_HOST
#include "lsc/serial.h"
#include "lsc/hid.h"
#include "lsc/files.h"
#include "lsc/arm.h"
#include "lsc/calibrate.h"
#include "lsc/device.h"
#include "lsc/link.h"
#include "lsc/bus.h"
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/env.h"
#include "lsc/discovery.h"
#include "lsc/convert.h"
#include "lsc/text.h"
#include "lsc/calibrated.h"
#include "lsc/lscd.h"
#endif

#endif
