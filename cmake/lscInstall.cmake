# Install rules, the CMake package (find_package(lsc) -> lsc::lsc) and the
# pkg-config file (lsc.pc). Included last by the top-level CMakeLists.txt; the
# rules themselves run at the end of the top-level directory (cmake_language
# DEFER), so they see every target and link library, whatever order the
# subdirectories were added in. Programs, man pages and the completion script are
# installed when they exist.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LSC_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/lsc" CACHE STRING
  "Where the CMake package files go (relative to the prefix)")
option(LSC_INSTALL_UDEV "Install the udev rule for HID controllers (60-lsc.rules)" ON)
set(LSC_UDEV_RULES_DIR "lib/udev/rules.d" CACHE STRING
  "Where the udev rule goes (relative: under the prefix; udev reads /usr/lib/udev/rules.d and /etc/udev/rules.d)")
set(LSC_BASH_COMPLETION_DIR "" CACHE PATH
  "Where the bash completion goes (empty: bash-completion's completionsdir under this prefix)")

# The private link dependencies of liblsc.a, for lsc.pc and lscConfig.cmake:
# PkgConfig::NAME targets become pkg-config modules, plain names -lNAME.
function(_lsc_link_dependencies out_modules out_prefixes out_libs)
  get_target_property(items lsc LINK_LIBRARIES)
  set(modules "")
  set(prefixes "")
  set(libs "")
  foreach(item IN LISTS items)
    if(NOT item OR item STREQUAL "lsc_warnings" OR item MATCHES "^\\$<BUILD_INTERFACE:")
      continue() # build-only
    elseif(item MATCHES "^PkgConfig::(.+)$")
      set(prefix "${CMAKE_MATCH_1}")
      if(NOT DEFINED ${prefix}_MODULE_NAME)
        message(FATAL_ERROR "lsc links ${item}, whose pkg-config module is unknown")
      endif()
      list(APPEND modules "${${prefix}_MODULE_NAME}")
      list(APPEND prefixes "${prefix}")
    elseif(TARGET "${item}")
      message(FATAL_ERROR "lsc links target ${item}: wrap it in $<BUILD_INTERFACE:> if it "
        "is build-only, or teach cmake/lscInstall.cmake how to install it")
    elseif(item MATCHES "^-l")
      list(APPEND libs "${item}")
    else()
      list(APPEND libs "-l${item}")
    endif()
  endforeach()
  set(${out_modules} "${modules}" PARENT_SCOPE)
  set(${out_prefixes} "${prefixes}" PARENT_SCOPE)
  set(${out_libs} "${libs}" PARENT_SCOPE)
endfunction()

function(_lsc_install)
  # Libraries and headers. With both built, lsc::lsc is the shared library and
  # lsc::lsc_static the static one; a static-only build exports it as lsc::lsc.
  # lsc_warnings (compile flags of this build) is a private link item of the
  # static lsc, which CMake carries in its link interface as LINK_ONLY; it means
  # nothing to an installed liblsc.a, so the exported interface leaves it out.
  get_target_property(iface lsc INTERFACE_LINK_LIBRARIES)
  if(iface)
    list(TRANSFORM iface REPLACE "^\\$<LINK_ONLY:lsc_warnings>$"
      "$<BUILD_INTERFACE:$<LINK_ONLY:lsc_warnings>>")
    set_property(TARGET lsc PROPERTY INTERFACE_LINK_LIBRARIES "${iface}")
  endif()

  set(lib_targets lsc)
  if(TARGET lsc_shared)
    list(APPEND lib_targets lsc_shared)
    set_target_properties(lsc_shared PROPERTIES EXPORT_NAME lsc)
    set_target_properties(lsc PROPERTIES EXPORT_NAME lsc_static)
  endif()
  install(TARGETS ${lib_targets} EXPORT lscTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/lsc DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    COMPONENT dev FILES_MATCHING PATTERN "*.h")

  _lsc_link_dependencies(pc_modules pc_prefixes pc_libs)

  # CMake package: relocatable (paths relative to the config file's location).
  install(EXPORT lscTargets NAMESPACE lsc:: DESTINATION ${LSC_INSTALL_CMAKEDIR} COMPONENT dev)
  set(LSC_CONFIG_DEPENDENCIES "")
  list(LENGTH pc_modules n)
  if(n GREATER 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE ${last})
      list(GET pc_prefixes ${i} prefix)
      list(GET pc_modules ${i} module)
      string(APPEND LSC_CONFIG_DEPENDENCIES "list(APPEND _lsc_pkg_deps ${prefix} ${module})\n")
    endforeach()
  endif()
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lscConfig.cmake.in
    ${PROJECT_BINARY_DIR}/lscConfig.cmake INSTALL_DESTINATION ${LSC_INSTALL_CMAKEDIR})
  # While the major version is 0 a minor release may change the API, so a
  # request for 0.1 accepts 0.1.x only; from 1.0 on, any 1.x accepts a 1.y <= x.
  if(PROJECT_VERSION_MAJOR EQUAL 0)
    set(compat SameMinorVersion)
  else()
    set(compat SameMajorVersion)
  endif()
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/lscConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY ${compat})
  install(FILES ${PROJECT_BINARY_DIR}/lscConfig.cmake ${PROJECT_BINARY_DIR}/lscConfigVersion.cmake
    DESTINATION ${LSC_INSTALL_CMAKEDIR} COMPONENT dev)

  # pkg-config: `pkg-config --libs lsc` for the shared library; `--static` adds
  # what liblsc.a needs.
  list(JOIN pc_modules ", " LSC_PC_REQUIRES_PRIVATE)
  list(JOIN pc_libs " " LSC_PC_LIBS_PRIVATE)
  # The prefix is found from the file's own place (${pcfiledir}), so that
  # `cmake --install --prefix X` or a moved install gives a lsc.pc that points
  # at X; an absolute libdir outside the prefix keeps the configured prefix.
  if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(LSC_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  else()
    # one ".." per part of LIBDIR/pkgconfig
    string(REGEX REPLACE "[^/]+" ".." up "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
    set(LSC_PC_PREFIX "\${pcfiledir}/${up}")
  endif()
  if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(LSC_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
  else()
    set(LSC_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  endif()
  if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
    set(LSC_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
  else()
    set(LSC_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
  endif()
  configure_file(${PROJECT_SOURCE_DIR}/lsc.pc.in ${PROJECT_BINARY_DIR}/lsc.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/lsc.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
    COMPONENT dev)

  # The arm profiles (examples/arms), which lsc_arm_open finds by name
  # (lsc/arm.h: --arm xarm): the directory src/CMakeLists.txt compiles in.
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/arms/ DESTINATION ${CMAKE_INSTALL_DATADIR}/lsc/arms
    COMPONENT runtime FILES_MATCHING PATTERN "*.conf")

  # Programs (cli/), when they are part of the build.
  foreach(program lscctl lsc-sim lsc_sim)
    if(TARGET ${program})
      install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT programs)
    endif()
  endforeach()
  file(GLOB man1 ${PROJECT_SOURCE_DIR}/cli/*.1)
  if(man1)
    install(FILES ${man1} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT programs)
  endif()
  set(completion ${PROJECT_SOURCE_DIR}/cli/lscctl.bash-completion)
  if(EXISTS ${completion})
    set(dir "${LSC_BASH_COMPLETION_DIR}")
    if(NOT dir)
      # bash-completion's own completionsdir, moved under this prefix.
      find_package(PkgConfig QUIET)
      if(PKG_CONFIG_FOUND)
        execute_process(COMMAND ${PKG_CONFIG_EXECUTABLE}
          --define-variable=datadir=${CMAKE_INSTALL_FULL_DATADIR}
          --variable=completionsdir bash-completion
          OUTPUT_VARIABLE dir OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      endif()
    endif()
    if(NOT dir)
      set(dir "${CMAKE_INSTALL_DATADIR}/bash-completion/completions")
    elseif(dir MATCHES "^${CMAKE_INSTALL_PREFIX}/(.+)$")
      set(dir "${CMAKE_MATCH_1}") # relative: follows `cmake --install --prefix`
    endif()
    install(FILES ${completion} RENAME lscctl DESTINATION ${dir} COMPONENT programs)
  endif()
  # The udev rule that lets the seat's user and plugdev open an xArm's hidraw
  # node (the Debian package installs the same file with dh_installudev).
  set(rule ${PROJECT_SOURCE_DIR}/debian/lscctl.lsc.udev)
  if(LSC_INSTALL_UDEV AND EXISTS ${rule} AND TARGET lscctl)
    install(FILES ${rule} RENAME 60-lsc.rules DESTINATION ${LSC_UDEV_RULES_DIR}
      COMPONENT programs)
  endif()
endfunction()

if(CMAKE_SOURCE_DIR STREQUAL PROJECT_SOURCE_DIR)
  set(_lsc_top ON)
else()
  set(_lsc_top OFF) # lsc added with add_subdirectory: the parent installs what it needs
endif()
option(LSC_INSTALL "Generate the install rules" ${_lsc_top})
if(LSC_INSTALL)
  if(CMAKE_VERSION VERSION_LESS 3.19)
    message(WARNING "lsc: no install rules (they need CMake 3.19 or later)")
  else()
    cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL _lsc_install)
  endif()
endif()
