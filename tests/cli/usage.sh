#!/usr/bin/env bash
# Invalid command lines exit 2, print one line on stderr and nothing on
# stdout, and not one byte reaches the port (a pty whose peer records every
# byte); valid ones reach it, so the check can fail.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

start_peer
many() { local i; for i in $(seq "$1"); do printf "%s " "$i${2:-}"; done; }
bad=(
  "move 256:1500|id 256 is out of range"
  "move 0x100:1500|id 0x100 is out of range"
  "move 1:65536|position 65536 is out of range"
  "move --time 65536 1:1500|time 65536 is out of range"
  "move 1:1500 --time=-1|negative"
  "move -1:1500|negative"
  "move 1:-5|negative"
  "move 1:abc|not a number"
  "move x:1|not a number"
  "move 1:0x|not a number"
  "move 1:|not a number"
  "move 1500|is not ID:POS"
  "move 1:100 2:5 1:200|servo 1 is given twice"
  "move|missing arguments"
  "move $(many 84 :1500)|84 servos do not fit in one frame"
  "move 1:1500 --time|--time needs a value"
  "move --wait 1:1500|--wait is an option of 'run'"
  "move --bogus 1:1500|unknown option '--bogus'"
  "run|missing arguments"
  "run 1 2|unexpected argument '2'"
  "run 256|group 256 is out of range"
  "run 1 --times 65536|times 65536 is out of range"
  "run 1 --times -1|negative"
  "run 1 --wait=yes|--wait takes no value"
  "stop now|unexpected argument 'now'"
  "speed 1|missing arguments"
  "speed 256 100|group 256 is out of range"
  "speed all 65536|percent 65536 is out of range"
  "speed every 100|not a number"
  "battery 1|unexpected argument"
  "unload|missing arguments"
  "unload 1 2 1|id 1 is given twice"
  "unload 300|id 300 is out of range"
  "unload $(many 82)|82 ids cannot be sent in one frame"
  "read 1 1|id 1 is given twice"
  "read $(many 82)|82 ids cannot be sent in one frame"
  "read $(many 85)|too many ids for one frame"
  "read -5|negative"
  "send 8|add --force"
  "send 0x08 1 0 0|add --force"
  "send 256|command 256 is out of range"
  "send 3 1 256|byte 256 is out of range"
  "send|missing arguments"
  "wait 5|unexpected argument"
  "monitor --count 0|--count 0"
  "monitor --count many|not a number"
  "monitor now|unexpected argument"
  "decode --from sideways 55 55 02 07|--from host or --from controller"
  "decode 55 55 0|not hex bytes"
  "decode 55 55 02 0G|not hex bytes"
  "ports all|unexpected argument"
  "frobnicate|unknown command 'frobnicate'"
  "help frobnicate|unknown command 'frobnicate'"
  "help move battery|takes one command name"
  "--time 5 move 1:1|--time is an option of 'move': put it after the command"
  "--timeout soon battery|timeout 'soon' is not a number"
  "--baud 0 battery|baud rate 0"
  "-x battery|unknown option '-x'"
  "|no command given"
)
for entry in "${bad[@]}"; do
  args=${entry%%|*}
  why=${entry#*|}
  # shellcheck disable=SC2086  # the arguments are words
  if expect_out 2 "" "$LSCCTL" --port "$TTY" $args; then
    expect_err_has "$why"
  fi
  # the same with the options first and with --dry-run: still refused
  # shellcheck disable=SC2086
  expect_out 2 "" "$LSCCTL" -n --port "$TTY" $args
done
sleep 0.1
[ ! -s "$CAPTURE" ] || fail "bytes reached the port for refused command lines: $(captured)"

# The positive control: valid commands do reach the port.
expect_out 0 "" "$LSCCTL" --port "$TTY" move 1:2000
expect_out 0 "" "$LSCCTL" --port "$TTY" send 0x0B 0xFF 0x2C 0x01
expect_out 0 "" "$LSCCTL" --port "$TTY" send 8 8 1 0 --force
sleep 0.1
[ "$(captured)" = "55 55 08 03 01 E8 03 01 D0 07 55 55 05 0B FF 2C 01 55 55 05 08 08 01 00" ] ||
  fail "the port got: $(captured)"
finish
