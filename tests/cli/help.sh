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
version=$(cut -d' ' -f2 "$OUT")

# issue 16's smaller items
# 'help' with two names: its own error, not one of the command named
expect_out 2 "" "$LSCCTL" help move run
grep -q "^lscctl: 'lscctl help' takes one command name (got 'run' after 'move')$" "$ERR" ||
  fail "help move run: $(cat "$ERR")"
# speed sets a speed, it runs nothing
expect 0 "$LSCCTL" help speed
grep -q "Runs action group" "$OUT" && fail "help speed says it runs a group: $(cat "$OUT")"
grep -q "It starts nothing" "$OUT" || fail "help speed: $(cat "$OUT")"
# --help says which commands wait without limit, and the -t range
expect 0 "$LSCCTL" --help
grep -q "wait, monitor and run --wait: no limit unless given" "$OUT" || fail "--help: $(cat "$OUT")"
grep -q "1..86400000" "$OUT" || fail "--help does not give -t's range: $(cat "$OUT")"
# wait points to run --wait (the race of 'run 8 && wait')
expect 0 "$LSCCTL" help wait
grep -q "use 'lscctl run GROUP --wait' instead" "$OUT" || fail "help wait: $(cat "$OUT")"
grep -q "run 8 && lscctl wait" "$OUT" && fail "help wait shows the racy example: $(cat "$OUT")"
# lsc-sim -V is --version, and prints as lscctl -V does
if [ -n "${LSC_SIM:-}" ]; then
  expect_out 0 "lsc-sim $version" "$LSC_SIM" -V
  expect_out 0 "lsc-sim $version" "$LSC_SIM" --version
fi
# the man pages' footers agree: the same date and source (with the version)
th() { sed -n 's/^\.TH [^ ]* [0-9] //p' "$here/../../cli/$1"; }
[ "$(th lscctl.1)" = "$(th lsc-sim.1)" ] ||
  fail "man page footers differ: lscctl.1: $(th lscctl.1); lsc-sim.1: $(th lsc-sim.1)"
th lscctl.1 | grep -qF "\"lsc $version\"" || fail "lscctl.1's footer is not version $version: $(th lscctl.1)"

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
  grep -vq '^{"path":".*,"controller":\(true\|false\)}$' "$OUT" && fail "ports --json: $(cat "$OUT")"
fi
finish
