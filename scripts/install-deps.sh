#!/usr/bin/env bash
# Installs Debian 12 packages the project uses. Needs root (or sudo). Safe to
# run again: what is installed already is skipped (nothing to do: no apt-get).
#
# Usage: scripts/install-deps.sh [--all] [PACKAGE...]
#   (no option)  what building the whole tool (lscctl, lsc-sim, lscd, lsc-panel)
#                and scripts/demo.sh need: a C compiler, make, CMake,
#                pkg-config; the libraries of USB HID (the xArm), .d6a files
#                (SQLite), port listing (libserialport) and lsc-panel
#                (libmicrohttpd); and python3, for the README's Python example
#                from the build tree
#   --all        also everything the test suite, the analysers, the embedded
#                tests and the packaging use (scripts/test.sh runs this itself)
#   PACKAGE...   extra packages a stage may ask for
#
# Quiet: one line per step; apt's own output goes to a log file whose path is
# printed, and whose end is shown if a step fails.
set -euo pipefail

# building and the demo. CMake finds the libraries when present (never
# required: cmake/lscOptional.cmake), but a build without them lacks what the
# README shows first: USB HID for the xArm (libhidapi-dev), .d6a files
# (libsqlite3-dev), port listing (libserialport-dev), lsc-panel
# (libmicrohttpd-dev); pkg-config finds them all
packages=(gcc libc6-dev make cmake python3 pkg-config
  libhidapi-dev libsqlite3-dev libserialport-dev libmicrohttpd-dev)
foreign=()
if [ "${1:-}" = --all ]; then
  shift
  packages+=(
    build-essential pkg-config git
    libcmocka-dev
    clang gcovr valgrind cppcheck clang-tidy
    gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi
    gcc-avr avr-libc binutils-avr
    # packaging: the abi stage and scripts/package-test.sh
    abigail-tools debhelper devscripts dpkg-dev fakeroot lintian
    # hardening (SECURITY.md): libFuzzer runtime, big-endian cross build and emulator
    libclang-rt-14-dev gcc-s390x-linux-gnu libc6-dev-s390x-cross qemu-user
  )
  packages+=(python3) # tests/lsc_sim_test.py, tests/cli/docs.py (stdlib only)
  # The embedded tests (tests/embedded): Arduino sketches in simavr, STM32 firmware in QEMU.
  packages+=(simavr libsimavr-dev arduino-core-avr qemu-system-arm util-linux)
  packages+=(bash-completion) # tests/cli/completion.sh: lscctl's bash completion
  packages+=(stress-ng) # scripts/test.sh stress: the suites while every core is busy
  packages+=(sqlite3) # the sqlite3 shell: tests/cli/play.sh builds a .d6a file
  packages+=(zlib1g-dev) # sqlite3's static link (-lz): debian/pc-dev-depends, package-test's --static build
  # the Python bindings (bindings/python): their tests, and python3-lsc's packaging
  # (dh-python with the pyproject plugin and setuptools; autopkgtest runs debian/tests)
  packages+=(python3-pytest dh-python pybuild-plugin-pyproject python3-setuptools python3-all autopkgtest)
  # mypy --strict over the package (bindings/python/tests/test_types.py)
  packages+=(python3-mypy)
  # lsc-panel (panel/) on libmicrohttpd; its page's tests in headless Chromium
  # (tests/panel, bench/bench_panel.py: selenium for Debian's /usr/bin/python3)
  packages+=(libmicrohttpd-dev chromium chromium-driver python3-selenium)
  packages+=(coreutils) # stdbuf: the lsc-sim --log pipeline in cli/lscctl.1 (tests/cli/docs.sh)
  # The s390x stage links Debian's own cmocka for s390x (Multi-Arch: same).
  foreign=(libcmocka-dev:s390x)
fi
packages+=("$@")

# the packages not installed yet (one dpkg-query for all of them)
missing=()
# (a plain name counts only for the native architecture's package: libcmocka-dev:s390x
# alone must not make libcmocka-dev look installed)
installed=$(dpkg-query -W -f='${binary:Package} ${Package} ${Status}\n' 2>/dev/null |
  awk -v native="$(dpkg --print-architecture)" '/ install ok installed$/ {
    print $1; if ($1 !~ /:/ || $1 ~ ":" native "$") print $2 }' | sort -u)
for p in "${packages[@]}" "${foreign[@]}"; do
  grep -qxF -- "$p" <<<"$installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
log=$(mktemp --suffix=.log "${TMPDIR:-/tmp}/lsc-install-deps.XXXXXX")
echo "install-deps: ${#missing[@]} packages to install (${missing[*]}); apt's output goes to $log"
# step WHAT CMD...: one line for WHAT; CMD's output into the log; on failure
# the log's end and its path
step() {
  local what=$1 start=$SECONDS; shift
  printf 'install-deps: %s ... ' "$what"
  if "$@" >>"$log" 2>&1 </dev/null; then
    echo "done ($((SECONDS - start)) s)"
  else
    echo "FAILED"
    echo "--- the end of $log:" >&2
    tail -n 30 "$log" >&2
    echo "install-deps: $what failed; the whole output is in $log" >&2
    exit 1
  fi
}
# s390x packages come from the same archive once dpkg knows the architecture
if [ ${#foreign[@]} -gt 0 ] && ! dpkg --print-foreign-architectures | grep -qx s390x; then
  step "dpkg --add-architecture s390x" $sudo dpkg --add-architecture s390x
fi
step "apt-get update" $sudo apt-get update -q
step "apt-get install" \
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
  -o Dpkg::Use-Pty=0 "${missing[@]}"
