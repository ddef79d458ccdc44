#!/usr/bin/env python3
"""Relations (Freiburg benchmark format, "t1 t2 x y 0 0 0 yaw") from a reference trajectory.

Usage: relations-from-reference.py REFERENCE OUT [--revisit-travel M] [--revisit-seconds S]
                                   [--travel M]

REFERENCE is a trajectory file "timestamp x y theta" (atlas-replay's reference.tsv).
Revisits: for a pose, the nearest earlier pose at most 1.5 m away with at least
--revisit-travel metres of travel (default 20) and --revisit-seconds seconds (default 0)
between them; at most one pair per 5 poses. These are where the robot returns.
With --travel M, also one pair per pose M metres of travel apart (local relations), written
before the revisits. Used by eval-corrected.sh and eval-kinds.sh.
"""
import argparse
import math


def relation(a, b):
    ta, xa, ya, tha = a
    tb, xb, yb, thb = b
    c, s = math.cos(tha), math.sin(tha)
    dth = (thb - tha + math.pi) % (2 * math.pi) - math.pi
    return "%.6f %.6f %.6f %.6f 0 0 0 %.6f\n" % (
        ta, tb, c * (xb - xa) + s * (yb - ya), -s * (xb - xa) + c * (yb - ya), dth)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("reference")
    p.add_argument("out")
    p.add_argument("--revisit-travel", type=float, default=20.0)
    p.add_argument("--revisit-seconds", type=float, default=0.0)
    p.add_argument("--travel", type=float, default=0.0)
    a = p.parse_args()
    ref = [tuple(map(float, l.split()[:4])) for l in open(a.reference)
           if l.strip() and not l.startswith("#")]
    travel = [0.0]
    for u, v in zip(ref, ref[1:]):
        travel.append(travel[-1] + math.hypot(v[1] - u[1], v[2] - u[2]))
    with open(a.out, "w") as out:
        if a.travel > 0:
            j = 0
            for i in range(len(ref)):
                while j < len(ref) and travel[j] - travel[i] < a.travel:
                    j += 1
                if j == len(ref):
                    break
                out.write(relation(ref[i], ref[j]))
        last = -5
        for i, (t, x, y, th) in enumerate(ref):
            if i - last < 5:
                continue
            best = None
            for j in range(i):
                if travel[i] - travel[j] < a.revisit_travel or t - ref[j][0] < a.revisit_seconds:
                    break
                d = math.hypot(ref[j][1] - x, ref[j][2] - y)
                if d < 1.5 and (best is None or d < best[0]):
                    best = (d, j)
            if best is None:
                continue
            out.write(relation(ref[best[1]], ref[i]))
            last = i


main()
