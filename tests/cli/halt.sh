#!/usr/bin/env bash
# halt, hold, id lists (all, ranges) and a group that never starts, against
# lsc-sim on a pseudo-terminal (real time) and --port sim.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

T=(--timeout "$(test_ms 10000)")
sim a --fast --groups "$here/groups.txt"
P=("$LSCCTL" --port "$TMP/a" "${T[@]}")

# position ID: servo ID's position as lscctl reads it
position() { "${P[@]}" read "$1" | sed 's/^[0-9]*://'; }
moved_from() { [ "$(position "$1")" != "$2" ]; }

# halt during a six-second move: the servo stops where it is (between its
# start and its target) and stays there: two reads 0.6 s apart agree
expect_out 0 "" "${P[@]}" move --time "$(test_ms 6000)" 1:2500
wait_for "servo 1 did not start moving" moved_from 1 1500
expect_out 0 "" "${P[@]}" halt
first=$(position 1)
sleep 0.6
second=$(position 1)
checks=$((checks + 1))
[ "$first" = "$second" ] || fail "servo 1 moved on after halt: $first, then $second"
[ "$first" -gt 1500 ] && [ "$first" -lt 2500 ] || fail "servo 1 stopped at $first: not between 1500 and 2500"
# what went out: the stop, one read of 1..32, one move of 32 servos
checks=$((checks + 1))
grep -q " rx 55 55 02 07$" "$TMP/a.log" || fail "no stop reached lsc-sim: $(tail -5 "$TMP/a.log")"
grep -q " rx 55 55 23 15 20 01 02 03 " "$TMP/a.log" || fail "no read of 1..32: $(tail -5 "$TMP/a.log")"
grep -q " rx 55 55 65 03 20 14 00 01 " "$TMP/a.log" || fail "no hold of 32 servos: $(tail -5 "$TMP/a.log")"

# halt during a looping action group: its stop is sent (lsc-sim reports
# that it stopped) and every servo holds
expect_out 0 "" "${P[@]}" run 2 --times 0
wait_for "group 2 did not start" grep -q " tx 55 55 05 06 02 00 00$" "$TMP/a.log"
expect_out 0 "" "${P[@]}" halt
checks=$((checks + 1))
grep -q " tx 55 55 02 07$" "$TMP/a.log" || fail "lsc-sim did not report the group stopped: $(tail -5 "$TMP/a.log")"
first=$(position 3)
sleep 0.6
second=$(position 3)
checks=$((checks + 1))
[ "$first" = "$second" ] || fail "servo 3 moved on after halt: $first, then $second"

# hold: the servos listed, or all
expect_out 0 "" "${P[@]}" hold 1-3
checks=$((checks + 1))
grep -q " rx 55 55 06 15 03 01 02 03$" "$TMP/a.log" || fail "hold 1-3 did not read 1, 2, 3"
expect_out 0 "" "${P[@]}" hold

# unload all, unload 1-6, read of a list
# (unload has no reply: lscctl may be done before lsc-sim logged the frame)
expect_out 0 "" "${P[@]}" unload 1-6
wait_for "unload 1-6 did not reach lsc-sim" grep -q " rx 55 55 09 14 06 01 02 03 04 05 06$" "$TMP/a.log"
expect_out 0 "" "${P[@]}" unload all
wait_for "unload all did not unload 1..32" grep -q " rx 55 55 23 14 20 01 02 03 " "$TMP/a.log"
expect_out 0 "55 55 09 14 06 01 02 03 04 05 06" "$LSCCTL" -n --port hid unload all
expect_out 0 "55 55 08 14 05 01 03 04 05 08" "$LSCCTL" -n --port sim unload 1,3-5 8
expect_out 0 "55 55 05 14 02 06 01" "$LSCCTL" -n --port sim --arm "$here/../../examples/arms/xarm.conf" unload base gripper
expect_out 0 "55 55 09 14 06 01 02 03 04 05 06" "$LSCCTL" -n --port sim --arm "$here/../../examples/arms/xarm.conf" unload all
expect 2 "$LSCCTL" -n --port sim unload 1-3 2
expect_err_has "id 2 is given twice"
expect 2 "$LSCCTL" -n --port sim unload 5-3
expect_err_has "the range 5-3 is empty"
expect 2 env -u LSC_PORT "$LSCCTL" -n unload all
expect_err_has "'all' stands for the controller's servos, which its kind tells: name it with --port"

# record --ids all: the arm profile's joints
expect 0 "$LSCCTL" --port sim --arm "$here/../../examples/arms/xarm.conf" record "$TMP/all.csv" --ids all --every 100 --count 1
checks=$((checks + 1))
head -1 "$TMP/all.csv" | grep -q "1.*2.*3.*4.*5.*6" || fail "record --ids all recorded: $(head -2 "$TMP/all.csv")"
expect 2 env -u LSC_PORT "$LSCCTL" record "$TMP/x.csv" --ids all --every 100 --count 1
expect_err_has "--ids all stands for the controller's servos"

# a gripper opened by hand past its limit (900, limit 700): hold and halt
# hold it there and say so (exit 0); moving it further out stays refused
XARM=$here/../../examples/arms/xarm.conf
sim x --fast --arm "$XARM"
X=("$LSCCTL" --port "$TMP/x" --arm "$XARM" "${T[@]}")
expect_out 0 "" "${X[@]}" send 3 1 0 0 1 0x84 0x03
expect_out 0 "" "${X[@]}" unload gripper
expect 0 "${X[@]}" hold
expect_err_has "lscctl: hold: held where it is, beyond its limits: position 900 is outside the limits of joint gripper (servo 1)"
expect_out 0 "1:900" "$LSCCTL" --port "$TMP/x" "${T[@]}" read 1
expect 0 "${X[@]}" halt
expect_err_has "lscctl: halt: held where it is, beyond its limits"
expect 2 "${X[@]}" move gripper:950
expect_out 0 "" "${X[@]}" move gripper:600

# a group the board does not have never starts: its own message and exit 5,
# within about a second of the run, however long --timeout is
start=$SECONDS
expect 5 "${P[@]}" --timeout 30000 run 9 --wait
expect_err_has "group 9 never started: the controller on $TMP/a did not report its start within"
checks=$((checks + 1))
[ $((SECONDS - start)) -lt 25 ] || fail "run 9 --wait took $((SECONDS - start)) s"
# a group it has: its end
expect_out 0 "action_group_complete group=1 times=1" "${P[@]}" run 1 --wait
# --port sim knows at once
expect 5 "$LSCCTL" --port sim run 9 --wait
expect_err_has "the virtual controller (--port sim) has no group 9, so it never starts"
finish
