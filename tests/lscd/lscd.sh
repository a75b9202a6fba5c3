#!/usr/bin/env bash
# lscd's command line, its socket (made, replaced, refused; $LSC_LSCD_DIR and
# --instance), lscctl status through it, and its systemd units
# (systemd-analyze verify, when installed).
# Environment: LSCD, LSCCTL, LSC_SIM (the built programs), UNITS (the
# configured units' directory).
mine=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$mine/lib.sh" # lscd's and lscctl's test helpers (answers, wait_for, expect, sim, ...)

# stop_lscd PID: SIGTERM; it exits 0
stop_lscd() {
  kill "$1"
  wait "$1"
  local rc=$?
  checks=$((checks + 1))
  [ "$rc" = 0 ] || fail "lscd (pid $1) exited $rc after SIGTERM, want 0"
}

# ---- the command line: one line on stderr, exit 2, nothing made
expect 2 "$LSCD"
expect_err_has "give --port PORT"
expect 2 "$LSCD" --port sim --bogus
expect_err_has "unknown option '--bogus'"
expect 2 "$LSCD" --port sim --timeout 0
expect_err_has "--timeout"
expect 2 "$LSCD" --port sim --client-queue 100
expect 2 "$LSCD" --port sim --mode 999
expect 2 "$LSCD" --port sim --instance sim
expect 2 "$LSCD" --instance a/b
expect 2 "$LSCD" --port sim extra
expect 2 "$LSCD" --port sim --socket ""
expect 2 "$LSCD" --port sim --timeout
expect_err_has "needs a value"
expect 0 "$LSCD" --help
grep -q -- "--exit-on-loss" "$OUT" || fail "--help does not list --exit-on-loss"
expect 0 "$LSCD" --version
[ "$(cat "$OUT")" = "lscd $("$LSCCTL" --version | sed 's/^lscctl //')" ] ||
  fail "lscd --version: $(cat "$OUT")"
# $LSC_HID_ID as every front end reads it: a malformed one is refused first
LSC_HID_ID=usb expect 2 "$LSCD" --port sim --socket "$TMP/env.sock"
expect_err_has "\$LSC_HID_ID needs a USB VID:PID in hex"
[ -e "$TMP/env.sock" ] && fail "lscd made a socket with a malformed \$LSC_HID_ID"
# a port that cannot be opened: exit 1, no socket made
expect 1 "$LSCD" --port "$TMP/nothing" --socket "$TMP/no.sock"
[ -e "$TMP/no.sock" ] && fail "lscd made a socket for a port it could not open"

# ---- $LSC_LSCD_DIR, --instance, lscd:NAME, the socket's mode
export LSC_LSCD_DIR=$TMP/run
"$LSCD" --instance sim 2>"$TMP/lscd.log" &
pid=$!
wait_for "lscd --instance sim did not answer on lscd:sim" answers sim
checks=$((checks + 1))
[ "$(stat -c %a "$TMP/run/sim.sock")" = 660 ] || fail "socket mode $(stat -c %a "$TMP/run/sim.sock"), want 660"
expect 0 "$LSCCTL" --port lscd:sim status
grep -qx "port: sim" "$OUT" || fail "status: $(cat "$OUT")"
grep -qx "controller: present" "$OUT" || fail "status: $(cat "$OUT")"
grep -qx "socket: $TMP/run/sim.sock" "$OUT" || fail "status: $(cat "$OUT")"
expect 0 "$LSCCTL" --port lscd:sim --json status
grep -q '^{"version":".*,"clients":1,.*"client":\["[0-9]* pid=' "$OUT" || fail "status --json: $(cat "$OUT")"
expect 0 "$LSCCTL" -n --port lscd:sim status
# status of a port that is not lscd's, or of no lscd
expect_out 2 "" "$LSCCTL" --port sim status
expect_err_has "lscd:NAME"
expect_out 1 "" "$LSCCTL" --port lscd:none status
expect_err_has "no lscd at $TMP/run/none.sock"
# a second lscd on the same socket: refused, the first one serves on
expect 1 "$LSCD" --port sim
expect_err_has "another lscd serves this socket"
expect 0 "$LSCCTL" --port lscd:sim status
stop_lscd "$pid"
checks=$((checks + 1))
[ -e "$TMP/run/sim.sock" ] && fail "lscd left its socket behind"
unset LSC_LSCD_DIR

# ---- a port another program holds: exit 4 (busy)
export LSC_LSCD_DIR=$TMP/run # its record goes there, not to /run/lsc
sim a --fast
"$LSCD" --port "$TMP/a" --socket "$TMP/a.sock" 2>"$TMP/lscd-a.log" &
pid=$!
wait_for "lscd on lsc-sim did not answer" answers "$TMP/a.sock"
expect 4 "$LSCD" --port "$TMP/a" --socket "$TMP/b.sock"
expect_err_has "busy"
expect 0 "$LSCCTL" --port "lscd:$TMP/a.sock" status
grep -qx "kind: serial" "$OUT" || fail "status: $(cat "$OUT")"
stop_lscd "$pid"
unset LSC_LSCD_DIR

# ---- lscd at its client limit: lscctl says so (the limit, how to raise it), exit 4 (busy)
"$LSCD" --port sim --socket "$TMP/full.sock" --max-clients 1 2>"$TMP/lscd-full.log" &
pid=$!
wait_for "lscd --max-clients 1 did not answer" answers "$TMP/full.sock"
coproc FILLER { exec python3 -c '
import socket, sys
s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
s.connect(sys.argv[1])
print("in", flush=True)
sys.stdin.read()' "$TMP/full.sock"; }
read -r -t "$(($(test_ms 30000) / 1000 + 1))" _ <&"${FILLER[0]}" ||
  fail "the client that fills lscd did not connect"
expect 4 "$LSCCTL" --port "lscd:$TMP/full.sock" battery
expect_err_has "at most 1 clients" && expect_err_has "--max-clients"
eval "exec ${FILLER[1]}>&-"
wait "$FILLER_PID"
stop_lscd "$pid"

# ---- a hostile lscd's status text: escaped on the terminal, exact in --json
python3 - "$TMP/evil.sock" 2>"$TMP/evil.log" <<'PY' &
import os, socket, sys
def ctl(op, args=b""):
    return bytes([0x55, 0x55, len(args) + 3, 0xCD, op]) + args
srv = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
srv.bind(sys.argv[1])
srv.listen(4)
for _ in range(2):
    c, _ = srv.accept()
    c.sendall(ctl(0x80, b"\x01\x01"))
    data = b""
    while True:
        got = c.recv(4096)
        if not got:
            break
        data += got
        while len(data) >= 3 and len(data) >= data[2] + 2:
            frame, data = data[:data[2] + 2], data[data[2] + 2:]
            if frame[3] == 0xCD and frame[4] == 0x07:  # PING
                c.sendall(ctl(0x87, frame[5:9]))
            elif frame[3] == 0xCD and frame[4] == 0x06:  # STATUS
                c.sendall(ctl(0x85, b"port=\x1b]0;pwned\x07\x1b[2J\x1b[31mred\nforged: line"))
                c.sendall(ctl(0x86))
    c.close()
PY
evil=$!
wait_for "the hostile lscd did not listen" test -S "$TMP/evil.sock"
expect 0 "$LSCCTL" --port "lscd:$TMP/evil.sock" status
checks=$((checks + 1))
[ "$(cat "$OUT")" = 'port: \x1B]0;pwned\x07\x1B[2J\x1B[31mred\x0Aforged: line' ] ||
  fail "status printed a hostile lscd's text as: $(od -c "$OUT" | head -5)"
expect 0 "$LSCCTL" --port "lscd:$TMP/evil.sock" --json status
[ "$(cat "$OUT")" = '{"port":"\u001b]0;pwned\u0007\u001b[2J\u001b[31mred\u000aforged: line"}' ] ||
  fail "status --json: $(cat "$OUT")"
wait "$evil"

# ---- socket activation: lscd starts at the first connection
if command -v systemd-socket-activate >/dev/null; then
  systemd-socket-activate -l "$TMP/act.sock" "$LSCD" --port sim 2>"$TMP/act.log" &
  pid=$!
  wait_for "systemd-socket-activate did not listen" test -S "$TMP/act.sock"
  expect 0 "$LSCCTL" --port "lscd:$TMP/act.sock" status
  grep -qx "socket: $TMP/act.sock (systemd)" "$OUT" || fail "status: $(cat "$OUT")"
  stop_lscd "$pid"
else
  echo "systemd-socket-activate is not installed (package systemd): socket activation not tried"
fi

# ---- the systemd units pass systemd-analyze verify (the program as built)
if command -v systemd-analyze >/dev/null && [ -n "${UNITS:-}" ]; then
  mkdir "$TMP/units"
  for u in "lscd@" "lscd-hid@"; do
    for kind in socket service; do
      sed "s|^ExecStart=[^ ]*|ExecStart=$LSCD|" "$UNITS/$u.$kind" >"$TMP/units/$u.$kind"
    done
  done
  cp "$TMP/units/lscd@.socket" "$TMP/units/lscd@ttyUSB0.socket"
  cp "$TMP/units/lscd@.service" "$TMP/units/lscd@ttyUSB0.service"
  cp "$TMP/units/lscd-hid@.socket" "$TMP/units/lscd-hid@hidraw0.socket"
  cp "$TMP/units/lscd-hid@.service" "$TMP/units/lscd-hid@hidraw0.service"
  checks=$((checks + 1))
  (cd "$TMP/units" && SYSTEMD_LOG_LEVEL=notice systemd-analyze verify --man=no \
    lscd@ttyUSB0.socket lscd@ttyUSB0.service lscd-hid@hidraw0.socket lscd-hid@hidraw0.service) \
    >"$TMP/verify" 2>&1 || fail "systemd-analyze verify: $(cat "$TMP/verify")"
  [ -s "$TMP/verify" ] && fail "systemd-analyze verify said: $(cat "$TMP/verify")"
  # the service runs lscd --instance with the instance
  grep -qx "ExecStart=.*/lscd --instance %i" "$UNITS/lscd@.service" ||
    fail "lscd@.service: $(grep ExecStart "$UNITS/lscd@.service")"
else
  echo "systemd-analyze is not installed (package systemd): the units were not verified"
fi
finish
