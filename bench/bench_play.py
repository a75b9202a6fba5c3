#!/usr/bin/env python3
"""Python keeps lscctl's schedule: a play and reads of six servos on lsc-sim
paced at 9600 baud, from Python (lsc.Controller.play with a progress
callback; Controller.read) and from C through the call lscctl play makes
(lsc_device_play with a callback: bench_device_play), and lscctl play itself,
in one run, through the build's liblsc.so.2.

For each play, a fresh lsc-sim (--log) on a pseudo-terminal:
- callback lateness: elapsed_ms - step.due_ms of every frame sent, as the
  library's callback gives it (whole ms; lscctl has no callback to ask);
- arrival lateness: when each move arrived at lsc-sim (its --log time stamps,
  microseconds) minus its due time, counted from the move that was least
  late (also for lscctl play).
Prints p50 / p99 / max of each, and Python's against C's.
Then COUNT reads of servos 1..6 from C and from Python on one lsc-sim
(alternating blocks): median and p99 of a read.

Usage: bench/bench_play.py BUILD_DIR [--keyframes N] [--every MS] [--lead MS]
                           [--rounds N] [--reads N] [--apart]
(The three plays of a round run at once, each on its own lsc-sim, so that
they meet the same moments of a busy machine; --apart: one after the other,
in an order that changes with each round.)
(BUILD_DIR: a CMake build with lsc_shared, lscctl, lsc-sim and
 bench_device_play, e.g.
 cmake -S . -B build/bench -DCMAKE_BUILD_TYPE=Release -DLSC_BUILD_TESTS=OFF
 cmake --build build/bench -j2 --target lsc_shared lscctl lsc-sim bench_device_play)
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
IDS = [1, 2, 3, 4, 5, 6]


def quantile(values, q):
    """The smallest value with at least q of the values at or below it."""
    v = sorted(values)
    k = max(1, min(len(v), int(q * len(v) + 0.999999)))
    return v[k - 1]


class Sim:
    """lsc-sim --link DIR/tty --log (paced at 9600 baud, its default)."""

    def __init__(self, lsc_sim, tmp, name):
        self.link = os.path.join(tmp, name)
        self.log = os.path.join(tmp, name + ".log")
        self.proc = subprocess.Popen([lsc_sim, "--link", self.link, "--log"],
                                     stdout=subprocess.DEVNULL, stderr=open(self.log, "w"))
        end = time.monotonic() + 30
        while not os.path.exists(self.link):
            if time.monotonic() > end or self.proc.poll() is not None:
                raise RuntimeError("lsc-sim did not make %s" % self.link)
            time.sleep(0.005)

    def stop(self):
        """Stops it; returns the times (s) of the moves it received."""
        self.proc.send_signal(signal.SIGTERM)
        self.proc.wait(timeout=30)
        moves = []
        with open(self.log) as f:
            for line in f:  # lsc-sim: T rx 55 55 LEN CMD ...
                p = line.split()
                if len(p) > 6 and p[2] == "rx" and p[6] == "03":
                    moves.append(float(p[1]))
        return moves


def arrival_lateness(moves, dues):
    """Each move's arrival minus its due time, in ms, counted from the
    earliest of them: a frame is never sent before its time, so the move
    that arrived soonest after its due time shows the schedule's start (plus
    the fixed cost of a write); the others are late by what they add to it."""
    if len(moves) != len(dues):
        raise RuntimeError("lsc-sim received %d moves, %d were sent" % (len(moves), len(dues)))
    offsets = [t * 1e3 - d for t, d in zip(moves, dues)]
    return [o - min(offsets) for o in offsets]


def main(argv):
    args = argv[1:]
    if not args or args[0].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    build = args[0]
    opts = {"--keyframes": 200, "--every": 50, "--lead": 500, "--rounds": 3, "--reads": 100}
    rest = args[1:]
    together = "--apart" not in rest
    rest = [a for a in rest if a != "--apart"]
    while rest:
        if rest[0] not in opts or len(rest) < 2 or not rest[1].isdigit():
            print(__doc__, file=sys.stderr)
            return 2
        opts[rest[0]] = int(rest[1])
        rest = rest[2:]
    keyframes, every, lead = opts["--keyframes"], opts["--every"], opts["--lead"]
    library = os.path.join(build, "src", "liblsc.so.2")
    os.environ["LSC_LIBRARY"] = library
    sys.path.insert(0, os.path.join(HERE, "..", "bindings", "python"))
    import lsc

    lscctl = os.path.join(build, "cli", "lscctl")
    lsc_sim = os.path.join(build, "cli", "lsc-sim")
    helper = os.path.join(build, "bench", "bench_device_play")
    tmp = tempfile.mkdtemp(prefix="bench_play.")
    try:
        # every keyframe moves all six servos (none is left out of a frame)
        action = lsc.Action(IDS, [(every, tuple(1000 + 100 * ((k + i) % 5) for i in range(6)))
                                  for k in range(keyframes)])
        csv = os.path.join(tmp, "play.csv")
        action.save(csv)
        late = {"C": [], "Python": []}            # callback: elapsed - due (ms)
        arrive = {"lscctl": [], "C": [], "Python": []}  # at lsc-sim (ms)
        # the schedule's due times: the same play on "sim" (its clock is virtual)
        out = subprocess.run([helper, "play", "sim", csv, str(lead)], check=True,
                             capture_output=True, text=True).stdout
        dues = [int(l.split()[1]) for l in out.splitlines()]

        # each starts a play and returns what ends it and takes its figures
        def play_c():
            """lsc_device_play with a callback (bench_device_play)."""
            sim = Sim(lsc_sim, tmp, "c")
            p = subprocess.Popen([helper, "play", sim.link, csv, str(lead)],
                                 stdout=subprocess.PIPE, text=True)

            def finish():
                out = p.communicate()[0]
                if p.returncode != 0:
                    raise RuntimeError("bench_device_play exited %d" % p.returncode)
                steps = [tuple(float(x) for x in l.split()[1:]) for l in out.splitlines()]
                late["C"].extend(s[1] - s[0] for s in steps)
                arrive["C"].extend(arrival_lateness(sim.stop(), [int(s[0]) for s in steps]))
            return finish

        def play_lscctl():
            """lscctl play (no callback: only its frames' arrival)."""
            sim = Sim(lsc_sim, tmp, "lscctl")
            p = subprocess.Popen([lscctl, "--port", sim.link, "play", csv, "--lead", str(lead)])

            def finish():
                if p.wait() != 0:
                    raise RuntimeError("lscctl play exited %d" % p.returncode)
                arrive["lscctl"].extend(arrival_lateness(sim.stop(), dues))
            return finish

        def play_python():
            """Controller.play with a progress callback (here, in this process)."""
            sim = Sim(lsc_sim, tmp, "py")
            got = []

            def progress(step, elapsed):
                if step is not None:
                    got.append((step.due_ms, elapsed))

            with lsc.open(sim.link) as c:
                c.play(lsc.Action.load(csv), lead_ms=lead, progress=progress)

            def finish():
                late["Python"].extend(e - d for d, e in got)
                arrive["Python"].extend(arrival_lateness(sim.stop(), [d for d, _ in got]))
            return finish

        for r in range(opts["--rounds"]):
            if together:
                # the three at once (each on its own lsc-sim): the same moments of the machine
                finishes = [play_c(), play_lscctl()]
                finishes.append(play_python())
                for f in finishes:
                    f()
            else:
                # one after the other, each round in another order
                for play in [(play_c, play_python, play_lscctl),
                             (play_python, play_lscctl, play_c),
                             (play_lscctl, play_c, play_python)][r % 3]:
                    play()()

        # reads of six servos: C and Python in turn, on one lsc-sim
        sim = Sim(lsc_sim, tmp, "read")
        reads = {"C": [], "Python": []}
        for _ in range(2):
            out = subprocess.run([helper, "read", sim.link, str(opts["--reads"] // 2)],
                                 check=True, capture_output=True, text=True).stdout
            reads["C"] += [float(l.split()[1]) / 1e3 for l in out.splitlines()]
            with lsc.open(sim.link) as c:
                for _ in range(opts["--reads"] // 2):
                    t0 = time.perf_counter()
                    c.read(IDS)
                    reads["Python"].append((time.perf_counter() - t0) * 1e3)
        sim.stop()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    print("host: %s, %d cores, load average %s; Python %s" % (
        os.uname().machine, os.cpu_count(), " ".join(open("/proc/loadavg").read().split()[:3]),
        sys.version.split()[0]))
    print("library: %s; lsc-sim at 9600 baud; %d keyframes of 6 servos every %d ms, lead %d ms, "
          "%d play(s) each, %s" % (library, keyframes, every, lead, opts["--rounds"],
                                   "at once" if together else "one after the other"))
    print("keyframe lateness (ms)           callback: elapsed - due     at lsc-sim: arrival - due")
    print("%-32s %7s %7s %7s     %7s %7s %7s" % ("", "p50", "p99", "max", "p50", "p99", "max"))
    for who, what in (("lscctl", "lscctl play"), ("C", "C, lsc_device_play"),
                      ("Python", "Python, Controller.play")):
        cb = late.get(who)
        row = ("%7.0f %7.0f %7.0f" % (quantile(cb, .5), quantile(cb, .99), max(cb))) if cb else \
            "%7s %7s %7s" % ("-", "-", "-")
        a = arrive[who]
        print("%-32s %s     %7.3f %7.3f %7.3f" % (what, row, quantile(a, .5), quantile(a, .99), max(a)))
    d_cb = quantile(late["Python"], .99) - quantile(late["C"], .99)
    d_ar = quantile(arrive["Python"], .99) - quantile(arrive["C"], .99)
    d_ctl = quantile(arrive["Python"], .99) - quantile(arrive["lscctl"], .99)
    def verdict(d):
        return "met" if d <= 1.0 else "MISSED"
    print("%-32s %7s %7.0f %7s     %7s %7.3f %7s   target <= 1 ms: %s, %s" % (
        "Python - C, p99", "", d_cb, "", "", d_ar, "", verdict(d_cb), verdict(d_ar)))
    print("%-32s %7s %7s %7s     %7s %7.3f %7s   target <= 1 ms: %s" % (
        "Python - lscctl, p99", "", "", "", "", d_ctl, "", verdict(d_ctl)))
    print("read of servos 1..6 (ms)         median     p99  (%d each)" % len(reads["C"]))
    for who in ("C", "Python"):
        r = reads[who]
        print("%-32s %7.3f %7.3f" % (who, quantile(r, .5), quantile(r, .99)))
    print("%-32s %7.3f %7.3f" % ("Python - C", quantile(reads["Python"], .5) - quantile(reads["C"], .5),
                                 quantile(reads["Python"], .99) - quantile(reads["C"], .99)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
