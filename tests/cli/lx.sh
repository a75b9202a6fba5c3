#!/usr/bin/env bash
# lscctl on a bus of serial bus servos (--port lx:PATH) served by lsc-sim --lx
# over a pseudo-terminal: the board's commands with the same words (move of
# several servos started together, read, unload, --wait, settle by reading,
# an arm profile), the bus's default baud rate, and what a bus has not
# (action groups, the board's battery) refused with exit 2 and not one byte
# sent (lsc-sim --log shows what arrived).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

# frames_in NAME: the frames lsc-sim received
frames_in() { grep -aE ' rx ' "$TMP/$1.log" | sed 's/.* rx /rx /'; }

T=(--timeout "$(test_ms 10000)")
sim bus --lx 1-6
P=("$LSCCTL" --port "lx:$TMP/bus" "${T[@]}")

# a move of two servos: MOVE_TIME_WAIT_WRITE to each, then one broadcast
# MOVE_START; --wait reads positions until they are there
expect_out 0 "" "${P[@]}" move --time 300 --wait --tolerance 0 2:700 3:250
want="rx 55 55 02 07 07 BC 02 2C 01 04
rx 55 55 03 07 07 FA 00 2C 01 C7
rx 55 55 FE 03 0B F3"
[ "$(frames_in bus | head -3)" = "$want" ] ||
  fail "a move of two servos on a bus sent: $(frames_in bus | head -3)"
expect_out 0 "1:500
2:700
3:250" "${P[@]}" read 1 2 3
expect_out 0 "" "${P[@]}" unload 2
expect_out 0 "2:700" "${P[@]}" read 2
# --json: a board's objects, so a script reads a bus and a board alike
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":2,"position":700}]}' \
  "${P[@]}" --json read 2
before=$(frames_in bus | wc -l)

# refused, nothing sent: out of the bus's ranges, what a bus has not
expect 2 "${P[@]}" move 1:1001
expect_err_has "position 1001 is out of range for bus servos (0..1000); nothing was sent"
expect 2 "${P[@]}" move --time 30001 1:100
expect_err_has "out of range for bus servos (0..30000)"
expect 2 "${P[@]}" battery
expect_err_has "a bus has no battery reading; a servo's supply voltage: lscctl servo info ID"
expect 2 "${P[@]}" run 1
expect_err_has "is a bus of servos, which has no action groups; nothing was sent"
expect 2 "${P[@]}" stop
expect_err_has "which has no action groups"
expect 2 "${P[@]}" speed 1 50
expect_out 0 "1:500" "${P[@]}" read 1
[ "$(frames_in bus | tail -n +$((before + 1)))" = "rx 55 55 01 03 1C DF" ] ||
  fail "refused commands sent bytes to the bus: $(frames_in bus | tail -n +$((before + 1)))"

# a servo that is not there: exit 3, the line names it and where to look
expect 3 "$LSCCTL" --port "lx:$TMP/bus" --timeout "$(test_ms 200)" read 9
expect_err_has "no reply from servo 9 on lx:$TMP/bus"
expect_err_has "baud rate (115200)"
# the baud rate given is the one the line names (a pseudo-terminal has none)
expect 3 "$LSCCTL" --port "lx:$TMP/bus" --baud 9600 --timeout "$(test_ms 200)" read 9
expect_err_has "baud rate (9600)"

# an arm profile: xarm.conf's joints are the xArm's bus servos (1..6)
expect_out 0 "" "${P[@]}" --arm "$here/../../examples/arms/xarm.conf" move --time 200 --wait --tolerance 0 \
  base:30deg
expect_out 0 "6:625" "${P[@]}" read 6

# "all" on a bus: the xArm's six servos
expect_out 0 "1:500
2:700
3:250
4:500
5:500
6:625" "${P[@]}" read all

# --dry-run prints a board's frames: refused on a bus (-v shows its frames)
expect 2 "${P[@]}" -n move 1:100
expect_err_has "--dry-run prints a board's frames; a bus of servos (lx:PATH) gets others"
expect_out 0 "1:500" "${P[@]}" -v read 1
grep -qF "lscctl: sent bus frame: servo 1, command 28 (55 55 01 03 1C DF)" "$ERR" ||
  fail "-v on a bus: $(cat "$ERR")"

# lx: without a path
expect 2 "$LSCCTL" --port lx: read 1
expect_err_has "lx: needs the path of the bus's serial port"

# a bus that echoes the host's bytes (a one-wire bus) reads the same
sim echo --lx 1-3 --echo
expect_out 0 "" "$LSCCTL" --port "lx:$TMP/echo" "${T[@]}" move --time 0 --wait --tolerance 0 1:123
expect_out 0 "1:123
2:500" "$LSCCTL" --port "lx:$TMP/echo" "${T[@]}" read 1 2

# the virtual bus inside the library: lx:sim (servos 1..6), lx:sim:IDS; each
# open starts afresh, so a move and its read are one run (--wait reads back)
expect_out 0 "1
2
3
4
5
6" "$LSCCTL" --port lx:sim "${T[@]}" servo scan 0-9
expect_out 0 "3
9" "$LSCCTL" --port lx:sim:3,9 "${T[@]}" servo scan
expect_out 0 "" "$LSCCTL" --port lx:sim "${T[@]}" move --time 100 --wait --tolerance 0 2:700
expect_out 0 "2:500" "$LSCCTL" --port lx:sim "${T[@]}" read 2
"$LSCCTL" --port lx:sim "${T[@]}" servo info 2 --json >"$TMP/info.json" ||
  fail "servo info on lx:sim: $(cat "$TMP/info.json")"
grep -qF '"id":2,"position":500,"temperature_c":30,"vin_mv":7500' "$TMP/info.json" ||
  fail "servo info on lx:sim: $(cat "$TMP/info.json")"
expect 2 "$LSCCTL" --port lx:sim:254 read 1
expect_err_has "lx:sim:IDS: id 254 is not a servo's"

finish
