#!/usr/bin/env bash
# Prints a markdown table of flash and RAM, in bytes, at -Os: the portable
# library parts (the sum of their object files, every function included) for
# Cortex-M0+, Cortex-M4 and AVR (ATmega328P), and each example as a whole
# program on its own target (the STM32 firmware, the Arduino sketches built
# for an Uno as the Arduino IDE does). Flash = code + constants + initialised
# data, RAM = initialised + zeroed data (static memory; stack not included).
#
#   scripts/sizes.sh [OUTDIR]       (default build/sizes)
#   scripts/sizes.sh --vendor SKETCH [OUTDIR]
#
# --vendor builds only SKETCH (VendorParity or VendorParityRead) and prints
# its row of the table beside the vendor's figures (at the end of this
# script); exits 1 when its goal is not met, 77 when a tool is missing (the
# tests/embedded size tests run it).
#
# Needs gcc-arm-none-eabi, libnewlib-arm-none-eabi, gcc-avr, avr-libc and
# arduino-core-avr (scripts/install-deps.sh installs them).
set -euo pipefail
cd "$(dirname "$0")/.."
vendor_only=
if [ "${1:-}" = --vendor ]; then
  vendor_only=${2:?--vendor needs a sketch}
  shift 2
fi
out=$(realpath -m "${1:-build/sizes}")
mkdir -p "$out"

flags=(-std=c99 -Os -ffreestanding -ffunction-sections -fdata-sections -Iinclude -Wall -Wextra)
declare -A cc=(
  [m0plus]="arm-none-eabi-gcc -mcpu=cortex-m0plus -mthumb"
  [m4]="arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb"
  [avr]="avr-gcc -mmcu=atmega328p"
)
declare -A size=([m0plus]=arm-none-eabi-size [m4]=arm-none-eabi-size [avr]=avr-size)
declare -A libc=([m0plus]=--specs=nano.specs [m4]=--specs=nano.specs [avr]=)
targets=(m0plus m4 avr)

# "flash ram" of ELF or object files, summed from their sections: code and
# constants (.text*, .rodata*) and initialised data (.data*, in flash and in
# RAM), zeroed data (.bss*, RAM). On AVR, constants not marked PROGMEM are
# copied to RAM at start-up: .rodata counts as data there (the tables marked
# PROGMEM, .progmem*, stay in flash).
measure() {
  local tool=$1; shift
  local ro=text
  [ "$tool" = avr-size ] && ro=data
  "$tool" -A "$@" | awk -v ro="$ro" '
    $1 ~ /^\.rodata/ { if (ro == "data") r += $2; f += $2; next }
    $1 ~ /^\.text/ || $1 ~ /^\.progmem/ { f += $2 }
    $1 ~ /^\.data/ { f += $2; r += $2 }
    $1 ~ /^\.bss/ { r += $2 }
    END { printf "%d %d\n", f, r }'
}

# Compiles the given sources for every target; prints "| name | f r | f r | f r |".
# With linked=1: what a program calling every client function links of them
# (--gc-sections), less the C library's memcpy and memset.
part() {
  local name=$1; shift
  local row="| $name |"
  for t in "${targets[@]}"; do
    local objs=()
    mkdir -p "$out/$t"
    for src in "$@"; do
      local obj
      obj="$out/$t/$(echo "${src%.c}" | tr / _).o"
      # shellcheck disable=SC2086
      ${cc[$t]} "${flags[@]}" -c "$src" -o "$obj"
      objs+=("$obj")
    done
    if [ "${linked:-0}" = 1 ]; then
      local roots=() base=(-Wl,-u,memcpy -Wl,-u,memset) f0 r0
      # (lsc_client_init is a macro over lsc_client_init_checked)
      for fn in $(grep -o 'lsc_client_[a-z_]*(' include/lsc/client.h | tr -d '(' | sort -u |
        grep -vx lsc_client_init); do
        roots+=("-Wl,-u,$fn")
      done
      # shellcheck disable=SC2086
      ${cc[$t]} -Os -nostartfiles -Wl,--gc-sections -Wl,--entry=lsc_client_init_checked "${base[@]}" \
        "${roots[@]}" "${objs[@]}" ${libc[$t]} -o "$out/$t/linked.elf"
      # shellcheck disable=SC2086
      ${cc[$t]} -Os -nostartfiles -Wl,--gc-sections -Wl,--entry=memcpy "${base[@]}" \
        ${libc[$t]} -o "$out/$t/libc.elf"
      read -r f r < <(measure "${size[$t]}" "$out/$t/linked.elf")
      read -r f0 r0 < <(measure "${size[$t]}" "$out/$t/libc.elf")
      row+=" $((f - f0)) | $((r - r0)) |"
    else
      read -r f r < <(measure "${size[$t]}" "${objs[@]}")
      row+=" $f | $r |"
    fi
  done
  echo "$row"
}

# The vendor's sketches cannot be built here (their code is not in the
# repository): their figures are quoted, labelled with where they come from,
# and set beside our sketches' figures as built above (the goal: ours no
# bigger than the vendor's). They were measured by building the example of
# the vendor's LobotServoController Arduino library (Hiwonder's download for
# the LSC boards) with the toolchain named below; docs/performance.md quotes
# the same figures.
# Each line: quoted flash, quoted RAM, the flash ours may have over it (the
# read sketch: what its checks of every reply were measured to cost, 588 B,
# rounded), the flash the size test holds ours to while that goal is not met
# (what it measures now: it may shrink, never grow), our sketch, what the
# vendor's does.
vendor_figures() {
  cat <<'VENDOR'
2800 239 0 2800 VendorParity LobotServoController example
3012 272 600 3612 VendorParityRead the same calls plus a battery read and a six-servo position read
VENDOR
}

# The rows of the vendor table for the sketches named (all: every one);
# returns 1 when a sketch grew past what is held, or its RAM past the goal.
vendor_rows() {
  local f0 r0 extra held s what f r goal verdict status=0
  while read -r f0 r0 extra held s what; do
    [ $# -eq 0 ] || [ "$s" = "$1" ] || continue
    read -r f r < <(measure avr-size "$out/arduino/$s/$s.elf")
    goal="flash <= quoted, RAM <= quoted"
    [ "$extra" -eq 0 ] || goal="flash <= quoted + $extra, RAM <= quoted"
    verdict=""
    [ "$f" -le $((f0 + extra)) ] || verdict="flash over by $((f - f0 - extra)) B"
    [ "$r" -le "$r0" ] || verdict="${verdict:+$verdict, }RAM over by $((r - r0)) B"
    [ "$f" -le "$held" ] || { verdict="${verdict:+$verdict; }grew past the $held B held"; status=1; }
    [ "$r" -le "$r0" ] || status=1
    echo "| $what | $f0 | $r0 | examples/arduino/$s | $f | $r | $goal: ${verdict:-met} |"
  done < <(vendor_figures)
  return $status
}

vendor_head() {
  echo "| vendor sketch (Uno), built outside this repository | flash (quoted) | RAM (quoted) | ours, built here | flash | RAM | goal |"
  echo "|---|---:|---:|---|---:|---:|---|"
}

if [ -n "$vendor_only" ]; then
  vendor_figures | awk -v s="$vendor_only" '$5 == s { found = 1 } END { exit !found }' ||
    { echo "sizes.sh: no vendor figures for $vendor_only" >&2; exit 2; }
  for tool in avr-gcc avr-size make flock; do
    command -v $tool >/dev/null || { echo "SKIP: $tool is not installed"; exit 77; }
  done
  [ -f /usr/share/arduino/hardware/arduino/avr/cores/arduino/Arduino.h ] ||
    { echo "SKIP: the Arduino AVR core (package arduino-core-avr) is not installed"; exit 77; }
  mkdir -p "$out/arduino"
  # one build tree for the sketches; flock keeps parallel runs from racing on it
  unset MAKEFLAGS MFLAGS MAKELEVEL
  flock "$out/arduino/.lock" make -s -f tests/embedded/arduino.mk OUT="$out/arduino" \
    SKETCHES="$vendor_only" LIB_WARN=-w >/dev/null
  vendor_head
  vendor_rows "$vendor_only"
  exit
fi

# the board's codec, and apart from it the bus servos' (src/core/lx_*.c); the
# virtual controller, and apart from it the virtual bus (src/sim/lxbus*.c)
core=() sim=()
for f in src/core/*.c; do [[ $f == */lx_* ]] || core+=("$f"); done
for f in src/sim/*.c; do [[ $f == */lxbus* ]] || sim+=("$f"); done
lx=(src/core/lx_*.c)
lxbus=(src/sim/lxbus*.c)
client=(src/client/*.c)
lxclient=(src/lxclient/*.c)

make -s -C examples/stm32 OUT="$out/stm32" >/dev/null
make -s -f tests/embedded/arduino.mk OUT="$out/arduino" LIB_WARN=-w >/dev/null

echo "| part | Cortex-M0+ flash | RAM | Cortex-M4 flash | RAM | AVR flash | RAM |"
echo "|---|---:|---:|---:|---:|---:|---:|"
part "core (src/core, every function)" "${core[@]}"
part "client (src/client, every function)" "${client[@]}"
part "core + client, all of both" "${core[@]}" "${client[@]}"
linked=1 part "core + client as a program using every client function links them" \
  "${core[@]}" "${client[@]}"
part "virtual controller (src/sim, optional)" "${sim[@]}"
part "bus-servo codec (src/core/lx_*.c, optional)" "${lx[@]}"
part "virtual bus of servos (src/sim/lxbus*.c, optional)" "${lxbus[@]}"
part "bus client (src/lxclient, optional)" "${lxclient[@]}"
part "bus-servo codec + bus client, all of both" "${lx[@]}" "${lxclient[@]}"
read -r f r < <(measure arm-none-eabi-size "$out/stm32/lsc-stm32.elf")
echo "| examples/stm32 (whole firmware, STM32F405) | | | $f | $r | | |"
for d in examples/arduino/*/; do
  s=$(basename "$d")
  read -r f r < <(measure avr-size "$out/arduino/$s/$s.elf")
  echo "| examples/arduino/$s (whole sketch, Uno) | | | | | $f | $r |"
done
echo
echo "Not built by this script (quoted): the example of the vendor's LobotServoController Arduino library,"
echo "built once outside this repository with Debian 12 arduino-core-avr, avr-gcc 5.4 and the Arduino IDE 1.8"
echo "recipe (flash = .text + .data, RAM = .data + .bss; docs/performance.md quotes the same figures),"
echo "beside the sketch of ours that makes the same calls, built above:"
echo
vendor_head
vendor_rows || true
