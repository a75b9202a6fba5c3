# Helpers for lscctl's integration tests (sourced by each test script).
# Usage in a script: . lib.sh; ...; finish
# Environment: LSCCTL (the built program), PTY_PEER (tests/cli/pty_peer),
# LSC_TEST_TIME_SCALE (a positive integer, default 1: every wall-clock wait
# of a test is multiplied by it; the sanitize and valgrind stages raise it).
set -u
: "${LSCCTL:?set LSCCTL to the lscctl binary}"

# test_ms MS: MS scaled by LSC_TEST_TIME_SCALE (tests/test_time.sh)
# shellcheck source=../test_time.sh
. "$here/../test_time.sh"

# skip WHAT: the test cannot run here (ctest SKIP_RETURN_CODE 77), saying why
skip() { echo "SKIP: $*"; exit 77; }

# wait_for WHAT CMD...: polls CMD until it succeeds; after a generous deadline
# (30 s, scaled) fails saying WHAT did not happen. A condition, not a guess.
wait_for() {
  local what=$1; shift
  local deadline=$((SECONDS + $(test_ms 30000) / 1000))
  until "$@"; do
    if [ "$SECONDS" -ge "$deadline" ]; then
      fail "$what (waited $(test_ms 30000) ms)"
      return 1
    fi
    sleep 0.01
  done
}

TMP=$(mktemp -d)
PEER_PID=""
SIMS=() # the lsc-sim processes sim started
cleanup() {
  if [ -n "$PEER_PID" ]; then kill "$PEER_PID" 2>/dev/null; wait "$PEER_PID" 2>/dev/null; fi
  local p
  for p in "${SIMS[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done
  rm -rf "$TMP"
}
trap cleanup EXIT
failures=0
checks=0
OUT=$TMP/out
ERR=$TMP/err


# sim NAME [lsc-sim options]: serves a virtual controller ($LSC_SIM) at
# $TMP/NAME, logging to $TMP/NAME.log, until the test ends
sim() {
  local name=$1; shift
  "$LSC_SIM" --link "$TMP/$name" --log "$@" >/dev/null 2>"$TMP/$name.log" &
  SIMS+=($!)
  wait_for "lsc-sim did not make $TMP/$name" test -e "$TMP/$name" ||
    fail "lsc-sim's log: $(cat "$TMP/$name.log")"
}
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
  # it lives until stop_peer or cleanup kills it (or this shell is gone)
  "${PTY_PEER:?set PTY_PEER}" "$@" "$TTY" "$CAPTURE" &
  PEER_PID=$!
  wait_for "pty_peer did not make $TTY" test -e "$TTY"
}

stop_peer() {
  if [ -n "$PEER_PID" ]; then kill "$PEER_PID" 2>/dev/null; wait "$PEER_PID" 2>/dev/null; fi
  PEER_PID=""
}

# captured: the bytes that reached the peer, as upper-case spaced hex
captured() { od -An -v -tx1 "$CAPTURE" | tr -s ' \n' '  ' | sed 's/^ //; s/ $//' | tr a-f A-F; }
# captured_at_least N: the peer has received N bytes or more
captured_at_least() { [ "$(wc -c <"$CAPTURE")" -ge "$1" ]; }

# expect_captured HEX: the peer received exactly HEX (upper-case spaced) in
# all. lscctl has exited when this runs, but the peer may not have read yet:
# wait until at least that many bytes arrived, then compare. Checking that
# nothing arrived for refused commands is done this way too: by a valid
# command afterwards whose bytes must be all there is.
expect_captured() {
  local want=$1 n
  checks=$((checks + 1))
  n=$(( (${#want} + 1) / 3 ))
  wait_for "the peer did not receive $n bytes" captured_at_least "$n" || return 1
  [ "$(captured)" = "$want" ] || fail "the port got: $(captured); want: $want"
}

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

# holds_lock PID: PID holds a flock (lscctl locks the port it opens; Linux /proc/locks)
holds_lock() { awk -v pid="$1" '$2 == "FLOCK" && $5 == pid { found = 1 } END { exit !found }' /proc/locks; }
# locked_or_gone PID: PID holds a lock, or has exited (then it never will)
locked_or_gone() { holds_lock "$1" || ! kill -0 "$1" 2>/dev/null; }

# expect_busy PORT COMMAND...: while another lscctl holds PORT, COMMAND on it
# exits 4 saying the port is busy (and sends nothing).
expect_busy() {
  local port=$1; shift
  expect_busy_program "$port" "$LSCCTL" --port "$port" "$@"
}

# expect_busy_program PORT PROGRAM ARGS...: the same for any program (PORT is
# one of its ARGS). The holder waits until this kills it (its --timeout is only
# a safety limit); it holds the port once its lock shows in /proc/locks.
expect_busy_program() {
  local port=$1 holder; shift
  "$LSCCTL" --port "$port" --timeout "$(test_ms 300000)" monitor </dev/null >/dev/null 2>&1 &
  holder=$!
  wait_for "the holding lscctl did not lock $port" locked_or_gone "$holder"
  if holds_lock "$holder"; then
    expect_out 4 "" "$@"
    expect_err_has "busy"
  else
    fail "the holding lscctl exited before it locked $port"
  fi
  kill "$holder" 2>/dev/null
  wait "$holder" 2>/dev/null
}
