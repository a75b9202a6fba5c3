# The shared library liblsc.so (target lsc_shared), included by src/CMakeLists.txt.
# liblsc.so is built from exactly the sources, include paths, definitions and
# link libraries of the static `lsc`, whoever adds them and wherever (the
# generator expressions are read when the build is generated). Only symbols
# marked LSC_API (include/lsc/core.h) are exported: hidden visibility by default.
#
# LSC_ABI_VERSION is the SONAME number (liblsc.so.N, Debian package liblscN),
# kept apart from the project version. The rule: bump it when a release breaks
# binary compatibility with the previous one (a public function or variable is
# removed or renamed, a parameter or return type changes, a public struct or enum
# a function takes changes its layout or meaning); do not bump it when functions
# are only added. `scripts/abi.sh check` (test stage `abi`) compares the build
# against abi/liblsc.abi and fails on an incompatible change made without a bump;
# `scripts/abi.sh update` rewrites the baseline (README: "ABI").
set(LSC_ABI_VERSION 2)
if(CMAKE_SYSTEM_NAME STREQUAL "Generic")
  set(_lsc_shared_default OFF) # bare-metal targets have no shared libraries
elseif(LSC_COVERAGE)
  set(_lsc_shared_default OFF) # coverage counts the library the tests link (static)
else()
  set(_lsc_shared_default ON)
endif()
option(LSC_BUILD_SHARED "Also build the shared library liblsc.so" ${_lsc_shared_default})
if(LSC_BUILD_SHARED)
  add_library(lsc_shared SHARED $<TARGET_PROPERTY:lsc,SOURCES>)
  target_include_directories(lsc_shared
    PRIVATE $<TARGET_PROPERTY:lsc,INCLUDE_DIRECTORIES>
    INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_compile_definitions(lsc_shared PRIVATE LSC_SHARED_BUILD
    $<TARGET_PROPERTY:lsc,COMPILE_DEFINITIONS>)
  target_compile_options(lsc_shared PRIVATE $<TARGET_PROPERTY:lsc,COMPILE_OPTIONS>)
  target_link_libraries(lsc_shared PRIVATE lsc_warnings
    $<TARGET_GENEX_EVAL:lsc,$<TARGET_PROPERTY:lsc,LINK_LIBRARIES>>)
  # --no-undefined: every symbol the library uses must come from a library it
  # names. libc is named explicitly: the toolchain links --as-needed, and Debian
  # policy (lintian library-not-linked-against-libc) wants a hosted library to
  # record its libc even while only the freestanding core is in it.
  # (Not with sanitizers: clang leaves their runtime to the executable.)
  if(NOT LSC_SANITIZE)
    target_link_options(lsc_shared PRIVATE LINKER:--no-undefined)
  endif()
  target_link_libraries(lsc_shared PRIVATE -Wl,--push-state,--no-as-needed -lc -Wl,--pop-state)
  set_target_properties(lsc_shared PROPERTIES
    OUTPUT_NAME lsc
    C_VISIBILITY_PRESET hidden
    SOVERSION ${LSC_ABI_VERSION}
    VERSION ${LSC_ABI_VERSION}.${PROJECT_VERSION_MINOR}.${PROJECT_VERSION_PATCH})
endif()
