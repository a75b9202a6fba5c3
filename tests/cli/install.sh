#!/usr/bin/env bash
# cmake --install puts lscctl and lsc-sim, their man pages, lscctl's bash
# completion and the udev rule for HID controllers in place
# (examples/linux/README.md runs the installed lsc-sim).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${BUILD_DIR:?set BUILD_DIR to the build tree}"
checks=$((checks + 1))
cmake --install "$BUILD_DIR" --prefix "$TMP/usr" >"$OUT" 2>&1 || fail "cmake --install: $(cat "$OUT")"
for f in bin/lscctl bin/lsc-sim share/man/man1/lscctl.1 share/man/man1/lsc-sim.1 \
  share/bash-completion/completions/lscctl; do
  checks=$((checks + 1))
  [ -s "$TMP/usr/$f" ] || fail "not installed: $f"
done
expect 0 "$TMP/usr/bin/lscctl" --version
expect 0 "$TMP/usr/bin/lsc-sim" --version
# the udev rule, the Debian package's, unless configured out (-DLSC_INSTALL_UDEV=OFF,
# as the Debian build does: dh_installudev installs it there)
checks=$((checks + 1))
rule=$TMP/usr/lib/udev/rules.d/60-lsc.rules
if [ "${LSC_INSTALL_UDEV:-1}" = 1 ]; then
  cmp -s "$rule" "$here/../../debian/lscctl.lsc.udev" ||
    fail "60-lsc.rules not installed, or not debian/lscctl.lsc.udev"
else
  [ ! -e "$rule" ] || fail "60-lsc.rules installed with LSC_INSTALL_UDEV=OFF"
fi
finish
