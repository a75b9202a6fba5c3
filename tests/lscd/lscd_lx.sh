#!/usr/bin/env bash
# lscd serving a bus of servos: the bus inside the library (--port lx:sim)
# and lsc-sim --lx's on a pseudo-terminal (--port lx:PTY). lscctl through it
# (lscd:lx-NAME): a move of several servos started together, read, "all" as
# a bus's six, unload, halt; what a bus has not (groups, a battery) and values
# out of its range refused with exit 2 and the device's line, nothing sent.
# Environment: LSCD, LSCCTL, LSC_SIM.
mine=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$mine/lib.sh"

export LSC_LSCD_DIR=$TMP/run
T=(--timeout "$(test_ms 10000)")

# serve PORT NAME: lscd on PORT, its socket $TMP/run/NAME.sock
serve() {
  "$LSCD" --port "$1" 2>"$TMP/lscd-$2.log" &
  LSCD_PID=$!
  SIMS+=("$LSCD_PID") # (ended with the test, whatever happens)
  wait_for "lscd did not answer on $TMP/run/$2.sock: $(cat "$TMP/lscd-$2.log")" \
    answers "$TMP/run/$2.sock"
}
stop() {
  kill "$LSCD_PID"
  wait "$LSCD_PID" || fail "lscd exited $? after SIGTERM"
}

serve lx:sim lx-sim
P=("$LSCCTL" --port lscd:lx-sim "${T[@]}")
expect 0 "${P[@]}" status
grep -qx "kind: lx" "$OUT" || fail "lscd's status on lx:sim: $(cat "$OUT")"
expect_out 0 "" "${P[@]}" move --time 200 --wait --tolerance 0 2:700 3:250
expect_out 0 "1:500
2:700
3:250" "${P[@]}" read 1 2 3
expect_out 0 "1:500
2:700
3:250
4:500
5:500
6:500" "${P[@]}" read all
expect_out 0 "" "${P[@]}" unload 2
expect_out 0 "2:700" "${P[@]}" read 2
expect_out 0 "" "${P[@]}" --arm "$mine/../../examples/arms/xarm.conf" move --time 200 --wait \
  --tolerance 0 base:30deg
expect_out 0 "6:625" "${P[@]}" read 6
# refused at lscd with the device's line (the VERDICT's text), nothing sent
expect 2 "${P[@]}" run 1
expect_err_has "lx:sim is a bus of servos, which has no action groups; nothing was sent (lscd at"
expect 2 "${P[@]}" battery
expect_err_has "a bus has no battery reading; a servo's supply voltage: lscctl servo info ID"
expect 2 "${P[@]}" move 1:1001
expect_err_has "position 1001 is out of range for bus servos (0..1000); nothing was sent"
expect_out 0 "" "${P[@]}" halt
expect_out 0 "6:625" "${P[@]}" read 6
# a halt stops a move under way: servo 2 (at 700) on its way to 1000 over
# 20 s stays where the halt found it (unhalted it would go on by 15 a second)
expect_out 0 "" "${P[@]}" move --time 20000 2:1000
expect_out 0 "" "${P[@]}" halt
expect 0 "${P[@]}" read 2
first=$(cat "$OUT")
pos=${first#2:}
[ "$pos" -ge 700 ] && [ "$pos" -lt 1000 ] || fail "after a halt, servo 2 is at $pos"
sleep 1 # (not a synchronisation: the time in which a servo not halted moves)
expect_out 0 "$first" "${P[@]}" read 2
stop

# systemd's instance names a bus: lscd@lx-sim is lx:sim
"$LSCD" --instance lx-sim 2>"$TMP/lscd-instance.log" &
LSCD_PID=$!
SIMS+=("$LSCD_PID")
wait_for "lscd --instance lx-sim did not answer: $(cat "$TMP/lscd-instance.log")" \
  answers "$TMP/run/lx-sim.sock"
expect 0 "$LSCCTL" --port lscd:lx-sim "${T[@]}" status
grep -qx "port: lx:sim" "$OUT" || fail "lscd --instance lx-sim serves: $(cat "$OUT")"
stop

# lsc-sim --lx's bus on its pseudo-terminal
sim bus --lx 1-3 --fast
serve "lx:$TMP/bus" lx-bus
P=("$LSCCTL" --port lscd:lx-bus "${T[@]}")
expect_out 0 "" "${P[@]}" move --time 100 --wait --tolerance 0 1:123 3:900
expect_out 0 "1:123
2:500
3:900" "${P[@]}" read 1 2 3
# the bus's own name reaches it through the lscd that holds it, as a board's
# port does; servo's commands are not passed: refused, nothing sent
expect_out 0 "1:123
3:900" "$LSCCTL" --port "lx:$TMP/bus" "${T[@]}" read 1 3
expect 2 "$LSCCTL" --port "lx:$TMP/bus" "${T[@]}" servo scan 1
expect_err_has "is reached through lscd, which passes moves and reads to a bus but not servo's"
stop
finish
