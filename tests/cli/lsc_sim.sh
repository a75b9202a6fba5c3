#!/usr/bin/env bash
# lscctl against lsc-sim over a real pseudo-terminal: every command, text and
# JSON, state that persists between commands, exit codes 0/1/2/3; for every
# invalid command line, lsc-sim --log shows that not one byte arrived.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

# frames_in NAME: what lsc-sim received (rx frames, noise bytes, beeps)
frames_in() { grep -E ' (rx|noise|beep)' "$TMP/$1.log"; }

# Every reply the test expects comes from lsc-sim, late on a busy machine:
# a generous timeout (scaled); checks of exit 3 give their own short one.
T=(--timeout "$(test_ms 10000)")
sim a --fast --groups "$here/groups.txt"
P=("$LSCCTL" --port "$TMP/a" "${T[@]}")

# Invalid command lines: exit 2 and not one byte reaches the controller:
# once the reply to a valid request is back, lsc-sim has logged every byte
# that came before it, and that request is all it got.
check_bad --port "$TMP/a"
expect_out 0 "7.500 V (7500 mV)" "${P[@]}" battery
[ "$(frames_in a | sed 's/.* rx /rx /')" = "rx 55 55 02 0F" ] ||
  fail "lsc-sim received bytes for refused command lines: $(frames_in a)"

# move, then read back: the controller keeps the positions.
expect_out 0 "" "${P[@]}" move --time 0 1:2000 2:0x4B0
expect_out 0 "1:2000
2:1200
3:1500" "${P[@]}" read 1 2 3
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":2,"position":1200}]}' "${P[@]}" --json read 2
expect_out 0 '{"cmd":3,"name":"servo_move","time_ms":0,"servos":[{"id":5,"position":700}]}' \
  "${P[@]}" --json move 5:700 --time 0
expect_out 0 "5:700" "${P[@]}" read 5
# unload: the servo stays where it is
expect_out 0 "" "${P[@]}" unload 5
expect_out 0 '{"cmd":20,"name":"mult_servo_unload","ids":[5]}' "${P[@]}" unload 5 --json
expect_out 0 "5:700" "${P[@]}" read 5

expect_out 0 "7.500 V (7500 mV)" "${P[@]}" battery
expect_out 0 '{"cmd":15,"name":"get_battery_voltage","millivolts":7500,"volts":7.500}' "${P[@]}" --json battery

# groups: run and wait for them, speed, stop
expect_out 0 "action_group_complete group=1 times=1" "${P[@]}" run 1 --wait
expect_out 0 "1:1500" "${P[@]}" read 1
expect_out 0 "" "${P[@]}" speed all 200
expect_out 0 '{"cmd":11,"name":"action_group_speed","group":2,"percent":300}' "${P[@]}" --json speed 2 300
expect_out 0 '{"cmd":8,"name":"action_group_complete","group":2,"times":2}' "${P[@]}" --json run 2 --times 2 --wait
expect_out 0 "" "${P[@]}" run 2 --times 0
expect_out 0 "" "${P[@]}" stop
expect_out 0 '{"cmd":7,"name":"action_group_stop"}' "${P[@]}" --json stop
# wait and monitor see what a group started by an earlier command sends.
# The group must still run when the next lscctl has started: slowed down to
# last 1.5 s (scaled) instead of its 300 ms.
slow=$((100 * 300 / $(test_ms 1500)))
[ "$slow" -ge 1 ] || slow=1
expect_out 0 "" "${P[@]}" speed all "$slow"
expect_out 0 "" "${P[@]}" run 1
expect_out 0 "action_group_complete group=1 times=1" "${P[@]}" wait
expect_out 0 "" "${P[@]}" run 1
# monitor opens the port (discarding what waits) as the simulator answers the
# run frame: it may or may not see the start; then it must see the end
started='{"cmd":6,"name":"action_group_run","group":1,"times":1}'
ended='{"cmd":8,"name":"action_group_complete","group":1,"times":1}'
expect 0 "${P[@]}" --json monitor --count 1
if [ "$(cat "$OUT")" = "$started" ]; then
  expect_out 0 "$ended" "${P[@]}" --json monitor --count 1
elif [ "$(cat "$OUT")" != "$ended" ]; then
  fail "monitor --count 1 after run 1 -> $(cat "$OUT"), want the group's start or end"
fi
expect_out 0 "" "${P[@]}" speed all 100
expect_out 3 "" "${P[@]}" --timeout 300 wait
expect_out 3 "" "${P[@]}" --timeout 300 monitor
# a raw frame, traced with -v
expect_out 0 "" "${P[@]}" -v send 0x0F
expect_err_has "lscctl: sent get_battery_voltage (55 55 02 0F)"
expect_out 0 "1:1500" "${P[@]}" -v read 1
expect_err_has "lscctl: received mult_servo_pos_read servos=1:1500 (55 55 06 15 01 01 DC 05)"
# (lsc-sim logs what it receives before it replies: the reply just read
# means every earlier frame is in the log)
grep -q ' rx 55 55 05 0B FF C8 00$' "$TMP/a.log" || fail "speed all 200 did not arrive"
grep -q ' rx 55 55 02 07$' "$TMP/a.log" || fail "stop did not arrive"
grep -q ' rx 55 55 04 14 01 05$' "$TMP/a.log" || fail "unload did not arrive"
# Every frame lscctl sent was well formed: the board never beeped.
beeps=$(grep ' beep' "$TMP/a.log" || true)
[ -z "$beeps" ] || fail "lsc-sim beeped: $beeps"

# run --wait while another group runs: the controller stops that one (7)
# before it starts ours (6); only the end of ours ends the wait
expect_out 0 "" "${P[@]}" run 1 --times 0
expect_out 0 "action_group_complete group=2 times=1" "${P[@]}" run 2 --wait
expect_out 0 "" "${P[@]}" run 2 --times 0
expect_out 0 '{"cmd":8,"name":"action_group_complete","group":2,"times":1}' "${P[@]}" --json run 2 --wait
# a busy port: exit 4
expect_busy "$TMP/a" battery

# no reply (exit 3) and a bad reply (exit 1), then good again
sim b --fast --drop-replies 1 --battery 8100
expect_out 3 "" "$LSCCTL" --port "$TMP/b" --timeout 300 battery
expect_out 0 "8.100 V (8100 mV)" "$LSCCTL" --port "$TMP/b" "${T[@]}" battery
sim c --fast --corrupt 1
# (a bad reply ends the wait at the timeout: long enough for the reply to come)
expect_out 1 "" "$LSCCTL" --port "$TMP/c" --timeout "$(test_ms 2000)" read 1
expect_err_has "bad reply"
expect_out 0 "1:1500" "$LSCCTL" --port "$TMP/c" "${T[@]}" read 1
# --arm: a virtual xArm, its joints at 0 degrees (500), a move beyond a bus
# servo's 0..1000 stopping at 1000; servos on no joint as without it
XARM=$here/../../examples/arms/xarm.conf
sim e --fast --arm "$XARM"
expect_out 0 "1:500
6:500
7:1500" "$LSCCTL" --port "$TMP/e" "${T[@]}" read 1 6 7
expect_out 0 "" "$LSCCTL" --port "$TMP/e" "${T[@]}" move --time 0 6:1500 7:2500
expect_out 0 "6:1000
7:2500" "$LSCCTL" --port "$TMP/e" "${T[@]}" read 6 7
expect_out 0 "base:0.00deg" "$LSCCTL" --port sim --arm "$XARM" read base
expect 2 "$LSC_SIM" --arm "$TMP/no-such.conf"
expect_err_has "no-such.conf"
printf 'base 6 nonsense\n' >"$TMP/bad.conf"
expect 2 "$LSC_SIM" --arm "$TMP/bad.conf"
expect_err_has "bad.conf:1"

# paced at the real 9600 baud
sim d
expect_out 0 "1:1500
2:1500" "$LSCCTL" --port "$TMP/d" "${T[@]}" read 1 2
# a joint whose servo is beyond its range has no degrees: the xArm's profile
# on a board whose servos are at 1500 (the profile is for another arm)
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":6,"position":1500,"joint":"base"}]}' \
  "$LSCCTL" --port "$TMP/d" --arm "$XARM" "${T[@]}" --json read 6
# a gripper held by an object at 600 (--block): move --wait ends when it
# stops, says where (stderr; --json a "stopped" line) and exits 0, well
# before its timeout; --strict makes it exit 3; opening it is free
sim e --fast --block 1:600 --block 2:400:below
start=$(date +%s%N)
expect_out 0 "" "$LSCCTL" --port "$TMP/e" --timeout "$(test_ms 10000)" move --time 500 --wait 1:700
spent=$((($(date +%s%N) - start) / 1000000))
[ "$spent" -lt "$(test_ms 3000)" ] || fail "move --wait on a held servo took $spent ms"
expect_err_has "servo 1 stopped at 600, 100 short of its target 700"
expect_out 0 '{"cmd":3,"name":"servo_move","time_ms":100,"servos":[{"id":1,"position":700},{"id":2,"position":300},{"id":3,"position":300}]}
{"stopped":[{"id":1,"position":600,"target":700,"short":100},{"id":2,"position":400,"target":300,"short":100}]}' \
  "$LSCCTL" --port "$TMP/e" "${T[@]}" --json move --time 100 --wait 1:700 2:300 3:300
expect_out 3 "" "$LSCCTL" --port "$TMP/e" "${T[@]}" move --time 100 --wait --strict 1:700
expect_err_has "servo 1 stopped at 600, 100 short of its target 700 (--strict)"
expect_out 0 "" "$LSCCTL" --port "$TMP/e" "${T[@]}" move --time 100 --wait --strict 1:300
expect_out 0 "1:300" "$LSCCTL" --port "$TMP/e" "${T[@]}" read 1
# with --arm as well: the block takes the place of the arm's servo range
sim g --fast --arm "$XARM" --block 1:600
expect_out 0 "" "$LSCCTL" --port "$TMP/g" "${T[@]}" move --time 100 --wait 1:700
expect_err_has "servo 1 stopped at 600, 100 short of its target 700"
for bad in 1 1:x 256:600 1:600:up 1:70000 :600; do
  checks=$((checks + 1))
  run "$LSC_SIM" --block "$bad"
  [ "$rc" = 2 ] || fail "lsc-sim --block $bad -> exit $rc, want 2"
  expect_err_has "invalid --block '$bad'"
done
finish
