/*
 * lsc version: the version of the library these headers belong to, the
 * same as CMake's project version, pkg-config's (lsc.pc) and the Arduino
 * library's (library.properties, library.json): the build refuses to
 * configure when this file and CMake's project() disagree, and the test
 * lsc_library_files checks the rest. lsc_version() (lsc/core.h) gives the
 * version of the library a program runs with, which may be newer than the
 * headers it was built with.
 */
#ifndef LSC_VERSION_H
#define LSC_VERSION_H

#define LSC_VERSION_MAJOR 0
#define LSC_VERSION_MINOR 4
#define LSC_VERSION_PATCH 0
#define LSC_VERSION_STRING "0.4.0" /* MAJOR.MINOR.PATCH */

/* A version as one number, to compare: LSC_VERSION_NUMBER(0, 3, 0) <=
 * LSC_VERSION_NUMBER(LSC_VERSION_MAJOR, LSC_VERSION_MINOR, LSC_VERSION_PATCH). */
#define LSC_VERSION_NUMBER(major, minor, patch) \
    (((unsigned long)(major) << 16) | ((unsigned long)(minor) << 8) | (unsigned long)(patch))

#endif /* LSC_VERSION_H */
