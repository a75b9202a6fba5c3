#!/usr/bin/env bash
# Compiles the portable core (or other portable layers) for Cortex-M0+ and AVR
# with -Werror, freestanding, and prints each object's code size.
# Usage: scripts/cross-core.sh [OUTDIR [SRCDIR...]]   (SRCDIR default: src/core)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/cross}
shift || true
dirs=("$@")
[ ${#dirs[@]} -gt 0 ] || dirs=(src/core)
warn=(-std=c99 -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Wcast-align
      -Wundef -Wlogical-op -Werror -ffreestanding -ffunction-sections -fdata-sections -Iinclude)
declare -A cc=(
  [cortex-m0plus]="arm-none-eabi-gcc -mcpu=cortex-m0plus -mthumb -Os"
  [atmega328p]="avr-gcc -mmcu=atmega328p -Os"
)
declare -A size=([cortex-m0plus]=arm-none-eabi-size [atmega328p]=avr-size)
for target in cortex-m0plus atmega328p; do
  mkdir -p "$out/$target"
  objs=()
  for src in $(for d in "${dirs[@]}"; do echo "$d"/*.c; done); do
    obj="$out/$target/$(basename "${src%.c}").o"
    # shellcheck disable=SC2086
    ${cc[$target]} "${warn[@]}" -c "$src" -o "$obj"
    objs+=("$obj")
  done
  echo "== ${dirs[*]} on $target (${cc[$target]}): text = code + constants, bytes"
  ${size[$target]} "${objs[@]}" | awk 'NR==1{print} NR>1{print; t+=$1; d+=$2; b+=$3} END{printf "%7d %7d %7d (total)\n", t, d, b}'
done
