#!/usr/bin/env python3
"""How much of a deposit's area its most dilated points hold.

Reads the particle output of each run directory nearest --time (the last
one without it) and prints, for the points whose det F exceeds each of
--thresholds: their number, their mass (per unit thickness in 2D) and
the area they cover now (the sum of V0 det F), beside the totals of all
points. A tension-free damaged material lets a few light points dilate
without bound; this table says how much of the bulking they carry.

Example (doc/joss_bay/weak_damping.md, "Splitting the stretched points"):
  dilation_classes.py --time 9.5 "L3=output/joss_bay_refined/L3_..." \\
      "L3 split=output/joss_bay_refined/L3_..._split"
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import particle_outputs, read_particles  # noqa: E402


def classes(p, thresholds):
    """(threshold, count, mass, area now) per threshold; threshold None
    is all points."""
    jacobians = [a * d - b * c for a, b, c, d in
                 zip(p["F_00"], p["F_01"], p["F_10"], p["F_11"])]
    rows = []
    for threshold in [None] + thresholds:
        count, mass, area = 0, 0.0, 0.0
        for j, m, v0 in zip(jacobians, p["mass"], p["reference_volume"]):
            if threshold is None or j > threshold:
                count += 1
                mass += m
                area += v0 * j
        rows.append((threshold, count, mass, area))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    parser.add_argument("--time", type=float, default=None,
                        help="the output nearest this time [s]")
    parser.add_argument("--thresholds", default="10,100,1000,10000",
                        help="det F thresholds, comma-separated")
    args = parser.parse_args()
    thresholds = [float(t) for t in args.thresholds.split(",")]
    print("| run | output at t | points with det F above | number | mass "
          "[kg/m] | area now [m^2] |")
    print("|---|---|---|---|---|---|")
    for item in args.runs:
        label, directory = item.rsplit("=", 1)
        outputs = particle_outputs(directory)
        if args.time is None:
            t, name = outputs[-1]
        else:
            t, name = min(outputs, key=lambda o: abs(o[0] - args.time))
        for threshold, count, mass, area in classes(read_particles(name),
                                                    thresholds):
            which = "(all)" if threshold is None else f"{threshold:g}"
            print(f"| {label} | {t:.2f} s | {which} | {count} | {mass:.1f} "
                  f"| {area:.1f} |")


if __name__ == "__main__":
    main()
