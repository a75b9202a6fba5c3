#!/bin/sh
# Builds an example sketch for an Arduino Uno with Debian's Arduino AVR core,
# runs it in simavr with its UART wired to the virtual controller
# (lsc_avr_harness), and compares the exchange, the sketch's console output
# and its exit code with tests/embedded/expected/arduino-<Sketch>.txt.
#
#   run-arduino.sh BUILD_DIR HARNESS SKETCH
#
# Exits 77 (ctest: skipped) when a tool is missing, saying which package
# provides it; HARNESS is empty when libsimavr was not found at configure time.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=$1
harness=$2
sketch=$3

skip() {
    echo "SKIP: $* is not installed"
    exit 77
}
command -v avr-gcc >/dev/null 2>&1 || skip "avr-gcc (package gcc-avr)"
[ -f /usr/lib/avr/include/avr/io.h ] || skip "avr-libc (package avr-libc)"
[ -f /usr/share/arduino/hardware/arduino/avr/cores/arduino/Arduino.h ] ||
    skip "the Arduino AVR core (package arduino-core-avr)"
[ -n "$harness" ] || skip "libsimavr (package libsimavr-dev; then re-run cmake)"
command -v make >/dev/null 2>&1 || skip "make (package make)"
command -v flock >/dev/null 2>&1 || skip "flock (package util-linux)"

# Under `make -jN test` the environment names make's jobserver, whose file
# descriptors ctest did not pass on: the build below would fail reading them
# ("read jobs pipe: Bad file descriptor"). It is a make of its own.
unset MAKEFLAGS MFLAGS MAKELEVEL

# One build tree for every sketch; flock keeps parallel tests from racing on it.
mkdir -p "$out"
flags="-include $here/simavr_console.h"
args=""
case $sketch in
ReadSplit | Joints | OddStreams | ParserRules) flags="$flags -include $here/sketch_check.h" ;;
StaleInput | Running) flags="$flags -include $here/sketch_check.h" args="--groups $here/groups.txt" ;;
ActionGroup) args="--groups $here/groups.txt" ;;
BusServo) args="--lx 3,5 --battery 7400" ;;
VendorParity | VendorParityRead) flags="$flags -include $here/simavr_fast.h" args="--groups $here/groups.txt" ;;
esac
if ! flock "$out/.lock" make -s -f "$here/arduino.mk" OUT="$out" SKETCHES="$sketch" \
    SKETCH_FLAGS="$flags" >"$out/$sketch.build.log" 2>&1; then
    cat "$out/$sketch.build.log"
    echo "FAIL: building $sketch"
    exit 1
fi

status=0
# The harness stops at a cycle limit (simulated time); the wall-clock limit
# is only for a hang, scaled for slow machines (tests/test_time.sh).
. "$here/../test_time.sh"
# shellcheck disable=SC2086
timeout "$(test_ms 120)" "$harness" $args "$out/$sketch/$sketch.elf" >"$out/$sketch.log" || status=$?
echo "harness exit status: $status" >>"$out/$sketch.log"
if ! diff -u "$here/expected/arduino-$sketch.txt" "$out/$sketch.log"; then
    echo "FAIL: $sketch: the exchange differs from expected/arduino-$sketch.txt (above)"
    exit 1
fi
echo "ok: $sketch"
