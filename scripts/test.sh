#!/usr/bin/env bash
# The whole test suite: every stage must pass. Usage: scripts/test.sh [STAGE...]
# Stages: gcc clang sanitize coverage cross abi analyze valgrind s390x fuzz.
# Build trees go under build/test-*.
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
  scripts/cross-core.sh build/test-cross-portable src/client src/sim src/units
}
# liblsc.so against the ABI baseline abi/liblsc.abi, then the check's own cases.
stage_abi() { echo "=== abi"; scripts/abi.sh check; scripts/abi-selftest.sh; }

# ---- Hardening stages (issue 8; SECURITY.md) ----------------------------------
# analyze: clang-tidy (.clang-tidy) and cppcheck on every source; any finding fails.
stage_analyze() {
  echo "=== analyze"
  cmake -S . -B build/test-analyze -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang \
    -DLSC_ANALYZE=ON >/dev/null
  cmake --build build/test-analyze -j "$jobs" --clean-first
}
# valgrind: every test program the project builds (the tests whose command is
# one of its executables; script-driven tests would check the shell) under
# memcheck; any error or leak fails.
stage_valgrind() {
  echo "=== valgrind"
  local dir=build/test-valgrind programs
  cmake -S . -B $dir -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=gcc \
    -DLSC_FUZZ_MUTATIONS=2000 >/dev/null
  cmake --build $dir -j "$jobs"
  programs=$(ctest --test-dir $dir --show-only=json-v1 | python3 -c '
import json, os, sys
build = os.path.realpath(sys.argv[1]) + os.sep
names = [t["name"] for t in json.load(sys.stdin)["tests"]
         if os.path.realpath(t["command"][0]).startswith(build)]
print("^(" + "|".join(names) + ")$")' $dir)
  echo "programs under valgrind: $programs"
  ctest --test-dir $dir --output-on-failure -j "$jobs" -R "$programs" -T memcheck \
    --overwrite MemoryCheckCommand="$(command -v valgrind)" \
    --overwrite "MemoryCheckCommandOptions=--error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible"
}
# s390x: big-endian; cross-built statically and run under qemu-user. Runs the
# test programs of the portable code (core, client, sim, lscctl's parsers, the
# seeded fuzz harnesses); tests that need ptys, other processes, python or the
# MCU emulators are host-only.
stage_s390x() {
  echo "=== s390x (big-endian, qemu-user)"
  cmake -S . -B build/test-s390x -DCMAKE_TOOLCHAIN_FILE=cmake/s390x-linux-gnu.cmake \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLSC_FUZZ_MUTATIONS=5000 >/dev/null
  cmake --build build/test-s390x -j "$jobs"
  ctest --test-dir build/test-s390x --output-on-failure -j "$jobs" --no-tests=error \
    -R '^(test_cmocka_shim|test_core_.*|test_client|example_core|test_sim|test_sim_groups|test_sim_io|test_sim_client|test_fault_sim|test_units|test_lscctl_parse|fuzz_.*)$'
}
# fuzz: every libFuzzer target for LSC_FUZZ_SECONDS (default 20) from its seed
# corpus and regression inputs; a finding fails and is kept in build/test-fuzz/findings.
stage_fuzz() {
  echo "=== fuzz"
  local secs=${LSC_FUZZ_SECONDS:-20} dir=build/test-fuzz
  local targets=()
  for t in fuzz/corpus/*/; do
    targets+=("fuzz_$(basename "$t")" "fuzz_$(basename "$t")_libfuzzer")
  done
  cmake -S . -B $dir -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DLSC_FUZZ=ON \
    -DLSC_BUILD_SHARED=OFF >/dev/null
  cmake --build $dir -j "$jobs" --target "${targets[@]}"
  ctest --test-dir $dir --output-on-failure -j "$jobs" -R '^fuzz_'
  mkdir -p $dir/findings
  for t in fuzz/corpus/*/; do
    t=$(basename "$t")
    rm -rf "$dir/corpus-$t" && mkdir -p "$dir/corpus-$t"
    cp fuzz/corpus/"$t"/* "$dir/corpus-$t"/
    find fuzz/regress/"$t" -type f ! -name '.*' -exec cp {} "$dir/corpus-$t"/ \;
    echo "--- fuzz_$t: ${secs} s"
    "$dir/fuzz/fuzz_${t}_libfuzzer" -max_total_time="$secs" -print_final_stats=1 \
      -artifact_prefix="$dir/findings/$t-" "$dir/corpus-$t" 2>&1 | grep -E '^(Done|stat::number_of|#[0-9]+ *DONE)|ERROR|property' \
      || true
    if ls "$dir/findings/$t-"* >/dev/null 2>&1; then
      echo "fuzz_$t found a failing input: $(ls "$dir/findings/$t-"*)"; return 1
    fi
  done
}

stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(gcc clang sanitize coverage cross abi analyze valgrind s390x fuzz)
for s in "${stages[@]}"; do
  "stage_$s"
done
echo "=== all stages passed: ${stages[*]}"
