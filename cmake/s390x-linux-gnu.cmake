# Cross-build for s390x (64-bit, big-endian) with Debian's gcc-s390x-linux-gnu,
# linked statically; ctest runs the programs under qemu-user (qemu-s390x).
# Used by `scripts/test.sh s390x`. cmocka is not available for s390x (Debian
# ships no cross-built libcmocka, and the CI machine has no network to build
# it), so tests link the small cmocka-compatible shim in tests/cmocka-shim
# (LSC_CMOCKA_SHIM) instead.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR s390x)
set(CMAKE_C_COMPILER s390x-linux-gnu-gcc)
set(CMAKE_FIND_ROOT_PATH /usr/s390x-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_EXE_LINKER_FLAGS_INIT -static)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-s390x -L /usr/s390x-linux-gnu)
set(LSC_CMOCKA_SHIM ON CACHE BOOL "Use tests/cmocka-shim instead of the system's cmocka")
# pkg-config must not hand the host's x86-64 libraries to the cross build;
# the serial transport uses its termios backend there.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/s390x-linux-gnu/pkgconfig:/usr/s390x-linux-gnu/lib/pkgconfig)
set(LSC_WITH_LIBSERIALPORT OFF CACHE BOOL "No libserialport for s390x")
set(LSC_WITH_HIDAPI OFF CACHE BOOL "No hidapi for s390x")
