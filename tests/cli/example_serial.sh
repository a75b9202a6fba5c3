#!/usr/bin/env bash
# examples/linux/lsc-serial (built in this tree with the project's warnings)
# against lsc-sim: its output, and each failure's exit status and one-line
# message. (The README's run of it, against an installed library, is in
# tests/check-install.sh and scripts/package-test.sh.)
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"
: "${LSC_SERIAL:?set LSC_SERIAL to the lsc-serial example}"

# invalid command lines: exit 2, nothing opened
for args in "" "a b c" "PORT x" "PORT 256" "PORT -1" "PORT 1x" "PORT ''"; do
  eval "set -- $args"
  expect_out 2 "" "$LSC_SERIAL" "$@" && expect_err_has "usage: lsc-serial PORT [GROUP]"
done

# ports that are not there, or not serial ports: exit 1
expect_out 1 "" "$LSC_SERIAL" "$TMP/nothing"
expect_err_has "$TMP/nothing"
: >"$TMP/file"
expect_out 1 "" "$LSC_SERIAL" "$TMP/file"
expect_err_has "not a serial port"

# the whole run, with the groups of the tests (group 2: 200 ms)
sim board --fast --battery 7400 --groups "$here/groups.txt"
expect_out 0 "battery: 7400 mV
servo 1: moving to 2000 in 500 ms
servo 1: at 2000
group 2: started (1 time)
group 2: finished (1 time)" "$LSC_SERIAL" "$TMP/board" 2
grep -q "rx 55 55 05 06 02 01 00" "$TMP/board.log" || fail "lsc-sim did not get 'run group 2 once': $(cat "$TMP/board.log")"

# a group the board does not have: no "started", exit 3 saying so
expect_out 3 "battery: 7400 mV
servo 1: moving to 2000 in 500 ms
servo 1: at 2000" "$LSC_SERIAL" "$TMP/board" 9
expect_err_has "did not say group 9 started"

# another program has the port: exit 4
expect_busy_program "$TMP/board" "$LSC_SERIAL" "$TMP/board"

# a controller that answers every frame with a battery reply (7400 mV), servo 1
# at 2000, "group 1 started" and "group stopped": the run ends stopped, exit 1
start_peer -r "55 55 04 0F E8 1C 55 55 06 15 01 01 D0 07 55 55 05 06 01 01 00 55 55 02 07"
expect 1 "$LSC_SERIAL" "$TMP/tty" 1
expect_err_has "group 1 was stopped before its end"
grep -qx "battery: 7400 mV" "$OUT" || fail "no battery line: $(cat "$OUT")"
stop_peer

# a board whose servos do not report positions (an LSC board's PWM servos):
# every frame answered with a battery reply, "group 1 started" and "group 1
# complete", never a position reply: said once, the run still goes, exit 0
start_peer -r "55 55 04 0F E8 1C 55 55 05 06 01 01 00 55 55 05 08 01 01 00"
expect 0 "$LSC_SERIAL" "$TMP/tty" 1
grep -qx "servo 1: the controller does not report its position" "$OUT" ||
  fail "no 'does not report' line: $(cat "$OUT")"
grep -q "^group 1: finished" "$OUT" || fail "the run did not finish: $(cat "$OUT")"
stop_peer

# no reply to the battery request: exit 3; a garbled one: exit 1
sim quiet --fast --drop-replies 1
expect_out 3 "" "$LSC_SERIAL" "$TMP/quiet"
expect_err_has "battery: no reply within"
sim garbled --fast --corrupt 1
expect_out 1 "" "$LSC_SERIAL" "$TMP/garbled"
expect_err_has "battery: what came was not the reply asked for"
finish
