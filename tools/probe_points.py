#!/usr/bin/env python3
"""Prints fields of the material points nearest to given reference
positions, at every particles output of a run (the time from particles.pvd).

    python3 tools/probe_points.py output/run --at 10,15 10,13 \\
        --fields stress_xx stress_yy nonlocal_driver kappa

A point is found by its reference position (reference_position_0/1 in the
VTU), so the same piece of material is followed through the run even after
it moved; split points keep their parent's neighbourhood, so the nearest
one is a point of the same material.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import particle_outputs, read_particles  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="output directory of a run")
    parser.add_argument("--at", nargs="+", required=True,
                        help="reference positions x,y (m)")
    parser.add_argument("--fields", nargs="+", required=True,
                        help="VTU field names, e.g. stress_xx damage")
    parser.add_argument("--every", type=int, default=1,
                        help="use every n-th output (default 1)")
    args = parser.parse_args()
    probes = [tuple(float(c) for c in a.split(",")) for a in args.at]
    print("| t [s] | x0, y0 [m] | " + " | ".join(args.fields) + " |")
    print("|---" * (2 + len(args.fields)) + "|")
    for time, pvtu in particle_outputs(args.directory)[::args.every]:
        points = read_particles(pvtu)
        missing = [f for f in args.fields if f not in points]
        if missing:
            raise SystemExit("%s has no field %s (it has: %s)" %
                             (pvtu, ", ".join(missing),
                              ", ".join(sorted(points))))
        x0 = points["reference_position_0"]
        y0 = points["reference_position_1"]
        for px, py in probes:
            j = min(range(len(x0)),
                    key=lambda i: (x0[i] - px) ** 2 + (y0[i] - py) ** 2)
            values = " | ".join("%.4g" % points[f][j] for f in args.fields)
            print("| %.3f | %.2f, %.2f | %s |" % (time, x0[j], y0[j], values))


if __name__ == "__main__":
    main()
