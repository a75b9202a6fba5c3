/* lsc: whether this build is on a host, where the host library exists (the
 * serial and HID transports, action files, arm profiles, the device layer,
 * the lscd client): a POSIX system that is not an Arduino build. The Arduino
 * IDE compiles every .c under src/, so each host-only file tests LSC_HOST
 * (1 or 0) and compiles to nothing elsewhere. */
#ifndef LSC_HOST_H
#define LSC_HOST_H

#if (defined(__unix__) || defined(__APPLE__)) && !defined(ARDUINO)
#define LSC_HOST 1
#else
#define LSC_HOST 0
#endif

/* A declaration, so that a host-only file is still a translation unit where
 * it compiles to nothing (ISO C forbids an empty one). */
typedef int lsc_host_unit;

#endif
