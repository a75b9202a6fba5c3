#!/bin/sh
# Installs the build under a temporary prefix and moves the whole prefix
# elsewhere, then, against the moved prefix:
#  - runs the installed programs, without LD_LIBRARY_PATH: lscctl on its
#    built-in sim, lscd serving it and lscctl through that lscd; none of them
#    loads a library from outside the prefix that the system does not have;
#  - builds examples/linux with find_package(lsc) (lsc::lsc and lsc::lsc_static)
#    and runs each program (lsc-serial against the installed lsc-sim): the CMake
#    package is relocatable and complete;
#  - runs examples/linux/README.md's sections "Under another prefix" and "Run"
#    as shown (tests/cli/docs.py --here, PREFIX = the prefix, no LD_LIBRARY_PATH),
#    and checks that the programs found the prefix's liblsc.so.2 through their
#    RUNPATH; then "Without RUNPATH" (make RPATH= and LD_LIBRARY_PATH).
#    Without python3 (for docs.py) that part is skipped: exit 77.
# Usage: check-install.sh BUILD_DIR SOURCE_DIR C_COMPILER
set -eu
build=$1 src=$2 cc=$3
. "$src/tests/test_time.sh"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lsc-install.XXXXXX")
sim=""
cleanup() {
  if [ -n "$sim" ]; then kill "$sim" 2>/dev/null || true; wait "$sim" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 1' INT TERM
fail() { echo "FAIL: $*" >&2; exit 1; }
# until the background program $sim (WHAT, its stderr in LOG) has made PATH
wait_made() {
  deadline=$(($(date +%s) + $(test_ms 30)))
  until [ -e "$3" ]; do
    if [ "$(date +%s)" -ge "$deadline" ] || ! kill -0 "$sim" 2>/dev/null; then
      fail "$1 did not make $3: $(cat "$2")"
    fi
    sleep 0.01
  done
}
# The programs must find the library through what they were built with, never
# through the caller's environment.
unset LD_LIBRARY_PATH

cmake --install "$build" --prefix "$tmp/first" >"$tmp/install.log"
# everything goes under the prefix given at install time
outside=$(sed -n 's/^-- \(Installing\|Up-to-date\): //p' "$tmp/install.log" | grep -v "^$tmp/first/" || true)
[ -z "$outside" ] || fail "installed outside the prefix: $outside"
mv "$tmp/first" "$tmp/moved"
prefix=$tmp/moved
for f in include/lsc/lsc.h include/lsc/core.h bin/lsc-sim; do
  [ -f "$prefix/$f" ] || fail "not installed: $f"
done
pc=$(find "$prefix" -name lsc.pc)
[ -n "$pc" ] || fail "not installed: lsc.pc"
libdir=$(dirname "$(dirname "$pc")") # lib, or lib/<multiarch> for a build configured for /usr
# lsc.pc finds its prefix from where it lies: after the move it names the new one.
pcprefix=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --variable=prefix lsc)
[ "$(readlink -f "$pcprefix")" = "$(readlink -f "$prefix")" ] ||
  fail "lsc.pc: prefix $pcprefix after a move to $prefix"
# One version everywhere: lsc.pc's, the headers' macros, lsc_version() of the
# installed library.
pcversion=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --modversion lsc)
cat >"$tmp/version.c" <<'EOC'
#include <stdio.h>
#include <string.h>
#include "lsc/lsc.h"
int main(void)
{
    char m[32];
    snprintf(m, sizeof m, "%d.%d.%d", LSC_VERSION_MAJOR, LSC_VERSION_MINOR, LSC_VERSION_PATCH);
    printf("%s %s %s\n", lsc_version(), LSC_VERSION_STRING, m);
    return strcmp(lsc_version(), m) != 0;
}
EOC
# shellcheck disable=SC2046  # pkg-config's flags are words
"$cc" -o "$tmp/version" "$tmp/version.c" $(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags --libs lsc) \
  -Wl,-rpath,"$libdir" || fail "a program against the installed headers and lsc.pc did not build"
out=$("$tmp/version") || fail "lsc_version() is not the headers' version: $out"
[ "$out" = "$pcversion $pcversion $pcversion" ] ||
  fail "versions differ: lsc_version(), LSC_VERSION_STRING, the macros: $out; lsc.pc: $pcversion"
echo "version: $pcversion (lsc.pc, lsc_version(), LSC_VERSION_*)"

# The installed programs run from the moved prefix with nothing in the
# environment: lscctl, then lscd serving sim and lscctl through it.
for program in lscctl lscd; do
  [ -x "$prefix/bin/$program" ] || continue
  missing=$(ldd "$prefix/bin/$program" | grep 'not found' || true)
  [ -z "$missing" ] || fail "installed $program: $missing"
  # a liblsc it loads (if any) is the prefix's own
  lib=$(ldd "$prefix/bin/$program" | sed -n 's/^[[:space:]]*liblsc\.so[.0-9]* => \([^ ]*\).*/\1/p')
  case $lib in "" | "$prefix"/*) ;; *) fail "installed $program loads $lib, not the prefix's" ;; esac
done
if [ -x "$prefix/bin/lscctl" ]; then
  out=$("$prefix/bin/lscctl" --port sim battery) || fail "installed lscctl: exit $?: $out"
  case $out in *"(7500 mV)"*) ;; *) fail "installed lscctl --port sim battery: '$out'" ;; esac
  echo "installed lscctl: --port sim battery: $out"
fi
# The arm profiles, in share/lsc/arms; lscctl finds them by name from any
# directory (the prefix moved: $LSC_ARMS_DIR names where they are now), after
# the user's own in $XDG_CONFIG_HOME/lsc/arms.
for f in xarm learm; do
  [ -f "$prefix/share/lsc/arms/$f.conf" ] || fail "not installed: share/lsc/arms/$f.conf"
done
if [ -x "$prefix/bin/lscctl" ]; then
  mkdir -p "$tmp/elsewhere" "$tmp/config/lsc/arms"
  out=$(cd "$tmp/elsewhere" && XDG_CONFIG_HOME="$tmp/config" LSC_ARMS_DIR="$prefix/share/lsc/arms" \
    "$prefix/bin/lscctl" --port sim --arm xarm read base) || fail "installed lscctl --arm xarm: exit $?: $out"
  [ "$out" = "base:0.00deg" ] || fail "installed lscctl --arm xarm read base: '$out'"
  printf 'hand 3 pwm\n' >"$tmp/config/lsc/arms/xarm.conf" # the user's own comes first
  out=$(cd "$tmp/elsewhere" && XDG_CONFIG_HOME="$tmp/config" LSC_ARMS_DIR="$prefix/share/lsc/arms" \
    "$prefix/bin/lscctl" --port sim --arm xarm read hand) || fail "lscctl --arm xarm (the user's): exit $?: $out"
  [ "$out" = "hand:0.00deg" ] || fail "lscctl --arm xarm read hand with the user's profile: '$out'"
  echo "installed profiles: lscctl --arm xarm from another directory, the user's own first"
fi
if [ -x "$prefix/bin/lscd" ] && [ -x "$prefix/bin/lscctl" ]; then
  "$prefix/bin/lscd" --port sim --socket "$tmp/lscd.sock" >/dev/null 2>"$tmp/lscd.log" &
  sim=$! # (cleaned up like lsc-sim below)
  wait_made "installed lscd" "$tmp/lscd.log" "$tmp/lscd.sock"
  # the socket's file comes with bind(), before lscd listens: wait for an answer
  deadline=$(($(date +%s) + $(test_ms 30)))
  until "$prefix/bin/lscctl" --port "lscd:$tmp/lscd.sock" status >/dev/null 2>&1; do
    if [ "$(date +%s)" -ge "$deadline" ] || ! kill -0 "$sim" 2>/dev/null; then
      fail "installed lscd does not answer on $tmp/lscd.sock: $(cat "$tmp/lscd.log")"
      break
    fi
    sleep 0.01
  done
  out=$("$prefix/bin/lscctl" --port "lscd:$tmp/lscd.sock" battery) ||
    fail "installed lscctl through the installed lscd: exit $?: $out"
  case $out in *"(7500 mV)"*) ;; *) fail "installed lscctl through lscd: '$out'" ;; esac
  kill "$sim"
  status=0
  wait "$sim" || status=$?
  sim=""
  [ "$status" = 0 ] || fail "installed lscd: exit $status on SIGTERM: $(cat "$tmp/lscd.log")"
  echo "installed lscd: served sim to the installed lscctl: $out"
fi

# A virtual board for lsc-serial, from the installed lsc-sim.
"$prefix/bin/lsc-sim" --link "$tmp/board" --groups "$src/examples/groups/arm-demo.txt" \
  >/dev/null 2>"$tmp/sim.log" &
sim=$!
wait_made lsc-sim "$tmp/sim.log" "$tmp/board"

for kind in shared static; do
  static=OFF
  [ "$kind" = static ] && static=ON
  cmake -S "$src/examples/linux" -B "$tmp/ex-$kind" -DCMAKE_C_COMPILER="$cc" \
    -DCMAKE_PREFIX_PATH="$prefix" -DLSC_EXAMPLE_STATIC=$static >/dev/null
  cmake --build "$tmp/ex-$kind" >/dev/null
  for name in lsc-example lsc-battery lsc-serial; do
    bin=$tmp/ex-$kind/$name
    [ -x "$bin" ] || fail "$kind: $name was not built"
    arg=""
    [ "$name" = lsc-serial ] && arg=$tmp/board
    # shellcheck disable=SC2086  # no argument when empty
    out=$("$bin" $arg) || fail "$kind $name: exit $?: $out"
    echo "$kind $name: $(printf '%s\n' "$out" | tail -n1)"
  done
done
kill "$sim"
wait "$sim" 2>/dev/null || true
sim=""

# The README, in a copy of examples/ (its commands use ../groups). It says
# $PREFIX/lib: a build configured for /usr (Debian's: lib/<multiarch>) is
# checked by scripts/package-test.sh instead.
if [ "$libdir" != "$prefix/lib" ]; then
  echo "README: skipped (the library is in ${libdir#"$prefix"/}, the README's commands say lib)"
  exit 0
fi
command -v python3 >/dev/null || { echo "SKIP: README: python3 is not installed (scripts/install-deps.sh --all)"; exit 77; }
readme() { PREFIX=$prefix python3 "$src/tests/cli/docs.py" --here --section "Under another prefix" --section "$1" README.md; }
for copy in runpath ldpath; do
  mkdir -p "$tmp/$copy"
  cp -R "$src/examples/linux" "$src/examples/groups" "$tmp/$copy/"
done
(cd "$tmp/runpath/linux" && readme "Run") ||
  fail "examples/linux/README.md under another prefix (above)"
for bin in "$tmp/runpath/linux/lsc-serial" "$tmp/runpath/linux/build/lsc-serial"; do
  runpath=$(readelf -d "$bin" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]$/\1/p')
  [ "$runpath" = "$libdir" ] || fail "$bin: RUNPATH '$runpath', want $libdir"
  found=$(ldd "$bin" | sed -n 's/^[[:space:]]*liblsc\.so\.2 => \([^ ]*\).*/\1/p')
  [ "$found" = "$libdir/liblsc.so.2" ] || fail "$bin: loads liblsc.so.2 from '$found'"
done
echo "README: RUNPATH $libdir, liblsc.so.2 found there"
(cd "$tmp/ldpath/linux" && readme "Without RUNPATH") ||
  fail "examples/linux/README.md without RUNPATH (above)"
! readelf -d "$tmp/ldpath/linux/lsc-example" | grep -q RUNPATH ||
  fail "make RPATH= left a RUNPATH in lsc-example"
echo "README: make RPATH= builds without RUNPATH; LD_LIBRARY_PATH finds the library"
