#!/usr/bin/env python3
"""A Python call against the same call from C, in one run: battery() and a read
of six servos on the virtual controller ("sim"), through the build's
liblsc.so.2 (bench_device for C, the bindings of this tree for Python). Prints
the best of ROUNDS rounds of CALLS calls, in microseconds per call, and what
Python adds.

Usage: bench/bench_python.py BUILD_DIR [CALLS] [ROUNDS]
(BUILD_DIR: a CMake build with the targets lsc_shared and bench_device, e.g.
 cmake -S . -B build/bench -DCMAKE_BUILD_TYPE=Release -DLSC_BUILD_TESTS=OFF
 cmake --build build/bench -j2 --target lsc_shared bench_device)
"""
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    build = argv[1]
    calls = int(argv[2]) if len(argv) > 2 else 20000
    rounds = int(argv[3]) if len(argv) > 3 else 5
    library = os.path.join(build, "src", "liblsc.so.2")
    os.environ["LSC_LIBRARY"] = library
    sys.path.insert(0, os.path.join(HERE, "..", "bindings", "python"))
    import lsc

    out = subprocess.run([os.path.join(build, "bench", "bench_device"), str(calls), str(rounds)],
                         check=True, capture_output=True, text=True).stdout
    c = {k: float(v) for k, v in (line.split() for line in out.splitlines())}

    py = {"battery": 1e30, "read6": 1e30}
    ids = [1, 2, 3, 4, 5, 6]
    with lsc.open("sim") as ctl:
        battery, read = ctl.battery, ctl.read
        for _ in range(rounds):
            t0 = time.perf_counter()
            for _ in range(calls):
                battery()
            t1 = time.perf_counter()
            for _ in range(calls):
                read(ids)
            t2 = time.perf_counter()
            py["battery"] = min(py["battery"], (t1 - t0) * 1e6 / calls)
            py["read6"] = min(py["read6"], (t2 - t1) * 1e6 / calls)

    print("host: %s, %d cores, load average %s; Python %s" % (
        os.uname().machine, os.cpu_count(), " ".join(open("/proc/loadavg").read().split()[:3]),
        sys.version.split()[0]))
    print("library: %s; best of %d rounds of %d calls on \"sim\"" % (library, rounds, calls))
    print("%-24s %10s %10s %12s" % ("call", "C (us)", "Python (us)", "Python adds"))
    for name, what in (("battery", "battery()"), ("read6", "read([1..6])")):
        print("%-24s %10.2f %10.2f %12.2f" % (what, c[name], py[name], py[name] - c[name]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
