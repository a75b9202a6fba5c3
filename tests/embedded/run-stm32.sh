#!/bin/sh
# Builds examples/stm32 with arm-none-eabi-gcc, runs it in QEMU (netduinoplus2,
# an STM32F405) with USART1 wired to the virtual controller
# (lsc_qemu_harness), and compares the exchange and the firmware's exit code
# (semihosting) with tests/embedded/expected/stm32.txt. With LSC_SIM (the
# lsc-sim program), then runs examples/stm32/README.md's "Build and run" as it
# shows it (tests/cli/docs.py --here) in a copy of the tree's include/, src/
# and examples/, with that lsc-sim on PATH (skipped, exit 77, without python3).
#
#   run-stm32.sh BUILD_DIR HARNESS [LSC_SIM]
#
# Exits 77 (ctest: skipped) when a tool is missing, saying which package
# provides it.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$1
harness=$2
lsc_sim=${3:-}

skip() {
    echo "SKIP: $* is not installed"
    exit 77
}
command -v arm-none-eabi-gcc >/dev/null 2>&1 || skip "arm-none-eabi-gcc (package gcc-arm-none-eabi)"
[ -f "$(arm-none-eabi-gcc -print-file-name=nano.specs)" ] ||
    skip "newlib (package libnewlib-arm-none-eabi)"
command -v qemu-system-arm >/dev/null 2>&1 || skip "qemu-system-arm (package qemu-system-arm)"
command -v make >/dev/null 2>&1 || skip "make (package make)"

# A make of its own, not a job of a `make -jN test` above (see run-arduino.sh).
unset MAKEFLAGS MFLAGS MAKELEVEL
mkdir -p "$out"
if ! make -s -C "$root/examples/stm32" OUT="$out" >"$out/build.log" 2>&1; then
    cat "$out/build.log"
    echo "FAIL: building examples/stm32"
    exit 1
fi
status=0
# QEMU runs the firmware in real time: the harness's limit (default 20 s) and
# timeout(1)'s, only for a hang, scale for slow machines (tests/test_time.sh).
. "$here/../test_time.sh"
timeout "$(test_ms 60)" "$harness" --seconds "$(test_ms 20)" --groups "$here/groups.txt" \
    qemu-system-arm netduinoplus2 \
    "$out/lsc-stm32.elf" >"$out/run.log" || status=$?
echo "harness exit status: $status" >>"$out/run.log"
if ! diff -u "$here/expected/stm32.txt" "$out/run.log"; then
    echo "FAIL: the exchange differs from expected/stm32.txt (above)"
    exit 1
fi
echo "ok: stm32"
[ -n "$lsc_sim" ] || exit 0
command -v python3 >/dev/null 2>&1 || skip "python3 (package python3), for examples/stm32/README.md"

copy=$out/readme
rm -rf "$copy"
mkdir -p "$copy"
cp -R "$root/include" "$root/src" "$root/examples" "$copy/"
if ! (cd "$copy/examples/stm32" && PATH=$(dirname "$lsc_sim"):$PATH \
    python3 "$here/../cli/docs.py" --here --section "Build and run" README.md); then
    echo "FAIL: examples/stm32/README.md (above)"
    exit 1
fi
echo "ok: examples/stm32/README.md"
