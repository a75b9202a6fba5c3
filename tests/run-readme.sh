#!/usr/bin/env bash
# Runs the shell examples of a README as it shows them, so that a README whose
# example no longer works or prints something else fails the suite.
#
#   run-readme.sh README HEADING...
#
# For each HEADING (the text of a Markdown heading, any level, without the
# #s), in the order given: every ```sh block between that heading and the next
# heading is in prompt form: a line `$ COMMAND` is a command, the lines after it
# (up to the next `$` line or the end of the block) its output. Each command
# runs in this one shell (so `export`, `cd` and `kill %1` work as in a
# terminal), in the current directory, with stdin closed; it must exit 0, and
# when output lines are shown its stdout must be exactly those lines (a
# command shown without output, such as a build, is not compared). A command
# that ends in `&` runs in the background; if it has `--link PATH` (lsc-sim),
# the next command waits until PATH exists. Background commands still running
# at the end are stopped. A heading that is missing, or has no command, fails.
set -u
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=test_time.sh
. "$here/test_time.sh"
readme=$1
shift
work=$(mktemp -d "${TMPDIR:-/tmp}/lsc-readme.XXXXXX")
cleanup() {
  local p
  for p in $(jobs -p); do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $readme: $*" >&2; failures=$((failures + 1)); }

# section HEADING: prints the section's ```sh lines, one per line
section() {
  awk -v want="$1" '
    /^```/ { if (fence) { fence = 0; sh = 0 } else { fence = 1; sh = ($0 == "```sh") } next }
    !fence && /^#+ / { h = $0; sub(/^#+ /, "", h); on = (h == want); found = found || on; next }
    on && sh { print }
    END { exit !found }' "$readme"
}

# check COMMAND WANT N: runs COMMAND (the Nth) and compares its stdout with WANT
# (nothing to compare if WANT is empty)
check() {
  local cmd=$1 want=$2 n=$3 out="$work/out.$3" err="$work/err.$3" rc link
  echo "\$ $cmd"
  if [[ $cmd =~ \&[[:space:]]*(#.*)?$ ]]; then
    eval "$cmd" </dev/null 2>"$err"
    if [[ $cmd =~ --link[[:space:]=]+([^[:space:]]+) ]]; then
      link=${BASH_REMATCH[1]}
      local deadline=$((SECONDS + $(test_ms 30000) / 1000))
      until [ -e "$link" ]; do
        if [ "$SECONDS" -ge "$deadline" ] || ! kill -0 $! 2>/dev/null; then
          fail "$cmd: $link did not appear; stderr: $(cat "$err")"
          return
        fi
        sleep 0.01
      done
    fi
    return
  fi
  eval "$cmd" </dev/null >"$out" 2>"$err"
  rc=$?
  if [ "$rc" != 0 ]; then
    fail "$cmd -> exit $rc; stdout: $(head -c 500 "$out"); stderr: $(head -c 500 "$err")"
  elif [ -n "$want" ] && [ "$(cat "$out")" != "$want" ]; then
    fail "$cmd -> stdout:"$'\n'"$(cat "$out")"$'\n'"the README shows:"$'\n'"$want"
  else
    [ -z "$want" ] || printf '%s\n' "$want"
  fi
}

n=0
for heading; do
  lines=$(section "$heading") || { fail "no heading '$heading'"; continue; }
  [ -n "$lines" ] || { fail "'$heading' has no \`\`\`sh block"; continue; }
  cmd="" want="" ran=0
  while IFS= read -r line; do
    if [[ $line == '$ '* ]]; then
      if [ -n "$cmd" ]; then n=$((n + 1)); ran=$((ran + 1)); check "$cmd" "$want" "$n"; fi
      cmd=${line#'$ '} want=""
    elif [ -z "$cmd" ]; then
      fail "'$heading': a line that is neither a \$ command nor its output: $line"
    else
      want+=${want:+$'\n'}$line
    fi
  done <<<"$lines"
  if [ -n "$cmd" ]; then n=$((n + 1)); ran=$((ran + 1)); check "$cmd" "$want" "$n"; fi
  [ "$ran" -gt 0 ] || fail "'$heading' has no \$ command"
done
echo "$n commands, $failures failures"
[ "$failures" = 0 ]
