#!/usr/bin/env bash
# lscctl --arm FILE (docs/arm-profile.md): joint names and degrees in move and
# read, limits refused with nothing sent (the position that would be sent is
# what is checked), move --wait, profile errors with FILE:LINE:COLUMN, only
# regular files, LSC_ARM; profiles by name (--arm xarm: the user's, then the
# installed ones) in lscctl, convert and lsc-sim.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
arms=$here/../../examples/arms
scale=${LSC_TEST_TIME_SCALE:-1}
XARM=("$LSCCTL" --arm "$arms/xarm.conf")

# base (servo 6) 30deg -> 500 + 125 = 625 (71 02),
# shoulder (servo 5) -20deg -> 500 - 83.3 = 417 (A1 01).
expect_out 0 "55 55 0B 03 02 E8 03 06 71 02 05 A1 01" "${XARM[@]}" --port sim -n move base:30deg shoulder:-20deg
expect_out 0 "" "${XARM[@]}" --port sim -v move base:30deg shoulder:-20deg
expect_err_has "sent servo_move time_ms=1000 servos=6:625,5:417 (55 55 0B 03 02 E8 03 06 71 02 05 A1 01)"
# ids and positions mix with names and degrees; decimals; LSC_ARM
expect_out 0 "55 55 0B 03 02 E8 03 02 B3 01 01 BC 02" "${XARM[@]}" -n move 2:-15.5deg gripper:700
expect_out 0 "55 55 08 03 01 E8 03 04 0E 02" env LSC_ARM="$arms/xarm.conf" "$LSCCTL" -n move elbow:6.24deg
expect_out 0 "55 55 08 03 01 E8 03 09 D0 07" "${XARM[@]}" -n move 9:2000   # not a joint: a position
# the LeArm: PWM servos, a reversed shoulder with its zero 90 degrees off
expect_out 0 "55 55 0B 03 02 E8 03 05 C4 09 06 4B 06" "$LSCCTL" --arm "$arms/learm.conf" -n move shoulder:0deg base:10deg
expect_out 0 "55 55 08 03 01 E8 03 05 DC 05" "$LSCCTL" --arm "$arms/learm.conf" -n move shoulder:90deg

# Out of limits: exit 2, nothing sent, the joint and its limits named.
expect_out 2 "" "${XARM[@]}" --port sim -v move base:114.60deg
expect_err_has "114.60deg is outside the limits of joint base (servo 6): -114.59deg..114.59deg, positions 23..977"
expect_out 2 "" "${XARM[@]}" -n move shoulder:0deg gripper:701
expect_err_has "position 701 is outside the limits of joint gripper (servo 1): -120.00deg..48.00deg, positions 0..700"
expect_out 2 "" "${XARM[@]}" -n move base:-400deg
expect_err_has "joint base"
expect_out 2 "" "${XARM[@]}" -n move base:999999.99deg
expect_err_has "999999.99deg is outside the limits of joint base"
# an id is at most 7 characters in JOINT:VALUE
expect_out 0 "55 55 08 03 01 E8 03 06 F4 01" "${XARM[@]}" -n move 0000006:500
expect_out 2 "" "${XARM[@]}" -n move 00000006:500
expect_err_has "'00000006' is neither a joint of the arm profile nor a servo id"
expect_out 2 "" "$LSCCTL" --arm "$arms/learm.conf" -n move shoulder:-0.01deg
expect_err_has "limits of joint shoulder (servo 5): 0.00deg..175.00deg"
expect_out 0 "55 55 08 03 01 E8 03 06 17 00" "${XARM[@]}" -n move base:-114.59deg
# bad targets
for bad in "wrist:" "wrist:1.5" "wrist:15.555deg" "wrist:1rad" "wrist:+" "hand:10deg" \
           "9:10deg" "base" "base:1.deg" "gripper:70000"; do
  expect_out 2 "" "${XARM[@]}" -n move "$bad"
done
expect_out 2 "" "${XARM[@]}" -n move base:10deg 6:500
expect_err_has "servo 6 is given twice"
# without a profile: degrees need one, ID:POSITION as always
expect_out 2 "" "$LSCCTL" -n move 1:30deg
expect_err_has "arm profile (--arm FILE)"
expect_out 0 "55 55 08 03 01 E8 03 01 DC 05" "$LSCCTL" -n move 1:1500

# read: degrees by joint name (the form move takes), both in JSON
expect_out 0 "55 55 05 15 02 06 05" "${XARM[@]}" -n read base shoulder
# (with a profile the sim stands in for the arm: its joints at 0 degrees, an
# xArm's at 500; servos on no joint at 1500)
expect_out 0 "base:0.00deg
shoulder:0.00deg
7:1500" "${XARM[@]}" --port sim read base 5 7
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":6,"position":500,"joint":"base","degrees":0.00},{"id":1,"position":500,"joint":"gripper","degrees":0.00},{"id":7,"position":1500}]}' \
  "${XARM[@]}" --port sim --json read base gripper 7
# (the LeArm's shoulder reads 0 degrees at the end of its servo's range)
expect_out 0 "shoulder:0.00deg" "$LSCCTL" --arm "$arms/learm.conf" --port sim read shoulder
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":5,"position":2500,"joint":"shoulder","degrees":0.00}]}' \
  "$LSCCTL" --arm "$arms/learm.conf" --port sim --json read 5
expect_out 2 "" "${XARM[@]}" -n read hand
expect_err_has "'hand' is neither a joint of the arm profile nor a servo id"
expect_out 2 "" "${XARM[@]}" -n read base 6
expect_err_has "id 6 is given twice"

# Profile errors: FILE:LINE:COLUMN: reason, exit 2, nothing sent.
profile() { printf '%b' "$1" >"$TMP/arm.conf"; }
bad_profile() { # TEXT WHERE-AND-WHY
  profile "$1"
  expect_out 2 "" "$LSCCTL" --arm "$TMP/arm.conf" -n move 1:500
  expect_err_has "$TMP/arm.conf:$2"
}
bad_profile "# nothing\n" " no joints"
bad_profile "base 6\n" "1:7: a joint is NAME ID KIND"
bad_profile "base 6 bus\nbase 5 bus\n" "2:1: joint base is named twice"
bad_profile "base 6 bus\narm 6 bus\n" "2:5: servo 6 is joint base already"
bad_profile "6base 6 bus\n" "1:1: a joint's name starts with a letter"
bad_profile "ba.se 6 bus\n" "1:3: a joint's name has letters"
bad_profile "base 256 bus\n" "1:6: id 256 is out of range"
bad_profile "base 6 servo\n" "1:8: kind: use pwm"
bad_profile "base 6 0..4095/0deg\n" "1:8: kind: positions are"
bad_profile "base 6 bus dir=2\n" "1:16: dir: use +1 or -1"
bad_profile "base 6 bus  offset=600\n" "1:20: offset: the joint's zero would be outside"
bad_profile "base 6 bus offset=1.5\n" "1:19: offset: a position is a whole number"
# angles and positions far out of range (no conversion wraps or overflows)
bad_profile "base 6 bus offset=400deg\n" "1:19: offset: the joint's zero would be outside"
bad_profile "base 6 bus offset=-999999.99deg\n" "1:19: offset: the joint's zero would be outside"
bad_profile "base 6 bus limits=0..70000\n" "1:12: limits: position 70000 is outside the servo's range 0..1000"
bad_profile "base 6 bus limits=-1..10\n" "1:12: limits: position -1 is outside"
bad_profile "base 6 bus limits=0..999999\n" "1:12: limits: position 999999 is outside"
bad_profile "base 0x00000000000006 bus\n" "1:6: id: use 0..255"
bad_profile "base 0x0000000000006 bus\nx\n" "2:2: a joint is NAME ID KIND"
bad_profile "base 6 bus limits=10deg\n" "1:19: limits: write LOW..HIGH"
bad_profile "base 6 bus limits=0..1001\n" "1:12: limits: position 1001 is outside"
bad_profile "base 6 bus limits=0..400deg\n" "1:12: limits: an angle is within"
bad_profile "base 6 bus speed=3\n" "1:12: 'speed=3': settings are"
bad_profile "base 6 bus dir=1 dir=-1\n" "1:18: dir is given twice"
bad_profile "base 6 bus dir=1 offset=0 limits=0..9 open=1 closed=2 x\n" "1:55: too many fields"
bad_profile "base 6 bus\x01\n" "1:11: unexpected byte 0x01"
bad_profile "ok 1 bus\n\n  # c\nbase 6 bus # comment\r\nx\n" "5:2: a joint is NAME ID KIND"
expect_out 2 "" "$LSCCTL" --arm "$TMP/none.conf" -n move 1:500
expect_err_has "cannot read the arm profile $TMP/none.conf"
head -c 70000 /dev/zero | tr '\0' '#' >"$TMP/big.conf"
expect_out 2 "" "$LSCCTL" --arm "$TMP/big.conf" -n move 1:500
expect_err_has "longer than 65536 bytes"
# only regular files: a directory, a FIFO (no writer: no wait) or a device is refused at once
expect_out 2 "" "$LSCCTL" --arm "$TMP" -n move 1:500
expect_err_has "cannot read the arm profile $TMP: it is a directory (an arm profile is a regular file)"
mkfifo "$TMP/fifo.conf"
expect_out 2 "" "$LSCCTL" --arm "$TMP/fifo.conf" -n move 1:500
expect_err_has "cannot read the arm profile $TMP/fifo.conf: it is a FIFO"
expect_out 2 "" env LSC_ARM="$TMP/fifo.conf" "$LSCCTL" -n read 1
expect_err_has "it is a FIFO"
if [ -c /dev/zero ]; then
  expect_out 2 "" "$LSCCTL" --arm /dev/zero -n move 1:500
  expect_err_has "cannot read the arm profile /dev/zero: it is a device"
fi
# a file name with a newline or an escape sequence: one line, escaped
expect_out 2 "" "$LSCCTL" --arm "$TMP/a"$'\n'"b"$'\033'"[2J.conf" -n move 1:500
expect_err_has "cannot read the arm profile $TMP/a\x0Ab\x1B[2J.conf: No such file or directory"
[ "$(wc -l <"$ERR")" -eq 1 ] || fail "a file name broke the message's line: $(cat -v "$ERR")"
# a UTF-8 byte-order mark (as some Windows editors write) is skipped
profile "\0357\0273\0277# xArm\r\nbase 6 bus\r\n"
expect_out 0 "55 55 08 03 01 E8 03 06 71 02" "$LSCCTL" --arm "$TMP/arm.conf" -n move base:30deg
# limits that hold no position of the servo
bad_profile "base 6 bus limits=0.01deg..0.02deg\n" "1:19: limits: 0.01deg..0.02deg hold no position of the servo"
# exact limits: the position that would be sent is what is checked
profile "base 6 bus limits=0deg..10deg\n"
expect_out 2 "" "$LSCCTL" --arm "$TMP/arm.conf" -n move base:542
expect_err_has "position 542 is outside the limits of joint base (servo 6): 0.00deg..10.00deg, positions 500..541"
expect_out 2 "" "$LSCCTL" --arm "$TMP/arm.conf" -n move base:10deg
expect_err_has "10deg (position 542) is outside the limits of joint base (servo 6): 0.00deg..10.00deg, positions 500..541"
expect_out 0 "55 55 08 03 01 E8 03 06 1D 02" "$LSCCTL" --arm "$TMP/arm.conf" -n move base:9.95deg
# without limits, every position of the servo (both ends) is allowed
profile "w 3 0..4095/360deg\n"
expect_out 0 "55 55 08 03 01 E8 03 03 FF 0F" "$LSCCTL" --arm "$TMP/arm.conf" -n move w:4095
# a valid one with every setting: 12-bit servo over 360 degrees, reversed, offset
profile "# a comment\n\twrist 3 0..4095/360deg dir=-1 offset=-10deg limits=100..4000 # c\r\n"
expect_out 0 "55 55 08 03 01 E8 03 03 8D 07" "$LSCCTL" --arm "$TMP/arm.conf" -n move wrist:0deg
expect_out 0 "55 55 08 03 01 E8 03 03 8D 03" "$LSCCTL" --arm "$TMP/arm.conf" -n move wrist:90deg
expect_out 2 "" "$LSCCTL" --arm "$TMP/arm.conf" -n move wrist:170deg
expect_err_has "-181.72deg..161.15deg, positions 100..4000"
# commands that do not use the profile do not read it
expect_out 0 "55 55 02 07" env LSC_ARM="$TMP/none.conf" "$LSCCTL" -n stop
expect_out 2 "" "$LSCCTL" --arm "" -n stop

# move --wait: the sim's servos reach their targets; --json prints the move
expect_out 0 "" "${XARM[@]}" --port sim move --wait --time 500 base:30deg shoulder:-20deg
expect_out 0 '{"cmd":3,"name":"servo_move","time_ms":200,"servos":[{"id":1,"position":2000}]}' \
  "$LSCCTL" --port sim --json move --wait --time 200 1:2000
# a board whose servo stays away from the target: it stopped short (its
# reads no longer change), said on stderr, exit 0; --strict: exit 3
peer() { stop_peer; start_peer "$@"; }
peer -r "55 55 06 15 01 01 F4 01"
expect_out 0 "" "$LSCCTL" --port "$TMP/tty" --timeout $((1000 * scale)) move --wait --time 10 1:2000
expect_err_has "servo 1 stopped at 500, 1500 short of its target 2000"
expect_out 3 "" "$LSCCTL" --port "$TMP/tty" --timeout $((1000 * scale)) move --wait --strict --time 10 1:2000
expect_err_has "servo 1 stopped at 500, 1500 short of its target 2000 (--strict)"
# ... within a wider tolerance: done
expect_out 0 "" "$LSCCTL" --port "$TMP/tty" --timeout $((1000 * scale)) move --wait --tolerance 1500 --time 10 1:2000
# a board that does not answer position reads: done when the time has passed
peer
expect_out 0 "" "$LSCCTL" --port "$TMP/tty" --timeout $((300 * scale)) move --wait --time 10 1:2000
stop_peer
expect_out 2 "" "$LSCCTL" -n move --tolerance x 1:2000


# Servo offsets (xArm commands 23, 24) and the refusal of command 27.
expect_out 0 "55 55 04 18 06 F6" "$LSCCTL" -n offset set 6 -10
expect_out 0 "55 55 04 18 01 7F" "$LSCCTL" -n offset set 1 127
expect_out 0 "55 55 04 18 01 80" "$LSCCTL" -n offset set 1 -128
expect_out 0 "55 55 05 17 02 06 01" "$LSCCTL" -n offset read 6 1
# -n --json names them (lscctl's message printer knows commands 23 and 24)
expect_out 0 '{"hex":"55 55 04 18 06 F6","cmd":24,"name":"servo_offset_adjust","id":6,"offset":-10}' \
  "$LSCCTL" -n --json offset set 6 -10
expect_out 0 '{"hex":"55 55 05 17 02 06 01","cmd":23,"name":"servo_offset_read","ids":[6,1]}' \
  "$LSCCTL" -n --json offset read 6 1
expect_out 0 "1:0
6:0" "$LSCCTL" --port sim offset read 1 6
expect_out 0 '{"cmd":23,"name":"servo_offset_read","servos":[{"id":1,"offset":0}]}' "$LSCCTL" --port sim --json offset read 1
expect_out 0 "" "$LSCCTL" --port sim offset set 6 -10
for bad in "offset set 6 128" "offset set 6 -129" "offset set 256 0" "offset set 6" "offset set 6 1 2" \
           "offset get 1" "offset read 1 1" "offset read x" "offset read $(seq -s ' ' 1 41)"; do
  # shellcheck disable=SC2086
  expect_out 2 "" "$LSCCTL" -n $bad
done
expect_out 2 "" "$LSCCTL" -n send 27 1
expect_err_has "command 27 writes a setting"
expect_out 0 "55 55 03 1B 01" "$LSCCTL" -n send 27 1 --force
start_peer -r "55 55 07 17 02 06 F6 01 05"
expect_out 0 "6:-10
1:5" "$LSCCTL" --port "$TMP/tty" offset read 6 1
stop_peer
start_peer -r "55 55 07 17 02 06 F6 01 05"
expect_out 0 '{"cmd":23,"name":"servo_offset_read","servos":[{"id":6,"offset":-10},{"id":1,"offset":5}]}' \
  "$LSCCTL" --port "$TMP/tty" --json offset read 6 1
stop_peer
# -v names the offset frames it traces
expect_out 0 "1:0" "$LSCCTL" --port sim -v offset read 1
expect_err_has "lscctl: sent servo_offset_read ids=1 (55 55 04 17 01 01)"
expect_err_has "lscctl: received servo_offset_read servos=1:0 (55 55 05 17 01 01 00)"
start_peer
expect_out 3 "" "$LSCCTL" --port "$TMP/tty" --timeout $((200 * scale)) offset read 6
expect_err_has "LSC-6/16/32 boards may not answer"
stop_peer

# Joint names in unload, offset and record --ids, beside ids (and ranges)
expect_out 0 "55 55 05 14 02 06 01" "${XARM[@]}" -n unload base gripper
expect_out 0 "55 55 05 14 02 06 01" env LSC_ARM="$arms/xarm.conf" "$LSCCTL" -n unload base 1
expect_out 0 "" "${XARM[@]}" --port sim unload wrist-rotate elbow
expect_out 2 "" "${XARM[@]}" -n unload base 6
expect_err_has "id 6 is given twice"
expect_out 2 "" "${XARM[@]}" -n unload elbw
expect_err_has "'elbw' is neither a joint of the arm profile nor a servo id"
expect_out 2 "" "$LSCCTL" -n unload base
expect_err_has "id 'base' is not a number: write it in decimal or 0x-hex; a joint name needs an arm profile (--arm FILE)"
expect_out 0 "55 55 05 17 02 06 01" "${XARM[@]}" -n offset read base gripper
expect_out 0 "55 55 04 18 06 F6" "${XARM[@]}" -n offset set base -10
expect_out 0 "6:0" "${XARM[@]}" --port sim offset read base
expect_out 0 "" "${XARM[@]}" --port sim offset set wrist 3
expect_out 2 "" "${XARM[@]}" -n offset set elbw 1
expect_err_has "'elbw' is neither a joint of the arm profile nor a servo id"
expect_out 2 "" "$LSCCTL" -n offset set base 1
expect_err_has "id 'base' is not a number: write it in decimal or 0x-hex; a joint name needs an arm profile (--arm FILE)"
expect_out 2 "" "$LSCCTL" --arm "$TMP/none.conf" -n offset read 1
expect_err_has "cannot read the arm profile $TMP/none.conf"
# record --ids: the unload and the read of base, shoulder, 3 and 4
expect_out 0 "55 55 07 14 04 06 05 03 04
55 55 07 15 04 06 05 03 04" "${XARM[@]}" -n record "$TMP/r.csv" --ids base,shoulder,3-4
expect_out 0 "keyframe 1 +10 ms: 6:500 1:500
keyframe 2 +10 ms: 6:500 1:500" "${XARM[@]}" --port sim record "$TMP/names.csv" --ids base,gripper --every 10 --count 2
expect_err_has "servos base,gripper go limp now"
[ "$(head -n 1 "$TMP/names.csv")" = "time_ms,6,1" ] || fail "record --ids base,gripper: $(cat "$TMP/names.csv")"
expect_out 2 "" "${XARM[@]}" -n record "$TMP/r.csv" --ids base,6
expect_err_has "--ids 'base,6': servo 6 listed twice"
expect_out 2 "" "${XARM[@]}" -n record "$TMP/r.csv" --ids elbw,1
expect_err_has "--ids 'elbw,1': 'elbw' is neither a joint of the arm profile nor a servo id"
expect_out 2 "" "$LSCCTL" -n record "$TMP/r.csv" --ids base
expect_err_has "--ids 'base': id 'base' is not a number"
expect_out 2 "" "$LSCCTL" --arm "$TMP/none.conf" -n record "$TMP/r.csv"
expect_err_has "cannot read the arm profile $TMP/none.conf"
expect_out 2 "" "${XARM[@]}" -n record "$TMP/r.csv" --ids -5
expect_err_has "--ids '-5': id '-5' is negative: use 0..255"
[ -e "$TMP/r.csv" ] && fail "record -n made $TMP/r.csv"

# ---- Profiles by name (lsc_arm_open): --arm NAME, $LSC_ARM=NAME, lsc-sim --arm NAME,
# from a directory that is not the tree: $XDG_CONFIG_HOME/lsc/arms/NAME.conf first
# (~/.config without it), then the installed ones ($LSC_ARMS_DIR here)
mkdir -p "$TMP/elsewhere" "$TMP/config/lsc/arms" "$TMP/home/.config/lsc/arms" "$TMP/installed"
cp "$arms/xarm.conf" "$arms/learm.conf" "$TMP/installed/"
named() { (cd "$TMP/elsewhere" && env HOME="$TMP/home" XDG_CONFIG_HOME="$TMP/config" \
  LSC_ARMS_DIR="$TMP/installed" "$@"); }
expect_out 0 "55 55 0B 03 02 E8 03 06 71 02 05 A1 01" named "$LSCCTL" --arm xarm -n move base:30deg shoulder:-20deg
expect_out 0 "base:0.00deg" named "$LSCCTL" --arm learm --port sim read base
expect_out 0 "55 55 08 03 01 E8 03 04 0E 02" named env LSC_ARM=xarm "$LSCCTL" -n move elbow:6.24deg
# the user's own profile of that name comes first ...
printf 'hand 3 pwm limits=-10deg..10deg\n' >"$TMP/config/lsc/arms/xarm.conf"
expect_out 0 "hand:0.00deg" named "$LSCCTL" --arm xarm --port sim read hand
expect_out 2 "" named "$LSCCTL" --arm xarm -n move base:30deg
expect_err_has "'base' is neither a joint of the arm profile nor a servo id"
# ... and ~/.config's when $XDG_CONFIG_HOME is unset
printf 'claw 4 pwm\n' >"$TMP/home/.config/lsc/arms/learm.conf"
expect_out 0 "claw:0.00deg" named env -u XDG_CONFIG_HOME "$LSCCTL" --arm learm --port sim read claw
# a name found nowhere: where it looked, in order, exit 2, nothing sent
expect_out 2 "" named "$LSCCTL" --arm xram -n move base:30deg
expect_err_has "no arm profile named xram: looked for $TMP/config/lsc/arms/xram.conf, $TMP/installed/xram.conf (a file in this directory: ./xram)"
# a path stays a path: '/' or .conf (a file of the working directory)
cp "$arms/xarm.conf" "$TMP/elsewhere/mine"
expect_out 0 "55 55 08 03 01 E8 03 06 71 02" named "$LSCCTL" --arm ./mine -n move base:30deg
expect_out 2 "" named "$LSCCTL" --arm xarm.conf -n move base:30deg
expect_err_has "cannot read the arm profile xarm.conf: No such file or directory"
# convert --from-arm/--to-arm and lsc-sim --arm take names too
printf 'time_ms,1,2,3,4,5,6\n1000,1500,1500,1500,1500,1500,1500\n' >"$TMP/elsewhere/pose.csv"
rm "$TMP/config/lsc/arms/xarm.conf" "$TMP/home/.config/lsc/arms/learm.conf"
expect_out 0 "" named "$LSCCTL" convert pose.csv pose.rob --from-arm learm --to-arm xarm
[ -s "$TMP/elsewhere/pose.rob" ] || fail "convert --from-arm learm --to-arm xarm wrote no pose.rob"
(cd "$TMP/elsewhere" && HOME="$TMP/home" XDG_CONFIG_HOME="$TMP/config" LSC_ARMS_DIR="$TMP/installed" \
  exec "$LSC_SIM" --link "$TMP/named-sim" --arm xarm >/dev/null 2>"$TMP/named-sim.log") &
SIMS+=($!)
wait_for "lsc-sim --arm xarm did not make $TMP/named-sim" test -e "$TMP/named-sim" ||
  fail "lsc-sim --arm xarm: $(cat "$TMP/named-sim.log")"
expect_out 0 "6:500" "$LSCCTL" --port "$TMP/named-sim" read 6   # the xArm's base, at 0 degrees
expect_out 2 "" named "$LSC_SIM" --link "$TMP/never" --arm xram
expect_err_has "lsc-sim: --arm: no arm profile named xram: looked for"

finish
