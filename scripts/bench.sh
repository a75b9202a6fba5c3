#!/usr/bin/env bash
# The core's cost: the parser's speed on this host (ns/byte, bytes/s, and
# instructions/byte counted by callgrind, byte at a time and through the bulk
# path lsc_parser_feed_buf), then the code size of each core
# object and function on Cortex-M0+ and AVR. Usage: scripts/bench.sh [MEGABYTES]
# Build tree: build/bench (Release). The figures go in docs/performance.md.
set -euo pipefail
cd "$(dirname "$0")/.."
mb=${1:-4}

echo "=== build (Release: $(cc --version | head -n1))"
cmake -S . -B build/bench -DCMAKE_BUILD_TYPE=Release -DLSC_BUILD_TESTS=OFF -DLSC_BUILD_BENCH=ON >/dev/null
cmake --build build/bench -j 2 >/dev/null
bench=build/bench/bench/bench_parser

echo "=== parser speed on $(uname -m)"
"$bench" "$mb" 5

# Instructions executed inside function FN (and what it calls) per byte of a
# 1 MiB stream. Usage: instructions FN LABEL [long]
instructions() {
  local fn=$1 what=$2; shift 2
  local out; out=$(mktemp)
  local log; log=$(valgrind --tool=callgrind --callgrind-out-file="$out" \
                  --toggle-collect="$fn" "$bench" 1 1 "$@" 2>&1)
  rm -f "$out"
  local bytes; bytes=$(sed -n 's/^parser: \([0-9]*\) bytes.*/\1/p' <<<"$log")
  local ir; ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' <<<"$log")
  awk -v ir="$ir" -v n="$bytes" -v what="$what" -v fn="$fn" \
    'BEGIN { printf "parser: %5.1f instructions/byte in %s (%s: %d instructions for %d bytes)\n", ir / n, fn, what, ir, n }'
}
if command -v valgrind >/dev/null; then
  echo "=== parser instructions/byte (valgrind --tool=callgrind --toggle-collect=FN)"
  mixed="replies, notifications, 5% noise"
  instructions lsc_parser_feed "$mixed, byte at a time: the call alone"
  instructions feed_bytes "$mixed, byte at a time: the call and the loop around it"
  instructions lsc_parser_feed_buf "$mixed, bulk path: the call alone (goal: <= 10)"
  instructions feed_bulk "$mixed, bulk path: the call and the loop around it"
  instructions lsc_parser_feed "frames of LEN 255, byte at a time: the call alone" long
  instructions lsc_parser_feed_buf "frames of LEN 255, bulk path: the call alone" long
  # The vendor's receive path on the same mixed stream (bench/bench_vendor.c):
  # with the Stream calls it makes (as it runs on an Arduino), and its own
  # instructions alone (callgrind_annotate's self cost of vendor_receive).
  instructions vendor_receive "$mixed, the vendor's receive path: the handler and its Stream calls"
  out=$(mktemp)
  log=$(valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=vendor_receive \
        "$bench" 1 1 2>&1)
  bytes=$(sed -n 's/^parser: \([0-9]*\) bytes.*/\1/p' <<<"$log")
  own=$(callgrind_annotate "$out" | awk '/:vendor_receive / { gsub(",", "", $1); print $1 }')
  rm -f "$out"
  awk -v ir="$own" -v n="$bytes" \
    'BEGIN { printf "parser: %5.1f instructions/byte in vendor_receive alone, without its Stream calls (%d instructions for %d bytes)\n", ir / n, ir, n }'
else
  echo "=== valgrind not installed: no instructions/byte (scripts/install-deps.sh installs it)"
fi

echo "=== code size"
scripts/cross-core.sh build/bench/cross
for target in cortex-m0plus atmega328p; do
  nm=arm-none-eabi-nm
  [ "$target" = atmega328p ] && nm=avr-nm
  echo "== functions and tables on $target, bytes (t/T code, r/R constants)"
  for obj in build/bench/cross/"$target"/*.o; do
    $nm -S --size-sort -t d "$obj" | awk -v o="$(basename "$obj")" '{ printf "%-8s %5d %s %s\n", o, $2, $3, $4 }'
  done
done
echo "== the vendor's receive path as bench/bench_vendor.c rewrites it, on cortex-m0plus (-Os), bytes"
arm-none-eabi-gcc -mcpu=cortex-m0plus -mthumb -Os -std=c99 -ffreestanding -ffunction-sections \
  -c bench/bench_vendor.c -o build/bench/cross/vendor.o
arm-none-eabi-nm -S --size-sort -t d build/bench/cross/vendor.o |
  awk '{ printf "%-8s %5d %s %s\n", "vendor", $2, $3, $4 }'
# The two side by side: the whole parser (every function of parser.o, its
# table included), the byte path alone (lsc_parser_feed, the rules it calls
# and their table), and the vendor's handler.
m0=build/bench/cross/cortex-m0plus
whole=$(arm-none-eabi-size -A "$m0/parser.o" | awk '$1 ~ /^\.(text|rodata)/ { s += $2 } END { print s }')
bytepath=$(arm-none-eabi-nm -S -t d "$m0/parser.o" |
  awk '$4 == "lsc_parser_feed" || $4 == "reject" || $4 == "shapes" { s += $2 } END { print s }')
vendor=$(arm-none-eabi-nm -S -t d build/bench/cross/vendor.o | awk '$4 == "vendor_receive" { print $2 + 0 }')
echo "== on cortex-m0plus (-Os): parser.o $whole B, its byte path (lsc_parser_feed, reject, shapes) $bytepath B; the vendor's vendor_receive $vendor B"
