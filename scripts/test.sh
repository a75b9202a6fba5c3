#!/usr/bin/env bash
# The whole test suite: every stage must pass. Usage: scripts/test.sh [STAGE...]
# Stages: gcc clang release nohid sanitize coverage cross abi analyze valgrind
# s390x fuzz python (the default list), and stress (not in the default list: it
# takes 3 runs of two suites; see stage_stress).
# Build trees go under build/test-*. Every stage builds with warnings as errors
# (-DLSC_WERROR=ON; a plain configure leaves it off, so that a user's build
# never fails on a warning a newer compiler adds).
#
# Wall-clock waits in the tests scale with LSC_TEST_TIME_SCALE (a positive
# integer, default 1; tests/test_time.h, tests/test_time.sh): the sanitize
# stage sets 4 and the valgrind stage 10 unless it is set already. Set it
# higher on a slow machine. A test that needs a tool that is not installed
# is skipped (ctest: "Not Run", with the tool's name in its output).
#
# First it installs the Debian packages the stages use (scripts/install-deps.sh
# --all: nothing happens when they are there; apt's output goes to a log);
# LSC_NO_INSTALL=1 skips that.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -n "${LSC_NO_INSTALL:-}" ] || scripts/install-deps.sh --all
jobs=$(nproc 2>/dev/null || echo 2)
# Tests at once in the whole-suite stages: most of a test's time is spent
# waiting (serial lines at 9600 baud, a servo's move time, another process),
# not computing, so three per core keep the machine busy without starving it
# (measured on 2 cores: the gcc stage's suite in 60 s at -j6, 137 s at -j2).
# LSC_CTEST_JOBS sets another number.
ctest_jobs=${LSC_CTEST_JOBS:-$((3 * jobs))}
# scripts/abi.sh, run by stage abi, configures its own build: it reads this
export LSC_WERROR=ON

# configure + build in build/test-NAME with extra cmake arguments
configure_and_build() {
  local name=$1; shift
  cmake -S . -B "build/test-$name" -DCMAKE_BUILD_TYPE=Debug -DLSC_WERROR=ON "$@" >/dev/null
  cmake --build "build/test-$name" -j "$jobs"
}
# the whole ctest suite of build/test-NAME (the TIMEOUT is a safety limit
# for a hang: the tests derive their waits from the work)
run_ctest() {
  ctest --test-dir "build/test-$1" --output-on-failure --timeout 900 -j "$ctest_jobs"
}
build_and_test() {
  echo "=== $1"
  configure_and_build "$@"
  run_ctest "$1"
}

# the sanitize build's runtime options and time scale, for COMMAND...
sanitize_env() {
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    LSC_TEST_TIME_SCALE=${LSC_TEST_TIME_SCALE:-4} "$@"
}
sanitize_args=(-DCMAKE_C_COMPILER=clang -DLSC_SANITIZE=ON)

stage_gcc() { build_and_test gcc -DCMAKE_C_COMPILER=gcc; }
stage_clang() { build_and_test clang -DCMAKE_C_COMPILER=clang; }
# release: what a user's build from source is, with the optimiser's warnings
# (hidapi and SQLite present), built whole (tests, benchmarks) with warnings as
# errors: the README's CMAKE_BUILD_TYPE Release with gcc (-O3), and a plain
# configure (RelWithDebInfo, -O2) with clang; then, in the first, the tests an
# optimiser could break that take seconds: the units' tests, lscctl's frames,
# the seeded fuzz inputs and the install into a scratch prefix (the whole
# suite runs in the other stages, which build without optimisation).
stage_release() {
  echo "=== release"
  configure_and_build release-default -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo
  configure_and_build release -DCMAKE_C_COMPILER=gcc -DCMAKE_BUILD_TYPE=Release
  ctest --test-dir build/test-release --output-on-failure --timeout 900 -j "$jobs" --no-tests=error \
    -R '^(test_core_.*|test_lx_.*|test_lxbus|test_lxclient|test_client|test_player|test_files|test_sim|test_sim_groups|test_units|test_arm|test_device|test_device_convert|test_hid|example_core|lscctl_frames|lscctl_decode|lscctl_usage|lscctl_help|lsc_install|fuzz_.*)$'
}
# nohid: a build without hidapi (-DLSC_WITH_HIDAPI=OFF) builds, its HID calls
# say "built without HID support", and the serial side still works.
stage_nohid() {
  echo "=== nohid"
  configure_and_build nohid -DCMAKE_C_COMPILER=gcc -DLSC_WITH_HIDAPI=OFF -DLSC_BUILD_BENCH=OFF
  ctest --test-dir build/test-nohid --output-on-failure --timeout 900 -j "$jobs" --no-tests=error \
    -R '^(test_hid_none|lscctl_hid_none|test_client|test_serial|test_sim_client|test_device|lscctl_sim|lscctl_frames|lscctl_ports)$'
}
stage_sanitize() { sanitize_env build_and_test sanitize "${sanitize_args[@]}"; }
stage_coverage() {
  # counts of an earlier run (other sources: gcov refuses to merge them) go first
  if [ -d build/test-coverage ]; then find build/test-coverage -name '*.gcda' -delete; fi
  build_and_test coverage -DCMAKE_C_COMPILER=gcc -DLSC_COVERAGE=ON
  # the portable core, the arm profiles, the device layer, the kinematics and the bus client:
  # every line and every branch
  local dir
  for dir in src/core src/arm src/device src/kinematics src/lxclient; do
    echo "=== coverage of $dir (must be 100% lines and branches)"
    gcovr --root . --filter "$dir/" --object-directory build/test-coverage \
      --exclude-unreachable-branches --print-summary \
      --fail-under-line 100 --fail-under-branch 100 build/test-coverage
  done
}
stage_cross() {
  echo "=== cross"
  scripts/cross-core.sh build/test-cross
  # the other portable layers must build freestanding for MCUs too
  scripts/cross-core.sh build/test-cross-portable src/client src/lxclient src/sim src/player src/units \
    src/kinematics
}
# liblsc.so against the ABI baseline abi/liblsc.abi, then the check's own cases.
stage_abi() { echo "=== abi"; scripts/abi.sh check; scripts/abi-selftest.sh; }

# python: the Python bindings' tests (bindings/python/tests, pytest with Debian's
# python3) over this build's liblsc.so.1, then again on the wheel that
# `pip install ./bindings/python` would install (built with python3 -m build,
# unpacked, imported instead of the tree's package).
stage_python() {
  echo "=== python"
  local dir build targets
  dir=build/test-python
  build=$PWD/$dir
  cmake -S . -B $dir -DCMAKE_BUILD_TYPE=Debug -DLSC_WERROR=ON -DCMAKE_C_COMPILER=gcc \
    -DLSC_BUILD_BENCH=OFF >/dev/null
  # what the tests use (lsc_python_library is lsc_shared in this build)
  targets=(lsc_shared lsc-sim lscd lscctl lsc_python_layout)
  # (grep reads the whole list: with -q it could stop early, cmake then dies of
  # SIGPIPE and pipefail drops the target)
  if cmake --build $dir --target help | grep ' lsc_python_hid_double$' >/dev/null; then
    targets+=(lsc_python_hid_double)
  fi
  cmake --build $dir -j "$jobs" --target "${targets[@]}"
  rm -rf $dir/wheel && mkdir -p $dir/wheel/src $dir/wheel/site
  cp -r bindings/python/. $dir/wheel/src/
  (cd $dir/wheel/src && /usr/bin/python3 -m build --wheel --no-isolation --outdir ../dist >../build.log 2>&1) ||
    { cat $dir/wheel/build.log; return 1; }
  /usr/bin/python3 -m zipfile -e $dir/wheel/dist/lsc-*.whl $dir/wheel/site
  # both runs at once (each test makes its own directories, ports and
  # sockets; the runs mostly wait), the wheel's output after the tree's
  local wheel_rc=0 tree_rc=0 wheel_pid
  env LSC_LIBRARY="$build/src/liblsc.so.1" LSC_SIM="$build/cli/lsc-sim" \
    LSCD="$build/cli/lscd" LSCCTL="$build/cli/lscctl" \
    LSC_LAYOUT="$build/bindings/python/lsc_python_layout" \
    LSC_HID_DOUBLE_LIB="$(ls "$build"/bindings/python/hid-double/liblsc.so.1 2>/dev/null)" \
    PYTHONPATH="$build/wheel/site" PYTHONDONTWRITEBYTECODE=1 \
    /usr/bin/python3 bindings/python/tests/run.py -q >$dir/wheel/test.log 2>&1 &
  wheel_pid=$!
  ctest --test-dir $dir --output-on-failure --timeout 900 --no-tests=error -R '^python_bindings$' ||
    tree_rc=$?
  wait "$wheel_pid" || wheel_rc=$?
  echo "--- the wheel"
  cat $dir/wheel/test.log
  [ "$tree_rc" -eq 0 ] && [ "$wheel_rc" -eq 0 ]
}

# ---- Hardening stages (SECURITY.md) --------------------------------------------
# analyze: clang-tidy (.clang-tidy) and cppcheck on every source; any finding fails.
stage_analyze() {
  echo "=== analyze"
  cmake -S . -B build/test-analyze -DCMAKE_BUILD_TYPE=Debug -DLSC_WERROR=ON \
    -DCMAKE_C_COMPILER=clang -DLSC_ANALYZE=ON >/dev/null
  cmake --build build/test-analyze -j "$jobs" --clean-first
}
# valgrind: every test program the project builds (the tests whose command is
# one of its executables; script-driven tests would check the shell) under
# memcheck; any error or leak fails.
stage_valgrind() {
  echo "=== valgrind"
  local dir=build/test-valgrind programs
  cmake -S . -B $dir -DCMAKE_BUILD_TYPE=Debug -DLSC_WERROR=ON -DCMAKE_C_COMPILER=gcc \
    -DLSC_FUZZ_MUTATIONS=2000 >/dev/null
  cmake --build $dir -j "$jobs"
  programs=$(ctest --test-dir $dir --show-only=json-v1 | python3 -c '
import json, os, sys
build = os.path.realpath(sys.argv[1]) + os.sep
names = [t["name"] for t in json.load(sys.stdin)["tests"]
         if os.path.realpath(t["command"][0]).startswith(build)]
print("^(" + "|".join(names) + ")$")' $dir)
  echo "programs under valgrind: $programs"
  LSC_TEST_TIME_SCALE=${LSC_TEST_TIME_SCALE:-10} ctest --test-dir $dir --output-on-failure -j "$jobs" -R "$programs" -T memcheck \
    --overwrite MemoryCheckCommand="$(command -v valgrind)" \
    --overwrite "MemoryCheckCommandOptions=--error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible"
}
# s390x: big-endian; cross-built and run under qemu-user, linked with Debian's
# cmocka for s390x (libcmocka-dev:s390x, multi-arch). Runs the test programs of
# the portable code (core, client, sim, lscctl's parsers, the seeded fuzz
# harnesses); tests that need ptys, other processes, python or the MCU
# emulators are host-only.
stage_s390x() {
  echo "=== s390x (big-endian, qemu-user)"
  cmake -S . -B build/test-s390x -DCMAKE_TOOLCHAIN_FILE=cmake/s390x-linux-gnu.cmake \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLSC_WERROR=ON -DLSC_FUZZ_MUTATIONS=5000 >/dev/null
  cmake --build build/test-s390x -j "$jobs"
  ctest --test-dir build/test-s390x --output-on-failure -j "$jobs" --no-tests=error \
    -R '^(test_core_.*|test_lx_.*|test_lxbus|test_lxclient|test_client|test_player|test_units|example_core|test_sim|test_sim_groups|test_sim_io|test_sim_client|test_fault_sim|test_lscctl_parse|fuzz_.*)$'
}
# fuzz: every libFuzzer target for LSC_FUZZ_SECONDS (default 10: a short run
# for every change; give it hours before a release) from its seed
# corpus and regression inputs; a finding fails and is kept in build/test-fuzz/findings.
stage_fuzz() {
  echo "=== fuzz"
  local secs=${LSC_FUZZ_SECONDS:-10} dir=build/test-fuzz
  local targets=()
  for t in fuzz/corpus/*/; do
    targets+=("fuzz_$(basename "$t")" "fuzz_$(basename "$t")_libfuzzer")
  done
  cmake -S . -B $dir -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLSC_WERROR=ON -DCMAKE_C_COMPILER=clang -DLSC_FUZZ=ON \
    -DLSC_BUILD_SHARED=OFF >/dev/null
  cmake --build $dir -j "$jobs" --target "${targets[@]}"
  ctest --test-dir $dir --output-on-failure -j "$jobs" -R '^fuzz_'
  rm -rf $dir/findings && mkdir -p $dir/findings
  # one libFuzzer run per target, as many at once as there are cores (each
  # is single-threaded); their reports are printed in order afterwards
  local names=() running=0
  for t in fuzz/corpus/*/; do
    t=$(basename "$t")
    names+=("$t")
    rm -rf "$dir/corpus-$t" && mkdir -p "$dir/corpus-$t"
    cp fuzz/corpus/"$t"/* "$dir/corpus-$t"/
    find fuzz/regress/"$t" -type f ! -name '.*' -exec cp {} "$dir/corpus-$t"/ \;
    if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
    "$dir/fuzz/fuzz_${t}_libfuzzer" -max_total_time="$secs" -print_final_stats=1 \
      -artifact_prefix="$dir/findings/$t-" "$dir/corpus-$t" >"$dir/fuzz-$t.log" 2>&1 &
    running=$((running + 1))
  done
  wait || true
  local found=0
  for t in "${names[@]}"; do
    echo "--- fuzz_$t: ${secs} s"
    grep -E '^(Done|stat::number_of|#[0-9]+ *DONE)|ERROR|property' "$dir/fuzz-$t.log" || true
    if ls "$dir/findings/$t-"* >/dev/null 2>&1; then
      echo "fuzz_$t found a failing input: $(ls "$dir/findings/$t-"*) (log: $dir/fuzz-$t.log)"
      found=1
    fi
  done
  return "$found"
}

# stress: the gcc and the sanitize builds' whole ctest suites, 3 times in a
# row, while stress-ng keeps every core busy twice over (--cpu 2 x nproc:
# 4 on a 2-core machine; started and stopped here). Every run must pass; prints each run's time. Not in the
# default list (CI's time budget): run it before trusting the suite on a
# loaded machine, and after changing how a test waits.
stage_stress() {
  echo "=== stress"
  command -v stress-ng >/dev/null ||
    { echo "stress-ng is not installed (package stress-ng; scripts/install-deps.sh)"; return 1; }
  configure_and_build gcc -DCMAKE_C_COMPILER=gcc
  configure_and_build sanitize "${sanitize_args[@]}"
  # the safety limit only matters if this script is killed without its trap
  stress-ng --cpu "$((2 * $(nproc)))" --timeout 4h --quiet &
  stress_pid=$!
  trap 'kill "$stress_pid" 2>/dev/null; wait "$stress_pid" 2>/dev/null' EXIT
  local run start gcc_s san_s
  for run in 1 2 3; do
    start=$(date +%s)
    echo "--- stress run $run/3: gcc"
    run_ctest gcc
    gcc_s=$(($(date +%s) - start))
    start=$(date +%s)
    echo "--- stress run $run/3: sanitize"
    sanitize_env run_ctest sanitize
    san_s=$(($(date +%s) - start))
    echo "stress run $run/3 passed: gcc suite ${gcc_s} s, sanitize suite ${san_s} s" \
      "(load average $(cut -d' ' -f1-3 /proc/loadavg))" | tee -a build/test-stress.log
  done
  kill "$stress_pid" 2>/dev/null
  wait "$stress_pid" 2>/dev/null || true
  trap - EXIT
}

stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(gcc clang release nohid sanitize coverage cross abi analyze valgrind s390x fuzz python)
all_start=$(date +%s)
for s in "${stages[@]}"; do
  start=$(date +%s)
  "stage_$s"
  echo "=== $s passed in $(($(date +%s) - start)) s"
done
echo "=== all stages passed in $(($(date +%s) - all_start)) s: ${stages[*]}"
