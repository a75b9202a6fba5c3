#!/usr/bin/env bash
# Installs, from Debian 12's packages, everything the build, the tests and the
# demos use. Needs root (or sudo). Safe to run again: installed packages are skipped.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libcmocka-dev libserialport-dev
  clang gcovr valgrind cppcheck clang-tidy
  gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi
  gcc-avr avr-libc binutils-avr
  # packaging: the abi stage and scripts/package-test.sh
  abigail-tools debhelper devscripts dpkg-dev fakeroot lintian bash-completion
  # hardening (issue 8): libFuzzer runtime, big-endian cross build and emulator
  libclang-rt-14-dev gcc-s390x-linux-gnu libc6-dev-s390x-cross qemu-user
)
packages+=(python3) # tests/lsc_sim_test.py: lsc-sim's pseudo-terminal tests (stdlib only)
# The embedded tests (tests/embedded): Arduino sketches in simavr, STM32 firmware in QEMU.
packages+=(simavr libsimavr-dev arduino-core-avr qemu-system-arm make util-linux)
packages+=(bash-completion) # tests/cli/completion.sh: lscctl's bash completion
packages+=(libhidapi-dev) # the HID transport (src/hid: the xArm over USB)
packages+=(stress-ng) # scripts/test.sh stress: the suites while every core is busy
# The s390x stage links Debian's own cmocka for s390x (Multi-Arch: same).
foreign=(libcmocka-dev:s390x)
packages+=(libsqlite3-dev sqlite3) # .d6a action files (src/files); tests/cli/play.sh builds one
# Extra packages a stage may ask for: scripts/install-deps.sh pkg...
packages+=("$@")

missing=()
for p in "${packages[@]}" "${foreign[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "installing: ${missing[*]}"
# s390x packages come from the same archive once dpkg knows the architecture
dpkg --print-foreign-architectures | grep -qx s390x || $sudo dpkg --add-architecture s390x
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
