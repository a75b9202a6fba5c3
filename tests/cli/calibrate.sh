#!/usr/bin/env bash
# lscctl calibrate (docs/arm-profile.md, "Calibration") on lsc-sim standing
# in for an xArm as its owner assembled it: the zeros of base, shoulder,
# elbow, wrist and wrist roll off by +23, -17, +30, -12 and +5 positions, the
# elbow's servo mounted the other way round. The servos are put "by hand" in
# each pose by moves through the arm's true profile; the steps one by one
# give a profile with which where and reach are right on that arm (the
# shipped profile is far off); --check; the default place of the result,
# found by every later lscctl without --arm, one per arm; the command
# line's errors, each with nothing sent.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"
command -v python3 >/dev/null || skip "python3 is not installed (scripts/install-deps.sh --all)"
arms=$here/../../examples/arms
export XDG_CONFIG_HOME=$TMP/config

T=(--timeout "$(test_ms 10000)")
sim a --fast --arm "$arms/xarm.conf"
sim b --fast --arm "$arms/xarm.conf"
P=("$LSCCTL" --port "$TMP/a" "${T[@]}")

# the arm as built, as a profile: what the calibration must find
python3 "$here/../arm_as_built.py" "$arms/xarm.conf" "$TMP/true.conf"
TRUE=("${P[@]}" --arm "$TMP/true.conf")
# by_hand JOINT:ANGLE...: the arm put in a pose (its true angles)
by_hand() { expect 0 "${TRUE[@]}" move --time 0 "$@"; }
# where_with PROFILE: x y z of where through PROFILE
where_with() {
  run "${P[@]}" --arm "$1" --json where
  python3 -c 'import json, sys
w = json.load(open(sys.argv[1])); print(w["x_mm"], w["y_mm"], w["z_mm"])' "$OUT"
}
# apart A B: the distance of two points "x y z"
apart() {
  python3 -c 'import sys
a = list(map(float, sys.argv[1].split())); b = list(map(float, sys.argv[2].split()))
print("%.2f" % sum((a[i] - b[i]) ** 2 for i in range(3)) ** 0.5)' "$1" "$2"
}
# below A LIMIT: A < LIMIT
below() { python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) < float(sys.argv[2]) else 1)' "$1" "$2"; }

CAL=$TMP/cal.conf
by_hand base:0deg shoulder:0deg elbow:0deg wrist:0deg wrist-rotate:0deg
expect_out 0 "home: base offset=+23 shoulder offset=-17 elbow offset=+30 wrist offset=-12 wrist-rotate offset=+5 (written to $CAL)" \
  "${P[@]}" calibrate --step home --arm "$arms/xarm.conf" --out "$CAL"
grep -q "^# calibrate home: .* UTC, from $arms/xarm.conf\$" "$CAL" || fail "no home stamp: $(head -3 "$CAL")"

# a lean too small is refused, the profile untouched
by_hand base:20deg shoulder:20deg elbow:3deg wrist:20deg wrist-rotate:20deg
cp "$CAL" "$TMP/before"
expect 2 "${P[@]}" calibrate --step lean --out "$CAL"
expect_err_has "lean further, then take this step again: elbow 3.12 degrees from the zero (at least 5 each)"
cmp -s "$CAL" "$TMP/before" || fail "a refused step changed the profile"

by_hand base:20deg shoulder:20deg elbow:20deg wrist:20deg wrist-rotate:20deg
expect_out 0 "lean: base dir=+1 shoulder dir=+1 elbow dir=-1 wrist dir=+1 wrist-rotate dir=+1 (written to $CAL)" \
  "${P[@]}" calibrate --step lean --out "$CAL"
expect 0 "${TRUE[@]}" move --time 0 gripper:650
expect 0 "${P[@]}" calibrate --step gripper-closed --out "$CAL"
expect 0 "${TRUE[@]}" move --time 0 gripper:120
expect_out 0 '{"step":"gripper-open","profile":"'"$CAL"'","joints":{"gripper":{"open":120,"closed":650}}}' \
  "${P[@]}" --json calibrate --step gripper-open --out "$CAL"
grep -q '^gripper  *1  *bus limits=120..650 open=120 closed=650' "$CAL" ||
  fail "the gripper's line: $(grep '^gripper' "$CAL")"

# where at a test pose: the calibrated profile agrees with the arm as built
by_hand base:30deg shoulder:20deg elbow:40deg wrist:30deg wrist-rotate:10deg
truth=$(where_with "$TMP/true.conf")
d=$(apart "$(where_with "$CAL")" "$truth")
below "$d" 1.5 || fail "where with the calibrated profile is $d mm from the arm's grasp point"
d=$(apart "$(where_with "$arms/xarm.conf")" "$truth")
below 100 "$d" || fail "where with the shipped profile is only $d mm off"
# reach with the calibrated profile lands where it was asked on the arm as built
for t in "180 0 150" "120 80 200" "150 -60 100"; do
  # shellcheck disable=SC2086  # three numbers
  expect 0 "${P[@]}" --arm "$CAL" reach $t --time 100 --wait --tolerance 0
  d=$(apart "$(where_with "$TMP/true.conf")" "$t")
  below "$d" 3 || fail "reach $t with the calibrated profile: $d mm off on the arm"
done
# --check: the point the grasp point is held on
read -r x y z <<<"$(where_with "$CAL")"
expect 0 "${P[@]}" --arm "$CAL" calibrate --check "$x" "$y" "$(python3 -c "print($z + 5)")"
grep -qE '^where: x -?[0-9]+\.[0-9] y -?[0-9]+\.[0-9] z -?[0-9]+\.[0-9] mm, 5\.0 mm from the point measured$' "$OUT" ||
  fail "calibrate --check: $(cat "$OUT")"
expect 0 "${P[@]}" --arm "$CAL" calibrate --check "$x" "$y" "$(python3 -c "print($z + 40)")"
grep -q ", 40.0 mm from the point measured: more than the servos and the links' lengths explain; calibrate again$" "$OUT" ||
  fail "calibrate --check 40 mm off: $(cat "$OUT")"

# a LeArm (PWM servos, positions 500..2500 over 180 degrees): its base's
# horn 40 positions off (3.6 degrees); the shoulder's zero is at its servo's
# end (offset=90deg in the shipped profile: +1000 positions), reversed
sim c --fast --arm "$arms/learm.conf"
L=("$LSCCTL" --port "$TMP/c" "${T[@]}")
expect 0 "${L[@]}" --arm "$arms/learm.conf" move --time 0 base:3.6deg shoulder:0deg elbow:0deg \
  wrist:0deg wrist-rotate:0deg
expect_out 0 "home: base offset=+40 shoulder offset=+1000 elbow offset=+0 wrist offset=+0 wrist-rotate offset=+0 (written to $TMP/learm.conf)" \
  "${L[@]}" calibrate --step home --arm "$arms/learm.conf" --out "$TMP/learm.conf"
expect 0 "${L[@]}" --arm "$arms/learm.conf" move --time 0 base:23.6deg shoulder:20deg elbow:20deg \
  wrist:20deg wrist-rotate:20deg
expect_out 0 "lean: base dir=+1 shoulder dir=-1 elbow dir=+1 wrist dir=+1 wrist-rotate dir=+1 (written to $TMP/learm.conf)" \
  "${L[@]}" calibrate --step lean --out "$TMP/learm.conf"
expect_out 0 "base:19.98deg" "${L[@]}" --arm "$TMP/learm.conf" read base

# errors: nothing sent (the log of lsc-sim gains no frame)
frames() { grep -c ' rx' "$TMP/a.log"; }
before=$(frames)
expect 2 "${P[@]}" calibrate --step sideways --out "$CAL"
expect_err_has "--step 'sideways': use home, lean, gripper-closed or gripper-open"
expect 2 "${P[@]}" calibrate --step home --check 1 2 3
expect 2 "${P[@]}" calibrate 1 2 3
expect_err_has "calibrate takes no arguments (X Y Z go with --check)"
expect 2 "${P[@]}" calibrate --check 1 2
expect 2 "${P[@]}" -n calibrate --step home --out "$CAL"
expect 2 "${P[@]}" calibrate --step home --out "$TMP/new.conf"
expect_err_has "calibration starts from the arm's profile: --arm NAME or FILE"
printf 'base 6 bus\n' >"$TMP/flat.conf"
expect 2 "${P[@]}" calibrate --step home --arm "$TMP/flat.conf" --out "$TMP/new.conf"
expect_err_has "chain:"
expect 2 "$LSCCTL" --port "$(readlink -f "$TMP/a")" "${T[@]}" calibrate --step home --arm "$arms/xarm.conf"
expect_err_has "give the file with --out FILE"
# no controller there: that is what is said (not that it has no name)
expect 1 "$LSCCTL" --port "lscd:nothing" calibrate --step home --arm "$arms/xarm.conf"
expect_err_has "no lscd at"
[ "$(frames)" = "$before" ] || fail "a refused calibrate sent frames"
# --arm given, a result there: continued, and said
expect 0 "${P[@]}" calibrate --step home --arm "$arms/learm.conf" --out "$CAL"
grep -q "continuing $CAL (not --arm's profile: remove the file to start over)" "$ERR" ||
  fail "no notice of the result continued: $(cat "$ERR")"
[ ! -e "$TMP/new.conf" ] || fail "a refused calibrate wrote a file"


# the default place: under the controller's key (the link's name), found by
# lscctl without --arm (-v says so); each arm its own
by_hand base:0deg shoulder:0deg elbow:0deg wrist:0deg wrist-rotate:0deg
expect 0 "${P[@]}" calibrate --step home --arm "$arms/xarm.conf"
[ -f "$XDG_CONFIG_HOME/lsc/arms/port-a.conf" ] || fail "no $XDG_CONFIG_HOME/lsc/arms/port-a.conf"
expect_out 0 "base:0.00deg" "${P[@]}" read base
expect 0 "${P[@]}" -v read 6
expect_err_has "the calibrated profile of this arm: $XDG_CONFIG_HOME/lsc/arms/port-a.conf"
expect 0 "$LSCCTL" --port "$TMP/b" "${T[@]}" move --time 0 6:400
expect 0 "$LSCCTL" --port "$TMP/b" "${T[@]}" calibrate --step home --arm "$arms/xarm.conf"
expect_out 0 "base:0.00deg" "$LSCCTL" --port "$TMP/b" "${T[@]}" read base
grep -q "^base.*offset=-100" "$XDG_CONFIG_HOME/lsc/arms/port-b.conf" || fail "arm b's profile"
grep -q "^base.*offset=+23" "$XDG_CONFIG_HOME/lsc/arms/port-a.conf" || fail "arm a's profile"
# lscctl status (lscd) names the calibrated profile of the arm lscd serves
if [ -n "${LSCD:-}" ]; then
  mkdir -p "$TMP/run"
  cp "$XDG_CONFIG_HOME/lsc/arms/port-a.conf" "$XDG_CONFIG_HOME/lsc/arms/sim.conf"
  LSC_LSCD_DIR=$TMP/run "$LSCD" --port sim 2>"$TMP/lscd.log" &
  LSCD_PID=$!
  lscd_up() { LSC_LSCD_DIR=$TMP/run "$LSCCTL" --port lscd:sim status >/dev/null 2>&1; }
  wait_for "lscd on sim did not answer" lscd_up
  LSC_LSCD_DIR=$TMP/run expect 0 "$LSCCTL" --port lscd:sim "${T[@]}" status
  grep -qx "calibrated profile: $XDG_CONFIG_HOME/lsc/arms/sim.conf" "$OUT" ||
    fail "status: $(cat "$OUT")"
  kill "$LSCD_PID"
  wait "$LSCD_PID"
fi
# --arm still wins
expect_out 0 "base:5.52deg" "${P[@]}" --arm "$arms/xarm.conf" read base

finish
