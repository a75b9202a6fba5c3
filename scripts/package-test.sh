#!/usr/bin/env bash
# The Debian packages, end to end: builds them from this tree (in a temporary
# directory outside it) with dpkg-buildpackage, which also runs the test suite;
# checks them with lintian (no errors, no warnings); installs them; runs
# examples/linux/README.md's Build and Run as shown (tests/cli/docs.py --here: make
# and cmake, each program's output, lsc-serial against the installed lsc-sim);
# builds the examples static too, and runs each; runs the installed
# `lscctl --port sim battery`; imports the installed python3-lsc and runs its
# autopkgtest (debian/tests: the bindings' tests against the installed
# packages); then removes the packages again.
# Needs root or sudo (apt-get install/purge) and scripts/install-deps.sh's
# packages. Usage: scripts/package-test.sh [--keep]  (--keep: leave the work
# directory, with the .debs and the build log, and print its path)
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
keep=0
[ "${1:-}" = "--keep" ] && keep=1
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
# dpkg-buildpackage's parallel=N: make's jobs and the tests ctest runs at
# once. The tests mostly wait (serial lines, moves), so three per core, as
# scripts/test.sh runs them, but at most 6.
jobs=$((3 * $(nproc 2>/dev/null || echo 2)))
[ "$jobs" -le 6 ] || jobs=6
# tests/cli/docs.py runs the example README
command -v python3 >/dev/null || { echo "package: python3 is needed (scripts/install-deps.sh --all)" >&2; exit 1; }

version=$(dpkg-parsechangelog -S Version)
upstream=${version%-*}
work=$(mktemp -d "${TMPDIR:-/tmp}/lsc-package-test.XXXXXX")
packages=()
sim=""
cleanup() {
  local rc=$?
  if [ -n "$sim" ]; then kill "$sim" 2>/dev/null; wait "$sim" 2>/dev/null; fi
  if [ ${#packages[@]} -gt 0 ]; then
    echo "=== package: removing ${packages[*]}"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get purge -y -q "${packages[@]}" >"$work/purge.log" 2>&1 ||
      { cat "$work/purge.log" >&2; rc=1; }
  fi
  if [ "$keep" -eq 1 ]; then echo "kept $work"; else rm -rf "$work"; fi
  exit $rc
}
trap cleanup EXIT

echo "=== package: build lsc $version in $work"
src="$work/lsc-$upstream"
mkdir -p "$src"
# The working tree as it is (tracked and new files, not ignored ones such as build/).
git ls-files --cached --others --exclude-standard --deduplicate | while IFS= read -r f; do
  [ ! -e "$f" ] || printf '%s\0' "$f"
done | xargs -0 cp --parents -t "$src"
profiles=()
if [ ! -f cli/lscctl.c ]; then
  echo "=== package: no lscctl in this tree yet: building without the lscctl package"
  profiles=(-Ppkg.lsc.nocli)
fi
if ! (cd "$src" && dpkg-buildpackage -us -uc -b -j"$jobs" "${profiles[@]}") >"$work/build.log" 2>&1; then
  tail -n 60 "$work/build.log" >&2
  echo "package: dpkg-buildpackage failed (log: $work/build.log, kept)" >&2
  keep=1
  exit 1
fi
grep -E '^(Test project|[0-9]+% tests passed|100% tests|No tests were found)' "$work/build.log" || true
debs=()
for deb in "$work"/*.deb; do
  case $deb in *-dbgsym_*) ;; *) debs+=("$deb") ;; esac
done
for deb in "${debs[@]}"; do echo "    $(basename "$deb")"; done
ls "$work"/python3-lsc_*_all.deb >/dev/null 2>&1 ||
  { echo "package: no python3-lsc package was built" >&2; exit 1; }

echo "=== package: lintian"
# (as root lintian adds a note on stderr that it prefers not to be root)
if ! lintian --fail-on error,warning --display-info "$work"/*.changes >"$work/lintian.log" 2>/dev/null; then
  cat "$work/lintian.log" >&2
  echo "package: lintian reports errors or warnings" >&2
  exit 1
fi
sed 's/^/    /' "$work/lintian.log"
echo "    no errors, no warnings"

echo "=== package: install"
for deb in "${debs[@]}"; do packages+=("$(dpkg-deb -f "$deb" Package)"); done
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${debs[@]}" \
  >"$work/install.log" 2>&1 || { cat "$work/install.log" >&2; exit 1; }

echo "=== package: the shared library exports only the public API (lsc_*)"
runtime=$(printf '%s\n' "${packages[@]}" | grep -E '^liblsc[0-9]+$')
lib=$(dpkg -L "$runtime" | grep -E '/liblsc\.so\.[0-9]+$' | head -n1)
exported=$(nm -D --defined-only "$lib" | awk '{print $3}')
others=$(printf '%s\n' "$exported" | grep -v '^lsc_' || true)
[ -z "$others" ] || { echo "package: $lib exports non-API symbols: $others" >&2; exit 1; }
echo "    $lib: $(printf '%s\n' "$exported" | wc -l) symbols, all lsc_*"

echo "=== package: examples/linux against the installed library"
mkdir -p "$work/examples"
cp -r examples/linux examples/groups "$work/examples/"
ex="$work/examples/linux"
board=""
if [ ${#profiles[@]} -eq 0 ]; then
  # a virtual board for lsc-serial, from the installed lscctl package
  lsc-sim --link "$work/board" --groups examples/groups/arm-demo.txt >/dev/null 2>"$work/sim.log" &
  sim=$!
  deadline=$((SECONDS + $(. tests/test_time.sh && test_ms 30)))
  until [ -e "$work/board" ] || ! kill -0 "$sim" 2>/dev/null || [ $SECONDS -ge $deadline ]; do sleep 0.01; done
  [ -e "$work/board" ] || { echo "package: lsc-sim did not start: $(cat "$work/sim.log")" >&2; exit 1; }
  board="$work/board"
fi
# The README's Build and Run as it shows them (make, cmake -B build, each
# program's output); without the lscctl package (no lsc-sim) only Build.
readme=(--section "Build" --section "Run")
[ -n "$board" ] || readme=(--section "Build")
(cd "$ex" && python3 "$OLDPWD/tests/cli/docs.py" --here "${readme[@]}" README.md) | sed 's/^/    /'
# run_examples HOW DIR SHARED: runs every example built in DIR, which must (1) or
# must not (0) use liblsc.so
run_examples() {
  local how=$1 dir=$2 shared=$3 bin n=0 args
  for bin in "$dir"/lsc-example "$dir"/lsc-battery "$dir"/lsc-serial; do
    [ -x "$bin" ] || continue
    if [[ $(ldd "$bin") == *liblsc.so.* ]]; then
      [ "$shared" -eq 1 ] || { echo "package: $how: $bin uses liblsc.so" >&2; exit 1; }
    else
      [ "$shared" -eq 0 ] || { echo "package: $how: $bin is not linked to liblsc.so" >&2; exit 1; }
    fi
    args=()
    if [ "$(basename "$bin")" = lsc-serial ]; then
      [ -n "$board" ] || continue
      args=("$board")
    fi
    # a failing example fails the test (a status inside printf's arguments is lost)
    local out
    out=$("$bin" "${args[@]}") || { echo "package: $how: $bin failed (exit $?)" >&2; exit 1; }
    printf '    %-24s %-12s %s\n' "$how:" "$(basename "$bin")" "${out##*$'\n'}"
    n=$((n + 1))
  done
  [ "$n" -gt 0 ] || { echo "package: $how: nothing built" >&2; exit 1; }
}
run_examples "pkg-config" "$ex" 1
run_examples "find_package lsc::lsc" "$ex/build" 1
make -s -C "$ex" clean >/dev/null
make -s -C "$ex" STATIC=1 >/dev/null
run_examples "pkg-config --static" "$ex" 0
cmake -S "$ex" -B "$ex/build-static" -DLSC_EXAMPLE_STATIC=ON >/dev/null
cmake --build "$ex/build-static" >/dev/null
run_examples "find_package lsc_static" "$ex/build-static" 0
if [ -n "$sim" ]; then kill "$sim"; wait "$sim" 2>/dev/null || true; sim=""; fi

echo "=== package: lscctl"
if [ ${#profiles[@]} -eq 0 ]; then
  # what the package holds (read from the .deb: minimal images skip installing man pages)
  contents=$(dpkg-deb -c "$work"/lscctl_*.deb | awk '{print $6}')
  for f in ./usr/bin/lscctl ./usr/bin/lsc-sim ./usr/share/man/man1/lscctl.1.gz \
           ./usr/share/man/man1/lsc-sim.1.gz ./usr/share/bash-completion/completions/lscctl; do
    printf '%s\n' "$contents" | grep -qx "$f" || { echo "package: lscctl lacks $f" >&2; exit 1; }
  done
  echo "    lscctl, lsc-sim, their man pages and the completion are in the package"
  # the udev rule for the xArm's hidraw node, in the udev rules directory
  rule=$(printf '%s\n' "$contents" | grep -E '^\./(usr/)?lib/udev/rules\.d/60-lsc\.rules$' || true)
  [ -n "$rule" ] || { echo "package: lscctl lacks the udev rule 60-lsc.rules" >&2; exit 1; }
  installed=$(dpkg -L lscctl | grep -E '/udev/rules\.d/60-lsc\.rules$' | head -n1)
  [ -n "$installed" ] && grep -q 'SUBSYSTEM=="hidraw", ATTRS{idVendor}=="0483", ATTRS{idProduct}=="5750".*TAG+="uaccess"' "$installed" ||
    { echo "package: the installed udev rule does not match the xArm's hidraw node" >&2; exit 1; }
  echo "    udev rule: $installed"
  # lsc-panel: its package holds the program, its man page and its unit
  contents=$(dpkg-deb -c "$work"/lsc-panel_*.deb | awk '{print $6}')
  for f in ./usr/bin/lsc-panel ./usr/share/man/man1/lsc-panel.1.gz \
           ./usr/lib/systemd/system/lsc-panel@.service; do
    printf '%s\n' "$contents" | grep -qx "$f" || { echo "package: lsc-panel lacks $f" >&2; exit 1; }
  done
  echo "    lsc-panel, its man page and its systemd unit are in the package: $(lsc-panel --version)"
  # the arm profiles (lsc-arms), found by name from any directory
  for f in xarm learm; do
    dpkg -L lsc-arms | grep -qx "/usr/share/lsc/arms/$f.conf" ||
      { echo "package: lsc-arms lacks /usr/share/lsc/arms/$f.conf" >&2; exit 1; }
  done
  echo "    \$ lscctl --port sim --arm xarm read base   # in /"
  out=$(cd / && env -u LSC_ARMS_DIR XDG_CONFIG_HOME="$work/no-config" lscctl --port sim --arm xarm read base) ||
    { echo "package: lscctl --arm xarm does not find the installed profile" >&2; exit 1; }
  echo "    $out"
  [ "$out" = base:0.00deg ] || { echo "package: lscctl --arm xarm read base printed $out" >&2; exit 1; }
  echo "    \$ lscctl --port sim battery"
  lscctl --port sim battery | sed 's/^/    /'
else
  echo "    skipped: lscctl is not on this tree yet (no cli/lscctl.c)"
fi

echo "=== package: python3-lsc"
# Debian's python3 by path (another one may come first on PATH)
echo "    \$ python3 -c 'import lsc; print(lsc.open(\"sim\").battery())'"
out=$(cd / && /usr/bin/python3 -c 'import lsc; print(lsc.open("sim").battery())') ||
  { echo "package: the installed python3-lsc does not work" >&2; exit 1; }
echo "    $out"
[ "$out" = 7500 ] || { echo "package: python3-lsc read $out, not 7500" >&2; exit 1; }
# its autopkgtest (debian/tests) against the installed packages, on this machine
if ! autopkgtest -B -o "$work/autopkgtest" "$src" -- null >"$work/autopkgtest.log" 2>&1; then
  tail -n 60 "$work/autopkgtest.log" >&2
  echo "package: the autopkgtest of python3-lsc failed (log: $work/autopkgtest.log, kept)" >&2
  keep=1
  exit 1
fi
grep -E '^(python3-lsc|=== python|[0-9]+ passed)' "$work/autopkgtest.log" | sed 's/^/    /' || true

echo "=== package: passed in $(( $(date +%s) - start )) s"
