# Cross-build for s390x (64-bit, big-endian) with Debian's gcc-s390x-linux-gnu;
# ctest runs the programs under qemu-user (qemu-s390x). Used by
# `scripts/test.sh s390x`. The tests link Debian's own cmocka for s390x
# (libcmocka-dev:s390x, Multi-Arch: same; scripts/install-deps.sh adds the
# architecture), dynamically: qemu-s390x -L / finds the s390x loader and
# libraries where multi-arch installs them (/lib/ld64.so.1, /usr/lib/s390x-linux-gnu).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR s390x)
set(CMAKE_C_COMPILER s390x-linux-gnu-gcc)
set(CMAKE_FIND_ROOT_PATH /usr/s390x-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-s390x -L /)
# tests/CMakeLists.txt: cmocka from Debian's multi-arch directory for this triplet
set(LSC_CMOCKA_MULTIARCH s390x-linux-gnu)
# pkg-config must not hand the host's x86-64 libraries to the cross build;
# the serial transport uses its termios backend there.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/s390x-linux-gnu/pkgconfig:/usr/s390x-linux-gnu/lib/pkgconfig)
set(LSC_WITH_LIBSERIALPORT OFF CACHE BOOL "No libserialport for s390x")
set(LSC_WITH_HIDAPI OFF CACHE BOOL "No hidapi for s390x")
