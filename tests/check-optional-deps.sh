#!/bin/sh
# The optional libraries (cmake/lscOptional.cmake) are looked for at every
# configure: a build tree configured while they were missing finds them once
# they are installed; an explicit -DLSC_WITH_X=OFF stays OFF; ON requires;
# every "OFF" names the Debian package to install. "Missing" is pkg-config
# told to look in an empty directory (PKG_CONFIG_LIBDIR), as on a machine
# without the -dev packages. Configures only (no build).
# Usage: check-optional-deps.sh CMAKE SOURCE_DIR
set -eu
cmake=$1 src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lsc-optional.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
for m in hidapi-hidraw sqlite3 libserialport; do
  pkg-config --exists "$m" 2>/dev/null ||
    { echo "SKIP: pkg-config finds no $m here (scripts/install-deps.sh)"; exit 77; }
done
mkdir "$tmp/empty"
b=$tmp/build
# configure [-D...]: its output in $tmp/out; hidden_configure: pkg-config finds nothing
hidden=0
hidden_configure() { hidden=1; r=0; configure "$@" || r=$?; hidden=0; return $r; }
configure() {
  if [ "$hidden" = 1 ]; then
    set -- env PKG_CONFIG_LIBDIR="$tmp/empty" PKG_CONFIG_PATH= "$cmake" -S "$src" -B "$b" "$@"
  else
    set -- "$cmake" -S "$src" -B "$b" "$@"
  fi
  "$@" >"$tmp/out" 2>&1 || { cat "$tmp/out" >&2; return 1; }
}
says() { grep -qF -- "$1" "$tmp/out" || fail "$2: no '$1' in: $(grep '^-- lsc' "$tmp/out")"; }
hid='lsc HID transport (the xArm on USB)'
d6a='lsc action files: .d6a (SQLite)'
sp='lsc serial transport: libserialport backend and port listing'

# 1. nothing installed: each OFF, naming its package
hidden_configure -DLSC_BUILD_TESTS=OFF -DLSC_BUILD_BENCH=OFF
says "$hid: OFF (pkg-config finds no hidapi-hidraw: install the Debian package libhidapi-dev" "without hidapi"
says "$d6a: OFF (pkg-config finds no sqlite3: install the Debian package libsqlite3-dev" "without SQLite"
says "$sp: OFF (pkg-config finds no libserialport: install the Debian package libserialport-dev" "without libserialport"
grep -q '^LSC_WITH_HIDAPI:STRING=AUTO$' "$b/CMakeCache.txt" || fail "the default is not AUTO: $(grep LSC_WITH_HIDAPI "$b/CMakeCache.txt")"

# 2. "installed" since: the same tree finds them, without being told
configure
says "$hid: ON (hidapi-hidraw" "hidapi installed after the first configure"
says "$d6a: ON (sqlite3" "SQLite installed after the first configure"
says "$sp: ON (libserialport" "libserialport installed after the first configure"

# 3. an explicit OFF stays OFF at the next configures; AUTO takes it back
configure -DLSC_WITH_HIDAPI=OFF
says "$hid: OFF (LSC_WITH_HIDAPI=OFF; -DLSC_WITH_HIDAPI=AUTO uses libhidapi-dev's" "explicit OFF"
configure
says "$hid: OFF (LSC_WITH_HIDAPI=OFF" "explicit OFF, configured again"
configure -DLSC_WITH_HIDAPI=AUTO
says "$hid: ON (hidapi-hidraw" "AUTO after OFF"

# 4. ON requires it: a tree that never found it fails, naming the package
rm -rf "$b"
if hidden_configure -DLSC_BUILD_TESTS=OFF -DLSC_BUILD_BENCH=OFF -DLSC_WITH_SQLITE=ON \
    2>/dev/null; then
  fail "-DLSC_WITH_SQLITE=ON without SQLite configured"
fi
tr -s ' \n' '  ' <"$tmp/out" >"$tmp/flat" # (CMake wraps an error's lines)
grep -qF "LSC_WITH_SQLITE is ON but pkg-config finds no sqlite3 (install the Debian package libsqlite3-dev" "$tmp/flat" ||
  fail "ON without SQLite: $(cat "$tmp/out")"
echo "optional libraries: looked for at every configure, explicit OFF kept, packages named"
