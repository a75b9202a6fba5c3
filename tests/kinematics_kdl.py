#!/usr/bin/env python3
"""The kinematics against an independent oracle: Orocos KDL (python3-pykdl)
with the xArm's chain written by hand from nuro-arm's URDF
(dmklee/nuro-arm, nuro_arm/assets/urdf/xarm.urdf: the joints' origins and
axes, in mm). Targets are KDL's forward kinematics of random angles within
examples/arms/xarm.conf's limits; lsc.Arm.inverse, without a pitch, must
solve every one, put the grasp point within 0.01 mm of it by KDL's forward
kinematics of its answer, and never go beyond a limit (the profile's, and the
URDF's in radians).

    kinematics_kdl.py XARM_CONF [TARGETS]      (default 3000)

Exit 77 (a skip for ctest) when PyKDL is not installed; it is Debian's
python3-pykdl, for /usr/bin/python3."""
import math
import random
import sys
import time

try:
    import PyKDL as kdl
except ImportError:
    print("SKIP: python3-pykdl is not installed (apt-get install python3-pykdl): "
          "the comparison with KDL is skipped")
    sys.exit(77)

import lsc

# nuro-arm's xarm.urdf: joint name, axis, the next joint's origin from this
# one (mm). base_joint sits 47 mm above base_link; the grasp point is
# virtual_grasp_joint, 100 mm along the hand from wrist_rotation_joint.
URDF = [
    ("base", "z", 17.7),          # base_joint -> shoulder_joint
    ("shoulder", "y", 98.8),      # shoulder_joint -> elbow_joint
    ("elbow", "y", 94.7),         # elbow_joint -> wrist_joint
    ("wrist", "y", 58.8),         # wrist_joint -> wrist_rotation_joint
    ("wrist-rotate", "z", 100.0), # wrist_rotation_joint -> virtual_grasp_joint
]
BASE_MM = 47.0
# the URDF's <limit lower upper> (rad), the same order
URDF_LIMITS = [(-2.0, 2.0), (-1.58, 1.58), (-2.0, 2.0), (-1.8, 2.0), (-2.0, 2.0)]


def chain():
    c = kdl.Chain()
    c.addSegment(kdl.Segment(kdl.Joint(kdl.Joint.Fixed), kdl.Frame(kdl.Vector(0, 0, BASE_MM))))
    for _, axis, mm in URDF:
        kind = kdl.Joint.RotZ if axis == "z" else kdl.Joint.RotY
        c.addSegment(kdl.Segment(kdl.Joint(kind), kdl.Frame(kdl.Vector(0, 0, mm))))
    return c


def forward(solver, degrees):
    q = kdl.JntArray(len(degrees))
    for i, d in enumerate(degrees):
        q[i] = math.radians(d)
    f = kdl.Frame()
    solver.JntToCart(q, f)
    return f.p


def main():
    arm = lsc.Arm(sys.argv[1])
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 3000
    joints = [arm.joint(name) for name, _, _ in URDF]
    fk = kdl.ChainFkSolverPos_recursive(chain())
    rng = random.Random(41)
    worst, worst_limit, solved, spent = 0.0, 0.0, 0, 0.0
    for k in range(n):
        q = [rng.uniform(j.min_deg, j.max_deg) for j in joints]
        p = forward(fk, q)
        start = time.perf_counter()
        try:
            got = arm.inverse((p.x(), p.y(), p.z()))
        except lsc.Unreachable as e:
            print("FAIL: target %d %s (angles %s) refused: %s" % (k, [p.x(), p.y(), p.z()], q, e))
            continue
        spent += time.perf_counter() - start
        a = [got[name] for name, _, _ in URDF]
        back = forward(fk, a)
        d = math.dist((back.x(), back.y(), back.z()), (p.x(), p.y(), p.z()))
        worst = max(worst, d)
        for j, v, (lo, hi) in zip(joints, a, URDF_LIMITS):
            past = max(j.min_deg - v, v - j.max_deg, math.degrees(lo) - v,
                       v - math.degrees(hi))
            worst_limit = max(worst_limit, past)
        if d > 0.01:
            print("FAIL: target %d: the answer %s is %.4f mm off by KDL" % (k, a, d))
            continue
        solved += 1
    print("%d of %d targets solved without a pitch, the worst %.5f mm from the target by KDL's "
          "forward kinematics; beyond a limit by at most %.5f degrees (<= 0: never); %.1f us per "
          "lsc.Arm.inverse call from Python" % (solved, n, worst, worst_limit, spent / n * 1e6))
    return 0 if solved == n and worst_limit <= 0.0 else 1


if __name__ == "__main__":
    sys.exit(main())
