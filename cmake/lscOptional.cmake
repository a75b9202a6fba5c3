# lsc_optional(VAR PREFIX MODULE PACKAGE WHAT): an optional library found with
# pkg-config. The cache variable VAR (LSC_WITH_HIDAPI, ...) is
#   AUTO (the default)  used when pkg-config finds MODULE, looked for again at
#                       every configure: a library installed after the first
#                       configure is found by the next one (pkg-config's
#                       results are cached only once found)
#   ON                  required: configuring fails without it
#   OFF                 never used, whatever is installed (an explicit choice,
#                       kept until changed)
# Sets LSC_HAVE_<VAR without LSC_WITH_> here and in the parent scope (ON/OFF);
# when found, PkgConfig::PREFIX (a global imported target) and PREFIX_MODULE_NAME
# (cmake/lscInstall.cmake writes it into lsc.pc). The configure's status line
# says which, and without it the Debian package to install.
# (A macro: pkg_check_modules' results stay in the caller's scope.)
macro(lsc_optional var prefix module package what)
  set(${var} AUTO CACHE STRING
    "${what}: AUTO (when pkg-config finds ${module}, looked for at every configure), ON (required) or OFF")
  set_property(CACHE ${var} PROPERTY STRINGS AUTO ON OFF)
  string(TOUPPER "${${var}}" _lsc_choice)
  string(REPLACE "LSC_WITH_" "LSC_HAVE_" _lsc_have "${var}")
  set(${_lsc_have} OFF)
  if(_lsc_choice STREQUAL "AUTO" OR _lsc_choice)
    find_package(PkgConfig QUIET)
    if(PKG_CONFIG_FOUND)
      pkg_check_modules(${prefix} QUIET IMPORTED_TARGET GLOBAL ${module})
    endif()
    if(${prefix}_FOUND)
      set(${_lsc_have} ON)
      message(STATUS "lsc ${what}: ON (${module} ${${prefix}_VERSION})")
    elseif(_lsc_choice STREQUAL "AUTO")
      message(STATUS "lsc ${what}: OFF (pkg-config finds no ${module}: install the Debian "
        "package ${package}, then configure again)")
    else()
      message(FATAL_ERROR "${var} is ${${var}} but pkg-config finds no ${module} (install the "
        "Debian package ${package}, or configure with -D${var}=AUTO or OFF)")
    endif()
  else()
    message(STATUS "lsc ${what}: OFF (${var}=${${var}}; -D${var}=AUTO uses ${package}'s "
      "${module} when it is installed)")
  endif()
  set(${_lsc_have} ${${_lsc_have}} PARENT_SCOPE)
endmacro()
