#!/usr/bin/env bash
# --help, help COMMAND, COMMAND --help, --version; ports (text and JSON).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

expect 0 "$LSCCTL" --help
grep -q '^Usage: lscctl \[OPTIONS\] COMMAND \[ARGS\]' "$OUT" || fail "--help: $(head -3 "$OUT")"
cp "$OUT" "$TMP/help"
for c in move run stop speed battery unload read wait monitor send decode ports; do
  grep -q "^  $c" "$TMP/help" || fail "--help does not list $c"
  expect 0 "$LSCCTL" help "$c"
  cp "$OUT" "$TMP/help1"
  grep -q "^Usage: lscctl \[OPTIONS\] $c" "$OUT" || fail "help $c: $(head -2 "$OUT")"
  grep -q "Example" "$OUT" || fail "help $c has no example"
  expect 0 "$LSCCTL" "$c" --help
  cmp -s "$OUT" "$TMP/help1" || fail "'$c --help' differs from 'help $c'"
done
# monitor prints (and --count counts) notifications, not every frame
expect 0 "$LSCCTL" help monitor
grep -q "stop after N notifications" "$OUT" || fail "help monitor: $(cat "$OUT")"
grep -q "every frame" "$OUT" && fail "help monitor promises every frame: $(cat "$OUT")"
expect 0 "$LSCCTL" -h
expect 0 "$LSCCTL" help
# --help wins over everything else on the line and sends nothing
expect 0 "$LSCCTL" --port /nonexistent/tty move 1:1 --help
grep -q "^Usage: lscctl \[OPTIONS\] move" "$OUT" || fail "move --help"
expect 0 "$LSCCTL" --version
grep -Eq '^lscctl [0-9]+\.[0-9]+\.[0-9]+$' "$OUT" || fail "--version: $(cat "$OUT")"
expect 0 "$LSCCTL" -V

# Short options: combined flags and attached values.
expect_out 0 "55 55 02 07" "$LSCCTL" -nv stop
expect_out 0 "55 55 02 07" "$LSCCTL" -psim -t10 -n stop
# '--' ends the options
expect_out 0 '{"dir":"host","hex":"55 55 02 07","cmd":7,"name":"action_group_stop"}' \
  "$LSCCTL" --json decode -- 55 55 02 07

# ports: one line (or JSON object) per port; none is fine on a machine without any
expect 0 "$LSCCTL" ports
expect 0 "$LSCCTL" --json ports
if [ -s "$OUT" ]; then
  grep -vq '^{"path":".*","controller":\(true\|false\)}$' "$OUT" && fail "ports --json: $(cat "$OUT")"
fi
finish
