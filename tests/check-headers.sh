#!/bin/sh
# Checks that every public header compiles alone: a translation unit that
# includes only include/lsc/X.h builds without warnings as C99 and, when a
# C++ compiler is given, as C++ (each header says what it needs itself).
# Usage: check-headers.sh INCLUDE_DIR C_COMPILER [CXX_COMPILER]
set -eu
inc=$1 cc=$2 cxx=${3:-}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lsc-headers.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
n=0
for h in "$inc"/lsc/*.h; do
  name=$(basename "$h")
  printf '#include "lsc/%s"\nint lsc_header_alone(void);\nint lsc_header_alone(void) { return 0; }\n' "$name" >"$tmp/alone.c"
  "$cc" -std=c99 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -I"$inc" "$tmp/alone.c" ||
    { echo "FAIL: lsc/$name does not compile alone as C99" >&2; exit 1; }
  if [ -n "$cxx" ]; then
    cp "$tmp/alone.c" "$tmp/alone.cpp"
    "$cxx" -std=c++11 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -I"$inc" "$tmp/alone.cpp" ||
      { echo "FAIL: lsc/$name does not compile alone as C++" >&2; exit 1; }
  fi
  n=$((n + 1))
done
echo "$n headers compile alone (C99${cxx:+ and C++})"
