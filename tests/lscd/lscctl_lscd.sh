#!/usr/bin/env bash
# lscctl through lscd: two programs on one arm at once (the README's two
# terminals): monitor in one, run --wait and move --wait in another; every
# command through lscd:PATH and lscd:NAME; a port that lscd holds is reached
# through lscd instead of "busy". Skipped while the device layer does not
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
wait "$mon"
checks=$((checks + 1))
[ "$(cat "$TMP/monitor")" = '{"cmd":6,"name":"action_group_run","group":1,"times":1}
{"cmd":8,"name":"action_group_complete","group":1,"times":1}' ] ||
  fail "monitor through lscd printed: $(cat "$TMP/monitor")"

# the port itself, held by lscd: lscctl goes through lscd
expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port "$TMP/a" "${T[@]}" battery

kill "$LSCD_PID"
wait "$LSCD_PID" || fail "lscd exited $? after SIGTERM"
finish
