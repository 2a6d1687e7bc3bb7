#!/usr/bin/env python3
"""Failed areas of cliff runs from their last particles output.

For each run directory: the points displaced by more than --threshold
(0.5 m, the default of Cliff diagnostics/Displacement threshold) in the
last particles_NNNNN.pvtu, and the sums of their current volumes
(reference volume times det F: the failed area as it lies, dilated debris
included) and of their reference volumes (the failed area before it
moved). The first must equal the run's own failed_area_m2 when that output
is the run's last state (checked, to 1e-6 relative: the sums are the same,
only their order differs); the second is what runs made before scarp wrote
failed_reference_area_m2 lack. Prints a Markdown table.

Example:
  failed_areas.py "L1=output/joss_bay_refined/L1_rg1e-2_seeded_ui10"
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import last_output, read_particles  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    parser.add_argument("--threshold", type=float, default=0.5)
    args = parser.parse_args()

    print("| run | points | failed area [m^2] | before it moved [m^2] | ratio |")
    print("|---|---|---|---|---|")
    status = 0
    for item in args.runs:
        label, directory = item.rsplit("=", 1)  # labels may hold "="
        p = read_particles(last_output(directory))
        current = reference = 0.
        for i in range(len(p["x"])):
            dx = p["x"][i] - p["reference_position_0"][i]
            dy = p["y"][i] - p["reference_position_1"][i]
            if math.hypot(dx, dy) > args.threshold:
                J = p["F_00"][i] * p["F_11"][i] - p["F_01"][i] * p["F_10"][i]
                current += p["reference_volume"][i] * J
                reference += p["reference_volume"][i]
        print(f"| {label} | {len(p['x'])} | {current:.2f} | {reference:.2f} | "
              f"{current / reference if reference > 0 else math.nan:.3f} |")
        try:
            cliff = json.load(open(f"{directory}/summary.json"))["cliff"]
        except (OSError, KeyError):
            continue
        written = cliff.get("failed_area_m2")
        if written is not None and not abs(current - written) <= 1e-6 * max(
                abs(written), 1.):
            print(f"{label}: {current} m^2 from the last output, the run "
                  f"wrote {written} m^2 (is the last output its last state?)",
                  file=sys.stderr)
            status = 1
    sys.exit(status)


if __name__ == "__main__":
    main()
