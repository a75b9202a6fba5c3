#!/usr/bin/env bash
# lscctl over a real pseudo-terminal whose far end (pty_peer) records what
# arrives and answers canned bytes: replies, notifications, silence (exit 3),
# bad replies, a device that goes away, a busy port (exit 4).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

# peer ARGS...: a fresh peer; then P=(lscctl --port TTY). Every reply the
# test expects comes from the peer: on a busy machine it may be late, so the
# default timeout is a generous one (scaled); the checks of exit 3 (nothing
# comes) give their own short --timeout.
peer() { stop_peer; start_peer "$@"; P=("$LSCCTL" --port "$TTY" --timeout "$(test_ms 10000)"); }

peer -r "55 55 04 0F 10 27"
expect_out 0 "10.000 V (10000 mV)" "${P[@]}" battery
expect_out 0 '{"cmd":15,"name":"get_battery_voltage","millivolts":10000,"volts":10.000}' "${P[@]}" --json battery
expect_out 0 "10.000 V (10000 mV)" "${P[@]}" --baud 115200 battery
expect_captured "55 55 02 0F 55 55 02 0F 55 55 02 0F"

peer -r "55 55 09 15 02 01 D0 07 02 F4 01"
expect_out 0 "1:2000
2:500" "${P[@]}" read 1 2
expect_out 0 '{"cmd":21,"name":"mult_servo_pos_read","servos":[{"id":1,"position":2000},{"id":2,"position":500}]}' \
  "${P[@]}" read 1 2 --json
# a reply for other ids is a bad reply: exit 1 (after the timeout: a good
# reply might still come; long enough for the peer's to arrive on a busy machine)
expect_out 1 "" "${P[@]}" -t "$(test_ms 2000)" read 2 1
expect_err_has "bad reply from the controller"

# a malformed reply: exit 1; silence: exit 3
peer -r "55 55 03 0F 00"
expect_out 1 "" "${P[@]}" -t "$(test_ms 2000)" battery
peer
expect_out 3 "" "${P[@]}" --timeout 300 battery
expect_err_has "no reply from the controller on $TTY within 300 ms"
expect_out 3 "" "${P[@]}" --timeout 300 read 1
expect_out 3 "" "${P[@]}" --timeout 300 wait
expect_out 3 "" "${P[@]}" --timeout 300 monitor
expect_out 3 "" "${P[@]}" --timeout 300 run 8 --wait

# notifications: the group started and completed
N="55 55 05 06 08 01 00 55 55 05 08 08 01 00"
peer -r "$N"
expect_out 0 "action_group_complete group=8 times=1" "${P[@]}" run 8 --wait
expect_out 0 '{"cmd":8,"name":"action_group_complete","group":8,"times":1}' "${P[@]}" run 8 --wait --json
# the end of another group does not end the wait for ours; a stop does
peer -r "55 55 05 06 08 01 00 55 55 05 08 03 01 00 55 55 02 07"
expect_out 0 "action_group_stop" "${P[@]}" run 8 --wait
# starting ours stopped the group that ran (7, then our 6): not our end
peer -r "55 55 02 07 55 55 05 06 08 01 00 55 55 05 08 08 01 00"
expect_out 0 "action_group_complete group=8 times=1" "${P[@]}" run 8 --wait
peer -r "55 55 02 07 55 55 05 06 08 01 00 55 55 02 07"
expect_out 0 "action_group_stop" "${P[@]}" run 8 --wait
# ends before our group started are not ours: it never started, exit 3
peer -r "55 55 02 07 55 55 05 08 08 01 00"
expect_out 3 "" "${P[@]}" -t 500 run 8 --wait
peer -s "$N"
expect_out 0 "action_group_complete group=8 times=1" "${P[@]}" wait
peer -s "$N"
expect_out 0 "action_group_run group=8 times=1
action_group_complete group=8 times=1" "${P[@]}" monitor --count 2
# only notifications are printed and counted: a reply in between is not
peer -s "55 55 04 0F 4C 1D $N"
expect_out 0 "action_group_run group=8 times=1" "${P[@]}" monitor --count 1
peer -s "55 55 04 0F 4C 1D $N"
expect_out 0 "action_group_run group=8 times=1
action_group_complete group=8 times=1" "${P[@]}" -v monitor --count 2
expect_err_has "lscctl: received get_battery_voltage millivolts=7500 volts=7.500 (55 55 04 0F 4C 1D)"
peer -s "$N 55 55 02 07"
expect_out 0 '{"cmd":6,"name":"action_group_run","group":8,"times":1}' "${P[@]}" --json monitor --count 1
# (sent 200 ms after lscctl opened the port, well within its timeout)
peer -s "$N" -d 200
expect_out 3 "action_group_run group=8 times=1
action_group_complete group=8 times=1" "${P[@]}" -t "$(test_ms 1500)" monitor

# -v over a real port
peer -r "55 55 04 0F 4C 1D"
expect_out 0 "7.500 V (7500 mV)" "${P[@]}" -v battery
expect_err_has "lscctl: sent get_battery_voltage (55 55 02 0F)"
expect_err_has "lscctl: received get_battery_voltage millivolts=7500 volts=7.500 (55 55 04 0F 4C 1D)"

# a frame that is not a valid reply is traced as such, then ignored
peer -r "55 55 02 0F 55 55 04 0F 4C 1D"
expect_out 0 "7.500 V (7500 mV)" "${P[@]}" -v battery
expect_err_has "lscctl: received not a valid get_battery_voltage reply (55 55 02 0F)"

# the device goes away while we wait: exit 1 (300 ms after lscctl opened it)
peer -x 300
expect_out 1 "" "${P[@]}" wait

# a port another lscctl holds is busy: exit 4
peer
expect_busy "$TTY" stop

# no such device: exit 1; a baud rate the port cannot do: exit 2
expect_out 1 "" "$LSCCTL" --port "$TMP/no-such-tty" stop
expect_err_has "('lscctl ports' lists the serial ports"
# the message names the port and what failed once (not "cannot open X: cannot open")
once() { [ "$(grep -o -F -- "$1" "$ERR" | wc -l)" = 1 ] || fail "'$1' not once in: $(cat "$ERR")"; }
once "$TMP/no-such-tty"
once "cannot open"
# not a serial port: a directory, a file, a device without termios
# each say what it is and what to pass instead, not only the OS's words
expect_out 1 "" "$LSCCTL" --port "$TMP" stop
once "$TMP"
expect_err_has "$TMP: a directory, not a device ('lscctl ports' lists the serial ports; --port sim"
: >"$TMP/file"
expect_out 1 "" "$LSCCTL" --port "$TMP/file" stop
expect_err_has "$TMP/file: not a serial port: Inappropriate ioctl for device ('lscctl ports'"
[ -s "$TMP/file" ] && fail "stop wrote into a regular file: $(od -An -tx1 "$TMP/file")"
if [ -r /dev/random ] && [ -w /dev/random ]; then
  expect_out 1 "" "$LSCCTL" --port /dev/random stop
  expect_err_has "/dev/random: not a serial port: Invalid argument ('lscctl ports'"
fi
peer
expect_out 2 "" "${P[@]}" --baud 12345 stop
# nothing went out: the next command's bytes are all the peer ever got
expect_out 0 "" "${P[@]}" stop
expect_captured "55 55 02 07"
finish
