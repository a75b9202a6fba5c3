#!/usr/bin/env bash
# --help, help COMMAND, COMMAND --help, --version; ports (text and JSON).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

expect 0 "$LSCCTL" --help
grep -q '^Usage: lscctl \[OPTIONS\] COMMAND \[ARGS\]' "$OUT" || fail "--help: $(head -3 "$OUT")"
cp "$OUT" "$TMP/help"
for c in move run stop speed battery unload read wait monitor send decode ports where reach; do
  grep -q "^  $c" "$TMP/help" || fail "--help does not list $c"
  expect 0 "$LSCCTL" help "$c"
  cp "$OUT" "$TMP/help1"
  grep -q "^Usage: lscctl \[OPTIONS\] $c" "$OUT" || fail "help $c: $(head -2 "$OUT")"
  grep -q "Example" "$OUT" || fail "help $c has no example"
  expect 0 "$LSCCTL" "$c" --help
  cmp -s "$OUT" "$TMP/help1" || fail "'$c --help' differs from 'help $c'"
done
# --help names every kind of port (lscd: included) and every variable lscctl reads
for word in /dev/ttyUSB0 'hid ' hid:SERIAL /dev/hidrawN 'sim:' lscd:NAME lscd:PATH \
  LSC_PORT LSC_ARM LSC_HID_ID LSC_LSCD_DIR /run/lsc 'lscd(8)'; do
  grep -qF -- "$word" "$TMP/help" || fail "--help does not name '$word'"
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
# ---- the usage lines come from the option table: every option a command's help
# lists is in its usage line, and the other way round
for c in move where reach run stop speed battery unload read wait monitor send decode record play convert offset status ports; do
  "$LSCCTL" help "$c" >"$OUT"
  usage_opts=$(head -1 "$OUT" | grep -o -- '\[--[a-z-]*' | tr -d '[' | sort | tr '\n' ' ')
  help_opts=$(sed -n '/^Options:/,/^$/p' "$OUT" | grep -o -- '^  --[a-z-]*' | tr -d ' ' | sort | tr '\n' ' ')
  checks=$((checks + 1))
  [ "$usage_opts" = "$help_opts" ] ||
    fail "help $c: the usage line has options '$usage_opts', the Options '$help_opts'"
done
expect 0 "$LSCCTL" help record
grep -qx 'Usage: lscctl \[OPTIONS\] record FILE \[--ids LIST\] \[--every MS\] \[--time MS\] \[--count N\]' "$OUT" ||
  fail "help record: $(head -1 "$OUT")"
expect 0 "$LSCCTL" help move
grep -qx 'Usage: lscctl \[OPTIONS\] move ID:POS... \[--time MS\] \[--speed DEG/S\] \[--wait\] \[--tolerance N\] \[--strict\]' "$OUT" ||
  fail "help move: $(head -1 "$OUT")"
expect 0 "$LSCCTL" help reach
grep -qx 'Usage: lscctl \[OPTIONS\] reach X Y Z \[--pitch DEG\] \[--roll DEG\] \[--time MS\] \[--speed DEG/S\] \[--line\] \[--step MM\] \[--wait\] \[--tolerance N\] \[--strict\]' "$OUT" ||
  fail "help reach: $(head -1 "$OUT")"
expect 0 "$LSCCTL" --help
grep -q '^  record FILE \[--ids LIST\] \[--every MS\] \[--time MS\] \[--count N\]$' "$OUT" ||
  fail "--help's record: $(grep record "$OUT")"
expect 2 "$LSCCTL" record && expect_err_has "missing arguments: usage: lscctl record FILE [--ids LIST] [--every MS] [--time MS] [--count N]"
expect 2 "$LSCCTL" -n move 1:1 --count 3 && expect_err_has "--count is an option of 'record' and 'monitor'"

# ---- ranges: a value refused says the range accepted
expect 2 "$LSCCTL" -n record r.csv --every 65536 && expect_err_has "--every: every 65536 is out of range: use 1..65535"
expect 2 "$LSCCTL" -n play p.csv --speed 65536 && expect_err_has "--speed: speed 65536 is out of range: use 1..65535"
expect 2 "$LSCCTL" -n play p.csv --times 65536 && expect_err_has "--times: times 65536 is out of range: use 1..65535"
expect 2 "$LSCCTL" -n record r.csv --time 70000 && expect_err_has "--time: time 70000 is out of range: use 1..65535"
expect 2 "$LSCCTL" -n run 1 --times 65536 && expect_err_has "--times: times 65536 is out of range: use 0..65535"
expect 2 "$LSCCTL" -n move 1:1 --time 65536 && expect_err_has "--time: time 65536 is out of range: use 0..65535"

# ---- messages: read of a joint name without a profile says how to give one;
# positions of joints are decimal or 0x-hex
expect 2 "$LSCCTL" -n read base && expect_err_has "a joint name needs an arm profile (--arm FILE)"
expect_out 0 "55 55 08 03 01 E8 03 06 BC 02" "$LSCCTL" --arm "$here/../../examples/arms/xarm.conf" -n move base:0x2BC
# offset: the unit, and whether it survives power-off
expect 0 "$LSCCTL" help offset
grep -q "0.24 degree a unit" "$OUT" || fail "help offset gives no unit: $(cat "$OUT")"
grep -q "forgets it at power-off" "$OUT" || fail "help offset: power-off: $(cat "$OUT")"
# the udev rule's path: the message, the README and the rule's own comment agree
for f in src/hid/hid.c README.md debian/lscctl.lsc.udev; do
  checks=$((checks + 1))
  grep -q "/lib/udev/rules.d/60-lsc.rules" "$here/../../$f" || fail "$f does not name /lib/udev/rules.d/60-lsc.rules"
  grep -q "/etc/udev/rules.d/60-lsc.rules" "$here/../../$f" || fail "$f does not name /etc/udev/rules.d/60-lsc.rules"
  grep -q "/usr/lib/udev/rules.d/60-lsc.rules" "$here/../../$f" && fail "$f names /usr/lib/udev/rules.d/60-lsc.rules, where no package puts it"
done

finish
