#!/bin/sh
# Checks that a shared liblsc exports exactly the functions the public headers
# mark LSC_API: nothing internal leaks, nothing public is missing.
# Usage: check-exports.sh NM LIBRARY INCLUDE_DIR
set -eu
nm=$1 lib=$2 inc=$3
tmp=${TMPDIR:-/tmp}/lsc-exports.$$
trap 'rm -f "$tmp".*' EXIT
"$nm" -D --defined-only "$lib" | awk '$2 ~ /^[TDBRVW]$/ {print $3}' | sort >"$tmp.exported"
# declarations: LSC_API <type> [*]name(   (the name is on the LSC_API line)
grep -h 'LSC_API' "$inc"/*.h | sed -n 's/.*[ *]\(lsc_[a-z0-9_]*\)(.*/\1/p' | sort -u >"$tmp.declared"
[ -s "$tmp.declared" ] || { echo "no LSC_API declarations found in $inc" >&2; exit 1; }
if ! diff -u "$tmp.declared" "$tmp.exported"; then
  echo "$lib: exported symbols (+) differ from the LSC_API declarations (-) in $inc" >&2
  exit 1
fi
echo "$lib exports the $(wc -l <"$tmp.declared") LSC_API functions and nothing else"
