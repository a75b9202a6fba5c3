#!/usr/bin/env bash
# lscctl against hostile peers (SECURITY.md): a port another program holds with
# TIOCEXCL only, replies that are noise, notifications or other frames, and a
# line that stops draining in the middle of a frame, with and without a
# signal arriving during that write.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

scale=${LSC_TEST_TIME_SCALE:-1}
ids=$(seq -s ' ' 252) # unload 1..252: a 257-byte frame
frame_len=257

# ---- a port held with TIOCEXCL only (no flock): busy, exit 4 ----------------
start_peer
python3 - "$TTY" "$TMP/holding" <<'EOF' &
import fcntl, os, signal, sys, termios, time
fd = os.open(sys.argv[1], os.O_RDWR | os.O_NOCTTY)
fcntl.ioctl(fd, termios.TIOCEXCL)
def leave(*_):  # a well-behaved holder clears its flag (it outlives the close)
    fcntl.ioctl(fd, termios.TIOCNXCL)
    sys.exit(0)
signal.signal(signal.SIGTERM, leave)
open(sys.argv[2], "w").close()
time.sleep(600)  # ended by the test
EOF
holder=$!
for _ in $(seq $((500 * scale))); do [ -e "$TMP/holding" ] && break; sleep 0.01; done
if [ "$(id -u)" = 0 ]; then want="TIOCEXCL"; else want="busy"; fi
expect_out 4 "" "$LSCCTL" --port "$TTY" stop && expect_err_has "$want"
kill "$holder"; wait "$holder" 2>/dev/null
[ -z "$(captured)" ] || fail "bytes reached a port another program holds: $(captured)"
expect_out 0 "" "$LSCCTL" --port "$TTY" stop # the holder is gone: free again
stop_peer

# ---- "no reply": the message says what did arrive ------------------------------
start_peer
expect_out 3 "" "$LSCCTL" --port "$TTY" -t 300 battery
expect_err_has "nothing arrived"
stop_peer
start_peer -r "00 11 22 33 44 F0 0F FF 12 34"
expect_out 3 "" "$LSCCTL" --port "$TTY" -t 300 battery
expect_err_has "only 10 byte(s) arrived that formed no frame: likely a wrong baud rate"
expect_err_has "(--baud N, --timeout MS)"
stop_peer
start_peer -r "55 55 02 07"
expect_out 3 "" "$LSCCTL" --port "$TTY" -t 300 battery
expect_err_has "only 1 notification(s) arrived"
expect_err_has "raise the timeout (--timeout MS)"
stop_peer
start_peer -r "55 55 03 33 01"
expect_out 3 "" "$LSCCTL" --port "$TTY" -t 300 read 1
expect_err_has "did not answer mult_servo_pos_read (command 21) within 300 ms: 1 frame(s) answering something else came instead (the last: unknown (command 51)), with 0 notification(s)"
stop_peer
# a reply to another request (not "no reply"): named, with the request
start_peer -r "55 55 06 15 01 01 DC 05"
expect_out 3 "" "$LSCCTL" --port "$TTY" -t 300 battery
expect_err_has "did not answer get_battery_voltage (command 15) within 300 ms: 1 frame(s) answering something else came instead (the last: mult_servo_pos_read (command 21))"
[ "$(grep -c "no reply" "$ERR")" = 0 ] || fail "a wrong reply is called no reply: $(cat "$ERR")"
stop_peer

# ---- a line that stops draining -------------------------------------------------
# stall_peer: a pty at $TTY whose far end reads nothing until $GO exists, then
# reads everything into $CAPTURE until the port is closed.
stall_peer() {
  stop_peer
  TTY=$TMP/stall-tty CAPTURE=$TMP/stall-capture GO=$TMP/go
  rm -f "$TTY" "$CAPTURE" "$GO"
  python3 - "$TTY" "$CAPTURE" "$GO" "$((120 * scale))" <<'EOF' &
import os, pty, sys, time
link, capture, go, limit = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
master, slave = pty.openpty()
os.symlink(os.ttyname(slave), link)
os.close(slave)
end = time.monotonic() + limit
while not os.path.exists(go) and time.monotonic() < end:
    time.sleep(0.01)
got = bytearray()
while time.monotonic() < end:
    try:
        b = os.read(master, 65536)
    except OSError:  # EIO: the port was closed
        break
    if not b:
        break
    got += b
with open(capture, "wb") as f:
    f.write(got)
EOF
  PEER_PID=$!
  for _ in $(seq $((500 * scale))); do [ -e "$TTY" ] && return 0; sleep 0.01; done
  fail "the stalling peer did not start"
}

# stalled_unload: sends 257-byte unloads (-v) until one cannot finish: its
# pid in $pid while it waits for the line mid-frame (state S after its trace
# line, seen 10 times in a row: a write can sleep for a moment while the
# kernel moves the pty's buffer along, late on a busy machine, and then
# finish; the stalled one sleeps until its 1.8 s write timeout). Earlier ones
# must succeed.
stalled_unload() {
  local n st asleep
  pid=""
  for n in $(seq 100); do
    # shellcheck disable=SC2086  # the ids are words
    "$LSCCTL" --port "$TTY" -v unload $ids </dev/null >"$OUT" 2>"$ERR" &
    pid=$!
    asleep=0
    for _ in $(seq $((3000 * scale))); do
      if ! kill -0 "$pid" 2>/dev/null; then break; fi
      st=$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)
      if [ "$st" = S ] && grep -q "sent mult_servo_unload" "$ERR"; then
        asleep=$((asleep + 1))
        [ "$asleep" -ge 10 ] && return 0
      else
        asleep=0
      fi
      sleep 0.01
    done
    wait "$pid"
    rc=$?
    if [ "$rc" != 0 ]; then fail "unload $n exited $rc before the line stalled: $(cat "$ERR")"; return 1; fi
  done
  fail "the line never stalled"
  return 1
}

# A timed-out write: exit 1, naming the frame and how much of it went out.
stall_peer
stalled_unload && {
  wait "$pid"; rc=$?
  [ "$rc" = 1 ] || fail "stalled unload exited $rc, want 1: $(cat "$ERR")"
  grep -q "unload: sending mult_servo_unload (command 20, 257 bytes): $TTY: write timed out: the line does not drain ([0-9]* of 257 bytes went out" "$ERR" ||
    fail "stalled unload: $(tail -c 400 "$ERR")"
}

# SIGTERM in the middle of the write: lscctl finishes the frame once the line
# drains, then ends by the signal; the far end got only whole frames.
stall_peer
stalled_unload && {
  kill -TERM "$pid"
  touch "$GO"
  wait "$pid"; rc=$?
  [ "$rc" = 143 ] || fail "SIGTERM mid-frame: exit $rc, want 143 (the signal, after the frame): $(cat "$ERR")"
  wait "$PEER_PID"; PEER_PID=""
  size=$(wc -c <"$CAPTURE")
  [ "$size" -gt 0 ] && [ $((size % frame_len)) = 0 ] ||
    fail "SIGTERM mid-frame: $size bytes reached the peer, not whole 257-byte frames"
}

# SIGHUP while the line never drains: the write gives up (bounded), lscctl
# says what it was sending and how much went out, then ends by the signal.
# (Not SIGINT: a script's background jobs ignore it.)
stall_peer
stalled_unload && {
  kill -HUP "$pid"
  wait "$pid"; rc=$?
  [ "$rc" = 129 ] || fail "SIGHUP on a stalled line: exit $rc, want 129: $(cat "$ERR")"
  grep -q "sending mult_servo_unload (command 20, 257 bytes): .*of 257 bytes went out" "$ERR" ||
    fail "SIGHUP on a stalled line said: $(tail -c 400 "$ERR")"
}
stop_peer

finish
