#!/usr/bin/env bash
# The ABI baseline of liblsc.so (abi/liblsc.abi, written by abidw from
# abigail-tools) and the check that keeps the SONAME rule (cmake/lscShared.cmake,
# LSC_ABI_VERSION):
#   scripts/abi.sh check    build liblsc.so and compare it with the baseline.
#                           Fails on a removed or changed public function, type
#                           or variable unless LSC_ABI_VERSION (the SONAME) was
#                           bumped; passes when functions were only added (and
#                           says to record them).
#   scripts/abi.sh update   rewrite abi/liblsc.abi and debian/liblsc<N>.symbols
#                           from the current build; commit them with the change.
# Build tree: build/abi (gcc, RelWithDebInfo: abidw reads the debug info;
# warnings are errors when LSC_WERROR=ON, as scripts/test.sh sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-check}
build=build/abi
baseline=abi/liblsc.abi

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=gcc \
  -DLSC_BUILD_SHARED=ON -DLSC_BUILD_TESTS=OFF -DLSC_WERROR="${LSC_WERROR:-OFF}" >/dev/null
cmake --build "$build" --target lsc_shared -j 2 >/dev/null
lib=$(readlink -f "$build/src/liblsc.so")
# Only what the public headers declare; no paths or line numbers, so the file
# changes only when the ABI does. --drop-undefined-syms: without it abidw 2.2
# describes a function that another file of the library also declares (the
# client calls the core) by that declaration, detached from its symbol, and
# abidiff then misses changes to it.
current="$build/liblsc.abi"
abidw --no-corpus-path --no-comp-dir-path --no-show-locs --type-id-style hash \
  --headers-dir include --drop-private-types --drop-undefined-syms --out-file "$current" "$lib"
# Every exported function must be described with its types, or abidiff cannot
# check it.
nsyms=$(grep -c "<elf-symbol name=.*type='func-type'" "$current" || true)
ndecls=$(grep -c "<function-decl .*elf-symbol-id=" "$current" || true)
if [ "$nsyms" -ne "$ndecls" ]; then
  echo "abi: abidw described $ndecls of the $nsyms exported functions of $lib" >&2
  exit 1
fi
soname_of() { sed -n "s/.*<abi-corpus [^>]*soname='\([^']*\)'.*/\1/p" "$1" | head -n1; }
new_soname=$(soname_of "$current")

# debian/liblsc<N>.symbols: every exported symbol with the version that
# introduced it (kept from the old file; new ones get this version).
write_symbols() {
  local abi=${new_soname##*.so.} version pkg file old
  version=$(sed -n 's/^project(lsc VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
  pkg="liblsc$abi"
  file="debian/$pkg.symbols"
  old=$(cat debian/liblsc*.symbols 2>/dev/null || true)
  {
    echo "$new_soname $pkg #MINVER#"
    echo "* Build-Depends-Package: liblsc-dev"
    nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBRV]$/ {print $3}' | sort | while read -r sym; do
      # (awk reads all of it: one that exits early would kill the writer
      # with SIGPIPE, and under pipefail end this loop half way)
      v=$(awk -v s="$sym@Base" '$1 == s && !seen {print $2; seen = 1}' <<<"$old")
      echo " $sym@Base ${v:-$version}"
    done
  } >"$file"
  echo "wrote $file"
}

case $mode in
update)
  mkdir -p abi
  cp "$current" "$baseline"
  echo "wrote $baseline ($new_soname)"
  write_symbols
  exit 0 ;;
check) ;;
*) echo "usage: $0 [check|update]" >&2; exit 2 ;;
esac

[ -f "$baseline" ] || { echo "abi: no $baseline; run: scripts/abi.sh update" >&2; exit 1; }
old_soname=$(soname_of "$baseline")
if [ "$old_soname" != "$new_soname" ]; then
  echo "abi: SONAME is now $new_soname, the baseline is for $old_soname (LSC_ABI_VERSION" \
       "was bumped): run scripts/abi.sh update, rename the Debian package (README: ABI)" \
       "and commit the new baseline" >&2
  exit 1
fi

# abidiff's exit status is a bit mask: 1 tool error, 2 usage error, 4 ABI
# change, 8 incompatible change. Added functions are compatible: compare
# without them first, so that any change left is one the rule forbids.
set +e
abidiff --no-added-syms --suppressions abi/suppressions.ini "$baseline" "$current" >"$build/abidiff.txt" 2>&1
rc=$?
set -e
if [ $((rc & 3)) -ne 0 ]; then
  cat "$build/abidiff.txt" >&2
  echo "abi: abidiff failed (status $rc)" >&2
  exit 1
fi
if [ $((rc & 12)) -ne 0 ]; then
  cat "$build/abidiff.txt" >&2
  echo "abi: the public ABI of $new_soname changed incompatibly. Undo the change, or" \
       "bump LSC_ABI_VERSION in cmake/lscShared.cmake and run scripts/abi.sh update" >&2
  exit 1
fi
set +e
abidiff --suppressions abi/suppressions.ini "$baseline" "$current" >"$build/abidiff.txt" 2>&1
rc=$?
set -e
if [ "$rc" -ne 0 ]; then
  grep -E '^(Functions|Variables) changes summary|added' "$build/abidiff.txt" || true
  echo "abi: compatible additions to $new_soname; record them with scripts/abi.sh update"
else
  echo "abi: $new_soname matches $baseline"
fi

# The Debian symbols file lists exactly the symbols of the baseline: update
# writes both (a file cut short, or one edited by hand, fails here, not in a
# package build that only warns; symbols added since the baseline are the
# additions reported above).
symfile="debian/liblsc${new_soname##*.so.}.symbols"
if [ -f "$symfile" ]; then
  listed=$(awk 'NR > 2 {sub(/@Base$/, "", $1); print $1}' "$symfile" | sort)
  recorded=$(sed -n "s/.*<elf-symbol name='\([^']*\)'.*/\1/p" "$baseline" | sort -u)
  if [ "$listed" != "$recorded" ]; then
    { diff <(printf '%s\n' "$listed") <(printf '%s\n' "$recorded") || true; } |
      sed -n 's/^[<>]/abi: &/p' >&2
    echo "abi: $symfile does not list exactly the symbols of $baseline (< listed only," \
         "> in the baseline only): run scripts/abi.sh update" >&2
    exit 1
  fi
fi
