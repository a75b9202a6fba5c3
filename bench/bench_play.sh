#!/usr/bin/env bash
# lscctl play against lsc-sim paced at 9600 baud, over a pseudo-terminal.
# Prints, from lsc-sim's own timestamps (--log: when each frame arrived):
#  1. schedule error: 1000 one-servo keyframes 20 ms apart; each frame's
#     arrival against its due time, relative to the first frame's arrival
#     (median, p99, max of |error|), and the drift (mean error of the last 100
#     frames minus that of the first 100);
#  2. line use: 1000 one-servo keyframes (each a new position) 10 ms apart (faster than the 10.42 ms
#     such a frame takes at 9600 baud) and 11 ms apart (just slower): frames
#     sent, frames dropped, and the share of the line's time their bytes fill
#     from the first frame's arrival to the last's end.
# Usage: bench/bench_play.sh LSCCTL LSC_SIM   (docs/performance.md, Playing action
# files: the build and the figures)
set -euo pipefail
echo "host: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
lscctl=$1
lsc_sim=$2
tmp=$(mktemp -d)
sim_pid=""
trap '[ -z "$sim_pid" ] || kill "$sim_pid" 2>/dev/null; rm -rf "$tmp"' EXIT

# keyframes FILE COUNT MS: one servo, its position changing every keyframe
keyframes() {
  awk -v n="$2" -v ms="$3" 'BEGIN { print "time_ms,1"; for (i = 0; i < n; i++) print ms "," 500 + i }' >"$1"
}

# play FILE LEAD: plays FILE on a fresh lsc-sim; its rx times (s) of moves in $tmp/rx
play() {
  rm -f "$tmp/tty"
  "$lsc_sim" --link "$tmp/tty" --log --baud 9600 >/dev/null 2>"$tmp/log" &
  sim_pid=$!
  for _ in $(seq 500); do [ -e "$tmp/tty" ] && break; sleep 0.01; done
  "$lscctl" --port "$tmp/tty" play "$1" --lead "$2" 2>"$tmp/play.err"
  kill "$sim_pid"; wait "$sim_pid" 2>/dev/null || true
  sim_pid=""
  # time (s) and keyframe (its position - 500) of each one-servo move
  awk 'function digit(c) { return index("0123456789abcdef", tolower(c)) - 1 }
    function hex(h) { return digit(substr(h, 1, 1)) * 16 + digit(substr(h, 2, 1)) }
    $3 == "rx" && $6 == "08" && $7 == "03" { printf "%s %d\n", $2, hex($13) * 256 + hex($12) - 500 }' \
    "$tmp/log" >"$tmp/rx"
}

echo "=== schedule error: 1000 keyframes, one servo, every 20 ms, 9600 baud"
keyframes "$tmp/timing.csv" 1000 20
play "$tmp/timing.csv" 20
# keyframe k (0: the lead-in) is due 20k ms after keyframe 0: its error in ms
awk 'NR == 1 { t0 = $1 } { printf "%d %.3f\n", $2, ($1 - t0) * 1000 - 20 * $2 }' "$tmp/rx" >"$tmp/err"
awk '{ a = $2 < 0 ? -$2 : $2; print a }' "$tmp/err" | sort -g >"$tmp/abs"
n=$(wc -l <"$tmp/err")
echo "frames: $n (want 1000)"
awk -v n="$n" '{ a[NR] = $1 } END {
  printf "|error| ms: median %.3f, p99 %.3f, max %.3f\n", a[int(n * 0.5)], a[int(n * 0.99)], a[n] }' "$tmp/abs"
awk -v n="$n" '{ e[NR] = $2 } END {
  for (k = 1; k <= 100; k++) { first += e[k]; last += e[n + 1 - k] }
  printf "drift: mean error of the last 100 frames - the first 100: %+.3f ms\n", (last - first) / 100 }' "$tmp/err"

for ms in 10 11; do
  echo "=== line use: 1000 keyframes, one servo, every $ms ms, 9600 baud (a frame is 10.417 ms)"
  keyframes "$tmp/fast.csv" 1000 "$ms"
  play "$tmp/fast.csv" "$ms"
  awk -v ms="$ms" '{ t[NR] = $1 } END {
    n = NR; span = (t[n] - t[1]) * 1000 + 10.4167 # from the first arrival to the last end
    printf "frames sent: %d, dropped: %d; line use: %.1f%% (%d x 10.417 ms in %.1f ms)\n", n, 1000 - n, 100 * n * 10.4167 / span, n, span
  }' "$tmp/rx"
  grep -h "dropped" "$tmp/play.err" || true
done
