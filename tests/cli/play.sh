#!/usr/bin/env bash
# Teach and play (docs/action-files.md): record, play and convert against --port sim and
# lsc-sim over a pseudo-terminal; every file format there and back; exit
# codes (2 for a bad file, nothing sent); lsc-sim --groups with action files.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"

# until_log NAME PATTERN: polls lsc-sim's log until PATTERN shows (bounded)
until_log() { wait_for "lsc-sim log $1 never showed '$2'" grep -qE "$2" "$TMP/$1.log"; }
# lsc-sim NAME's servos IDS... read as WANT ("ID:POS ID:POS"). play ends on the
# host's clock: lsc-sim's last move may end a moment later (it started the move
# when the frame arrived), so a read after play is waited for, not taken once.
reads() { [ "$("$LSCCTL" --port "$TMP/$1" read "${@:3}" | tr '\n' ' ')" = "$2 " ]; }
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
# the first keyframe on Enter is the move to the first pose: 1000 ms
[ "$(sed -n 2p "$TMP/e.csv" | cut -d, -f1)" = 1000 ] || fail "e.csv's first keyframe: $(cat "$TMP/e.csv")"
# --time MS: each keyframe on Enter MS after the one before; one servo, one keyframe
checks=$((checks + 1))
printf '\n\n\nq\n' | "$LSCCTL" "${S[@]}" record "$TMP/t.csv" --ids 4 --time 250 --count 2 >"$OUT" 2>"$ERR" ||
  fail "record --time: exit $?: $(cat "$ERR")"
[ "$(cat "$OUT")" = "keyframe 1 +250 ms: 4:1500
keyframe 2 +250 ms: 4:1500" ] || fail "record --time: $(cat "$OUT")"
[ "$(cat "$TMP/t.csv")" = "time_ms,4
250,1500
250,1500" ] || fail "t.csv: $(cat "$TMP/t.csv")"
expect_err_has "servo 4 goes limp now (powered off): hold it"
checks=$((checks + 1))
printf '\nq\n' | "$LSCCTL" "${S[@]}" record "$TMP/t1.csv" --ids 4 --time 0x20 >"$OUT" 2>"$ERR" ||
  fail "record --time 0x20: exit $?: $(cat "$ERR")"
grep -qx "lscctl: record: wrote 1 keyframe to $TMP/t1.csv" "$ERR" || fail "record of one keyframe: $(cat "$ERR")"
[ "$(sed -n 2p "$TMP/t1.csv")" = "32,1500" ] || fail "t1.csv: $(cat "$TMP/t1.csv")"
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
expect_out 0 '{"at_ms":1000,"keyframe":2,"time":1,"repetition":1,"lead_in":false,"time_ms":300,"dropped":0,"servos":[{"id":1,"position":150}]}' \
  bash -c '"$0" -n --json play "$1" | sed -n 2p' "$LSCCTL" "$TMP/s.csv"
# -n --json: the schedule, then its summary; "time" and "repetition" both
# count the repetitions (1-based), "time_ms" is the move's time
expect_out 0 '{"at_ms":0,"keyframe":1,"time":1,"repetition":1,"lead_in":true,"time_ms":500,"dropped":0,"servos":[{"id":1,"position":100},{"id":2,"position":200}]}
{"at_ms":500,"keyframe":2,"time":1,"repetition":1,"lead_in":false,"time_ms":150,"dropped":0,"servos":[{"id":1,"position":150}]}
{"at_ms":850,"keyframe":4,"time":1,"repetition":1,"lead_in":false,"time_ms":125,"dropped":0,"servos":[{"id":1,"position":900},{"id":2,"position":800}]}
{"at_ms":975,"keyframe":1,"time":2,"repetition":2,"lead_in":false,"time_ms":250,"dropped":0,"servos":[{"id":1,"position":100},{"id":2,"position":200}]}
{"at_ms":1225,"keyframe":2,"time":2,"repetition":2,"lead_in":false,"time_ms":150,"dropped":0,"servos":[{"id":1,"position":150}]}
{"at_ms":1575,"keyframe":4,"time":2,"repetition":2,"lead_in":false,"time_ms":125,"dropped":0,"servos":[{"id":1,"position":900},{"id":2,"position":800}]}
{"end_ms":1700,"keyframes":8,"frames":6,"dropped":0,"max_late_ms":0,"mean_late_ms":0,"stopped":false}' \
  "$LSCCTL" -n --json play "$TMP/s.csv" --times 2 --speed 200 --lead 500
# --json play on a port: each frame as it went out (sent_ms, late_ms), then the summary
expect_out 0 '{"at_ms":0,"keyframe":1,"time":1,"repetition":1,"lead_in":true,"time_ms":1000,"dropped":0,"sent_ms":0,"late_ms":0,"servos":[{"id":1,"position":100},{"id":2,"position":200}]}
{"at_ms":1000,"keyframe":2,"time":1,"repetition":1,"lead_in":false,"time_ms":300,"dropped":0,"sent_ms":1000,"late_ms":0,"servos":[{"id":1,"position":150}]}
{"at_ms":1700,"keyframe":4,"time":1,"repetition":1,"lead_in":false,"time_ms":250,"dropped":0,"sent_ms":1700,"late_ms":0,"servos":[{"id":1,"position":900},{"id":2,"position":800}]}
{"end_ms":1950,"keyframes":4,"frames":3,"dropped":0,"max_late_ms":0,"mean_late_ms":0,"stopped":false}' \
  "$LSCCTL" --port sim --json play "$TMP/s.csv"
# --port sim says its play took no time (its clock is virtual)
expect_err_has "lscctl: play: --port sim plays on the virtual controller's own clock: the 1.950 s schedule took no time"
# keyframes faster than 9600 baud carries: dropped, said
awk 'BEGIN { print "time_ms,1"; for (i = 0; i < 100; i++) print 2 "," i }' >"$TMP/fast.csv"
expect 0 "$LSCCTL" -n play "$TMP/fast.csv" --lead 0
grep -q "keyframes dropped: faster than 9600 baud carries" "$OUT" || fail "fast.csv: $(tail -2 "$OUT")"
# --json: one object per keyframe dropped, before the frame sent in their place
expect 0 "$LSCCTL" -n --json play "$TMP/fast.csv" --lead 0
[ "$(sed -n 2,7p "$OUT")" = '{"dropped_keyframe":2,"time":1,"repetition":1}
{"dropped_keyframe":3,"time":1,"repetition":1}
{"dropped_keyframe":4,"time":1,"repetition":1}
{"dropped_keyframe":5,"time":1,"repetition":1}
{"dropped_keyframe":6,"time":1,"repetition":1}
{"at_ms":10,"keyframe":7,"time":1,"repetition":1,"lead_in":false,"time_ms":2,"dropped":5,"servos":[{"id":1,"position":6}]}' ] ||
  fail "fast.csv --json: $(head -8 "$OUT")"
checks=$((checks + 1))
sent=$(grep -c '"at_ms"' "$OUT"); dropped=$(grep -c '"dropped_keyframe"' "$OUT")
[ "$((sent + dropped))" = 100 ] || fail "fast.csv --json: $sent sent and $dropped dropped of 100 keyframes"
tail -1 "$OUT" | grep -q "^{\"end_ms\":[0-9]*,\"keyframes\":100,\"frames\":$sent,\"dropped\":$dropped,\"max_late_ms\":[0-9]*,\"mean_late_ms\":[0-9]*,\"stopped\":false}$" ||
  fail "fast.csv --json summary: $(tail -1 "$OUT")"
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
# a .d6a cut by one byte is refused, not read with zeros for what is missing
head -c "$(($(stat -c %s "$TMP/x.d6a") - 1))" "$TMP/x.d6a" >"$TMP/cut.d6a"
expect 2 "$LSCCTL" convert "$TMP/cut.d6a" "$TMP/cut.csv" && expect_err_has "cut short"
[ ! -e "$TMP/cut.csv" ] || fail "a .d6a cut short was converted"
# too long a port name says its limit (not a baud rate)
expect 2 "$LSCCTL" --port "/dev/$(printf 'x%.0s' $(seq 300))" battery &&
  expect_err_has "is too long: at most 271 bytes" && ! grep -q -- "--baud" "$ERR" ||
  fail "too long a name: $(cat "$ERR")"
expect 2 "$LSCCTL" --port "/dev/$(printf 'x%.0s' $(seq 260))" battery &&
  expect_err_has "a serial port's path '/dev/xxx" && expect_err_has "at most 255 bytes" &&
  ! grep -q -- "--baud" "$ERR" || fail "too long a path: $(cat "$ERR")"
# -n convert says what it would write, and writes nothing; --json says what it wrote
expect_out 0 "$TMP/n.rob: rob file, 2 keyframes of 6 servos (1 2 3 4 5 6), 44 bytes; not written (-n)" \
  "$LSCCTL" -n convert "$TMP/x.csv" "$TMP/n.rob"
expect_out 0 "$TMP/n.txt: text file, 1 keyframe of 1 servo (7), 76 bytes; not written (-n)" \
  "$LSCCTL" -n convert "$TMP/j.csv" "$TMP/n.txt"
expect_out 0 "{\"file\":\"$TMP/n.csv\",\"format\":\"csv\",\"keyframes\":2,\"servos\":[1,2,3,4,5,6],\"bytes\":$(wc -c <"$TMP/x.csv"),\"written\":false}" \
  "$LSCCTL" -n --json convert "$TMP/x.rob" "$TMP/n.csv"
checks=$((checks + 1))
[ ! -e "$TMP/n.rob" ] && [ ! -e "$TMP/n.txt" ] && [ ! -e "$TMP/n.csv" ] || fail "convert -n wrote a file"
expect 2 "$LSCCTL" -n convert "$TMP/s.csv" "$TMP/n.rob" && expect_err_has "servo 3 missing"
expect_out 0 "{\"file\":\"$TMP/z.rob\",\"format\":\"rob\",\"keyframes\":2,\"servos\":[1,2,3,4,5,6],\"bytes\":44,\"written\":true}" \
  "$LSCCTL" --json convert "$TMP/x.csv" "$TMP/z.rob"
cmp -s "$TMP/x.rob" "$TMP/z.rob" || fail "convert --json wrote other bytes"
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
# the messages agree: .h is written, never read
expect 2 "${P[@]}" play "$TMP/arm.h" && expect_err_has "C headers are written, not read: lsc reads .txt, .csv, .rob and .d6a"
expect 2 "${P[@]}" play "$TMP/arm.wav" && expect_err_has "unknown file type: lsc reads .txt, .csv, .rob and .d6a (and writes those and .h)"
expect 2 "${P[@]}" convert "$TMP/s.csv" "$TMP/s.wav" && expect_err_has "unknown file type: lsc writes .txt, .csv, .rob, .d6a and .h"
expect 2 "${P[@]}" record "$TMP/r.wav" && expect_err_has "unknown file type: lsc writes .txt, .csv, .rob, .d6a and .h"
expect 2 "${P[@]}" record "$TMP/r.csv" --time 0 && expect_err_has "--time 0: give 1..65535 ms"
expect 2 "${P[@]}" record "$TMP/r.csv" --every 10 --time 5 && expect_err_has "--time is for keyframes on Enter"
[ -z "$(rx a)" ] || fail "lsc-sim received bytes for refused commands: $(rx a)"

# ---- a newcomer's session on lsc-sim: pose with move, record, play back ------------
expect_out 0 "" "${P[@]}" move --time 0 1:100 2:200 3:300 4:400 5:500 6:600
expect 0 "${P[@]}" record "$TMP/r.rob" --every 50 --count 2
expect_out 0 "" "${P[@]}" move --time 0 1:900 2:800 3:700 4:600 5:500 6:400
expect 0 "${P[@]}" record "$TMP/r2.csv" --every 50 --count 1
expect_out 0 "" "${P[@]}" play "$TMP/r.rob" --lead 100
wait_for "play r.rob did not end at 1:100 2:200 6:600" reads a "1:100 2:200 6:600" 1 2 6
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

# ---- play and convert --group N: one group of a group file of several ----------------
demo="$here/../../examples/groups/arm-demo.txt"
expect_out 2 "" "$LSCCTL" -n play "$demo" &&
  expect_err_has "arm-demo.txt: 3 groups: an action file holds one; read one of them by its number (groups 0, 1, 2): play --group N"
expect_out 0 "       0 ms  keyframe 1 (lead-in)  move 1000 ms 4:1200 5:1800 6:1500
    1000 ms  keyframe 2  move 300 ms 6:1100
    1300 ms  keyframe 3  move 300 ms 6:1900
    1600 ms  keyframe 4  move 300 ms 6:1100
    1900 ms  keyframe 5  move 300 ms 6:1900
    2200 ms  keyframe 6  move 500 ms 4:1500 5:1500 6:1500
    2700 ms  end" "$LSCCTL" -n play "$demo" --group 1
expect 2 "$LSCCTL" -n play "$demo" --group 7 &&
  expect_err_has "arm-demo.txt: no group 7 in the file (it holds groups 0, 1, 2)"
expect 2 "$LSCCTL" -n play "$demo" --group 255 && expect_err_has "--group: group 255 is out of range: use 0..254"
expect 2 "$LSCCTL" -n play "$demo" --group x && expect_err_has "--group"
expect 2 "$LSCCTL" -n move 1:1 --group 1 && expect_err_has "--group is an option of 'convert' and 'play'"
expect 2 "$LSCCTL" convert "$demo" "$TMP/demo.csv" &&
  expect_err_has "3 groups: an action file holds one; read one of them by its number (groups 0, 1, 2): convert --group N"
[ ! -e "$TMP/demo.csv" ] || fail "convert of a file of 3 groups wrote demo.csv"
expect_out 0 "" "$LSCCTL" convert "$demo" "$TMP/demo2.csv" --group 2
[ "$(head -2 "$TMP/demo2.csv")" = "time_ms,6,2,3,1
800,2200,1500,1500,1500" ] || fail "demo2.csv: $(cat "$TMP/demo2.csv")"
# a one-group file is the group its name numbers, else 1
cp "$TMP/x.rob" "$TMP/12.rob"
expect 0 "$LSCCTL" -n play "$TMP/12.rob" --group 12
expect 2 "$LSCCTL" -n play "$TMP/12.rob" --group 1 && expect_err_has "12.rob: no group 1 in the file: it is one group, group 12"
expect 0 "$LSCCTL" -n play "$TMP/x.csv" --group 1
# every group of the example group files plays, within the shipped profiles' limits
for g in 0 1 2; do
  expect 0 "$LSCCTL" --arm "$here/../../examples/arms/learm.conf" -n play "$demo" --group "$g"
done
xgroups="$here/../../examples/groups/xarm-bus-servos.txt"
for g in $(awk '$1 == "group" { print $2 }' "$xgroups"); do
  expect 0 "$LSCCTL" --arm "$here/../../examples/arms/xarm.conf" -n play "$xgroups" --group "$g"
done
# and plays on lsc-sim as the group the board runs: the same end
sim grp --fast --groups "$demo"
expect_out 0 "" "$LSCCTL" --port "$TMP/grp" play "$demo" --group 2 --lead 0
wait_for "group 2 played did not end where it ends" reads grp "6:1500 1:1500 2:1500 3:1500" 6 1 2 3

# ---- play --lead 0: the first keyframe at once, nothing dropped ---------------------
printf 'time_ms,1,2\n500,100,200\n500,300,400\n500,500,600\n' >"$TMP/slow.csv"
expect_out 0 "       0 ms  keyframe 1 (lead-in)  move 0 ms 1:100 2:200
       0 ms  keyframe 2  move 500 ms 1:300 2:400
     500 ms  keyframe 3  move 500 ms 1:500 2:600
    1000 ms  end" "$LSCCTL" -n play "$TMP/slow.csv" --lead 0
sim lead --fast
expect_out 0 "" "$LSCCTL" --port "$TMP/lead" play "$TMP/slow.csv" --lead 0
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "play --lead 0 said: $(cat "$ERR")"
wait_for "play --lead 0 did not end at 1:500 2:600" reads lead "1:500 2:600" 1 2
rx lead | grep -qi "rx 55 55 0b 03 02 00 00 01 64 00 02 c8 00" ||
  fail "play --lead 0 did not send keyframe 1 at once over 0 ms: $(rx lead | head -3)"

# ---- play --arm: every keyframe checked against the limits before anything is sent ----
xarm="$here/../../examples/arms/xarm.conf"
printf 'time_ms,6\n1000,2000\n' >"$TMP/l.csv"
expect_out 2 "" "$LSCCTL" --arm "$xarm" -n play "$TMP/l.csv" &&
  expect_err_has "l.csv: keyframe 1: position 2000 is outside the limits of joint base"
printf 'time_ms,1,6\n1000,100,500\n1000,700,500\n1000,701,500\n' >"$TMP/l3.csv"
sim lim --fast
expect_out 2 "" "$LSCCTL" --arm "$xarm" --port "$TMP/lim" play "$TMP/l3.csv" &&
  expect_err_has "l3.csv: keyframe 3: position 701 is outside the limits of joint gripper"
LSC_ARM=$xarm expect_out 2 "" "$LSCCTL" --port "$TMP/lim" play "$TMP/l3.csv" &&
  expect_err_has "keyframe 3: position 701 is outside the limits of joint gripper"
checks=$((checks + 1))
[ -z "$(rx lim)" ] || fail "play --arm sent bytes for a file outside the limits: $(rx lim)"
sed -i '$d' "$TMP/l3.csv"
expect_out 0 "" "$LSCCTL" --arm "$xarm" --port "$TMP/lim" play "$TMP/l3.csv" --lead 10
wait_for "play --arm did not end at 1:700" reads lim "1:700" 1

# ---- convert --from-arm --to-arm: positions through joint angles ------------------------
learm="$here/../../examples/arms/learm.conf"
printf 'time_ms,1,2,3,4,5,6\n1000,1500,1500,1500,1500,1500,1500\n500,2000,1000,1600,1400,1500,2200\n' >"$TMP/pwm.csv"
# PWM positions are no .rob positions: refused, pointing to the arms
expect 2 "$LSCCTL" convert "$TMP/pwm.csv" "$TMP/pwm.rob" &&
  expect_err_has "keyframe 1: servo 1: position 1500 is out of range 0..1000 for a .rob file; positions of another arm convert through joint angles with --from-arm and --to-arm"
expect_out 0 "" "$LSCCTL" convert "$TMP/pwm.csv" "$TMP/pwm.rob" --from-arm "$learm" --to-arm "$xarm"
expect_out 0 "" "$LSCCTL" convert "$TMP/pwm.rob" "$TMP/pwm-x.csv"
[ "$(cat "$TMP/pwm-x.csv")" = "time_ms,1,2,3,4,5,6
1000,500,500,500,500,875,500
500,688,312,538,462,875,763" ] || fail "pwm.rob: $(cat "$TMP/pwm-x.csv")"
# and back: the same angles, to the nearest position
expect_out 0 "" "$LSCCTL" convert "$TMP/pwm.rob" "$TMP/pwm-back.csv" --from-arm "$xarm" --to-arm "$learm"
[ "$(cat "$TMP/pwm-back.csv")" = "time_ms,1,2,3,4,5,6
1000,1500,1500,1500,1500,1500,1500
500,2001,999,1601,1399,1500,2201" ] || fail "pwm-back.csv: $(cat "$TMP/pwm-back.csv")"
# a pose outside the target's limits: the keyframe and the joint named, nothing written
printf 'time_ms,1,6\n1000,1500,1500\n1000,2500,1500\n' >"$TMP/grip.csv"
expect_out 2 "" "$LSCCTL" convert "$TMP/grip.csv" "$TMP/grip.rob" --from-arm "$learm" --to-arm "$xarm" &&
  expect_err_has "grip.csv: keyframe 2: joint gripper: 90.00deg (position 2500) is outside the target's limits of joint gripper (servo 1): -120.00deg..48.00deg"
[ ! -e "$TMP/grip.rob" ] || fail "convert wrote grip.rob outside the target's limits"
printf 'time_ms,7\n1000,1500\n' >"$TMP/seven.csv"
expect 2 "$LSCCTL" convert "$TMP/seven.csv" "$TMP/seven.csv2.csv" --from-arm "$learm" --to-arm "$xarm" &&
  expect_err_has "servo 7 is on no joint of the source profile"
expect 2 "$LSCCTL" convert "$TMP/pwm.csv" "$TMP/p.rob" --from-arm "$learm" &&
  expect_err_has "--from-arm and --to-arm go together"
expect 2 "$LSCCTL" convert "$TMP/pwm.csv" "$TMP/p.rob" --to-arm "$xarm" &&
  expect_err_has "--from-arm and --to-arm go together"
expect 2 "$LSCCTL" convert "$TMP/pwm.csv" "$TMP/p.rob" --from-arm "$TMP/none.conf" --to-arm "$xarm" &&
  expect_err_has "none.conf"
expect 2 "$LSCCTL" play "$TMP/pwm.csv" --from-arm "$learm" && expect_err_has "--from-arm is an option of 'convert'"
# -n: what it would write
expect_out 0 "$TMP/p.rob: rob file, 2 keyframes of 6 servos (1 2 3 4 5 6), 44 bytes; not written (-n)" \
  "$LSCCTL" -n convert "$TMP/pwm.csv" "$TMP/p.rob" --from-arm "$learm" --to-arm "$xarm"

# ---- record: the destination is checked before the servos go limp ----------------------
sim dest --fast
for target in /nonexistent/rec.csv "$TMP/dir.csv"; do
  mkdir -p "$TMP/dir.csv"
  checks=$((checks + 1))
  run "$LSCCTL" --port "$TMP/dest" record "$target" --every 10 --count 3
  [ "$rc" = 1 ] || [ "$rc" = 2 ] || fail "record $target: exit $rc: $(cat "$ERR")"
  [ "$(wc -l <"$ERR")" = 1 ] || fail "record $target: $(cat "$ERR")"
  expect_err_has "$target"
done
checks=$((checks + 1))
[ -z "$(rx dest)" ] || fail "record sent bytes for a destination it cannot write: $(rx dest)"
run "$LSCCTL" --port sim record /nonexistent/rec.csv --every 10 --count 3
checks=$((checks + 1))
! grep -q "go limp" "$ERR" || fail "the servos went limp for a destination that cannot be written"
[ "$rc" = 1 ] || [ "$rc" = 2 ] || fail "record /nonexistent/rec.csv on sim: exit $rc"

# ---- record: each keyframe reaches the disk as it is taken ------------------------------
# start_record NAME ARGS...: record on Enter on --port sim into $TMP/NAME.csv,
# its standard input the FIFO on descriptor 7 (one line: one keyframe)
start_record() {
  local name=$1; shift
  rm -f "$TMP/$name.in"
  mkfifo "$TMP/$name.in"
  "$LSCCTL" --port sim record "$TMP/$name.csv" --ids 1,2 "$@" <"$TMP/$name.in" \
    >"$TMP/$name.out" 2>"$TMP/$name.err" &
  recorder=$!
  exec 7>"$TMP/$name.in"
}
# journal_rows NAME N: the journal of $TMP/NAME.csv holds N keyframes or more
journal_rows() { [ -e "$TMP/$1.csv.journal.csv" ] && [ "$(($(wc -l <"$TMP/$1.csv.journal.csv") - 1))" -ge "$2" ]; }

# SIGKILL: what was taken is in the journal, a CSV that convert reads
start_record killed
echo >&7
echo >&7
wait_for "the journal never held 2 keyframes" journal_rows killed 2
kill -KILL "$recorder"
wait "$recorder" 2>/dev/null
exec 7>&-
checks=$((checks + 1))
[ ! -e "$TMP/killed.csv" ] || fail "killed.csv written by a killed record"
expect_out 0 "" "$LSCCTL" convert "$TMP/killed.csv.journal.csv" "$TMP/killed2.csv"
[ "$(cut -d, -f2- "$TMP/killed2.csv")" = "1,2
1500,1500
1500,1500" ] || fail "the journal of a killed record: $(cat "$TMP/killed.csv.journal.csv")"
# an earlier recording's journal is never overwritten: refused before the servos go limp
checks=$((checks + 1))
run "$LSCCTL" --port sim record "$TMP/killed.csv" --every 10 --count 1
[ "$rc" = 1 ] || [ "$rc" = 2 ] || fail "record over an earlier journal: exit $rc: $(cat "$ERR")"
expect_err_has "killed.csv.journal.csv"
! grep -q "go limp" "$ERR" || fail "the servos went limp though the journal exists"

# ---- record: SIGTERM and SIGHUP end it and save, like Ctrl-C -----------------------------
for sig in TERM HUP INT; do
  start_record "sig$sig"
  echo >&7
  wait_for "record never journalled its keyframe (SIG$sig)" journal_rows "sig$sig" 1
  kill "-$sig" "$recorder"
  wait "$recorder"
  rc=$?
  exec 7>&-
  checks=$((checks + 1))
  [ "$rc" = 0 ] || fail "record after SIG$sig: exit $rc: $(cat "$TMP/sig$sig.err")"
  grep -qF "wrote 1 keyframe to $TMP/sig$sig.csv" "$TMP/sig$sig.err" ||
    fail "record after SIG$sig: $(cat "$TMP/sig$sig.err")"
  [ "$(tail -n +2 "$TMP/sig$sig.csv" | cut -d, -f2-)" = "1500,1500" ] ||
    fail "sig$sig.csv: $(cat "$TMP/sig$sig.csv")"
  [ ! -e "$TMP/sig$sig.csv.journal.csv" ] || fail "the journal stayed after sig$sig.csv was written"
done

# ---- record: a target that cannot be written at the end leaves the journal, named --------
start_record blocked
echo >&7
wait_for "record never journalled its keyframe" journal_rows blocked 1
mkdir "$TMP/blocked.csv" # now the target cannot be replaced
echo q >&7
wait "$recorder"
rc=$?
exec 7>&-
checks=$((checks + 1))
[ "$rc" = 1 ] || fail "record onto a directory: exit $rc: $(cat "$TMP/blocked.err")"
grep -qF "the keyframes are saved in $TMP/blocked.csv.journal.csv" "$TMP/blocked.err" ||
  fail "the journal is not named: $(cat "$TMP/blocked.err")"
[ "$(tail -n +2 "$TMP/blocked.csv.journal.csv" | cut -d, -f2-)" = "1500,1500" ] ||
  fail "blocked.csv.journal.csv: $(cat "$TMP/blocked.csv.journal.csv")"

# ---- record stops at the most keyframes a file holds, and saves them ---------------------
checks=$((checks + 1))
run "$LSCCTL" --port sim record "$TMP/big.csv" --ids 1 --every 1
[ "$rc" = 0 ] || fail "record to the limit: exit $rc: $(tail -2 "$ERR")"
expect_err_has "stopped at 65535 keyframes"
expect_err_has "wrote 65535 keyframes"
[ "$(wc -l <"$TMP/big.csv")" = 65536 ] || fail "big.csv: $(wc -l <"$TMP/big.csv") lines"
expect_out 0 "" "$LSCCTL" --port sim play "$TMP/big.csv" --lead 0

# ---- record on a terminal: ECHO and ICANON are restored however it ends ------------------
# (TSTP: Ctrl-Z and fg: the terminal as it was while stopped, raw again after, and the
# recording goes on, ended by SIGQUIT. lscctl runs in a process group of its own in the
# foreground of the terminal's session, as a shell with job control runs it: the kernel
# discards a SIGTSTP to an orphaned process group.)
if command -v python3 >/dev/null; then
  for how in q TERM HUP QUIT TSTP; do
    checks=$((checks + 1))
    python3 - "$LSCCTL" "$TMP/tty$how.csv" "$how" "$(test_ms 30000)" >"$OUT" 2>&1 <<'PY' ||
import os, pty, select, signal, sys, termios, time
lscctl, target, how, limit = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]) / 1000
argv = [lscctl, "--port", "sim", "record", target, "--ids", "1"]
r, w = os.pipe()
pid, fd = pty.fork()
if pid == 0:
    if how != "TSTP":
        os.execv(lscctl, argv)
    gc = os.fork()  # the session leader: a shell with job control
    if gc == 0:
        os.setpgid(0, 0)
        signal.signal(signal.SIGTTOU, signal.SIG_IGN)
        os.tcsetpgrp(0, os.getpid())
        signal.signal(signal.SIGTTOU, signal.SIG_DFL)
        os.execv(lscctl, argv)
    os.write(w, b"%d\n" % gc)
    while True:
        _, st = os.waitpid(gc, 0)
        if os.WIFEXITED(st) or os.WIFSIGNALED(st):
            os._exit(os.WEXITSTATUS(st) if os.WIFEXITED(st) else 99)
rec = int(os.read(r, 64)) if how == "TSTP" else pid
out = b""
def until(text):
    global out
    end = time.monotonic() + limit
    while text not in out:
        left = end - time.monotonic()
        if left <= 0 or not select.select([fd], [], [], left)[0]:
            sys.exit("never saw %r: %r" % (text, out))
        try:
            out += os.read(fd, 4096)
        except OSError:
            sys.exit("the terminal closed before %r: %r" % (text, out))
def lflag():
    return termios.tcgetattr(fd)[3]
def wait(cond, what):
    end = time.monotonic() + limit
    while not cond():
        if time.monotonic() > end:
            sys.exit(what)
        time.sleep(0.005)
def state():
    with open("/proc/%d/stat" % rec) as f:
        return f.read().rsplit(")", 1)[1].split()[0]
until(b"Enter saves a keyframe")
if lflag() & (termios.ECHO | termios.ICANON):
    sys.exit("the terminal is not raw while recording")
os.write(fd, b"\n")
until(b"keyframe 1 +")
keyframes = 1
if how == "TSTP":
    os.kill(rec, signal.SIGTSTP)
    wait(lambda: state() == "T", "record did not stop on SIGTSTP")
    flags = lflag()
    if not (flags & termios.ECHO and flags & termios.ICANON):
        sys.exit("ECHO or ICANON off while record is stopped")
    os.kill(rec, signal.SIGCONT)
    wait(lambda: not lflag() & (termios.ECHO | termios.ICANON), "not raw again after SIGCONT")
    os.write(fd, b"\n")
    until(b"keyframe 2 +")
    keyframes, how = 2, "QUIT"
if how == "q":
    os.write(fd, b"q")
else:
    os.kill(rec, getattr(signal, "SIG" + how))
until(b"wrote %d keyframe" % keyframes)
_, status = os.waitpid(pid, 0)
flags = lflag()
if not (flags & termios.ECHO and flags & termios.ICANON):
    sys.exit("ECHO or ICANON left off after %s" % how)
if os.WEXITSTATUS(status) != 0:
    sys.exit("exit %d: %r" % (os.WEXITSTATUS(status), out))
PY
      fail "record on a terminal, ended by $how: $(cat "$OUT")"
  done
fi

# ---- every JSON key of play, record and convert is documented in lscctl.1 -------------
man="$here/../../cli/lscctl.1"
{
  "$LSCCTL" -n --json play "$TMP/fast.csv" --lead 0
  "$LSCCTL" --port sim --json play "$TMP/s.csv" 2>/dev/null
  "$LSCCTL" --port sim --json record "$TMP/keys.csv" --ids 1 --every 5 --count 1 2>/dev/null
  "$LSCCTL" -n --json convert "$TMP/x.csv" "$TMP/keys.rob"
} >"$TMP/keys.json"
checks=$((checks + 1))
keys=$(grep -o '"[a-z_]*":' "$TMP/keys.json" | tr -d '":' | sort -u)
[ "$(echo "$keys" | wc -l)" -ge 23 ] || fail "too few JSON keys seen: $(echo $keys)"
for key in $keys; do
  grep -qF "\\fB$key\\fR" "$man" || fail "the JSON key $key is not in lscctl.1"
done

finish
