#!/usr/bin/python3
"""How the debris angle of cliff runs depends on the band of the fit.

The debris angle (doc/scenes.md, "Collapse diagnostics", item 5) is the
slope of a least-squares line through the final surface of the bins from
the pile summit to the debris toe whose height above the beach lies within
[0.1, 0.9] of the pile height. This tool refits that line from each run's
cliff_profile.csv for other bands (--bands) and prints one row per run, so
that a change of the angle between runs can be told apart from a change of
which part of a stepped deposit the band takes in. The first band given
must reproduce the angle the run wrote itself (checked; the default bands
start with 0.1-0.9). Nothing here changes the study's definition.

Example:
  debris_angle_bands.py "L1=output/joss_bay_refined/L1_rg1e-2_seeded_ui10" \\
                        "L2=output/joss_bay_refined/L2_rg1e-2_seeded_ui10"
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_cliff import read_profile  # noqa: E402  (same directory)


def fit_angle(x, y, summit, toe, beach, height, low, high):
    """Angle [deg] and number of bins of the fit over the band [low, high]
    of the pile height, as CliffDiagnostics fits it (bin centres from the
    summit to the toe)."""
    points = [(xi, yi) for xi, yi in zip(x, y)
              if summit - 1e-9 <= xi <= toe
              and low * height <= yi - beach <= high * height]
    if len(points) < 2:
        return math.nan, len(points)
    mx = sum(p[0] for p in points) / len(points)
    my = sum(p[1] for p in points) / len(points)
    sxx = sum((p[0] - mx) ** 2 for p in points)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in points)
    return math.degrees(math.atan(abs(sxy / sxx))), len(points)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    parser.add_argument("--bands", nargs="+",
                        default=["0.1-0.9", "0.2-0.8", "0.3-0.7",
                                 "0.1-0.5", "0.5-0.9"],
                        help="bands LOW-HIGH of the pile height")
    parser.add_argument("--beach", type=float, default=0.,
                        help="beach level [m] (Body/Cliff/Beach level)")
    args = parser.parse_args()
    bands = [tuple(float(v) for v in b.split("-")) for b in args.bands]

    print("| run | " + " | ".join(f"{lo:g}-{hi:g} of the pile height"
                                  for lo, hi in bands) + " |")
    print("|---" * (len(bands) + 1) + "|")
    status = 0
    for item in args.runs:
        label, directory = item.rsplit("=", 1)  # labels may hold "="
        columns, d = read_profile(f"{directory}/cliff_profile.csv")
        x, y = columns["x"], columns["y_final"]
        cells = []
        for k, (lo, hi) in enumerate(bands):
            angle, n = fit_angle(x, y, d["pile_summit"], d["debris_toe"],
                                 args.beach, d["pile_height"], lo, hi)
            cells.append(f"{angle:.1f} deg ({n} bins)")
            # The first band must give the run's own number: else this
            # tool does not fit what the code fits.
            if k == 0 and (lo, hi) == (0.1, 0.9) and not (
                    abs(angle - d["debris_angle"]) < 1e-6):
                print(f"{label}: 0.1-0.9 gives {angle} deg, the run wrote "
                      f"{d['debris_angle']} deg", file=sys.stderr)
                status = 1
        print(f"| {label} | " + " | ".join(cells) + " |")
    sys.exit(status)


if __name__ == "__main__":
    main()
