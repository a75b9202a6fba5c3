#!/usr/bin/env bash
# run --wait on a real port: with standard error on a terminal, when
# the controller has not reported within 3 s that the group started, lscctl
# says once that the board may have no such group, and keeps waiting. Not on
# a pipe or file (a script gets the exit status), not for a group that did
# start, not for plain 'wait'. The terminal is a pty that tty_run reads.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
command -v python3 >/dev/null || skip "python3 is not installed"

# tty_run UNTIL CMD...: runs CMD with stdin from /dev/null, stdout into $OUT
# and stderr on a pty, whose output goes to $ERR. With UNTIL (not empty):
# ends CMD with SIGTERM once UNTIL appeared on the terminal (or after the
# scaled 30 s safety limit: then SIGKILL, $rc 137), and writes to $TMP/until_ms how long after CMD's
# start it appeared. Sets $rc (143: ended by the SIGTERM).
tty_run() {
  local until=$1; shift
  python3 - "$until" "$OUT" "$ERR" "$TMP/until_ms" "$(test_ms 30000)" "$@" <<'PY'
import os, pty, select, signal, subprocess, sys, time
until, out, err, until_file, limit_ms = sys.argv[1:6]
argv = sys.argv[6:]
master, slave = pty.openpty()
start = time.monotonic()
with open(out, "wb") as o:
    p = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=o, stderr=slave)
os.close(slave)
got = b""
deadline = start + int(limit_ms) / 1000
seen = None
while True:
    left = deadline - time.monotonic()
    if left <= 0:
        break
    r, _, _ = select.select([master], [], [], left)
    if not r:
        break
    try:
        b = os.read(master, 4096)
    except OSError:  # EIO: the program closed the terminal (it ended)
        break
    if not b:
        break
    got += b
    if until and seen is None and until.encode() in got:
        seen = time.monotonic() - start
        p.send_signal(signal.SIGTERM)
if p.poll() is None and seen is None:
    p.kill()  # the safety limit: exit 137, which no check accepts
rc = p.wait()
with open(err, "wb") as e:
    e.write(got.replace(b"\r\n", b"\n"))
if seen is not None:
    with open(until_file, "w") as f:
        f.write(str(int(seen * 1000)))
sys.exit(128 - rc if rc < 0 else rc)
PY
  rc=$?
}
notice="has not reported that group 8 started (3 s since it was sent): the board may have no group 8; still waiting (Ctrl-C to stop)"

# no start reported: the notice comes once, after 3 s, and lscctl waits on
start_peer
rm -f "$TMP/until_ms"
checks=$((checks + 1))
tty_run "Ctrl-C to stop" "$LSCCTL" --port "$TTY" run 8 --wait
[ "$rc" = 143 ] || fail "run --wait: exit $rc, want 143 (waiting on until the test ended it after the notice): $(cat "$ERR")"
grep -qF "lscctl: run: the controller on $TTY $notice" "$ERR" || fail "no notice: $(cat "$ERR")"
[ "$(grep -c "may have no group" "$ERR")" = 1 ] || fail "the notice is not said once: $(cat "$ERR")"
[ -s "$TMP/until_ms" ] && [ "$(cat "$TMP/until_ms")" -ge 3000 ] ||
  fail "the notice came before 3 s: $(cat "$TMP/until_ms" 2>/dev/null) ms"
expect_captured "55 55 05 06 08 01 00"
stop_peer

# ... and with --timeout, a wait that keeps on after it until the timeout
start_peer
checks=$((checks + 1))
tty_run "" "$LSCCTL" --port "$TTY" --timeout "$(test_ms 3000 | awk '{ print $1 + 1500 }')" run 8 --wait
[ "$rc" = 3 ] || fail "run --wait --timeout: exit $rc, want 3: $(cat "$ERR")"
grep -qF "$notice" "$ERR" || fail "no notice before the timeout: $(cat "$ERR")"
grep -qF "no action group ended within" "$ERR" || fail "no timeout message: $(cat "$ERR")"
stop_peer

# the group started (and ended): no notice
start_peer -r "55 55 05 06 08 01 00 55 55 05 08 08 01 00"
checks=$((checks + 1))
tty_run "" "$LSCCTL" --port "$TTY" run 8 --wait
[ "$rc" = 0 ] || fail "run --wait of a group that ran: exit $rc: $(cat "$ERR")"
[ -s "$ERR" ] && fail "run --wait of a group that ran said: $(cat "$ERR")"
[ "$(cat "$OUT")" = "action_group_complete group=8 times=1" ] || fail "run --wait printed: $(cat "$OUT")"
stop_peer

# standard error not a terminal: no notice, only the timeout's one line
start_peer
expect 3 "$LSCCTL" --port "$TTY" --timeout "$(test_ms 3000 | awk '{ print $1 + 1500 }')" run 8 --wait
expect_err_has "no action group ended within"
stop_peer

# plain wait waits for any group's end, not a start: no notice
start_peer
checks=$((checks + 1))
tty_run "" "$LSCCTL" --port "$TTY" --timeout "$(test_ms 3000 | awk '{ print $1 + 1500 }')" wait
[ "$rc" = 3 ] || fail "wait --timeout: exit $rc, want 3: $(cat "$ERR")"
grep -q "may have no group" "$ERR" && fail "wait gave the run --wait notice: $(cat "$ERR")"
stop_peer
finish
