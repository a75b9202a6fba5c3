#!/usr/bin/env bash
# Invalid command lines exit 2, print one line on stderr and nothing on
# stdout, and not one byte reaches the port (a pty whose peer records every
# byte); valid ones reach it, so the check can fail.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

start_peer
check_bad --port "$TTY"

# The positive control: valid commands do reach the port, and their bytes
# are all it ever got (none came from the refused command lines above).
expect_out 0 "" "$LSCCTL" --port "$TTY" move 1:2000
expect_out 0 "" "$LSCCTL" --port "$TTY" send 0x0B 0xFF 0x2C 0x01
expect_out 0 "" "$LSCCTL" --port "$TTY" send 8 8 1 0 --force
expect_captured "55 55 08 03 01 E8 03 01 D0 07 55 55 05 0B FF 2C 01 55 55 05 08 08 01 00"
finish
