#!/usr/bin/env python3
"""Print and draw the cliff diagnostics of runs over time.

Reads cliff_history.csv of each run directory (one row per particle output:
the debris angle, run-out, failed areas and scarp retreat of that state,
where the failed mass lies (when every run's history has it), with the
kinetic energy; doc/scenes.md, "History") and prints a table of
them, with the change of each quantity over the last --window seconds of
the history: when those changes are small, the deposit has settled,
whatever the kinetic energy still does. With --output, draws the
quantities against time (one panel per quantity, the runs together).

Example:
  plot_cliff_history.py --output history.png \\
      "L3 0.06 m=output/joss_bay_refined/L3_rg1e-2_seeded_ui10"
"""

import argparse
import csv
import math
import os

QUANTITIES = [("kinetic_energy", "kinetic energy [J]"),
              ("debris_angle", "debris angle [deg]"),
              ("run_out", "run-out [m]"),
              ("failed_area", "failed area [m^2]"),
              ("failed_reference_area", "failed area before it moved [m^2]"),
              ("scarp_retreat", "scarp retreat [m]")]
# Where the failed mass lies; histories begun before 2026-12-07 lack them,
# and they are printed and drawn only when every run has them.
MASS_QUANTITIES = [("failed_mass_centroid", "failed mass centroid x [m]"),
                   ("failed_mass_x95", "95 % of the failed mass left of x [m]"),
                   ("failed_mass_x99", "99 % of the failed mass left of x [m]")]


def read_history(directory):
    """The rows of DIR/cliff_history.csv as dicts of floats."""
    path = os.path.join(directory, "cliff_history.csv")
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()}
                for row in csv.DictReader(f)]


def change_over(rows, name, window):
    """Largest minus smallest value of @name over the rows of the last
    @window seconds (nan if fewer than two rows lie in it). Outputs fall
    up to a time step after their nominal times: a row counts if it lies
    within the window widened by 1 % of it."""
    end = rows[-1]["time"]
    values = [r[name] for r in rows
              if r["time"] >= end - 1.01 * window and not math.isnan(r[name])]
    if len(values) < 2:
        return math.nan
    return max(values) - min(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--window", type=float, default=1.0,
                        help="seconds at the end of each history over which "
                        "the change of each quantity is printed")
    parser.add_argument("--from-time", type=float, default=0.0,
                        help="print and draw rows from this time on [s]")
    parser.add_argument("--output", help="PNG of the quantities over time")
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    args = parser.parse_args()

    runs = []
    for item in args.runs:
        label, directory = item.rsplit("=", 1)  # labels may hold "="
        rows = [r for r in read_history(directory)
                if r["time"] >= args.from_time - 1e-9]
        if not rows:
            parser.error(f"{directory}: no rows from t = {args.from_time} s")
        runs.append((label, rows))

    quantities = QUANTITIES + (
        MASS_QUANTITIES if all(name in rows[0] for _, rows in runs
                               for name, _ in MASS_QUANTITIES) else [])
    for label, rows in runs:
        print(f"{label}:")
        print("| t [s] | " + " | ".join(t for _, t in quantities) + " |")
        print("|---" * (len(quantities) + 1) + "|")
        for r in rows:
            print(f"| {r['time']:.3f} | " + " | ".join(
                f"{r[name]:.4g}" for name, _ in quantities) + " |")
        print(f"| change over the last {args.window:g} s | " + " | ".join(
            f"{change_over(rows, name, args.window):.3g}"
            for name, _ in quantities) + " |")
        print()

    if args.output:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        n_rows = (len(quantities) + 2) // 3
        fig, axes = plt.subplots(n_rows, 3, figsize=(13, 3.25 * n_rows),
                                 constrained_layout=True, dpi=100)
        for ax, (name, title) in zip(axes.flat, quantities):
            for label, rows in runs:
                ax.plot([r["time"] for r in rows], [r[name] for r in rows],
                        marker="o", markersize=3, label=label)
            ax.set_title(title)
            ax.set_xlabel("t [s]")
            if name == "kinetic_energy":
                ax.set_yscale("log")
            ax.grid(True, alpha=0.3)
        axes.flat[0].legend()
        fig.savefig(args.output)
        print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
