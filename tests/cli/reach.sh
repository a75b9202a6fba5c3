#!/usr/bin/env bash
# lscctl where, reach and move --speed (docs/kinematics.md) with the shipped
# xArm profile on lsc-sim over a pseudo-terminal: where against the chain
# computed here, independently, as homogeneous transforms from the figures of
# nuro-arm's URDF; reach to points across the workspace, read back; targets
# out of reach or beyond a limit refused with not one byte sent; move --speed's
# time; reach --line's waypoints on the segment; reach --wait with a joint
# held (--strict); the command line's errors.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${LSC_SIM:?set LSC_SIM to the lsc-sim binary}"
command -v python3 >/dev/null || skip "python3 is not installed (scripts/install-deps.sh --all)"
arms=$here/../../examples/arms

frames_in() { grep -cE ' (rx|noise)' "$TMP/$1.log"; }

T=(--timeout "$(test_ms 10000)")
sim a --fast
P=("$LSCCTL" --port "$TMP/a" --arm "$arms/xarm.conf" "${T[@]}")

# fk.py: the grasp point and pitch of the angles on the command line (base,
# shoulder, elbow, wrist, roll in degrees), as 4x4 transforms.
cat >"$TMP/fk.py" <<'EOF'
import math, sys
def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
def rz(d):
    c, s = math.cos(math.radians(d)), math.sin(math.radians(d))
    return [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
def ry(d):
    c, s = math.cos(math.radians(d)), math.sin(math.radians(d))
    return [[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]]
def up(mm):
    return [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, mm], [0, 0, 0, 1]]
b, s, e, w, r = map(float, sys.argv[1:6])
t = rz(b)
for m in (up(47 + 17.7), ry(s), up(98.8), ry(e), up(94.7), ry(w), rz(r), up(58.8 + 100)):
    t = mul(t, m)
ax = [t[0][2], t[1][2], t[2][2]]
fwd = ax[0] * math.cos(math.radians(b)) + ax[1] * math.sin(math.radians(b))
print(t[0][3], t[1][3], t[2][3], math.degrees(math.atan2(ax[2], fwd)))
EOF
# near.py A B TOL: the first four numbers of A and B (x y z pitch) agree
# within TOL mm and 0.5 degree
near() {
  python3 -c 'import sys
a = list(map(float, sys.argv[1].split()))[:4]; b = list(map(float, sys.argv[2].split()))[:4]
d = sum((a[i] - b[i]) ** 2 for i in range(3)) ** 0.5
p = abs((a[3] - b[3] + 180) % 360 - 180)
sys.exit(0 if d <= float(sys.argv[3]) and p <= 0.5 else 1)' "$1" "$2" "$3"
}
# angles: the chain's angles as read back (base shoulder elbow wrist roll)
angles() {
  run "${P[@]}" --json read base shoulder elbow wrist wrist-rotate
  python3 -c 'import json, sys
d = {s["joint"]: s["degrees"] for s in json.load(open(sys.argv[1]))["servos"]}
print(*(d[j] for j in ("base", "shoulder", "elbow", "wrist", "wrist-rotate")))' "$OUT"
}
# where_now: x y z pitch of lscctl --json where
where_now() {
  run "${P[@]}" --json where
  python3 -c 'import json, sys
w = json.load(open(sys.argv[1])); print(w["x_mm"], w["y_mm"], w["z_mm"], w["pitch_deg"])' "$OUT"
}

# lsc-sim's servos start at 1500, outside a bus servo's 0..1000
expect 2 "${P[@]}" where
expect_err_has "servo 6 is at position 1500, outside its joint's range 0..1000"

# where at angles spread over the limits agrees with the transforms
for q in "0 0 0 0 0" "30 20 40 -30 10" "-100 -60 90 45 -90" "75.5 88 -110 12 0" \
         "-20 45 45 45 45" "110 -15 -80 -100 114"; do
  set -- $q
  expect 0 "${P[@]}" move --time 0 base:${1}deg shoulder:${2}deg elbow:${3}deg wrist:${4}deg \
    wrist-rotate:${5}deg
  got=$(where_now)
  want=$(python3 "$TMP/fk.py" $(angles))
  near "$got" "$want" 1 || fail "where at $q: $got, the transforms say $want"
done
expect_out 0 "" "${P[@]}" move --time 0 base:0deg \
  shoulder:0deg elbow:0deg wrist:0deg wrist-rotate:0deg
expect_out 0 "x 0.0 y 0.0 z 417.0 mm, pitch 90.0 deg" "${P[@]}" where
# a joint within 5 degrees of an end of its limits is told (and in --json)
expect 0 "${P[@]}" move --time 0 shoulder:88deg elbow:-112deg
expect 0 "${P[@]}" where
[ "$(cat "$OUT")" = "x -4.4 y 0.0 z 299.6 mm, pitch 114.0 deg
shoulder at 88.08 deg: within 5 deg of its upper limit 90.52 deg
elbow at -112.08 deg: within 5 deg of its lower limit -114.59 deg" ] || fail "where near the ends: $(cat "$OUT")"
expect 0 "${P[@]}" --json where
python3 -c 'import json, sys; w = json.load(open(sys.argv[1])); sys.exit(0 if w["near_end"] == {"shoulder": "upper", "elbow": "lower"} else 1)' "$OUT" ||
  fail "where --json near the ends: $(cat "$OUT")"
expect_out 0 "" "${P[@]}" move --time 0 shoulder:0deg elbow:0deg

# reach across the workspace: in front, to the side, high, low, pitches -90..30
for t in "150 0 0 -90" "150 150 50 -60" "250 0 30 -45" "0 250 150 0" "120 -180 250 30" \
         "100 50 280 10" "60 -60 200 0" "200 0 100 -45" "120 0 30 -90"; do
  set -- $t
  expect 0 "${P[@]}" reach "$1" "$2" "$3" --pitch "$4" --time 100 --wait --tolerance 1
  got=$(python3 "$TMP/fk.py" $(angles))
  near "$got" "$t" 2 || fail "reach $t: the angles read back put the grasp point at $got"
done
# without a pitch: one is chosen, the point is reached; behind the base too
# (leaning back: a pitch beyond -90)
for t in "200 50 120" "-200 -60 100"; do
  set -- $t
  expect 0 "${P[@]}" reach "$1" "$2" "$3" --time 100 --wait
  got=$(python3 "$TMP/fk.py" $(angles))
  near "$got" "$t $(echo "$got" | cut -d' ' -f4)" 2 || fail "reach $t: at $got"
done

# refused: exit 2 and not one byte sent (not even the read of the angles)
before=$(frames_in a)
expect 2 "${P[@]}" reach 0 0 600
expect_err_has "reach: (0.0, 0.0, 600.0) mm is out of reach by 183.0 mm; nothing was sent"
expect 2 "${P[@]}" reach -250 0 64.7 --pitch 0
expect_err_has "needs joint base (the base, servo 6) at 180.00deg, beyond its upper limit 114.59deg; pitches "
expect 2 "${P[@]}" reach 200 0 100 --pitch -45 --roll 120
expect_err_has "needs joint wrist-rotate (the wrist roll, servo 2) at 120.00deg"
expect 0 "${P[@]}" battery
[ "$(frames_in a)" = $((before + 1)) ] || fail "refused reaches sent bytes: $(tail -5 "$TMP/a.log")"

# move --speed 90 base:45deg from base 0: 45.12 degrees (position 688) in 502 ms
expect 0 "${P[@]}" move --time 0 base:0deg
expect 0 "${P[@]}" -v move --speed 90 base:45deg --wait
expect_err_has "sent servo_move time_ms=502 servos=6:688"
expect_err_has "the move takes 502 ms"
# the time from the last position this lscctl read (a new process reads it)
expect 0 "${P[@]}" -v move --speed 45 base:0deg
expect_err_has "sent mult_servo_pos_read ids=6"
expect_err_has "sent servo_move time_ms=1003 servos=6:500"
# reach --speed: the largest joint travel at that speed
expect 0 "${P[@]}" reach 200 0 100 --pitch -45 --time 1 --wait
expect 0 "${P[@]}" --json reach 250 0 30 --pitch -45 --speed 60
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); sys.exit(0 if r["waypoints"] == 1 and r["time_ms"] > 100 else 1)' "$OUT" ||
  fail "reach --speed: $(cat "$OUT")"

# reach --line: waypoints along the segment, the middle one within 3 mm of it
expect 0 "${P[@]}" reach 150 150 80 --pitch -30 --time 1 --wait
from=$(where_now)
expect 0 "${P[@]}" -v --json reach 250 -50 60 --pitch -30 --line --time 2000 --wait
n=$(grep -c "sent servo_move" "$ERR")
[ "$n" -ge 5 ] || fail "reach --line sent $n moves"
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); sys.exit(0 if r["waypoints"] == int(sys.argv[2]) and r["time_ms"] == 2000 else 1)' "$OUT" "$n" ||
  fail "reach --line: $(cat "$OUT") for $n moves"
mid=$(grep "sent servo_move" "$ERR" | sed -n "$(( (n + 1) / 2 ))p" |
  sed 's/.*servos=\([^ ]*\) .*/\1/')
# positions of servos 6 5 4 3 2 -> degrees (0.24 a unit, 0 at 500)
q=$(python3 -c 'import sys
p = dict(map(int, s.split(":")) for s in sys.argv[1].split(","))
print(*((p[i] - 500) * 0.24 for i in (6, 5, 4, 3, 2)))' "$mid")
python3 - "$from" "$(python3 "$TMP/fk.py" $q)" <<'EOF' || fail "the middle waypoint ($q) is off the line"
import sys
a = list(map(float, sys.argv[1].split()))[:3]; b = [250.0, -50.0, 60.0]
p = list(map(float, sys.argv[2].split()))[:3]
ab = [b[i] - a[i] for i in range(3)]; ap = [p[i] - a[i] for i in range(3)]
f = max(0.0, min(1.0, sum(ab[i] * ap[i] for i in range(3)) / sum(x * x for x in ab)))
d = sum((a[i] + ab[i] * f - p[i]) ** 2 for i in range(3)) ** 0.5
sys.exit(0 if d <= 3 else 1)
EOF
got=$(where_now)
near "$got" "250 -50 60 -30" 2 || fail "reach --line ended at $got"

# reach --wait with the elbow held at 600 on its way to 729 (lsc-sim --block):
# the wait ends when it stopped, well before the timeout, says where (stderr;
# --json a "stopped" line before the result's) and exits 0; --strict: exit 3
sim b --fast --block 4:600
B=("$LSCCTL" --port "$TMP/b" --arm "$arms/xarm.conf" "${T[@]}")
rest=(move --time 0 base:0deg shoulder:0deg elbow:0deg wrist:0deg wrist-rotate:0deg)
expect 0 "${B[@]}" "${rest[@]}"
start=$(date +%s%N)
expect_out 0 "" "${B[@]}" reach 200 0 100 --pitch -45 --time 500 --wait
spent=$((($(date +%s%N) - start) / 1000000))
[ "$spent" -lt "$(test_ms 3000)" ] || fail "reach --wait on a held joint took $spent ms"
expect_err_has "servo 4 stopped at 600, 129 short of its target 729"
expect 0 "${B[@]}" "${rest[@]}"
expect_out 0 '{"stopped":[{"id":4,"position":600,"target":729,"short":129}]}
{"x_mm":200.00,"y_mm":0.00,"z_mm":100.00,"pitch_deg":-45.00,"waypoints":1,"time_ms":100}' \
  "${B[@]}" --json reach 200 0 100 --pitch -45 --time 100 --wait
expect 0 "${B[@]}" "${rest[@]}"
expect_out 3 "" "${B[@]}" reach 200 0 100 --pitch -45 --time 100 --wait --strict
expect_err_has "servo 4 stopped at 600, 129 short of its target 729 (--strict)"
# not held (the elbow to 536): --strict is no error
expect 0 "${B[@]}" "${rest[@]}"
expect_out 0 "" "${B[@]}" reach 100 50 280 --pitch 10 --time 100 --wait --strict
[ ! -s "$ERR" ] || fail "reach --wait --strict that arrived said: $(cat "$ERR")"

# the command line: exit 2, nothing sent
before=$(frames_in a)
expect 2 "$LSCCTL" --port "$TMP/a" reach 1 2 3
expect_err_has "the hand's position needs an arm profile that states its geometry: --arm FILE"
printf 'base 6 bus\n' >"$TMP/plain.conf"
expect 2 "$LSCCTL" --port "$TMP/a" --arm "$TMP/plain.conf" where
expect_err_has "the arm profile states no geometry: add its chain: and links: lines"
expect 2 "${P[@]}" -n reach 1 2 3
expect_err_has "-n: this command reads where the servos are before it sends anything"
expect 2 "${P[@]}" reach 1 2 3 --step 3
expect_err_has "--step is the distance between the waypoints of --line"
expect 2 "${P[@]}" reach 1 2 3 --time 100 --speed 10
expect_err_has "give --time or --speed, not both"
expect 2 "${P[@]}" move base:10deg --time 100 --speed 10
expect_err_has "give --time or --speed, not both"
expect 2 "${P[@]}" reach 1 2 3 --time 0
expect 2 "${P[@]}" reach 1 2 x
expect_err_has "Z 'x' is not a number: write it in decimal (-15, 2.5) (millimetres)"
expect 2 "${P[@]}" reach 1 2 20000
expect_err_has "Z 20000 is out of range: use -10000..10000"
expect 2 "${P[@]}" reach 1 2 3 --pitch 1e3
expect 2 "${P[@]}" reach 1 2 3 --speed 0
expect 2 "${P[@]}" reach 1 2 3 --step 0.01 --line
expect 2 "${P[@]}" reach 1 2
expect 2 "${P[@]}" where 1
expect 2 "$LSCCTL" --port "$TMP/a" move --speed 10 6:500
expect_err_has "--speed in degrees a second needs an arm profile: --arm FILE"
expect 2 "${P[@]}" -n move --speed 10 base:10deg
expect 2 "${P[@]}" --speed 10 move base:10deg
expect_err_has "is an option of"
expect 0 "${P[@]}" battery
[ "$(frames_in a)" = $((before + 1)) ] || fail "refused command lines sent bytes: $(tail -5 "$TMP/a.log")"
# play's --speed is still a percentage
expect 2 "${P[@]}" play --speed 1.5 "$TMP/none.txt"
expect_err_has "speed"

finish
