#!/usr/bin/env python3
"""A stand-in bus of Hiwonder/LewanSoul serial bus servos on a pseudo-terminal.

Written from the vendor's "Bus Servo Communication Protocol" alone (the
frame, the command table, the broadcast rule, what is kept at power-off),
independently of lsc's own codec and virtual bus, so that lsc's bus support
is tested against a peer it did not write itself.

Usage:
    lxbus_peer.py --link PATH [--ids 1-6] [--state FILE] [--echo]
                  [--control SOCKET] [--watch-stdin]

It opens a pseudo-terminal (raw, 115200 8N1), links PATH to it, prints
"ready PATH" on stdout once the link exists, and answers frames written to
it as a bus of servos with the ids given (a list: "1,2,5" or "1-6").
It ends on SIGTERM or SIGINT, and with --watch-stdin when its standard input
closes (a test that dies takes its peer with it); the link is removed.

What it models (the document's words; nothing here was seen on a servo):
  - frame 55 55 ID LEN CMD P1..Pn CHK, LEN = n + 3, CHK = ~(ID+LEN+CMD+P..) & 0xFF;
    a frame whose checksum fails, whose LEN does not fit its command, or whose
    values are out of the document's ranges is ignored (no answer, no effect);
  - id 254 is the broadcast: every servo obeys, none answers, except ID_READ,
    which every servo answers; several servos answering at once collide, and
    on a UART line (idle high, a 0 wins) the bytes are ANDed together;
  - kept at power-off: id, saved offset, angle limits, input voltage limits,
    temperature limit, LED setting. Lost: an adjusted offset not saved, motor
    mode, torque (off after power-up), the alarm mask (7 after power-up), any
    move; the servo stays where it was;
  - position: a move commands the servo's own scale (0..1000); the shaft sits
    at the commanded position plus the offset (so adjusting the offset turns
    a held servo's shaft at once; a limp one reads differently), and POS_READ reports the shaft minus the offset
    (int16: negative below 0); moves are linear in real time over their time;
    positions are clamped into the angle limits; a move turns torque on;
  - motor mode: the shaft turns at SPEED (-1000..1000) units per second, the
    position wraps within 0..1000;
  - temperature and input voltage are readings (--temp, --vin, or the control
    socket); above the temperature limit or outside the voltage limits torque
    goes off.
With --echo every byte received is written back first, as on a one-wire bus
that hears its own host.

The control socket (--control PATH, a UNIX stream socket, one command a line,
each answered with one line: "ok ..." or "error ..."):
  dump                      the true state of every servo, as one JSON line
  power-cycle               power off and on: what is not kept is lost
  set ID pos N              a limp servo placed by hand: its shaft to N (reported: N - offset)
  set ID temp C | vin MV    readings
  flip                      flip one bit (the lowest of the last parameter) of the next reply
  add ID | remove ID        a servo connected to or taken from the bus
  count CMD                 how many frames of command CMD the bus received (ok N)
"""

import argparse
import json
import os
import select
import signal
import socket
import sys
import termios
import time
import tty

BROADCAST = 254

# command: (name, request LEN, reply LEN or None)
COMMANDS = {
    1: ("MOVE_TIME_WRITE", 7, None),
    2: ("MOVE_TIME_READ", 3, 7),
    7: ("MOVE_TIME_WAIT_WRITE", 7, None),
    8: ("MOVE_TIME_WAIT_READ", 3, 7),
    11: ("MOVE_START", 3, None),
    12: ("MOVE_STOP", 3, None),
    13: ("ID_WRITE", 4, None),
    14: ("ID_READ", 3, 4),
    17: ("ANGLE_OFFSET_ADJUST", 4, None),
    18: ("ANGLE_OFFSET_WRITE", 3, None),
    19: ("ANGLE_OFFSET_READ", 3, 4),
    20: ("ANGLE_LIMIT_WRITE", 7, None),
    21: ("ANGLE_LIMIT_READ", 3, 7),
    22: ("VIN_LIMIT_WRITE", 7, None),
    23: ("VIN_LIMIT_READ", 3, 7),
    24: ("TEMP_MAX_LIMIT_WRITE", 4, None),
    25: ("TEMP_MAX_LIMIT_READ", 3, 4),
    26: ("TEMP_READ", 3, 4),
    27: ("VIN_READ", 3, 5),
    28: ("POS_READ", 3, 5),
    29: ("OR_MOTOR_MODE_WRITE", 7, None),
    30: ("OR_MOTOR_MODE_READ", 3, 7),
    31: ("LOAD_OR_UNLOAD_WRITE", 4, None),
    32: ("LOAD_OR_UNLOAD_READ", 3, 4),
    33: ("LED_CTRL_WRITE", 4, None),
    34: ("LED_CTRL_READ", 3, 4),
    35: ("LED_ERROR_WRITE", 4, None),
    36: ("LED_ERROR_READ", 3, 4),
}

KEPT = ("id", "offset_saved", "limits", "vin_limits", "temp_limit", "led_off")


def checksum(body):
    """CHK over ID, LEN, CMD and the parameters."""
    return (~sum(body)) & 0xFF


def frame(servo_id, cmd, params):
    body = bytes([servo_id, len(params) + 3, cmd]) + bytes(params)
    return b"\x55\x55" + body + bytes([checksum(body)])


def u16(lo, hi):
    return lo | (hi << 8)


def s16(lo, hi):
    v = u16(lo, hi)
    return v - 0x10000 if v & 0x8000 else v


def le16(v):
    v &= 0xFFFF
    return [v & 0xFF, v >> 8]


def parse_ids(text):
    ids = []
    for part in text.split(","):
        if "-" in part:
            lo, hi = part.split("-", 1)
            ids.extend(range(int(lo), int(hi) + 1))
        elif part:
            ids.append(int(part))
    for i in ids:
        if not 0 <= i <= 253:
            raise ValueError("servo id %d is not 0..253" % i)
    return ids


class Servo:
    def __init__(self, servo_id, now, temp=30, vin=7400):
        # kept at power-off
        self.id = servo_id
        self.offset_saved = 0
        self.limits = [0, 1000]
        self.vin_limits = [4500, 12000]
        self.temp_limit = 85
        self.led_off = 0
        # readings
        self.temp = temp
        self.vin = vin
        # the shaft, in the servo's units, without the offset
        self.shaft = 500.0
        self.power_up(now)

    def power_up(self, now):
        self.offset = self.offset_saved
        self.motor = 0
        self.speed = 0
        self.torque = 0
        self.alarm_mask = 7
        self.move_from = self.shaft
        self.move_to = self.shaft
        self.move_start = now
        self.move_time = 0
        self.last_move = (int(round(self.shaft - self.offset)), 0)
        self.waiting = None

    def kept(self):
        return {k: getattr(self, k) for k in KEPT}

    def restore(self, state):
        for k in KEPT:
            if k in state:
                setattr(self, k, state[k])

    def update(self, now):
        """Advance the shaft to time now."""
        if self.motor and self.torque:
            elapsed = now - self.move_start
            self.move_start = now
            self.shaft = (self.shaft + self.speed * elapsed) % 1000.0
            return
        if self.move_time <= 0 or now >= self.move_start + self.move_time:
            self.shaft = self.move_to
        else:
            f = (now - self.move_start) / self.move_time
            self.shaft = self.move_from + (self.move_to - self.move_from) * f

    def protect(self, now):
        """Above the temperature limit or outside the voltage limits: torque off."""
        if self.temp > self.temp_limit or not self.vin_limits[0] <= self.vin <= self.vin_limits[1]:
            self.update(now)
            self.torque = 0
            self.move_from = self.move_to = self.shaft

    def alarms(self):
        bits = 0
        if self.temp > self.temp_limit:
            bits |= 1
        if not self.vin_limits[0] <= self.vin <= self.vin_limits[1]:
            bits |= 2
        return bits & self.alarm_mask

    def start_move(self, now, pos, ms):
        self.update(now)
        pos = min(max(pos, self.limits[0]), self.limits[1])
        self.motor = 0
        self.torque = 1
        self.move_from = self.shaft
        self.move_to = float(pos + self.offset)
        self.move_start = now
        self.move_time = ms / 1000.0
        self.last_move = (pos, ms)
        self.protect(now)

    def reported(self, now):
        self.update(now)
        return int(round(self.shaft)) - self.offset


class Bus:
    def __init__(self, ids, state_file, temp, vin):
        now = time.monotonic()
        self.servos = [Servo(i, now, temp, vin) for i in ids]
        self.state_file = state_file
        self.flip_next = False
        self.counts = {}
        self.temp = temp
        self.vin = vin
        if state_file and os.path.exists(state_file):
            with open(state_file) as f:
                saved = json.load(f)
            self.servos = []
            for s in saved["servos"]:
                servo = Servo(s["id"], now, temp, vin)
                servo.restore(s)
                servo.shaft = float(s.get("shaft", 500))
                servo.power_up(now)
                self.servos.append(servo)

    def save(self):
        if not self.state_file:
            return
        data = {"servos": [dict(s.kept(), shaft=s.shaft) for s in self.servos]}
        tmp = self.state_file + ".tmp"
        with open(tmp, "w") as f:
            json.dump(data, f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, self.state_file)

    def addressed(self, servo_id):
        if servo_id == BROADCAST:
            return list(self.servos)
        return [s for s in self.servos if s.id == servo_id]

    def handle(self, servo_id, cmd, p):
        """Act on one good frame; returns the bytes the bus answers."""
        now = time.monotonic()
        self.counts[cmd] = self.counts.get(cmd, 0) + 1
        replies = []
        kept_changed = False
        for s in self.addressed(servo_id):
            answer = self.act(s, cmd, p, now)
            if isinstance(answer, list):
                if servo_id != BROADCAST or cmd == 14:
                    replies.append(frame(s.id, cmd, answer))
            elif answer:
                kept_changed = True
        if kept_changed:
            self.save()
        if not replies:
            return b""
        # answers at once collide: a UART line idles high, a 0 wins
        out = bytearray(replies[0])
        for r in replies[1:]:
            for i in range(min(len(out), len(r))):
                out[i] &= r[i]
        if self.flip_next:
            self.flip_next = False
            out[-2] ^= 1
        return bytes(out)

    def act(self, s, cmd, p, now):
        """One servo's part: a list of reply parameters, True when kept state changed."""
        if cmd in (1, 7):
            pos, ms = u16(p[0], p[1]), u16(p[2], p[3])
            if pos > 1000 or ms > 30000:
                return None
            if cmd == 1:
                s.start_move(now, pos, ms)
            else:
                s.waiting = (pos, ms)
        elif cmd == 2:
            return le16(s.last_move[0]) + le16(s.last_move[1])
        elif cmd == 8:
            pos, ms = s.waiting if s.waiting else s.last_move
            return le16(pos) + le16(ms)
        elif cmd == 11:
            if s.waiting:
                s.start_move(now, *s.waiting)
                s.waiting = None
        elif cmd == 12:
            s.update(now)
            s.move_from = s.move_to = s.shaft
            s.move_time = 0
            s.waiting = None
        elif cmd == 13:
            if p[0] > 253:
                return None
            s.id = p[0]
            return True
        elif cmd == 14:
            return [s.id]
        elif cmd == 17:
            off = p[0] - 256 if p[0] & 0x80 else p[0]
            if not -125 <= off <= 125:
                return None
            s.update(now)
            if s.torque:  # a held servo turns by the change; a limp one reads differently
                s.shaft += off - s.offset
                s.move_from = s.shaft
                s.move_to += off - s.offset
            s.offset = off
        elif cmd == 18:
            s.offset_saved = s.offset
            return True
        elif cmd == 19:
            return [s.offset & 0xFF]
        elif cmd == 20:
            lo, hi = u16(p[0], p[1]), u16(p[2], p[3])
            if not lo < hi <= 1000:
                return None
            s.limits = [lo, hi]
            return True
        elif cmd == 21:
            return le16(s.limits[0]) + le16(s.limits[1])
        elif cmd == 22:
            lo, hi = u16(p[0], p[1]), u16(p[2], p[3])
            if not 4500 <= lo < hi <= 12000:
                return None
            s.vin_limits = [lo, hi]
            s.protect(now)
            return True
        elif cmd == 23:
            return le16(s.vin_limits[0]) + le16(s.vin_limits[1])
        elif cmd == 24:
            if not 50 <= p[0] <= 100:
                return None
            s.temp_limit = p[0]
            s.protect(now)
            return True
        elif cmd == 25:
            return [s.temp_limit]
        elif cmd == 26:
            return [max(0, min(255, s.temp))]
        elif cmd == 27:
            return le16(s.vin)
        elif cmd == 28:
            return le16(s.reported(now))
        elif cmd == 29:
            speed = s16(p[2], p[3])
            if p[0] > 1 or not -1000 <= speed <= 1000:
                return None
            s.update(now)
            s.motor, s.speed = p[0], speed
            s.move_from = s.move_to = s.shaft
            s.move_start, s.move_time = now, 0
            if s.motor:
                s.torque = 1
                s.protect(now)
        elif cmd == 30:
            return [s.motor, 0] + le16(s.speed)
        elif cmd == 31:
            if p[0] > 1:
                return None
            s.update(now)
            s.torque = p[0]
            s.move_from = s.move_to = s.shaft
            s.move_time = 0
            if s.torque:
                s.protect(now)
        elif cmd == 32:
            return [s.torque]
        elif cmd == 33:
            if p[0] > 1:
                return None
            s.led_off = p[0]
            return True
        elif cmd == 34:
            return [s.led_off]
        elif cmd == 35:
            if p[0] > 7:
                return None
            s.alarm_mask = p[0]
        elif cmd == 36:
            return [s.alarm_mask]
        return None

    def control(self, line):
        words = line.split()
        now = time.monotonic()
        if not words:
            return "error empty command"
        if words == ["dump"]:
            servos = []
            for s in self.servos:
                s.update(now)
                d = s.kept()
                d.update(offset=s.offset, shaft=round(s.shaft, 1), position=s.reported(now),
                         torque=s.torque, motor=s.motor, speed=s.speed,
                         alarm_mask=s.alarm_mask, alarms=s.alarms(), temp=s.temp, vin=s.vin,
                         waiting=s.waiting, moving=bool(s.shaft != s.move_to))
                servos.append(d)
            return "ok " + json.dumps({"servos": servos})
        if words == ["power-cycle"]:
            for s in self.servos:
                s.update(now)
                s.power_up(now)
            return "ok"
        if words == ["flip"]:
            self.flip_next = True
            return "ok"
        if len(words) == 2 and words[0] == "count":
            return "ok %d" % self.counts.get(int(words[1]), 0)
        if len(words) == 2 and words[0] in ("add", "remove"):
            sid = int(words[1])
            if words[0] == "add":
                self.servos.append(Servo(sid, now, self.temp, self.vin))
            else:
                self.servos = [s for s in self.servos if s.id != sid]
            return "ok"
        if len(words) == 4 and words[0] == "set":
            targets = [s for s in self.servos if s.id == int(words[1])]
            if not targets:
                return "error no servo %s" % words[1]
            value = int(words[3])
            for s in targets:
                s.update(now)
                if words[2] == "pos":
                    if s.torque:
                        return "error servo %d holds its position (torque on)" % s.id
                    s.shaft = s.move_from = s.move_to = float(value)
                    s.move_time = 0
                elif words[2] == "temp":
                    s.temp = value
                    s.protect(now)
                elif words[2] == "vin":
                    s.vin = value
                    s.protect(now)
                else:
                    return "error unknown setting %s" % words[2]
            return "ok"
        return "error unknown command: %s" % line.strip()


class Decoder:
    """Byte at a time: 55 55 ID LEN CMD P.. CHK; resynchronises on a bad frame."""

    def __init__(self):
        self.buf = bytearray()

    def feed(self, data):
        self.buf += data
        frames = []
        while True:
            start = self.buf.find(b"\x55\x55")
            if start < 0:
                del self.buf[:max(0, len(self.buf) - 1)]
                return frames
            del self.buf[:start]
            if len(self.buf) < 4:
                return frames
            length = self.buf[3]
            if length < 3 or length > 7:
                del self.buf[:1]
                continue
            if len(self.buf) < length + 3:
                return frames
            raw = bytes(self.buf[:length + 3])
            body = raw[2:-1]
            cmd = raw[4]
            info = COMMANDS.get(cmd)
            if checksum(body) != raw[-1] or info is None or info[1] != length:
                del self.buf[:1]
                continue
            del self.buf[:length + 3]
            frames.append((raw[2], cmd, list(raw[5:-1])))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--link", required=True, help="the path to link to the bus's pseudo-terminal")
    ap.add_argument("--ids", default="1", help="the servos' ids: 1,2,5 or 1-6 (default 1)")
    ap.add_argument("--state", help="keep what survives power-off in this JSON file")
    ap.add_argument("--echo", action="store_true", help="write every received byte back first")
    ap.add_argument("--control", help="a UNIX socket for control commands")
    ap.add_argument("--watch-stdin", action="store_true", help="end when standard input closes")
    ap.add_argument("--temp", type=int, default=30, help="every servo's temperature (C)")
    ap.add_argument("--vin", type=int, default=7400, help="every servo's input voltage (mV)")
    args = ap.parse_args()

    bus = Bus(parse_ids(args.ids), args.state, args.temp, args.vin)
    master, slave = os.openpty()
    tty.setraw(slave)
    attrs = termios.tcgetattr(slave)
    attrs[4] = attrs[5] = termios.B115200
    termios.tcsetattr(slave, termios.TCSANOW, attrs)
    if os.path.lexists(args.link):
        os.unlink(args.link)
    os.symlink(os.ttyname(slave), args.link)

    control = None
    clients = {}
    if args.control:
        if os.path.exists(args.control):
            os.unlink(args.control)
        control = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        control.bind(args.control)
        control.listen(4)

    stop = []

    def end(*_):
        # (select is restarted after a handler that returns: PEP 475; so the
        # handler ends the loop itself, through the finally below)
        raise SystemExit(0)

    signal.signal(signal.SIGTERM, end)
    signal.signal(signal.SIGINT, end)
    print("ready " + args.link, flush=True)

    decoder = Decoder()
    try:
        while not stop:
            watch = [master] + list(clients)
            if control:
                watch.append(control)
            if args.watch_stdin:
                watch.append(sys.stdin)
            try:
                ready, _, _ = select.select(watch, [], [])
            except InterruptedError:
                continue
            for r in ready:
                if r is master:
                    data = os.read(master, 4096)
                    if args.echo:
                        os.write(master, data)
                    for servo_id, cmd, params in decoder.feed(data):
                        answer = bus.handle(servo_id, cmd, params)
                        if answer:
                            os.write(master, answer)
                elif r is control:
                    conn, _ = control.accept()
                    clients[conn] = b""
                elif r is sys.stdin:
                    if not os.read(sys.stdin.fileno(), 4096):
                        stop.append(1)
                else:
                    data = r.recv(4096)
                    if not data:
                        del clients[r]
                        r.close()
                        continue
                    clients[r] += data
                    while b"\n" in clients[r]:
                        line, clients[r] = clients[r].split(b"\n", 1)
                        try:
                            reply = bus.control(line.decode())
                        except (ValueError, IndexError) as e:
                            reply = "error %s" % e
                        r.sendall(reply.encode() + b"\n")
    finally:
        if os.path.islink(args.link):
            os.unlink(args.link)
        if args.control and os.path.exists(args.control):
            os.unlink(args.control)


if __name__ == "__main__":
    main()
