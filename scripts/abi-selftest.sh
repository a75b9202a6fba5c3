#!/usr/bin/env bash
# Shows that scripts/abi.sh check enforces the SONAME rule: on copies of the
# committed tree it makes one change each and expects check to pass (added
# function, added enum value) or fail (removed function, changed parameter,
# changed struct layout, SONAME bumped without a new baseline, the Debian
# symbols file cut short).
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d "${TMPDIR:-/tmp}/lsc-abi-selftest.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0

# case NAME EXPECT(pass|fail) FILE SED [FILE SED]...
case_() {
  local name=$1 expect=$2 dir="$work/$1" got
  shift 2
  mkdir -p "$dir"
  git ls-files -z | xargs -0 cp --parents -t "$dir"
  while [ $# -gt 0 ]; do
    grep -q . "$dir/$1"
    cp "$dir/$1" "$dir/$1.orig"
    sed -i "$2" "$dir/$1"
    if cmp -s "$dir/$1" "$dir/$1.orig"; then
      echo "abi-selftest: $name: the edit of $1 changed nothing (stale pattern)" >&2
      exit 1
    fi
    shift 2
  done
  if (cd "$dir" && scripts/abi.sh check >"$dir.log" 2>&1); then got=pass; else got=fail; fi
  if [ "$got" = "$expect" ]; then
    echo "abi-selftest: $name: $got as expected"
  else
    echo "abi-selftest: $name: expected $expect, got $got:" >&2
    cat "$dir.log" >&2
    failures=$((failures + 1))
  fi
  rm -rf "$dir"
}

h=include/lsc/core.h
case_ unchanged pass $h 's|^/\* Forgets any partial frame|/* Forgets any partial frame|; $a /* comment */'
case_ added-function pass \
  $h 's|^LSC_API void lsc_parser_reset(lsc_parser \*p);|&\nLSC_API int lsc_selftest_added(int x);|' \
  src/core/error.c '$a int lsc_selftest_added(int x) { return x; }'
case_ added-enum-value pass $h 's|^    LSC_EINTR = -12 |    LSC_EINTR = -12, LSC_ESELFTEST = -99 |'
case_ removed-function fail $h 's|^LSC_API void lsc_parser_reset|void lsc_parser_reset|'
case_ changed-parameter fail \
  $h 's|lsc_decode_battery_reply(const lsc_frame \*f, uint16_t \*millivolts)|lsc_decode_battery_reply(const lsc_frame *f, uint32_t *millivolts)|' \
  src/core/decode.c 's|lsc_decode_battery_reply(const lsc_frame \*f, uint16_t \*millivolts)|lsc_decode_battery_reply(const lsc_frame *f, uint32_t *millivolts)|'
case_ changed-struct fail $h 's|^    uint32_t errors; |    uint32_t errors; uint32_t selftest;|'
case_ bumped-without-baseline fail cmake/lscShared.cmake 's|^set(LSC_ABI_VERSION \([0-9]*\))|set(LSC_ABI_VERSION 9\1)|'
case_ symbols-file-cut-short fail debian/liblsc2.symbols '$d'

[ "$failures" -eq 0 ] || { echo "abi-selftest: $failures case(s) wrong" >&2; exit 1; }
echo "abi-selftest: all cases as expected"
