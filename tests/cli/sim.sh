#!/usr/bin/env bash
# Every command against the built-in virtual controller (--port sim), in text
# and JSON, with exit codes 0 and 3, and the -v trace.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
S=("$LSCCTL" --port sim)

expect_out 0 "" "${S[@]}" move --time 500 1:2000 2:1200
expect_out 0 '{"cmd":3,"name":"servo_move","time_ms":500,"servos":[{"id":1,"position":2000},{"id":2,"position":1200}]}' \
  "${S[@]}" --json move 1:2000 2:1200 --time 500
expect_out 0 "" "${S[@]}" run 8
expect_out 0 '{"cmd":6,"name":"action_group_run","group":8,"times":3}' "${S[@]}" run 8 --times 3 --json
expect_out 0 "action_group_complete group=8 times=1" "${S[@]}" run 8 --wait
expect_out 0 '{"cmd":8,"name":"action_group_complete","group":1,"times":2}' \
  "${S[@]}" --json run --wait 1 --times 2
# a group that loops forever never completes: --timeout bounds the wait
expect_out 3 "" "${S[@]}" --timeout 2000 run 2 --times 0 --wait
expect_err_has "no action group ended within 2000 ms"
# a group that loops forever, without --timeout: nothing can end it, so
# exit 3 at once (not a wait without end; `timeout` turns a hang into 124)
expect_out 3 "" timeout 20 "${S[@]}" run 2 --times 0 --wait
expect_err_has "group 2 loops forever (--times 0) and nothing else on the virtual controller (--port sim) can stop it"
expect_out 3 "" timeout 20 "${S[@]}" --json run 8 --wait --times 0
expect_err_has "group 8 loops forever"
# a group the controller does not have: nothing will ever come
expect_out 5 "" "${S[@]}" run 9 --wait
expect_err_has "the virtual controller (--port sim) has no group 9, so it never starts: its groups are 1, 2 and 8"
expect_out 5 "" "${S[@]}" run 255 --wait --times 0
expect_err_has "has no group 255"
expect_out 3 "" "${S[@]}" wait
expect_err_has "nothing runs on the virtual controller (--port sim, groups 1, 2 and 8)"
expect_out 0 "" "${S[@]}" stop
expect_out 0 '{"cmd":7,"name":"action_group_stop"}' "${S[@]}" --json stop
expect_out 0 "" "${S[@]}" speed all 200
expect_out 0 '{"cmd":11,"name":"action_group_speed","group":8,"percent":50}' "${S[@]}" speed 8 50 --json
expect_out 0 "7.500 V (7500 mV)" "${S[@]}" battery
expect_out 0 '{"cmd":15,"name":"get_battery_voltage","millivolts":7500,"volts":7.500}' "${S[@]}" battery --json
expect_out 0 "" "${S[@]}" unload 1 2 3
expect_out 0 '{"cmd":20,"name":"mult_servo_unload","ids":[1,2,3]}' "${S[@]}" --json unload 1 2 3
expect_out 0 "3:1500
1:1500
16:1500" "${S[@]}" read 3 1 0x10
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":3,"position":1500},{"id":1,"position":1500}]}' \
  "${S[@]}" --json read 3 1
expect_out 3 "" "${S[@]}" wait
expect_out 3 "" "${S[@]}" --timeout 100 wait
expect_out 3 "" "${S[@]}" monitor --count 1
expect_out 0 "" "${S[@]}" send 15
expect_out 0 '{"cmd":15,"name":"get_battery_voltage"}' "${S[@]}" --json send 0x0F
# a raw frame that is not a valid message still goes out (raw means raw)
expect_out 0 '{"error":"not a valid servo_move","hex":"55 55 03 03 01"}' "${S[@]}" --json send 3 1

# $LSC_PORT chooses the port; --port wins over it.
checks=$((checks + 1))
[ "$(LSC_PORT=sim "$LSCCTL" battery </dev/null)" = "7.500 V (7500 mV)" ] || fail "LSC_PORT=sim"
checks=$((checks + 1))
LSC_PORT=/nonexistent/tty "$LSCCTL" -p sim battery </dev/null >/dev/null 2>&1 || fail "--port over LSC_PORT"

# No --port and no $LSC_PORT: the one port that looks like a controller, and
# a build machine has none: exit 2, saying how to choose.
expect_out 2 "" env -u LSC_PORT "$LSCCTL" battery
expect_err_has "choose one with --port PATH (see 'lscctl ports') or set LSC_PORT"

# -v: every frame sent and received on stderr, hex and meaning; stdout unchanged.
expect_out 0 "1:1500" "${S[@]}" -v read 1
expect_err_has "lscctl: sent mult_servo_pos_read ids=1 (55 55 04 15 01 01)"
expect_err_has "lscctl: received mult_servo_pos_read servos=1:1500 (55 55 06 15 01 01 DC 05)"
expect_out 0 "action_group_complete group=8 times=1" "${S[@]}" run 8 --wait --verbose
expect_err_has "lscctl: sent action_group_run group=8 times=1 (55 55 05 06 08 01 00)"
expect_err_has "lscctl: received action_group_run group=8 times=1 (55 55 05 06 08 01 00)"
expect_err_has "lscctl: received action_group_complete group=8 times=1 (55 55 05 08 08 01 00)"
[ "$(wc -l <"$ERR")" = 3 ] || fail "run -v: $(cat "$ERR")"
# commands without a reply go out through the client, traced the same way;
# send 8 --force (which the client refuses by design) has its own path
expect_out 0 "" "${S[@]}" -v stop
expect_err_has "lscctl: sent action_group_stop (55 55 02 07)"
expect_out 0 "" "${S[@]}" -v unload 1 2
expect_err_has "lscctl: sent mult_servo_unload ids=1,2 (55 55 05 14 02 01 02)"
expect_out 0 "" "${S[@]}" -v send 3 1
expect_err_has "lscctl: sent not a valid servo_move (55 55 03 03 01)"
expect_out 0 "" "${S[@]}" -v send 8 1 1 0 --force
expect_err_has "lscctl: sent action_group_complete group=1 times=1 (55 55 05 08 01 01 00)"
[ "$(wc -l <"$ERR")" = 1 ] || fail "send 8 -v: $(cat "$ERR")"

# Output that cannot be written is a failure, not a silent success.
checks=$((checks + 1))
"$LSCCTL" -n stop >/dev/full 2>"$ERR" </dev/null
[ $? = 1 ] && grep -q "cannot write the output" "$ERR" || fail "stdout on /dev/full: $(cat "$ERR")"

# --dry-run of commands that send nothing: no output, no port.
expect_out 0 "" "$LSCCTL" -n --port /nonexistent/tty wait
expect_out 0 "" "$LSCCTL" -n --port /nonexistent/tty monitor
expect_out 0 "" "$LSCCTL" -n ports
finish
