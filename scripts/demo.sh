#!/usr/bin/env bash
# A short demo of lscctl against the virtual controller: builds the programs
# (lscctl, lsc-sim, lscd and lsc-panel, all in build/demo/cli/), serves lsc-sim on a pseudo-terminal with the example arm's
# action groups, then moves servos, reads them back, reads the battery, runs a
# group and waits for it. Needs what scripts/install-deps.sh installs (a C
# compiler, make, CMake, pkg-config; hidapi, SQLite, libserialport and
# libmicrohttpd, without which the build leaves out USB HID, .d6a files, port
# listing and lsc-panel).
# Usage: scripts/demo.sh   (no hardware, no root; measured on a busy 2-core
# machine: 21 s with the build, 5 s once built)
set -euo pipefail
cd "$(dirname "$0")/.."

echo "=== building (build/demo)"
# AUTO: the optional libraries are looked for again (a build/demo configured
# before they were installed, or by an older tree, finds them now); what is
# left out is said, with the package to install
configured=$(cmake -S . -B build/demo -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLSC_BUILD_TESTS=OFF \
  -DLSC_WITH_HIDAPI=AUTO -DLSC_WITH_SQLITE=AUTO -DLSC_WITH_LIBSERIALPORT=AUTO)
grep -E '^-- lsc.*: OFF' <<<"$configured" | sed 's/^-- /demo: /' || true
cmake --build build/demo -j 2 --target lscctl lsc-sim lscd lsc-panel >/dev/null
bindir=$PWD/build/demo/cli
lscctl=$bindir/lscctl
lsc_sim=$bindir/lsc-sim
# the README puts this directory on PATH: every program it uses must be there
for program in lscctl lsc-sim lscd lsc-panel; do
  [ -x "$bindir/$program" ] || { echo "demo: $bindir/$program was not built" >&2; exit 1; }
done

tmp=$(mktemp -d)
sim_pid=""
finish() {
  [ -z "$sim_pid" ] || kill "$sim_pid" 2>/dev/null || true
  [ -z "$sim_pid" ] || wait "$sim_pid" 2>/dev/null || true
  rm -rf "$tmp"
}
trap finish EXIT

echo "=== starting the virtual controller: lsc-sim --groups examples/groups/arm-demo.txt"
"$lsc_sim" --link "$tmp/tty" --groups examples/groups/arm-demo.txt >/dev/null 2>"$tmp/sim.log" &
sim_pid=$!
for _ in $(seq 200); do [ -e "$tmp/tty" ] && break; sleep 0.02; done
[ -e "$tmp/tty" ] || { cat "$tmp/sim.log" >&2; echo "demo: lsc-sim did not start" >&2; exit 1; }
export LSC_PORT="$tmp/tty" # every lscctl below talks to it

# show and run one lscctl command
step() {
  echo
  echo "\$ lscctl $*"
  "$lscctl" "$@"
}

step --dry-run move --time 500 1:2000 2:1200
step move --wait --time 500 1:2000 2:1200
step read 1 2 3
step battery
step --json battery
step -v run 1 --wait
step read 4 5 6
step decode 55 55 05 08 01 01 00
echo
echo "=== done: lscctl, lsc-sim, lscd and lsc-panel are in build/demo/cli/; put them on your PATH with"
echo "  export PATH=$bindir:\$PATH"
echo "then see 'lscctl --help', 'man cli/lscctl.1', and README.md"
