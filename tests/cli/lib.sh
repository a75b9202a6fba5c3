# Helpers for lscctl's integration tests (sourced by each test script).
# Usage in a script: . lib.sh; ...; finish
# Environment: LSCCTL (the built program), PTY_PEER (tests/cli/pty_peer).
set -u
: "${LSCCTL:?set LSCCTL to the lscctl binary}"
TMP=$(mktemp -d)
PEER_PID=""
cleanup() {
  if [ -n "$PEER_PID" ]; then kill "$PEER_PID" 2>/dev/null; wait "$PEER_PID" 2>/dev/null; fi
  rm -rf "$TMP"
}
trap cleanup EXIT
failures=0
checks=0
OUT=$TMP/out
ERR=$TMP/err

fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# run CMD...: runs it with stdin closed (as in CI); sets $rc, $OUT and $ERR files
run() { "$@" </dev/null >"$OUT" 2>"$ERR"; rc=$?; }

# expect CODE CMD...: exit status CODE; a failure prints exactly one line on stderr
expect() {
  local code=$1; shift
  checks=$((checks + 1))
  run "$@"
  if [ "$rc" != "$code" ]; then
    fail "$* -> exit $rc, want $code; stdout: $(head -c 300 "$OUT"); stderr: $(head -c 300 "$ERR")"
    return 1
  fi
  if [ "$code" != 0 ] && [ "$(wc -l <"$ERR")" != 1 ]; then
    fail "$* -> exit $rc with $(wc -l <"$ERR") lines on stderr, want 1: $(cat "$ERR")"
    return 1
  fi
  return 0
}

# expect_out CODE WANT CMD...: as expect, and stdout is exactly WANT (plus newline)
expect_out() {
  local code=$1 want=$2; shift 2
  expect "$code" "$@" || return 1
  if [ "$(cat "$OUT")" != "$want" ]; then
    fail "$* -> stdout:"$'\n'"$(cat "$OUT")"$'\n'"want:"$'\n'"$want"
    return 1
  fi
}

# expect_err_has TEXT: the last command's stderr contains TEXT
expect_err_has() {
  grep -qF -- "$1" "$ERR" || fail "stderr lacks '$1': $(cat "$ERR")"
}

# start_peer [pty_peer options]: a pty at $TTY whose received bytes go to $CAPTURE
start_peer() {
  TTY=$TMP/tty
  CAPTURE=$TMP/capture
  rm -f "$TTY" "$CAPTURE"
  "${PTY_PEER:?set PTY_PEER}" "$@" "$TTY" "$CAPTURE" &
  PEER_PID=$!
  local i
  for i in $(seq 200); do [ -e "$TTY" ] && return 0; sleep 0.01; done
  fail "pty_peer did not start"
}

stop_peer() {
  if [ -n "$PEER_PID" ]; then kill "$PEER_PID" 2>/dev/null; wait "$PEER_PID" 2>/dev/null; fi
  PEER_PID=""
}

# captured: the bytes that reached the peer, as upper-case spaced hex
captured() { od -An -v -tx1 "$CAPTURE" | tr -s ' \n' '  ' | sed 's/^ //; s/ $//' | tr a-f A-F; }

finish() {
  echo "$checks checks, $failures failures"
  [ "$failures" = 0 ]
}

# bad_args: the entries of bad.txt, with $(many ...) expanded
many() { local i; for i in $(seq "$1"); do printf "%s " "$i${2:-}"; done; }
bad=()
while IFS= read -r line; do
  case "$line" in '#'*|'') continue ;; esac
  while [[ $line =~ \$\(many\ ([0-9]+)\ ?(:[0-9]+)?\) ]]; do
    line=${line/"${BASH_REMATCH[0]}"/$(many "${BASH_REMATCH[1]}" "${BASH_REMATCH[2]}")}
  done
  bad+=("$line")
done <"$here/bad.txt"
[ "${#bad[@]}" -ge 50 ] || fail "bad.txt: only ${#bad[@]} entries"

# check_bad ARGS...: every bad.txt entry exits 2, with its reason on stderr,
# nothing on stdout (also with the options first and with --dry-run)
check_bad() {
  local entry args why
  for entry in "${bad[@]}"; do
    args=${entry%%|*}
    why=${entry#*|}
    # shellcheck disable=SC2086  # the arguments are words
    if expect_out 2 "" "$LSCCTL" "$@" $args; then
      expect_err_has "$why"
    fi
    # shellcheck disable=SC2086
    expect_out 2 "" "$LSCCTL" -n "$@" $args
  done
}

# expect_busy PORT COMMAND...: while another lscctl holds PORT, COMMAND on it
# exits 4 saying the port is busy (and sends nothing)
expect_busy() {
  local port=$1 holder; shift
  "$LSCCTL" --port "$port" --timeout 3000 monitor </dev/null >/dev/null 2>&1 &
  holder=$!
  sleep 0.3
  expect_out 4 "" "$LSCCTL" --port "$port" "$@"
  expect_err_has "busy"
  kill "$holder" 2>/dev/null
  wait "$holder" 2>/dev/null
}
