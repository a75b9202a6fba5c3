#!/bin/sh
# Runs a firmware test (run-arduino.sh, run-stm32.sh) as `make -jN test` does:
# with make's jobserver named in the environment but its file descriptors not
# passed on. Here descriptor 3 is open for writing only, so a make that used
# it would stop with "read jobs pipe: Bad file descriptor" as soon as it tried
# to start a second job. BUILD_DIR is emptied first, so that the build has
# jobs to run side by side.
#
#   jobserver.sh BUILD_DIR SCRIPT [ARG...]   (runs SCRIPT BUILD_DIR ARG...)
set -eu
out=$1
script=$2
shift 2
rm -rf "$out"
MAKEFLAGS=" -j2 --jobserver-auth=3,3"
MFLAGS="-j2"
MAKELEVEL=1
export MAKEFLAGS MFLAGS MAKELEVEL
exec "$script" "$out" "$@" 3>/dev/null
