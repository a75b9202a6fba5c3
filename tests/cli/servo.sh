#!/usr/bin/env bash
# lscctl on a bus of servos (--port lx:PATH) against a bus written from the
# vendor's protocol document alone, not by lsc (tests/lxbus/lxbus_peer.py, on
# a pseudo-terminal): a scan of every id finds exactly the servos there in
# under 3 s; move then read; servo info's fields; the id changes refused with
# no ID_WRITE on the bus (the peer counts what it receives) and done; an
# offset saved survives the bus's power cycle, one not saved does not; a reply
# with a flipped bit is never printed; a bus that echoes reads the same; every
# setting written and read back; values out of range refused with nothing
# sent. Then lsc-sim --lx 1-6: a scan finds 1..6, an arm profile moves it.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"
command -v python3 >/dev/null || skip "python3 is not installed"
PEER_PY=$here/../lxbus/lxbus_peer.py

# peer NAME IDS [options]: the stand-in bus at $TMP/NAME, its control socket
# $TMP/NAME.ctl, until the test ends
peer() {
  local name=$1 ids=$2; shift 2
  python3 "$PEER_PY" --link "$TMP/$name" --ids "$ids" --control "$TMP/$name.ctl" "$@" \
    >"$TMP/$name.out" 2>&1 &
  SIMS+=($!)
  wait_for "the peer did not make $TMP/$name" test -S "$TMP/$name.ctl" ||
    fail "the peer's output: $(cat "$TMP/$name.out")"
}

# ctl NAME COMMAND: the peer's answer to a control command ("ok ...")
ctl() {
  python3 -c 'import socket, sys
s = socket.socket(socket.AF_UNIX)
s.connect(sys.argv[1])
s.sendall((sys.argv[2] + "\n").encode())
print(s.makefile().readline().strip())' "$TMP/$1.ctl" "$2"
}

# ms: the monotonic-enough wall clock in ms
ms() { echo $(($(date +%s%N) / 1000000)); }

ID_WRITE=13
peer bus 1,2,3
T=(--timeout "$(test_ms 2000)")
# calls that meet silence as well as answers (a joint not connected): shorter
T2=(--timeout "$(test_ms 500)")
P=("$LSCCTL" --port "lx:$TMP/bus")

# a scan of 0..253 at the bus client's own timeouts: exactly 1, 2, 3, in < 3 s
start=$(ms)
expect_out 0 "1
2
3" "${P[@]}" servo scan
took=$(($(ms) - start))
[ "$took" -lt "$(test_ms 3000)" ] || fail "a scan of every id took $took ms (want < 3000)"
echo "servo scan of 0..253 on the stand-in bus: $took ms"
expect_out 0 '{"id":2}' "${P[@]}" --json servo scan 2 7-9

# the board's commands with the same words
expect_out 0 "" "${P[@]}" "${T[@]}" move --time 300 --wait --tolerance 0 2:700 3:250
expect_out 0 "1:500
2:700
3:250" "${P[@]}" "${T[@]}" read 1 2 3

# info: every field, the servo's values
[ "$(ctl bus 'set 2 temp 41')" = ok ] || fail "the peer did not take set 2 temp 41"
[ "$(ctl bus 'set 2 vin 7600')" = ok ] || fail "the peer did not take set 2 vin 7600"
expect_out 0 '{"id":2,"position":700,"temperature_c":41,"vin_mv":7600,"offset":0,"limits":[0,1000],"vin_limits_mv":[4500,12000],"temp_limit_c":85,"mode":"servo","speed":0,"torque":true,"led":true,"alarms":7}' \
  "${P[@]}" "${T[@]}" --json servo info 2
expect_out 0 "servo 1: position 500, 30 C, 7400 mV, offset 0, limits 0..1000, voltage limits 4500..12000 mV, temperature limit 85 C, servo mode (speed 0), torque off, LED on, alarms 7" \
  "${P[@]}" "${T[@]}" servo info 1

# id changes refused: nothing written (the peer received no ID_WRITE)
expect 2 "${P[@]}" "${T[@]}" servo id 1 3
expect_err_has "servo id 1 3 on lx:$TMP/bus: a servo already answers at the new id"
expect 2 "${P[@]}" "${T[@]}" servo id 7
expect_err_has "connect the servo whose id you want to set alone; nothing was written"
expect 2 "${P[@]}" "${T[@]}" servo id 5 6
expect_err_has "no servo answers at that id; nothing was written"
[ "$(ctl bus "count $ID_WRITE")" = "ok 0" ] ||
  fail "refused id changes wrote an id: the peer counts $(ctl bus "count $ID_WRITE") ID_WRITE"
# and done: 2 becomes 9
expect_out 0 "servo 2 is now servo 9" "${P[@]}" "${T[@]}" servo id 2 9
[ "$(ctl bus "count $ID_WRITE")" = "ok 1" ] || fail "servo id 2 9: $(ctl bus "count $ID_WRITE") ID_WRITE"
expect_out 0 "1
3
9" "${P[@]}" servo scan

# offsets: one saved survives a power cycle, one not saved does not
expect_out 0 "servo 1: offset 15 (saved)" "${P[@]}" "${T[@]}" servo offset 1 15 --save
expect_out 0 "servo 3: offset -20 (not saved)" "${P[@]}" "${T[@]}" servo offset 3 -20
expect_out 0 '{"id":3,"offset":-20}' "${P[@]}" "${T[@]}" --json servo offset 3
[ "$(ctl bus power-cycle)" = ok ] || fail "the peer did not power-cycle"
expect_out 0 "servo 1: offset 15" "${P[@]}" "${T[@]}" servo offset 1
expect_out 0 "servo 3: offset 0" "${P[@]}" "${T[@]}" servo offset 3
expect 2 "${P[@]}" "${T[@]}" servo offset 1 111
expect_err_has "the result would leave the bus-servo protocol's range; nothing was written"

# a reply with a flipped bit is never printed
[ "$(ctl bus flip)" = ok ] || fail "the peer did not take flip"
expect 1 "${P[@]}" "${T[@]}" read 1
expect_err_has "bad reply from servo 1"
[ ! -s "$OUT" ] || fail "a reply with a flipped bit was printed: $(cat "$OUT")"
[ "$(ctl bus flip)" = ok ] || fail "the peer did not take flip"
expect 1 "${P[@]}" "${T[@]}" servo offset 1
[ ! -s "$OUT" ] || fail "a reply with a flipped bit was printed: $(cat "$OUT")"

# the settings, written and read back
expect_out 0 "servo 1: limits 10..990" "${P[@]}" "${T[@]}" servo limits 1 10 990
expect_out 0 '{"id":1,"limits":[10,990]}' "${P[@]}" "${T[@]}" --json servo limits 1
expect_out 0 "servo 1: voltage limits 5000..11000 mV" "${P[@]}" "${T[@]}" servo vin-limits 1 5000 11000
expect_out 0 "servo 1: temperature limit 70 C" "${P[@]}" "${T[@]}" servo temp-limit 1 70
expect_out 0 "servo 3: motor mode (speed -300)" "${P[@]}" "${T[@]}" servo mode 3 motor -300
expect_out 0 '{"id":3,"mode":"motor","speed":-300}' "${P[@]}" "${T[@]}" --json servo mode 3
expect_out 0 "servo 3: servo mode (speed 0)" "${P[@]}" "${T[@]}" servo mode 3 servo
expect_out 0 "servo 1: torque on" "${P[@]}" "${T[@]}" servo torque 1 on
expect_out 0 "servo 1: torque off" "${P[@]}" "${T[@]}" servo torque 1 off
expect_out 0 '{"id":1,"led":false}' "${P[@]}" "${T[@]}" --json servo led 1 off
expect_out 0 "servo 1: alarms 5" "${P[@]}" "${T[@]}" servo alarms 1 5

# out of range, or not a bus: exit 2, nothing sent (the peer's counts stand)
before=$(ctl bus "count 20")
for bad in "limits 1 20 10" "limits 1 0 1001" "limits 1 5" "vin-limits 1 4499 9000" \
  "temp-limit 1 101" "temp-limit 1 49" "mode 1 motor 1001" "mode 1 servo 5" "mode 1 fast" \
  "torque 1 maybe" "alarms 1 8" "offset 1 -251" "id 254" "id 3 3" "info 254" "scan 250-255" \
  "info 1 1" "nope" "limits 1 10 990 --save" "scan x"; do
  # shellcheck disable=SC2086
  expect 2 "${P[@]}" servo $bad
done
expect 2 "${P[@]}" servo
[ "$(ctl bus "count 20")" = "$before" ] || fail "refused commands wrote limits"
expect 2 "$LSCCTL" --port sim servo scan
expect_err_has "sim is no bus of servos: servo talks to serial bus servos directly, on --port lx:PATH"
expect 2 "$LSCCTL" --port "$TMP/bus" servo scan
expect 2 "$LSCCTL" --port "lx:$TMP/bus" -n servo scan
expect 3 "${P[@]}" servo scan 100-110
expect_err_has "no servo answered on lx:$TMP/bus (11 ids asked)"
expect 3 "${P[@]}" servo info 100
expect_err_has "no reply from servo 100 on lx:$TMP/bus within 100 ms"

# a bus that echoes the host's bytes reads the same
peer echo 4 --echo
expect_out 0 "4" "$LSCCTL" --port "lx:$TMP/echo" servo scan 1-10
expect_out 0 "" "$LSCCTL" --port "lx:$TMP/echo" "${T[@]}" move --time 0 --wait --tolerance 0 4:321
expect_out 0 "4:321" "$LSCCTL" --port "lx:$TMP/echo" "${T[@]}" read 4
expect_out 0 "servo 4 is now servo 7" "$LSCCTL" --port "lx:$TMP/echo" "${T[@]}" servo id 4 7

# the one servo on a bus, whatever its id, takes id 7
peer alone 5
expect_out 0 "servo 5 is now servo 7" "$LSCCTL" --port "lx:$TMP/alone" "${T[@]}" servo id 7
expect_out 0 "7" "$LSCCTL" --port "lx:$TMP/alone" "${T[@]}" servo scan
[ "$(ctl alone 'add 9')" = ok ] || fail "the peer did not add servo 9"
expect 2 "$LSCCTL" --port "lx:$TMP/alone" "${T[@]}" servo id 8
expect_err_has "connect the servo whose id you want to set alone"
[ "$(ctl alone "count $ID_WRITE")" = "ok 1" ] || fail "servo id 8 with two servos wrote an id"

# servo replace: the new servo alone takes the joint's id and limits; Enter,
# once the rest of the arm is connected, scans every joint
XARM=$here/../../examples/arms/xarm.conf
# replace_with NAME JOINT: lscctl servo replace on peer NAME in the background,
# its stdin the fifo $TMP/NAME.in (held open on fd 7), once it asks for Enter
replace_with() {
  mkfifo "$TMP/$1.in"
  "$LSCCTL" --port "lx:$TMP/$1" "${T2[@]}" --arm "$XARM" servo replace "$2" <"$TMP/$1.in" \
    >"$TMP/$1.rout" 2>"$TMP/$1.rerr" &
  REPLACE_PID=$!
  exec 7>"$TMP/$1.in"
  wait_for "servo replace did not ask for Enter: $(cat "$TMP/$1.rerr")" \
    grep -q "press Enter" "$TMP/$1.rerr"
}
peer arm 1
replace_with arm base
for id in 1 2 3 4 5; do [ "$(ctl arm "add $id")" = ok ] || fail "the peer did not add $id"; done
echo >&7
exec 7>&-
wait "$REPLACE_PID"
rc=$?
checks=$((checks + 1))
[ "$rc" = 0 ] || fail "servo replace base -> exit $rc: $(cat "$TMP/arm.rerr")"
[ "$(cat "$TMP/arm.rout")" = "joint base: servo 1 is now servo 6, limits 23..977
every joint answers once (6 joints)" ] || fail "servo replace base printed: $(cat "$TMP/arm.rout")"
expect_out 0 "servo 6: limits 23..977" "$LSCCTL" --port "lx:$TMP/arm" "${T[@]}" servo limits 6
# the rest not connected: the arm's scan misses a joint (exit 3)
peer arm2 1
replace_with arm2 wrist
echo >&7
exec 7>&-
wait "$REPLACE_PID"
rc=$?
checks=$((checks + 1))
[ "$rc" = 3 ] || fail "servo replace wrist alone, then Enter -> exit $rc, want 3"
grep -qF "joint gripper: no servo answers at id 1" "$TMP/arm2.rerr" ||
  fail "servo replace wrist: $(cat "$TMP/arm2.rerr")"
# not alone: refused, nothing written
expect 2 "$LSCCTL" --port "lx:$TMP/bus" "${T2[@]}" --arm "$XARM" servo replace base
expect_err_has "more than one servo answers on the bus"
expect 2 "$LSCCTL" --port "lx:$TMP/bus" servo replace base
expect_err_has "servo replace needs the arm's profile: --arm FILE"
expect 2 "$LSCCTL" --port "lx:$TMP/bus" --arm "$XARM" servo replace nose
expect_err_has "the arm profile has no joint 'nose'"

# lsc-sim --lx 1-6: a scan finds 1..6; xarm.conf's joints are its servos
sim sim --lx 1-6
expect_out 0 "1 2 3 4 5 6" bash -c '"$0" --port "lx:$1" servo scan | tr "\n" " " | sed "s/ $//"' \
  "$LSCCTL" "$TMP/sim"
expect_out 0 "" "$LSCCTL" --port "lx:$TMP/sim" "${T[@]}" --arm "$here/../../examples/arms/xarm.conf" \
  move --time 100 --wait --tolerance 0 base:30deg
expect_out 0 "6:625" "$LSCCTL" --port "lx:$TMP/sim" "${T[@]}" read 6

finish
