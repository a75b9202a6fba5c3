#!/usr/bin/env bash
# Every example frame of the protocol (docs/protocol.md): built by --dry-run (exact bytes, text and JSON)
# and decoded by 'decode --json' (exact fields), from frames.txt.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

n=0
while IFS='|' read -r args hex json; do
  case "$args" in '#'*|'') continue ;; esac
  n=$((n + 1))
  if [ "$args" != - ]; then
    # shellcheck disable=SC2086  # the arguments are words
    expect_out 0 "$hex" "$LSCCTL" --dry-run $args
    expect_out 0 "${json/\"dir\":\"host\",/}" "$LSCCTL" -n --json $args
  fi
  expect_out 0 "$json" "$LSCCTL" --json decode "$hex"
  # the same bytes unspaced, lower case, one byte per argument
  expect_out 0 "$json" "$LSCCTL" --json decode "$(echo "$hex" | tr -d ' ' | tr A-F a-f)"
  # shellcheck disable=SC2086
  expect_out 0 "$json" "$LSCCTL" --json decode $hex
done <"$here/frames.txt"
[ "$n" = 14 ] || fail "frames.txt has $n frames, want 14"

# Frames both sides send: from the controller they are notifications.
expect_out 0 '{"dir":"controller","hex":"55 55 05 06 08 01 00","cmd":6,"name":"action_group_run","group":8,"times":1}' \
  "$LSCCTL" --json decode --from controller 55 55 05 06 08 01 00
expect_out 0 '{"dir":"controller","hex":"55 55 02 07","cmd":7,"name":"action_group_stop"}' \
  "$LSCCTL" --json decode 55 55 02 07 --from controller

# The V1.2 document prints the position reply with big-endian positions
# (01 F4); that is a misprint (docs/protocol.md): read little-endian it is 62465.
expect 0 "$LSCCTL" --json decode 55 55 15 15 06 01 01 F4 02 01 F4 03 01 F4 04 01 F4 05 01 F4 06 01 F4
grep -q '{"id":1,"position":62465}' "$OUT" || fail "misprinted reply: $(cat "$OUT")"

finish
