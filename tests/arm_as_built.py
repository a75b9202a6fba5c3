#!/usr/bin/env python3
"""The xArm of the calibration tests as its owner assembled it: the zeros of
base, shoulder, elbow, wrist and wrist roll off by +23, -17, +30, -12 and +5
positions, the elbow's servo mounted the other way round, as a profile (the
shipped one with those settings). Moves through it put lsc-sim's servos
where that arm's would be.

Usage: arm_as_built.py SHIPPED_PROFILE OUT (or write_profile() from Python)."""
import sys

BUILT = {"base": "offset=23", "shoulder": "offset=-17", "elbow": "dir=-1 offset=30",
         "wrist": "offset=-12", "wrist-rotate": "offset=5"}


def write_profile(shipped, out):
    lines = []
    with open(shipped) as f:
        for line in f.read().splitlines():
            w = line.split()
            if w and w[0] in BUILT:
                line = " ".join(w[:3] + [BUILT[w[0]]] + w[3:])
            lines.append(line)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    return out


if __name__ == "__main__":
    write_profile(sys.argv[1], sys.argv[2])
