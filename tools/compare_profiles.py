#!/usr/bin/python3
"""Compare the final surface profiles of cliff runs run to rest.

Reads cliff_profile.csv of each run directory (written at the end of a
cliff run: optional "# name = value" lines with the diagnostics, then the
columns x, y_initial, y_final, one row per bin), draws the final free
surfaces over the initial one of the first run, and prints a table of the
diagnostics (debris angle, run-out, failed area, scarp retreat, failure
onset) of every run with the change from the run before it.

With three or more runs, given from the coarsest level to the finest, it
also judges the last three by the convergence criterion of the study
(doc/joss_bay.md): each quantity changes from the second to the third by
less than half its change from the first to the second, and the two finest
agree within 1.5 deg (debris angle), 0.5 m (run-out, scarp retreat) and
10 % (failure onset; the failed areas, current and before the points
moved, have the first test only; a quantity missing from a run's summary,
as the second area in older runs, is left out).

--particles-output draws the points at rest (cliff_end_particles.csv) of
each run side by side, one panel per run on the same axes, coloured by
damage, with the run's final surface over them.

Uses the Debian package python3-matplotlib, hence /usr/bin/python3.

Example:
  compare_profiles.py --output profiles.png \\
      "L1=output/joss_bay_refined/L1_rg5e-3_seeded_ui10" \\
      "L2=output/joss_bay_refined/L2_rg5e-3_seeded_ui10"
"""

import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_summary import read_summary  # noqa: E402

QUANTITIES = [
    ("debris_angle_deg", "debris angle [deg]"),
    ("run_out_m", "run-out [m]"),
    ("failed_area_m2", "failed area [m^2]"),
    ("failed_reference_area_m2", "failed area before it moved [m^2]"),
    ("scarp_retreat_m", "scarp retreat [m]"),
    ("failed_mass_centroid_x_m", "failed mass centroid x [m]"),
    ("mass_run_out_m", "run-out of 99 % of the failed mass [m]"),
    ("failure_onset_s", "failure onset [s]"),
]


# Largest difference allowed between the two finest levels: absolute, or
# relative to the finest level's value ("rel").
TOLERANCES = {
    "debris_angle_deg": (1.5, "abs"),
    "run_out_m": (0.5, "abs"),
    "scarp_retreat_m": (0.5, "abs"),
    # The study's 0.5 m for lengths.
    "failed_mass_centroid_x_m": (0.5, "abs"),
    "mass_run_out_m": (0.5, "abs"),
    "failure_onset_s": (0.10, "rel"),
}


def criterion(runs):
    """Print the second-change test and the tolerances for the last three
    runs; returns whether every quantity passes both."""
    (l1, _, c1), (l2, _, c2), (l3, _, c3) = runs[-3:]
    print()
    print(f"| criterion ({l1} -> {l2} -> {l3}) | change 1 | change 2 | "
          "|change 2| < |change 1| / 2 | finest two within | verdict |")
    print("|---|---|---|---|---|---|")
    converged = True
    for key, name in QUANTITIES:
        if any(key not in c for c in (c1, c2, c3)):
            # Summaries of older runs lack the newer quantities.
            print(f"| {name} | | | | | not in every run |")
            continue
        v1, v2, v3 = (c[key] for c in (c1, c2, c3))
        d1, d2 = v2 - v1, v3 - v2
        # No change at all between the two finest passes too.
        halves = abs(d2) < 0.5 * abs(d1) or d2 == 0
        tolerance = TOLERANCES.get(key)
        if tolerance is None:
            within, text = True, "(none)"
        else:
            limit, kind = tolerance
            allowed = limit * abs(v3) if kind == "rel" else limit
            within = abs(d2) <= allowed
            text = (f"{allowed:.2f} ({100 * limit:.0f} %): {within}"
                    if kind == "rel" else f"{allowed:.2f}: {within}")
        ok = halves and within
        converged = converged and ok
        print(f"| {name} | {d1:+.2f} | {d2:+.2f} | {halves} | {text} | "
              f"{'converged' if ok else 'not converged'} |")
    print(f"all quantities converged: {converged}")
    return converged


def read_profile(path):
    """Rows (x, y_initial, y_final) of a cliff_profile.csv (read by
    plot_cliff.read_profile, in the same directory)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import plot_cliff
    columns, _ = plot_cliff.read_profile(path)
    return columns["x"], columns["y_initial"], columns["y_final"]


def draw_particles(runs, filename, xlim=None):
    """One panel per run, stacked, on the same axes: the points at rest
    coloured by damage and the run's final surface."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from plot_cliff import read_particles  # same directory

    data = [(label, cliff, read_particles(f"{directory}/cliff_end_particles.csv"),
             read_profile(f"{directory}/cliff_profile.csv"))
            for label, directory, cliff in runs]
    x_range = xlim or (min(min(d[2][0]) for d in data),
                       max(max(d[2][0]) for d in data))
    y_range = (min(min(d[2][1]) for d in data) - 0.5,
               max(max(d[2][1]) for d in data) + 0.5)
    # Panels of the data's aspect ratio, about 7.5 inches wide (the
    # colour bar takes the rest of the 10).
    height = 7.5 * (y_range[1] - y_range[0]) / (x_range[1] - x_range[0])
    fig, axes = plt.subplots(len(runs), 1, sharex=True, sharey=True,
                             figsize=(10, (height + 0.4) * len(runs) + 0.5),
                             squeeze=False, layout="constrained")
    for ax, (label, cliff, (x, y, damage), (px, _, py)) in zip(axes[:, 0],
                                                                 data):
        # Marker area in points^2 shrinks with the number of points, so
        # that the finest run is not a solid blot, but stays visible for
        # the sparse points of dilated debris.
        size = max(0.3, min(1.0, 2.0e4 / max(len(x), 1)))
        image = ax.scatter(x, y, c=damage, s=size, cmap="viridis", vmin=0.,
                           vmax=1., linewidths=0, rasterized=True)
        ax.plot(px, py, color="k", lw=0.8, drawstyle="steps-mid")
        angle = cliff.get("debris_angle_deg") or math.nan
        ax.set_title(f"{label}: {len(x)} points, debris angle {angle:.1f} deg, "
                     f"run-out {cliff.get('run_out_m', math.nan):.2f} m",
                     fontsize=9)
        ax.set_aspect("equal")
        ax.set_ylabel("y [m]")
    axes[0, 0].set_xlim(*x_range)
    axes[0, 0].set_ylim(*y_range)
    axes[-1, 0].set_xlabel("x [m]")
    fig.colorbar(image, ax=axes[:, 0], label="damage", shrink=0.8)
    fig.savefig(filename, dpi=100)
    plt.close(fig)
    print(f"wrote {filename}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--output", required=True, help="PNG to write")
    parser.add_argument("--particles-output", metavar="PNG",
                        help="also draw each run's points at rest "
                        "(cliff_end_particles.csv), one panel per run")
    parser.add_argument("--xlim", type=float, nargs=2,
                        metavar=("XMIN", "XMAX"),
                        help="x range of the --particles-output panels")
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    args = parser.parse_args()

    runs = []
    for item in args.runs:
        label, directory = item.rsplit("=", 1)  # labels may hold "="
        summary = read_summary(directory)
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

    if len(runs) >= 3:
        criterion(runs)

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
    if args.particles_output:
        draw_particles(runs, args.particles_output, args.xlim)


if __name__ == "__main__":
    main()
