#!/usr/bin/env bash
# lscctl over USB HID (docs/hid.md): lscctl built with the hidapi test double
# (tests/hid_double.c) in place of libhidapi-hidraw, whose arms are the
# virtual controller behind the xArm's report rules. Arms come from
# $LSC_HID_DOUBLE ("NODE|SERIAL|FLAGS;..."); every report lscctl writes is
# logged to $LSC_HID_DOUBLE_LOG. The answers must be those of --port sim (the
# same model) and of the pty tests.
# With --none: lscctl built without hidapi says so (exit 2, nothing sent).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
unset LSC_PORT
if [ "${1:-}" = --none ]; then
  for port in hid hid:ARM-A /dev/hidraw0; do
    expect_out 2 "" "$LSCCTL" --port "$port" battery
    expect_err_has "built without HID support"
  done
  LSC_PORT=hid expect_out 2 "" "$LSCCTL" read 1
  expect_err_has "built without HID support"
  finish
  exit
fi
: "${LSCCTL_HID:?set LSCCTL_HID to lscctl built with the hidapi test double}"
A=$TMP/hidraw0
B=$TMP/hidraw1
: >"$A"
: >"$B"
export LSC_HID_DOUBLE_LOG=$TMP/reports
H=("$LSCCTL_HID")
zeros() { local i; for i in $(seq "$1"); do printf " 00"; done; }
# last_report: the last report written, as hex
last_report() { tail -n 1 "$LSC_HID_DOUBLE_LOG"; }

# same_as_sim ARGS...: over HID, exit 0 and the same stdout as --port sim
same_as_sim() {
  local want
  want=$("$LSCCTL_HID" --port sim "$@" </dev/null 2>/dev/null)
  expect_out 0 "$want" "${H[@]}" --port hid "$@"
}

export LSC_HID_DOUBLE="$A|ARM-A|"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid battery
# one 65-byte report: no report id (00), the frame, zero padding
[ "$(last_report)" = "00 55 55 02 0F$(zeros 60)" ] || fail "battery report: $(last_report)"
same_as_sim battery
same_as_sim --json battery
expect_out 0 "1:1500
2:1500
3:1500
4:1500
5:1500
6:1500" "${H[@]}" --port hid read 1 2 3 4 5 6
same_as_sim read 1 2 3 4 5 6
same_as_sim --json read 1 2 3 4 5 6
expect_out 0 "" "${H[@]}" --port hid move --time 500 1:2000 2:1200
[ "$(last_report)" = "00 55 55 0B 03 02 F4 01 01 D0 07 02 B0 04$(zeros 51)" ] ||
  fail "move report: $(last_report)"
expect_out 0 "action_group_complete group=8 times=1" "${H[@]}" --port hid run 8 --wait
same_as_sim run 8 --wait
same_as_sim --json run 1 --wait
for c in "stop" "speed 8 50" "unload 1 2 3"; do
  # shellcheck disable=SC2086  # the arguments are words
  expect_out 0 "" "${H[@]}" --port hid $c
done
[ "$(last_report)" = "00 55 55 06 14 03 01 02 03$(zeros 56)" ] || fail "unload report: $(last_report)"
expect_out 0 "" "${H[@]}" --port hid send 3 1 0xF4 0x01 1 0xD0 0x07
# every report lscctl wrote was 65 bytes with 00 first
awk 'NF != 65 || $1 != "00" { bad = 1 } END { exit bad }' "$LSC_HID_DOUBLE_LOG" ||
  fail "a report was not 65 bytes with 00 first: $(cat "$LSC_HID_DOUBLE_LOG")"

# -v traces HID frames like serial ones
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid -v battery
expect_err_has "lscctl: sent get_battery_voltage (55 55 02 0F)"
expect_err_has "lscctl: received get_battery_voltage millivolts=7500 volts=7.500 (55 55 04 0F 4C 1D)"

# monitor: an arm whose group 8 starts as it is opened (the handle's button)
export LSC_HID_DOUBLE="$A|ARM-A|run=8"
expect_out 0 "action_group_run group=8 times=1
action_group_complete group=8 times=1" "${H[@]}" --port hid monitor --count 2
expect_out 0 '{"cmd":6,"name":"action_group_run","group":8,"times":1}' \
  "${H[@]}" --port hid --json monitor --count 1
expect_out 0 "action_group_complete group=8 times=1" "${H[@]}" --port hid wait

# padding that is not zero, a notification before each reply, a report
# without a frame before each reply: the same answers
export LSC_HID_DOUBLE="$A|ARM-A|pad=55,notify,garbage"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid battery
expect_out 0 "1:1500
2:1500" "${H[@]}" --port hid read 1 2

# the first request after the open goes unanswered: sent once more
export LSC_HID_DOUBLE="$A|ARM-A|mute-first"
: >"$LSC_HID_DOUBLE_LOG"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid -t 300 battery
[ "$(wc -l <"$LSC_HID_DOUBLE_LOG")" = 2 ] || fail "mute first: $(cat "$LSC_HID_DOUBLE_LOG")"
expect_out 0 "1:1500" "${H[@]}" --port hid -t 300 read 1
: >"$LSC_HID_DOUBLE_LOG"
expect_out 0 "1:0" "${H[@]}" --port hid -t 300 offset read 1
[ "$(wc -l <"$LSC_HID_DOUBLE_LOG")" = 2 ] || fail "mute first, offsets: $(cat "$LSC_HID_DOUBLE_LOG")"
# unplugged while waiting for the reply: exit 1
export LSC_HID_DOUBLE="$A|ARM-A|unplug"
expect_out 1 "" "${H[@]}" --port hid battery
expect_err_has "the device went away"

# permission denied: exit 1 and the fix
export LSC_HID_DOUBLE="$A|ARM-A|deny"
expect_out 1 "" "${H[@]}" --port hid battery
expect_err_has "Permission denied"
expect_err_has "60-lsc.rules"
expect_err_has "plugdev"
# the rule's real installed path, and what a source install does
expect_err_has "the lscctl package installs it as /lib/udev/rules.d/60-lsc.rules"
expect_err_has "copy debian/lscctl.lsc.udev to /etc/udev/rules.d/60-lsc.rules"

# two arms: by serial number, by path, $LSC_PORT; --port hid refuses (exit 2)
export LSC_HID_DOUBLE="$A|ARM-A|;$B|ARM-B|"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid:ARM-B battery
[ "$(last_report)" = "00 55 55 02 0F$(zeros 60)" ] || fail "hid:ARM-B report: $(last_report)"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port "$B" battery
LSC_PORT=hid:ARM-A expect_out 0 "7.500 V (7500 mV)" "${H[@]}" battery
expect_out 2 "" "${H[@]}" --port hid battery
expect_err_has "serial numbers ARM-A, ARM-B"
expect_err_has "--port hid:SERIAL"
expect_out 1 "" "${H[@]}" --port hid:ARM-C battery
expect_err_has "no HID controller has serial number 'ARM-C' (present: ARM-A, ARM-B)"
expect_out 2 "" "${H[@]}" --port hid: battery
expect_err_has "needs a serial number"
# no port given and two arms: refuse, list them, say how to choose
expect_out 2 "" "${H[@]}" battery
expect_err_has "several look like a controller"
expect_err_has "hid:ARM-A (serial number ARM-A), hid:ARM-B (serial number ARM-B)"

# ports: HID controllers with their serial numbers and the --port for each
expect 0 "${H[@]}" ports
grep -qxF "$A	LOBOT (USB HID)	0483:5750	ARM-A	controller (--port hid:ARM-A)" "$OUT" ||
  fail "ports: $(cat "$OUT")"
grep -qxF "$B	LOBOT (USB HID)	0483:5750	ARM-B	controller (--port hid:ARM-B)" "$OUT" ||
  fail "ports: $(cat "$OUT")"
expect 0 "${H[@]}" --json ports
grep -qxF '{"path":"'"$A"'","description":"LOBOT (USB HID)","vid":"0483","pid":"5750","serial":"ARM-A","manufacturer":"MyUSB_HID","hid":true,"port":"hid:ARM-A","controller":true}' "$OUT" ||
  fail "ports --json: $(cat "$OUT")"

# one arm: it is the port when none is given
export LSC_HID_DOUBLE="$B|ARM-B|"
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" battery
# none: --port hid says so (exit 1)
export LSC_HID_DOUBLE=""
expect_out 1 "" "${H[@]}" --port hid battery
expect_err_has "no HID controller (USB 0483:5750) is present"

# a second opener: port busy (exit 4) while another process holds the node
export LSC_HID_DOUBLE="$A|ARM-A|"
exec 9<>"$A"
flock -n 9 || fail "cannot lock $A"
expect_out 4 "" "${H[@]}" --port hid battery
expect_err_has "port busy"
exec 9>&-
expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid battery

# Only a known controller's hidraw node is handed to hidapi. With the real
# hidapi ($LSCCTL) and the system's sysfs: a regular file (left as it was), a
# FIFO (no hang), a directory and a symbolic link to /dev/null are refused
# before anything opens them: exit 1, one line, no "(Success)". (/dev/null
# is checked loosely: on a shared machine a root process writing "atomically"
# over it can leave a regular file there for a moment; /dev/zero strictly.)
expect_err_lacks() { grep -qF -- "$1" "$ERR" && fail "stderr has '$1': $(cat "$ERR")"; }
mkdir "$TMP/hr"
echo x >"$TMP/hr/hidraw5"
mkfifo "$TMP/hr/hidraw6"
mkdir "$TMP/hr/hidraw7"
ln -s /dev/null "$TMP/hr/hidraw8"
ln -s /dev/zero "$TMP/hr/hidraw4"
for bad in "hidraw5|a regular file, not a device" "hidraw6|a FIFO, not a device" \
  "hidraw7|a directory, not a device" "hidraw8|, not a " \
  "hidraw4|not a hidraw node"; do
  for prog in "$LSCCTL" "$LSCCTL_HID"; do
    expect_out 1 "" "$prog" --port "$TMP/hr/${bad%%|*}" battery
    expect_err_has "$TMP/hr/${bad%%|*}: "
    expect_err_has "${bad#*|}"
    expect_err_lacks "Success"
  done
done
[ "$(cat "$TMP/hr/hidraw5")" = x ] || fail "the regular file was written: $(od -c "$TMP/hr/hidraw5")"
# under valgrind: hidapi is never called on such a path, so nothing is read
# after it was freed and nothing leaks (not with a sanitized lscctl)
if ! command -v valgrind >/dev/null; then
  echo "SKIP (part): valgrind is not installed: lscctl --port REGULAR_FILE not run under it"
elif grep -q __asan_init "$LSCCTL"; then
  echo "SKIP (part): lscctl is built with AddressSanitizer: not run under valgrind"
elif ! valgrind -q --log-file="$TMP/valgrind.log" "$LSCCTL" --version 2>/dev/null | grep -q '^lscctl '; then
  # Debian 12's valgrind 3.19 gives up on a clang build's DWARF 5
  echo "SKIP (part): valgrind cannot run this lscctl: $(grep -m1 -i 'debuginfo\|dwarf' "$TMP/valgrind.log")"
else
  # valgrind's own lines go to a log (an older valgrind also complains there
  # about a clang build's DWARF 5); an error or a leak is exit 99
  for f in hidraw5 hidraw6 hidraw8; do
    expect_out 1 "" valgrind -q --log-file="$TMP/valgrind.log" --error-exitcode=99 \
      --leak-check=full --errors-for-leak-kinds=definite,indirect,possible \
      "$LSCCTL" --port "$TMP/hr/$f" battery || cat "$TMP/valgrind.log" >&2
  done
fi

# a hidraw node whose ids are not a known controller's (a keyboard, say):
# refused, nothing sent; --port hid does not take it for an arm
export LSC_HID_DOUBLE="$A|KBD|id=046d:c52b"
: >"$LSC_HID_DOUBLE_LOG"
expect_out 1 "" "${H[@]}" --port "$A" move 1:1500
expect_err_has "$A: not a known servo controller: USB 046d:c52b (known: 0483:5750); nothing sent (if it is one: lscctl --hid-id 046d:c52b)"
[ ! -s "$LSC_HID_DOUBLE_LOG" ] || fail "sent to a foreign HID device: $(cat "$LSC_HID_DOUBLE_LOG")"
expect_out 1 "" "${H[@]}" --port hid battery
expect_err_has "no HID controller (USB 0483:5750) is present"
expect 0 "${H[@]}" ports
grep -q "KBD" "$OUT" && fail "ports lists a foreign HID device: $(cat "$OUT")"
# hidapi failing without saying why: no "(Success)"
export LSC_HID_DOUBLE="$A|ARM-A|silent"
expect_out 1 "" "${H[@]}" --port "$A" battery
expect_err_has "$A: hidapi cannot open it"
expect_err_lacks "Success"

# --hid-id VID:PID (and $LSC_HID_ID): hex USB ids, checked before anything is
# opened (exit 2)
for bad in "" bogus 0:0 0000:0000 12345:1 1:12345 1234 1234: :5678 "1234:5678 " 0x12:34 -1:2; do
  expect_out 2 "" "$LSCCTL" --port sim --hid-id "$bad" battery
  expect_err_has "--hid-id needs a USB VID:PID in hex"
  LSC_HID_ID=$bad run "$LSCCTL" --port sim battery
  if [ -n "$bad" ]; then
    [ "$rc" = 2 ] || fail "LSC_HID_ID='$bad' -> exit $rc, want 2"
    expect_err_has "\$LSC_HID_ID needs a USB VID:PID in hex"
  else
    [ "$rc" = 0 ] || fail "LSC_HID_ID='' -> exit $rc, want 0: $(cat "$ERR")"
  fi
done
for good in 046d:c52b 046D:C52B 1:2 ffff:0 0:1; do
  expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port sim --hid-id "$good" battery
  LSC_HID_ID=$good expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port sim battery
done
# the option wins over the variable (an invalid variable is then not read)
LSC_HID_ID=bogus expect_out 0 "7.500 V (7500 mV)" "$LSCCTL" --port sim --hid-id 1:2 battery
# The named ids reach the port: the foreign device opens. hid_id_wired is
# true once lscctl hands --hid-id to the HID port it opens (the device layer's
# lsc_device_config_set_hid_id -> lsc_hid_open_path_extra).
hid_id_wired=true
if $hid_id_wired; then
  saved_double=$LSC_HID_DOUBLE
  export LSC_HID_DOUBLE="$A|ARM-X|id=046d:c52b"
  expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port "$A" --hid-id 046d:c52b battery
  LSC_HID_ID=046d:c52b expect_out 0 "7.500 V (7500 mV)" "${H[@]}" --port hid:ARM-X battery
  expect_out 1 "" "${H[@]}" --port "$A" --hid-id 046d:c52c battery
  expect_err_has "known: 0483:5750 or 046d:c52c"
  export LSC_HID_DOUBLE=$saved_double # the arm the checks below expect
else
  echo "SKIP (part): --hid-id does not reach the HID port yet (hid_id_wired=false)"
fi

# a serial adapter and an arm, no port given: refuse, both listed (with
# libserialport's listing replaced, when the shim is built)
if [ -n "${PORTS_SHIM:-}" ]; then
  LSCCTL_TEST_PORTS="/dev/ttyUSB0|USB Serial|1a86:7523|S1" \
    expect_out 2 "" env LD_PRELOAD="$PORTS_SHIM" \
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" "$LSCCTL_HID" battery
  expect_err_has "/dev/ttyUSB0 (serial number S1), hid:ARM-A (serial number ARM-A)"
  # the xArm's ids on a serial port are no longer taken for a serial controller
  LSCCTL_TEST_PORTS="/dev/ttyX|x|0483:5750|" expect 0 env LD_PRELOAD="$PORTS_SHIM" \
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" "$LSCCTL_HID" ports
  grep -q "^/dev/ttyX.*controller$" "$OUT" && fail "0483:5750 listed as a serial controller"
fi

# At most 19 servos in one move over HID: refused with the other argument
# checks (exit 2), before any port opens (no arm is present here: an open
# would fail with exit 1), for move and play, with -n and $LSC_PORT too. The
# library decides what a name selects (lsc_device_kind_of_name).
servos() { local i; for i in $(seq "$1"); do printf "%s:500 " "$i"; done; }
export LSC_HID_DOUBLE=""
: >"$LSC_HID_DOUBLE_LOG"
for prog in "$LSCCTL" "$LSCCTL_HID"; do
  for port in hid hid:ARM-A "$TMP/none/hidraw3"; do
    # shellcheck disable=SC2046  # the servos are words
    expect_out 2 "" "$prog" --port "$port" move $(servos 20)
    expect_err_has "20 servos in one move on $port: at most 19 servos in one move over HID (a 64-byte report): split it over two moves"
    # shellcheck disable=SC2046
    expect_out 2 "" "$prog" -n --port "$port" move $(servos 20)
    expect_err_has "at most 19 servos in one move over HID"
  done
  # shellcheck disable=SC2046
  LSC_PORT=hid expect_out 2 "" "$prog" move --time 10 $(servos 83)
  expect_err_has "83 servos in one move on hid: at most 19"
done
{ printf 'time_ms'; printf ',%s' $(seq 20); printf '\n500'; printf ',1500%.0s' $(seq 20); echo; } >"$TMP/twenty.csv"
expect_out 2 "" "${H[@]}" --port hid play "$TMP/twenty.csv"
expect_err_has "$TMP/twenty.csv: 20 servos in one move on hid: at most 19 servos in one move over HID (a 64-byte report)"
expect_out 2 "" "${H[@]}" -n --port hid play "$TMP/twenty.csv"
expect_err_has "at most 19 servos in one move over HID"
LSC_PORT=hid:ARM-A expect_out 2 "" "${H[@]}" play "$TMP/twenty.csv"
expect_err_has "on hid:ARM-A: at most 19 servos"
[ ! -s "$LSC_HID_DOUBLE_LOG" ] || fail "sent over HID: $(cat "$LSC_HID_DOUBLE_LOG")"
# the same file and move elsewhere: fine; 19 servos over HID go out in one report
expect 0 "${H[@]}" -n --port sim play "$TMP/twenty.csv"
# shellcheck disable=SC2046
expect_out 0 "" "${H[@]}" --port sim move $(servos 20)
export LSC_HID_DOUBLE="$A|ARM-A|"
: >"$LSC_HID_DOUBLE_LOG"
# shellcheck disable=SC2046
expect_out 0 "" "${H[@]}" --port hid move --time 10 $(servos 19)
[ "$(wc -l <"$LSC_HID_DOUBLE_LOG")" = 1 ] || fail "19 servos: $(cat "$LSC_HID_DOUBLE_LOG")"
finish
