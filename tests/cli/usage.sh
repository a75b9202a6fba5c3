#!/usr/bin/env bash
# Invalid command lines exit 2, print one line on stderr and nothing on
# stdout, and not one byte reaches the port (a pty whose peer records every
# byte); valid ones reach it, so the check can fail.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

start_peer
check_bad --port "$TTY"

# Text from the user repeated in a message is escaped (\x0A, \x1B): the
# message stays one line, with no raw control character; nothing is sent.
# expect_shown CODE TEXT ARGS...: lscctl ARGS exits CODE, its one line on
# stderr holds TEXT and no ESC
expect_shown() {
  local code=$1 text=$2; shift 2
  if expect_out "$code" "" "$LSCCTL" --port "$TTY" "$@"; then
    expect_err_has "$text"
    if grep -q $'\033' "$ERR"; then fail "a raw ESC in the message: $(cat -v "$ERR")"; fi
  fi
}
printf 'time_ms,1\n500,1500\n' >"$TMP/ok.csv"
nl=$'\n' esc=$'\033'
expect_shown 2 "$TMP/a\x0Ab.csv: No such file or directory" play "$TMP/a${nl}b.csv"
expect_shown 2 "$TMP/a\x0Ab.csv: No such file or directory" -n play "$TMP/a${nl}b.csv"
expect_shown 2 "$TMP/\x1B[31m.csv: No such file or directory" convert "$TMP/${esc}[31m.csv" "$TMP/o.csv"
expect_shown 2 "\x1B[31m.bogus: unknown file type" convert "$TMP/ok.csv" "$TMP/${esc}[31m.bogus"
expect_shown 1 "$TMP/none/\x1B[31m.csv: No such file or directory" convert "$TMP/ok.csv" "$TMP/none/${esc}[31m.csv"
expect_shown 2 "$TMP/x\x0A.txt\x1B: unknown file type" record "$TMP/x${nl}.txt$esc"
expect_shown 1 "$TMP/none/a\x0Ab.csv: cannot create its journal" record "$TMP/none/a${nl}b.csv"
expect_shown 2 "--ids '1\x0A\x1B[2J': id '1\x0A\x1B[2J' is not a number" record "$TMP/r.csv" --ids "1$nl${esc}[2J"
expect_shown 2 "unknown command '\x1B[2J'" "${esc}[2J"
expect_shown 2 "unexpected argument '\x0A\x1B'" battery "$nl$esc"
expect_shown 2 "(got '\x1B' after 'move')" help move "$esc"
expect_shown 2 "--from '\x1B[1m': use --from host" decode --from "${esc}[1m" 55
expect_shown 2 "unknown option '--\x1B'" "--$esc" battery
expect_shown 2 "-n takes no value (in '-n\x1B')" "-n$esc" battery
expect_shown 2 "'\x1B' is neither read nor set" offset "$esc" 1
expect_shown 2 "offset '\x0A': use -128..127" offset set 1 "$nl"
expect_shown 2 "'1\x0A2' is not ID:POS" move "1${nl}2"
expect_shown 2 "id 'x\x0A' is not a number: write it in decimal or 0x-hex; a joint name needs an arm profile (--arm FILE)" unload "x$nl"
[ -e "$TMP/x$nl.txt$esc" ] && fail "record made a file it refused"
for c in status battery; do # the port's name: lscd's socket
  expect_out 1 "" "$LSCCTL" --port "lscd:$TMP/a${nl}b${esc}" "$c"
  expect_err_has "no lscd at $TMP/a\x0Ab\x1B"
done

# The positive control: valid commands do reach the port, and their bytes
# are all it ever got (none came from the refused command lines above).
expect_out 0 "" "$LSCCTL" --port "$TTY" move 1:2000
expect_out 0 "" "$LSCCTL" --port "$TTY" send 0x0B 0xFF 0x2C 0x01
expect_out 0 "" "$LSCCTL" --port "$TTY" send 8 8 1 0 --force
expect_captured "55 55 08 03 01 E8 03 01 D0 07 55 55 05 0B FF 2C 01 55 55 05 08 08 01 00"
finish
