#!/usr/bin/env bash
# cmake --install puts lscctl, lsc-sim and lscd, their man pages, lscctl's bash
# completion, the udev rules (60-lsc.rules, 61-lscd.rules) and lscd's systemd
# units in place, where the README's "Installing" says
# (examples/linux/README.md runs the installed lsc-sim).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${BUILD_DIR:?set BUILD_DIR to the build tree}"
checks=$((checks + 1))
cmake --install "$BUILD_DIR" --prefix "$TMP/usr" >"$OUT" 2>&1 || fail "cmake --install: $(cat "$OUT")"
for f in bin/lscctl bin/lsc-sim bin/lscd share/man/man1/lscctl.1 share/man/man1/lsc-sim.1 \
  share/man/man8/lscd.8 share/bash-completion/completions/lscctl \
  lib/systemd/system/lscd@.socket lib/systemd/system/lscd@.service \
  lib/systemd/system/lscd-hid@.socket lib/systemd/system/lscd-hid@.service; do
  checks=$((checks + 1))
  [ -s "$TMP/usr/$f" ] || fail "not installed: $f"
done
expect 0 "$TMP/usr/bin/lscctl" --version
expect 0 "$TMP/usr/bin/lsc-sim" --version
expect 0 "$TMP/usr/bin/lscd" --version
# the udev rule, the Debian package's, unless configured out (-DLSC_INSTALL_UDEV=OFF,
# as the Debian build does: dh_installudev installs it there)
checks=$((checks + 1))
rule=$TMP/usr/lib/udev/rules.d/60-lsc.rules
if [ "${LSC_INSTALL_UDEV:-1}" = 1 ]; then
  cmp -s "$rule" "$here/../../debian/lscctl.lsc.udev" ||
    fail "60-lsc.rules not installed, or not debian/lscctl.lsc.udev"
  cmp -s "${rule%/*}/61-lscd.rules" "$here/../../debian/lscd.lscd.udev" ||
    fail "61-lscd.rules not installed, or not debian/lscd.lscd.udev"
else
  [ ! -e "$rule" ] || fail "60-lsc.rules installed with LSC_INSTALL_UDEV=OFF"
  [ ! -e "${rule%/*}/61-lscd.rules" ] || fail "61-lscd.rules installed with LSC_INSTALL_UDEV=OFF"
fi
finish
