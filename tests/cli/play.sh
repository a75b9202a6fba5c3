#!/usr/bin/env bash
# Teach and play (issue 13): record, play and convert against --port sim and
# lsc-sim over a pseudo-terminal; every file format there and back; exit
# codes (2 for a bad file, nothing sent); lsc-sim --groups with action files.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

# until_log NAME PATTERN: polls lsc-sim's log until PATTERN shows (bounded)
until_log() { wait_for "lsc-sim log $1 never showed '$2'" grep -qE "$2" "$TMP/$1.log"; }
rx() { grep -E ' (rx|noise|beep)' "$TMP/$1.log"; }
hexof() { od -An -v -tx1 "$1" | tr -s ' \n' '  ' | sed 's/^ //; s/ $//'; }

S=(--port sim)

# ---- record on the built-in virtual controller ---------------------------------
# without a terminal each line of stdin is an Enter, 'q' ends
checks=$((checks + 1))
printf '\n\nq\n\n' | "$LSCCTL" "${S[@]}" record "$TMP/e.csv" --ids 1,3 >"$OUT" 2>"$ERR" ||
  fail "record on Enter: exit $?: $(cat "$ERR")"
expect_err_has "servos 1,3 go limp now"
expect_err_has "wrote 2 keyframes"
[ "$(head -1 "$TMP/e.csv")" = "time_ms,1,3" ] || fail "e.csv header: $(cat "$TMP/e.csv")"
[ "$(cut -d, -f2- "$TMP/e.csv" | tail -n +2 | sort -u)" = "1500,1500" ] ||
  fail "e.csv positions: $(cat "$TMP/e.csv")"
# --every on the virtual controller's clock: exact times
expect_out 0 "keyframe 1 +20 ms: 1:1500 2:1500
keyframe 2 +20 ms: 1:1500 2:1500
keyframe 3 +20 ms: 1:1500 2:1500" "$LSCCTL" "${S[@]}" record "$TMP/every.txt" --ids 1-2 --every 20 --count 3
[ "$(grep -c '^step 20 1:1500 2:1500$' "$TMP/every.txt")" = 3 ] || fail "every.txt: $(cat "$TMP/every.txt")"
expect_out 0 '{"keyframe":1,"time_ms":5,"servos":[{"id":7,"position":1500}]}' \
  "$LSCCTL" "${S[@]}" --json record "$TMP/j.csv" --ids 7 --every 5 --count 1
# -n: the unload and the read it would send
expect_out 0 "55 55 05 14 02 01 02
55 55 05 15 02 01 02" "$LSCCTL" -n record "$TMP/n.csv" --ids 1-2
[ ! -e "$TMP/n.csv" ] || fail "record -n wrote a file"
# -n --json: the same frames as messages, like every other command's -n --json
expect_out 0 '{"hex":"55 55 05 14 02 01 02","cmd":20,"name":"mult_servo_unload","ids":[1,2]}
{"hex":"55 55 05 15 02 01 02","cmd":21,"name":"mult_servo_pos_read","ids":[1,2]}' \
  "$LSCCTL" -n --json record "$TMP/n.csv" --ids 1-2
[ ! -e "$TMP/n.csv" ] || fail "record -n --json wrote a file"

# ---- play -n: the schedule ------------------------------------------------------
printf 'time_ms,1,2\n500,100,200\n300,150,200\n400,150,200\n250,900,800\n' >"$TMP/s.csv"
expect_out 0 "       0 ms  keyframe 1 (lead-in)  move 500 ms 1:100 2:200
     500 ms  keyframe 2  move 150 ms 1:150
     850 ms  keyframe 4  move 125 ms 1:900 2:800
     975 ms  keyframe 1 (time 2)  move 250 ms 1:100 2:200
    1225 ms  keyframe 2 (time 2)  move 150 ms 1:150
    1575 ms  keyframe 4 (time 2)  move 125 ms 1:900 2:800
    1700 ms  end" "$LSCCTL" -n play "$TMP/s.csv" --times 2 --speed 200 --lead 500
expect_out 0 '{"at_ms":1000,"keyframe":2,"time":1,"lead_in":false,"time_ms":300,"dropped":0,"servos":[{"id":1,"position":150}]}' \
  bash -c '"$0" -n --json play "$1" | sed -n 2p' "$LSCCTL" "$TMP/s.csv"
# keyframes faster than 9600 baud carries: dropped, said
awk 'BEGIN { print "time_ms,1"; for (i = 0; i < 100; i++) print 2 "," i }' >"$TMP/fast.csv"
expect 0 "$LSCCTL" -n play "$TMP/fast.csv" --lead 0
grep -q "keyframes dropped: faster than 9600 baud carries" "$OUT" || fail "fast.csv: $(tail -2 "$OUT")"
# play on the built-in controller (virtual time), then read where it ended
expect_out 0 "" "$LSCCTL" "${S[@]}" play "$TMP/s.csv"

# ---- every format there and back --------------------------------------------------
printf 'time_ms,1,2,3,4,5,6\n1000,0,100,200,300,400,1000\n500,500,500,500,500,500,500\n' >"$TMP/x.csv"
expect_out 0 "" "$LSCCTL" convert "$TMP/x.csv" "$TMP/x.rob"
# the .rob layout: SOBARM, count 2, 8 zero bytes, 14-byte records
[ "$(hexof "$TMP/x.rob")" = "53 4f 42 41 52 4d 02 00 00 00 00 00 00 00 00 00 e8 03 00 00 64 00 c8 00 2c 01 90 01 e8 03 f4 01 f4 01 f4 01 f4 01 f4 01 f4 01 f4 01" ] ||
  fail "x.rob bytes: $(hexof "$TMP/x.rob")"
expect_out 0 "" "$LSCCTL" convert "$TMP/x.rob" "$TMP/x.d6a"
expect_out 0 "" "$LSCCTL" convert "$TMP/x.d6a" "$TMP/x.txt"
expect_out 0 "" "$LSCCTL" convert "$TMP/x.txt" "$TMP/y.csv"
expect_out 0 "" "$LSCCTL" convert "$TMP/y.csv" "$TMP/y.rob"
cmp -s "$TMP/x.csv" "$TMP/y.csv" || fail "csv -> rob -> d6a -> txt -> csv changed: $(cat "$TMP/y.csv")"
cmp -s "$TMP/x.rob" "$TMP/y.rob" || fail "the .rob round trip changed bytes"
if command -v sqlite3 >/dev/null; then
  [ "$(sqlite3 "$TMP/x.d6a" 'SELECT * FROM ActionGroup')" = "1|1000|0|100|200|300|400|1000
2|500|500|500|500|500|500|500" ] || fail "x.d6a rows: $(sqlite3 "$TMP/x.d6a" 'SELECT * FROM ActionGroup')"
  # a file like the vendor's software writes, with columns left out
  sqlite3 "$TMP/v.d6a" 'CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT,
    Time INT, Servo1 INT, Servo2 INT, Servo6 INT);
    INSERT INTO ActionGroup(Time, Servo1, Servo2, Servo6) VALUES(800, 1500, 1200, 900);
    INSERT INTO ActionGroup(Time, Servo1, Servo2, Servo6) VALUES(600, 1600, 1200, 950);'
  expect_out 0 "       0 ms  keyframe 1 (lead-in)  move 1000 ms 1:1500 2:1200 6:900
    1000 ms  keyframe 2  move 600 ms 1:1600 6:950
    1600 ms  end" "$LSCCTL" -n play "$TMP/v.d6a"
fi
# the C header compiles and plays with lsc_player
if [ -n "${LSC_INCLUDE:-}" ] && command -v cc >/dev/null; then
  expect_out 0 "" "$LSCCTL" convert "$TMP/x.rob" "$TMP/arm.h"
  cat >"$TMP/h.c" <<'C'
#include "lsc/player.h"
#include "arm.h"
int main(void)
{
    lsc_track t = {arm_ids, ARM_SERVOS, ARM_COUNT, arm_keyframes, 0};
    lsc_player_config c = {100, 1, 1000, 9600};
    lsc_player p;
    return lsc_player_init(&p, &t, &c) == 0 && lsc_player_total_ms(&p) == 1500 ? 0 : 1;
}
C
  checks=$((checks + 1))
  cc -std=c99 -Wall -Wextra -Werror -I"$LSC_INCLUDE" -I"$TMP" -fsyntax-only "$TMP/h.c" 2>"$ERR" ||
    fail "arm.h does not compile: $(cat "$ERR")"
fi

# the Arduino example's header is what convert writes from its .rob
ex="$here/../../examples/arduino/PlayKeyframes"
expect_out 0 "" "$LSCCTL" convert "$ex/wave.rob" "$TMP/wave.h"
cmp -s "$ex/wave.h" "$TMP/wave.h" || fail "examples/arduino/PlayKeyframes/wave.h is not what 'lscctl convert wave.rob wave.h' writes"

# ---- bad files and options: exit 2, one line, nothing sent -----------------------
printf 'SOBARM\002\000' >"$TMP/short.rob"
printf 'XOBARM\000\000\000\000\000\000\000\000\000\000' >"$TMP/magic.rob"
printf 'time_ms,1\n100,5\n100\n' >"$TMP/cols.csv"
printf 'time_ms,1\n100,70000\n' >"$TMP/range.csv"
: >"$TMP/empty.csv"
printf 'time_ms,1\n' >"$TMP/none.csv"
printf 'group 1\nstep 100 1:5 2:x\n' >"$TMP/bad.txt"
sim a --fast
P=("$LSCCTL" --port "$TMP/a")
expect 2 "${P[@]}" play "$TMP/short.rob" && expect_err_has "short.rob: truncated header: 8 of 16 bytes"
expect 2 "${P[@]}" play "$TMP/magic.rob" && expect_err_has 'magic.rob: not a .rob file'
expect 2 "${P[@]}" play "$TMP/cols.csv" && expect_err_has "cols.csv: line 3: too few values"
expect 2 "${P[@]}" play "$TMP/range.csv" && expect_err_has "range.csv: line 2: column 2"
expect 2 "${P[@]}" play "$TMP/empty.csv" && expect_err_has "line 1: the file is empty"
expect 2 "${P[@]}" play "$TMP/none.csv" && expect_err_has "none.csv: no keyframes to play"
expect 2 "${P[@]}" play "$TMP/bad.txt" && expect_err_has "bad.txt: line 2:16: position must be 0..65535"
expect 2 "${P[@]}" play "$TMP/missing.csv" && expect_err_has "missing.csv: No such file"
expect 2 "${P[@]}" play "$TMP/arm.wav" && expect_err_has "unknown file type"
expect 2 "${P[@]}" play "$TMP/s.csv" --speed 0 && expect_err_has "--speed 0"
expect 2 "${P[@]}" play "$TMP/s.csv" --times 0 && expect_err_has "--times 0"
expect 2 "${P[@]}" play "$TMP/s.csv" --lead 65536 && expect_err_has "--lead"
expect 2 "${P[@]}" play && expect_err_has "missing arguments"
expect 2 "${P[@]}" record "$TMP/r.csv" --ids 5-3 && expect_err_has "range 5-3 is empty"
expect 2 "${P[@]}" record "$TMP/r.csv" --ids 1,1 && expect_err_has "servo 1 listed twice"
expect 2 "${P[@]}" record "$TMP/r.csv" --ids 0-40 && expect_err_has "more than 32 servos"
expect 2 "${P[@]}" record "$TMP/r.csv" --ids x && expect_err_has "--ids 'x'"
expect 2 "${P[@]}" record "$TMP/r.csv" --every 0 && expect_err_has "--every 0"
expect 2 "${P[@]}" record "$TMP/r.wav" && expect_err_has "unknown file type"
expect 2 "${P[@]}" record "$TMP/r.csv" --speed 5 && expect_err_has "--speed is an option of 'play'"
expect 2 "${P[@]}" convert "$TMP/s.csv" "$TMP/s.rob" && expect_err_has "servo 3 missing: a .rob file holds servos 1..6"
sed 's/^500,500,/500,1001,/' "$TMP/x.csv" >"$TMP/far.csv"
expect 2 "${P[@]}" convert "$TMP/far.csv" "$TMP/far.rob" &&
  expect_err_has "keyframe 2: servo 1: position 1001 is out of range 0..1000 for a .rob file"
expect 2 "${P[@]}" convert "$TMP/s.csv" "$TMP/s.wav" && expect_err_has "unknown file type"
expect 2 "${P[@]}" convert "$TMP/arm.h" "$TMP/s.csv" && expect_err_has "C headers are written, not read"
[ -z "$(rx a)" ] || fail "lsc-sim received bytes for refused commands: $(rx a)"

# ---- a newcomer's session on lsc-sim: pose with move, record, play back ------------
expect_out 0 "" "${P[@]}" move --time 0 1:100 2:200 3:300 4:400 5:500 6:600
expect 0 "${P[@]}" record "$TMP/r.rob" --every 50 --count 2
expect_out 0 "" "${P[@]}" move --time 0 1:900 2:800 3:700 4:600 5:500 6:400
expect 0 "${P[@]}" record "$TMP/r2.csv" --every 50 --count 1
expect_out 0 "" "${P[@]}" play "$TMP/r.rob" --lead 100
expect_out 0 "1:100
2:200
6:600" "${P[@]}" read 1 2 6
rx a | grep -q "rx 55 55 17 03 06 64 00 01 64 00 02 c8 00" ||
  rx a | grep -qi "rx 55 55 17 03 06 64 00 01 64 00 02 C8 00" || fail "no lead-in move in the log: $(rx a | tail -3)"
[ -z "$(grep beep "$TMP/a.log")" ] || fail "lsc-sim beeped: $(grep beep "$TMP/a.log")"
expect_out 0 "" "${P[@]}" convert "$TMP/r.rob" "$TMP/r.csv"
# (the times are the link's real clock here: the positions are exact)
[ "$(cut -d, -f2- "$TMP/r.csv")" = "1,2,3,4,5,6
100,200,300,400,500,600
100,200,300,400,500,600" ] || fail "recorded r.rob: $(cat "$TMP/r.csv")"
# the keyframes a .rob cannot hold are kept in a CSV beside it
expect_out 0 "" "${P[@]}" move --time 0 1:2000
checks=$((checks + 1))
run "${P[@]}" record "$TMP/far.rob" --ids 1-6 --every 10 --count 1
[ "$rc" = 2 ] || fail "record far.rob: exit $rc"
expect_err_has "the keyframes are saved in $TMP/far.rob.csv"
grep -q ",2000,200,300,400,500,600$" "$TMP/far.rob.csv" || fail "far.rob.csv: $(cat "$TMP/far.rob.csv")"

# ---- reads that time out are reported, retried, never saved ------------------------
sim d --fast --drop-replies 2
expect_out 0 "" "$LSCCTL" --port "$TMP/d" move --time 0 1:321
checks=$((checks + 1))
"$LSCCTL" --port "$TMP/d" --timeout "$(test_ms 100)" record "$TMP/d.csv" --ids 1 --every 10 --count 2 \
  </dev/null >"$OUT" 2>"$ERR" || fail "record with dropped replies: exit $?: $(cat "$ERR")"
[ "$(grep -c 'retrying' "$ERR")" = 2 ] || fail "retries not reported: $(cat "$ERR")"
[ "$(tail -n +2 "$TMP/d.csv" | cut -d, -f2 | sort -u)" = "321" ] || fail "d.csv: $(cat "$TMP/d.csv")"

# ---- Ctrl-C ends play after a whole frame ------------------------------------------
sim c
awk 'BEGIN { print "time_ms,1"; for (i = 0; i < 600; i++) print 100 "," 500 + i }' >"$TMP/long.csv"
"$LSCCTL" --port "$TMP/c" play "$TMP/long.csv" --lead 10 </dev/null >"$OUT" 2>"$ERR" &
player=$!
until_log c 'rx 55 55 08 03 01'
kill -INT "$player"
wait "$player"
rc=$?
checks=$((checks + 1))
[ "$rc" = 0 ] || fail "play after Ctrl-C: exit $rc: $(cat "$ERR")"
expect_err_has "stopped (Ctrl-C) after keyframe"
[ -z "$(grep -E 'beep|noise' "$TMP/c.log")" ] || fail "half a frame on the wire: $(grep -E 'beep|noise' "$TMP/c.log")"

# ---- lsc-sim --groups takes action files: one group, numbered by the name -----------
cp "$TMP/x.rob" "$TMP/7-wave.rob"
sim g --fast --groups "$TMP/7-wave.rob"
grep -q "7-wave.rob: group 7" "$TMP/g.log" || fail "lsc-sim did not say the group: $(head -2 "$TMP/g.log")"
expect_out 0 "action_group_complete group=7 times=1" "$LSCCTL" --port "$TMP/g" run 7 --wait
expect_out 0 "1:500" "$LSCCTL" --port "$TMP/g" read 1
checks=$((checks + 1))
"$LSC_SIM" --groups "$TMP/short.rob" </dev/null >/dev/null 2>"$ERR" & wait $!
rc=$?
[ "$rc" = 2 ] || fail "lsc-sim --groups short.rob: exit $rc"
expect_err_has "short.rob: truncated header"

finish
