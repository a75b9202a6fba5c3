#!/bin/sh
# Installs the build under a temporary prefix, moves the whole prefix elsewhere,
# and builds and runs examples/linux there with find_package(lsc) (lsc::lsc and
# lsc::lsc_static): the CMake package is relocatable and complete.
# Usage: check-install.sh BUILD_DIR SOURCE_DIR C_COMPILER
set -eu
build=$1 src=$2 cc=$3
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lsc-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/first" >"$tmp/install.log"
# everything goes under the prefix given at install time
outside=$(sed -n 's/^-- \(Installing\|Up-to-date\): //p' "$tmp/install.log" | grep -v "^$tmp/first/" || true)
[ -z "$outside" ] || { echo "installed outside the prefix: $outside" >&2; exit 1; }
mv "$tmp/first" "$tmp/moved"
for f in include/lsc/lsc.h include/lsc/core.h; do
  [ -f "$tmp/moved/$f" ] || { echo "not installed: $f" >&2; exit 1; }
done
for kind in shared static; do
  static=OFF
  [ "$kind" = static ] && static=ON
  cmake -S "$src/examples/linux" -B "$tmp/ex-$kind" -DCMAKE_C_COMPILER="$cc" \
    -DCMAKE_PREFIX_PATH="$tmp/moved" -DLSC_EXAMPLE_STATIC=$static >/dev/null
  cmake --build "$tmp/ex-$kind" >/dev/null
  for bin in "$tmp/ex-$kind"/lsc-example "$tmp/ex-$kind"/lsc-battery; do
    [ -x "$bin" ] || continue
    # the imported target's RPATH-free link: point the loader at the moved prefix
    out=$(LD_LIBRARY_PATH="$tmp/moved/lib:$tmp/moved/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$bin")
    echo "$kind $(basename "$bin"): $(printf '%s\n' "$out" | tail -n1)"
  done
done
