#!/usr/bin/env bash
# ports (text and JSON) and the choice of a port when none is given: the one
# that looks like a controller (USB VID:PID of CH340, CP210x, FTDI; the xArm
# is a HID device: hid.sh),
# else exit 2 saying how to choose. libserialport's listing is replaced by
# sp_ports_shim (LD_PRELOAD) with the ports in $LSCCTL_TEST_PORTS.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${PORTS_SHIM:?set PORTS_SHIM to sp_ports_shim.so}"
unset LSC_PORT
# lscctl (only) with the shim
L=(env LD_PRELOAD="$PORTS_SHIM" ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
  "$LSCCTL" --timeout "$(test_ms 10000)")

start_peer -r "55 55 04 0F 4C 1D"
serial0="/dev/ttyS0|ttyS0|-|"
ch340="$TTY|USB Serial|1a86:7523|"
cp210x="/dev/ttyUSB7|CP2102 USB to UART Bridge Controller|10c4:ea60|0001"
mouse="/dev/ttyACM3|Some \"modem\"|1234:5678|XYZ"

export LSCCTL_TEST_PORTS="$serial0;$ch340;$mouse"
expect_out 0 "/dev/ttyS0	ttyS0	-	-
$TTY	USB Serial	1a86:7523	-	controller
/dev/ttyACM3	Some \"modem\"	1234:5678	XYZ" "${L[@]}" ports
# every line has the same keys: vid, pid and serial are null off USB
expect_out 0 '{"path":"/dev/ttyS0","description":"ttyS0","vid":null,"pid":null,"serial":null,"controller":false}
{"path":"'"$TTY"'","description":"USB Serial","vid":"1a86","pid":"7523","serial":"","controller":true}
{"path":"/dev/ttyACM3","description":"Some \"modem\"","vid":"1234","pid":"5678","serial":"XYZ","controller":false}' \
  "${L[@]}" --json ports

# the one controller-looking port is used when no port is given
expect_out 0 "7.500 V (7500 mV)" "${L[@]}" battery
expect_captured "55 55 02 0F"

# two of them: exit 2, nothing sent, and how to choose
export LSCCTL_TEST_PORTS="$ch340;$cp210x"
expect_out 2 "" "${L[@]}" battery
expect_err_has "several look like a controller: choose one with --port PATH"
# none: exit 2 as well
export LSCCTL_TEST_PORTS="$serial0;$mouse"
expect_out 2 "" "${L[@]}" stop
expect_err_has "none looks like a controller"
# every known adapter is recognised
for id in 1a86:7523 10c4:ea60 0403:6001; do
  export LSCCTL_TEST_PORTS="/dev/ttyX|x|$id|"
  expect 0 "${L[@]}" ports
  grep -q "controller$" "$OUT" || fail "$id is not recognised: $(cat "$OUT")"
done
# no ports at all: nothing listed (and a hint on stderr), exit 0
export LSCCTL_TEST_PORTS=""
expect_out 0 "" "${L[@]}" ports
# nothing went out since the first battery: the next one's bytes follow it
export LSCCTL_TEST_PORTS="$ch340"
expect_out 0 "7.500 V (7500 mV)" "${L[@]}" battery
expect_captured "55 55 02 0F 55 55 02 0F"
finish
