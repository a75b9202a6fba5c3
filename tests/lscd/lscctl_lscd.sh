#!/usr/bin/env bash
# lscctl through lscd: two programs on one arm at once (the README's two
# terminals): monitor in one, run --wait and move --wait in another; every
# command through lscd:PATH and lscd:NAME; a port that lscd holds is reached
# through lscd instead of "busy", wherever lscd's socket is (its record).
# Skipped while the device layer does not
# know lscd: names.
# Environment: LSCD, LSCCTL, LSC_SIM.
mine=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$mine/lib.sh" # lscd's and lscctl's test helpers (answers, wait_for, expect, sim, ...)

# clients_are N: lscd at $S has N clients
clients_are() { "$LSCCTL" --port "lscd:$S" status 2>/dev/null | grep -qx "clients: $(($1 + 1))"; }

sim a --fast --groups "$mine/groups.txt"
export LSC_LSCD_DIR=$TMP/run
"$LSCD" --port "$TMP/a" 2>"$TMP/lscd.log" &
LSCD_PID=$!
S=$TMP/run/a.sock
wait_for "lscd did not answer on $S" answers "$S"

run "$LSCCTL" --port "lscd:$S" battery
if [ "$rc" != 0 ] && grep -q "cannot open: No such file or directory" "$ERR"; then
  kill "$LSCD_PID"; wait "$LSCD_PID"
  skip "the device layer does not open lscd: names yet ($(cat "$ERR"))"
fi
T=(--timeout "$(test_ms 10000)")
expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port "lscd:$S" "${T[@]}" battery
expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port lscd:a "${T[@]}" battery

# terminal 1: monitor; terminal 2: run --wait, then move --wait
"$LSCCTL" --port lscd:a --json --timeout "$(test_ms 60000)" monitor --count 2 >"$TMP/monitor" 2>&1 &
mon=$!
wait_for "monitor did not connect" clients_are 1
expect_out 0 "action_group_complete group=1 times=1" "$LSCCTL" --port lscd:a "${T[@]}" run 1 --wait
expect_out 0 "" "$LSCCTL" --port lscd:a "${T[@]}" move --wait --time 100 5:1200
expect_out 0 "5:1200" "$LSCCTL" --port lscd:a "${T[@]}" read 5
# halt through lscd: a move under way stops where the servo is
expect_out 0 "" "$LSCCTL" --port lscd:a "${T[@]}" move --time "$(test_ms 6000)" 5:2500
expect_out 0 "" "$LSCCTL" --port lscd:a "${T[@]}" halt
first=$("$LSCCTL" --port lscd:a "${T[@]}" read 5)
sleep 0.6
second=$("$LSCCTL" --port lscd:a "${T[@]}" read 5)
checks=$((checks + 1))
[ "$first" = "$second" ] || fail "servo 5 moved on after halt through lscd: $first, then $second"
[ "$first" != "5:2500" ] || fail "halt through lscd did not stop servo 5 before its target"
wait "$mon"
checks=$((checks + 1))
[ "$(cat "$TMP/monitor")" = '{"cmd":6,"name":"action_group_run","group":1,"times":1}
{"cmd":8,"name":"action_group_complete","group":1,"times":1}' ] ||
  fail "monitor through lscd printed: $(cat "$TMP/monitor")"

# the port itself, held by lscd: lscctl goes through lscd
expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port "$TMP/a" "${T[@]}" battery
checks=$((checks + 1))
[ -e "$TMP/run/a.record" ] && fail "a record beside the socket where programs look first"

kill "$LSCD_PID"
wait "$LSCD_PID" || fail "lscd exited $? after SIGTERM"

# lscd with its socket anywhere (--socket): its record in lscd's directory
# sends lscctl --port PORT there; removed when lscd stops
sim b --fast
mkdir "$TMP/elsewhere"
"$LSCD" --port "$TMP/b" --socket "$TMP/elsewhere/b.sock" 2>"$TMP/lscd-b.log" &
LSCD_PID=$!
wait_for "lscd did not answer on $TMP/elsewhere/b.sock" answers "$TMP/elsewhere/b.sock"
checks=$((checks + 1))
[ -f "$TMP/run/b.record" ] || fail "lscd made no record: $(ls "$TMP/run"; cat "$TMP/lscd-b.log")"
[ -e "$TMP/run/b.sock" ] && fail "lscd made a socket in its directory as well"
expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port "$TMP/b" "${T[@]}" battery
# a record whose socket is not lscd's: busy, naming lscd and the socket
PY=/usr/bin/python3
if [ -x "$PY" ]; then
  # (bound under another name and renamed once it listens: a connect between
  # bind and listen would be refused, and the test would see no socket)
  "$PY" -c 'import os, socket, sys
s = socket.socket(socket.AF_UNIX); s.bind(sys.argv[1] + ".new"); s.listen(4)
os.rename(sys.argv[1] + ".new", sys.argv[1])
kept = []
while True:  # a frame, but not lscd'"'"'s greeting
    c, _ = s.accept(); c.sendall(bytes.fromhex("5555020f")); kept.append(c)' "$TMP/junk.sock" &
  JUNK=$!
  wait_for "the stand-in socket was not made" test -S "$TMP/junk.sock"
  cp "$TMP/run/b.record" "$TMP/b.record.kept"
  sed "s|^socket .*|socket $TMP/junk.sock|" "$TMP/b.record.kept" >"$TMP/run/b.record"
  expect 4 "$LSCCTL" --port "$TMP/b" "${T[@]}" battery
  expect_err_has "port busy: lscd holds it"
  expect_err_has "$TMP/junk.sock"
  kill "$JUNK"; wait "$JUNK" 2>/dev/null
  cp "$TMP/b.record.kept" "$TMP/run/b.record"
fi
kill "$LSCD_PID"
wait "$LSCD_PID" || fail "lscd exited $? after SIGTERM"
checks=$((checks + 1))
[ -e "$TMP/run/b.record" ] && fail "lscd left its record behind"

# teaching a virtual xArm (README, Teach a virtual arm): record through lscd,
# Enter from a pipe, the limp servos moved by another lscctl between Enters
XARM=$mine/../../examples/arms/xarm.conf
sim x --fast --arm "$XARM"
"$LSCD" --port "$TMP/x" 2>"$TMP/lscd-x.log" &
LSCD_PID=$!
wait_for "lscd did not answer on $TMP/run/x.sock" answers "$TMP/run/x.sock"
mkfifo "$TMP/keys"
"$LSCCTL" --port "$TMP/x" --arm "$XARM" record "$TMP/teach.rob" --ids 1-6 --time 1000 \
  <"$TMP/keys" >"$TMP/rec.out" 2>&1 &
REC=$!
exec 3>"$TMP/keys"
keyframes() { [ "$(grep -c '^keyframe' "$TMP/rec.out")" -ge "$1" ]; }
echo >&3
wait_for "record took no keyframe 1: $(cat "$TMP/rec.out")" keyframes 1
# (--tolerance 0: the keyframe is taken when the wait ends, and the default
# tolerance ends it while a servo may still be a few positions away)
expect 0 "$LSCCTL" --port "$TMP/x" --arm "$XARM" "${T[@]}" move --wait --tolerance 0 --time 100 \
  base:40deg shoulder:-30deg
echo >&3
wait_for "record took no keyframe 2: $(cat "$TMP/rec.out")" keyframes 2
expect 0 "$LSCCTL" --port "$TMP/x" --arm "$XARM" "${T[@]}" move --wait --tolerance 0 --time 100 \
  base:-40deg elbow:25deg gripper:200
echo >&3
wait_for "record took no keyframe 3: $(cat "$TMP/rec.out")" keyframes 3
echo q >&3
exec 3>&-
wait "$REC" || fail "record exited $?: $(cat "$TMP/rec.out")"
checks=$((checks + 1))
[ "$(grep '^keyframe' "$TMP/rec.out")" = "keyframe 1 +1000 ms: 1:500 2:500 3:500 4:500 5:500 6:500
keyframe 2 +1000 ms: 1:500 2:500 3:500 4:500 5:375 6:667
keyframe 3 +1000 ms: 1:200 2:500 3:500 4:604 5:375 6:333" ] ||
  fail "record on the virtual xArm: $(cat "$TMP/rec.out")"
expect 0 "$LSCCTL" convert "$TMP/teach.rob" "$TMP/teach.csv"
kill "$LSCD_PID"
wait "$LSCD_PID" || fail "lscd exited $? after SIGTERM"
finish
