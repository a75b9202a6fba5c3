#!/usr/bin/env bash
# The whole test suite: every stage must pass. Usage: scripts/test.sh [STAGE...]
# Stages: gcc clang sanitize coverage cross abi. Build trees go under build/test-*.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

# configure + build + ctest in build/test-NAME with extra cmake arguments
build_and_test() {
  local name=$1; shift
  echo "=== $name"
  cmake -S . -B "build/test-$name" -DCMAKE_BUILD_TYPE=Debug "$@" >/dev/null
  cmake --build "build/test-$name" -j "$jobs"
  ctest --test-dir "build/test-$name" --output-on-failure --timeout 300 -j "$jobs"
}

stage_gcc() { build_and_test gcc -DCMAKE_C_COMPILER=gcc; }
stage_clang() { build_and_test clang -DCMAKE_C_COMPILER=clang; }
stage_sanitize() {
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    build_and_test sanitize -DCMAKE_C_COMPILER=clang -DLSC_SANITIZE=ON
}
stage_coverage() {
  build_and_test coverage -DCMAKE_C_COMPILER=gcc -DLSC_COVERAGE=ON
  echo "=== coverage of src/core (must be 100% lines and branches)"
  gcovr --root . --filter 'src/core/' --object-directory build/test-coverage \
    --exclude-unreachable-branches --print-summary \
    --fail-under-line 100 --fail-under-branch 100 build/test-coverage
}
stage_cross() {
  echo "=== cross"
  scripts/cross-core.sh build/test-cross
  # the other portable layers must build freestanding for MCUs too
  scripts/cross-core.sh build/test-cross-portable src/client src/sim
}
# liblsc.so against the ABI baseline abi/liblsc.abi, then the check's own cases.
stage_abi() { echo "=== abi"; scripts/abi.sh check; scripts/abi-selftest.sh; }

stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(gcc clang sanitize coverage cross abi)
for s in "${stages[@]}"; do
  "stage_$s"
done
echo "=== all stages passed: ${stages[*]}"
