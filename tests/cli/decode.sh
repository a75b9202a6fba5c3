#!/usr/bin/env bash
# lscctl decode: text and JSON, arguments and standard input, direction,
# invalid bytes (exit 1, reported as {"error","hex"}), invalid hex (exit 2).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
D=("$LSCCTL" decode)

# Text: one line per frame, "DIR NAME key=value... (HEX)".
expect_out 0 "host servo_move time_ms=800 servos=2:1200,9:2300 (55 55 0B 03 02 20 03 02 B0 04 09 FC 08)
host action_group_speed group=all percent=300 (55 55 05 0B FF 2C 01)
controller get_battery_voltage millivolts=7500 volts=7.500 (55 55 04 0F 4C 1D)
host mult_servo_pos_read ids=1,2 (55 55 05 15 02 01 02)
controller mult_servo_pos_read servos=1:500 (55 55 06 15 01 01 F4 01)
host mult_servo_unload ids=7 (55 55 04 14 01 07)" \
  "${D[@]}" 5555 0b0302 2003 02b00409fc08 0x55 0x55 0x5 0xB 0xFF 0x2C 0x1 55:55:04:0F:4C:1D 55,55,05,15,02,01,02 \
  "55 55 06 15 01 01 F4 01" 55550414 0107

# Unknown commands are frames too (the xArm has more): their bytes are shown.
expect_out 0 "host unknown cmd=22 params=0102 (55 55 04 16 01 02)" "${D[@]}" 55 55 04 16 01 02
expect_out 0 '{"dir":"host","hex":"55 55 04 16 01 02","cmd":22,"name":"unknown","params":"01 02"}' \
  "${D[@]}" --json 55 55 04 16 01 02
expect_out 0 "host unknown cmd=30 params=none (55 55 02 1E)" "${D[@]}" 5555021e

# The xArm's servo offsets (commands 23 and 24) are known messages, not unknown
# ones: request and reply told apart by length like mult_servo_pos_read.
expect_out 0 "host servo_offset_read ids=1,2 (55 55 05 17 02 01 02)
controller servo_offset_read servos=1:0,2:-3 (55 55 07 17 02 01 00 02 FD)
host servo_offset_adjust id=1 offset=-5 (55 55 04 18 01 FB)" \
  "${D[@]}" 55 55 05 17 02 01 02 55 55 07 17 02 01 00 02 FD 55 55 04 18 01 FB
expect_out 0 '{"dir":"host","hex":"55 55 05 17 02 01 02","cmd":23,"name":"servo_offset_read","ids":[1,2]}
{"dir":"controller","hex":"55 55 07 17 02 01 00 02 FD","cmd":23,"name":"servo_offset_read","servos":[{"id":1,"offset":0},{"id":2,"offset":-3}]}
{"dir":"host","hex":"55 55 04 18 01 80","cmd":24,"name":"servo_offset_adjust","id":1,"offset":-128}' \
  "${D[@]}" --json 55 55 05 17 02 01 02 55 55 07 17 02 01 00 02 FD 55 55 04 18 01 80
expect_out 1 "error not a valid servo_offset_read reply (55 55 05 17 02 01 02)" \
  "${D[@]}" --from controller 55 55 05 17 02 01 02
expect_out 1 "error not a valid servo_offset_adjust (55 55 03 18 01)" "${D[@]}" 55 55 03 18 01

# A LEN byte of 0x55 is one more header byte: 55 55 55 02 07 is a stop.
expect_out 0 "host action_group_stop (55 55 02 07)" "${D[@]}" 55 55 55 02 07

# Invalid bytes: reported in place, exit 1 with one line on stderr.
expect_out 1 '{"error":"bytes outside a frame","hex":"01 02"}
{"dir":"host","hex":"55 55 02 07","cmd":7,"name":"action_group_stop"}
{"error":"malformed frame","hex":"55 55 03 07"}
{"error":"bytes outside a frame","hex":"00"}
{"dir":"host","hex":"55 55 02 0F","cmd":15,"name":"get_battery_voltage"}
{"error":"incomplete frame","hex":"55 55 05"}' \
  "${D[@]}" --json 01 02 55 55 02 07 55 55 03 07 00 55 55 02 0F 55 55 05
expect_err_has "10 bytes were not a valid frame"
expect_out 1 "error bytes outside a frame (FF)" "${D[@]}" FF
expect_err_has "1 byte was not a valid frame"
# a frame of the right length whose contents contradict it (a repeated id)
expect_out 1 '{"error":"not a valid servo_move","hex":"55 55 0B 03 02 E8 03 01 D0 07 01 D0 07"}' \
  "${D[@]}" --json 55 55 0B 03 02 E8 03 01 D0 07 01 D0 07

# --from: who sent the bytes decides between request and reply.
expect_out 0 "controller action_group_run group=8 times=1 (55 55 05 06 08 01 00)" \
  "${D[@]}" --from controller 55 55 05 06 08 01 00
expect_out 1 "error not a valid get_battery_voltage reply (55 55 02 0F)" \
  "${D[@]}" --from controller 55 55 02 0F
expect_out 1 "error not a valid get_battery_voltage request (55 55 04 0F 4C 1D)" \
  "${D[@]}" --from host 55 55 04 0F 4C 1D
expect_out 0 "host mult_servo_pos_read ids=1 (55 55 04 15 01 01)" "${D[@]}" --from=host 55550415 0101

# Standard input: line by line, a frame may span lines; same output.
printf '55 55 08 03 01\nE8 03 01 D0 07\n\n  5555020f  \n' >"$TMP/in"
checks=$((checks + 1))
"${D[@]}" <"$TMP/in" >"$OUT" 2>"$ERR" || fail "stdin decode exit $?"
[ "$(cat "$OUT")" = "host servo_move time_ms=1000 servos=1:2000 (55 55 08 03 01 E8 03 01 D0 07)
host get_battery_voltage (55 55 02 0F)" ] || fail "stdin decode: $(cat "$OUT")"
[ ! -s "$ERR" ] || fail "stdin decode wrote on stderr: $(cat "$ERR")"
# empty input: nothing to say, success
expect_out 0 "" "${D[@]}"
# decode_stdin CODE FORMAT [OPTIONS]: decode of printf FORMAT's bytes on
# standard input exits CODE (then check $ERR)
decode_stdin() {
  local code=$1 format=$2; shift 2
  # shellcheck disable=SC2059  # the format is the input
  printf "$format" >"$TMP/in"
  checks=$((checks + 1))
  "${D[@]}" "$@" <"$TMP/in" >"$OUT" 2>"$ERR"
  rc=$?
  [ "$rc" = "$code" ] || fail "decode of $(printf %q "$format") on stdin: exit $rc, want $code"
}
# invalid hex on a line: exit 2, naming the line
decode_stdin 2 '55 55 02 07\nhello\n' --json
expect_err_has "line 2: 'hello' is not hex bytes"
# a NUL byte in a line is not hex, nor the end of the line
decode_stdin 2 '55 55 02 07\0 zz garbage\n'
expect_err_has "line 1: a NUL byte (column 12) is not hex"
decode_stdin 2 '55 55 02 07\n\0\n'
expect_err_has "line 2: a NUL byte (column 1) is not hex"
# bad input repeated in a message: control bytes escaped as \xNN, never raw
decode_stdin 2 '55 55 02 07\n55 \001\033[2J\\x\377 07\n'
expect_err_has 'line 2: '"'"'\x01\x1B[2J\\x\xFF'"'"' is not hex bytes'
grep -q "$(printf '[\001\033\377]')" "$ERR" && fail "raw control bytes on stderr: $(cat -v "$ERR")"
expect_out 2 "" "$LSCCTL" -n move "$(printf '1:\a\t2')"
expect_err_has "position '\x07\x092' is not a number"
expect_out 2 "" "$LSCCTL" decode "$(printf '55\r')x"
expect_err_has "'x' is not hex bytes"
# binary garbage over stdin: every byte accounted for, never a crash
decode_stdin 1 "55 55 $(head -c 600 /dev/zero | tr '\0' 'a')\n" --json
finish
