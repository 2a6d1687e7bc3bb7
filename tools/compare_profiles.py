#!/usr/bin/python3
"""Compare the final surface profiles of cliff runs run to rest.

Reads cliff_profile.csv of each run directory (written at the end of a
cliff run: optional "# name = value" lines with the diagnostics, then the
columns x, y_initial, y_final, one row per bin), draws the final free
surfaces over the initial one of the first run, and prints a table of the
diagnostics (debris angle, run-out, failed area, scarp retreat, failure
onset) of every run with the change from the run before it.

Uses the Debian package python3-matplotlib, hence /usr/bin/python3.

Example:
  compare_profiles.py --output profiles.png \\
      "L1=output/joss_bay_refined/L1_rg5e-3_seeded_ui10" \\
      "L2=output/joss_bay_refined/L2_rg5e-3_seeded_ui10"
"""

import argparse
import csv
import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

QUANTITIES = [
    ("debris_angle_deg", "debris angle [deg]"),
    ("run_out_m", "run-out [m]"),
    ("failed_area_m2", "failed area [m^2]"),
    ("scarp_retreat_m", "scarp retreat [m]"),
    ("failure_onset_s", "failure onset [s]"),
]


def read_profile(path):
    """Rows (x, y_initial, y_final) of a cliff_profile.csv."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = list(csv.DictReader(lines))
    x = [float(r["x"]) for r in rows]
    y0 = [float(r["y_initial"]) for r in rows]
    y1 = [float(r["y_final"]) for r in rows]
    return x, y0, y1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output", required=True, help="PNG to write")
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    args = parser.parse_args()

    runs = []
    for item in args.runs:
        label, directory = item.split("=", 1)
        summary = json.load(open(f"{directory}/summary.json"))
        runs.append((label, directory, summary.get("cliff", {})))

    header = "| quantity | " + " | ".join(label for label, _, _ in runs) + " |"
    print(header)
    print("|---" * (len(runs) + 1) + "|")
    for key, name in QUANTITIES:
        cells = []
        previous = None
        for _, _, cliff in runs:
            value = cliff.get(key)
            value = math.nan if value is None else value
            text = f"{value:.2f}"
            if previous is not None and math.isfinite(previous):
                text += f" ({value - previous:+.2f})"
            cells.append(text)
            previous = value
        print(f"| {name} | " + " | ".join(cells) + " |")

    fig, ax = plt.subplots(figsize=(10, 4))
    for k, (label, directory, cliff) in enumerate(runs):
        x, y0, y1 = read_profile(f"{directory}/cliff_profile.csv")
        if k == 0:
            ax.plot(x, y0, color="0.6", lw=1, label="initial surface")
        angle = cliff.get("debris_angle_deg") or math.nan
        ax.plot(x, y1, lw=1.5, label=f"{label}: final ({angle:.1f} deg)")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal")
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
