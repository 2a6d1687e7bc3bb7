#!/usr/bin/python3
"""Draw the material points of several runs side by side, at the same time
after each run's failure onset: one row per run, damage on the left, speed
on the right.

Runs of different resolutions fail at different times; comparing them at
equal time after their onsets shows which of them is ahead. Each run
directory needs its particles.pvd (the particle VTU outputs) and its
summary.json (the collapse stage's start and the failure onset, written
also while a run is in progress or was stopped). For each run the particle
output nearest to the asked time is drawn; "end" takes the run's last
output. Prints, per run, the output used, its time after the onset, its
kinetic energy and the points faster than --fast.

With --bands X1,X2,... it also prints where the kinetic energy is: its
share in the bands of x between the edges, and how much of it is on fully
damaged points (d >= 0.99).

Uses the Debian package python3-matplotlib, hence /usr/bin/python3.

Example:
  plot_snapshots.py --output snapshots.png --xlim 10 45 --ylim -2 17 \\
      "L2=output/joss_bay_refined/L2_rg5e-3_seeded_ui10_pts_cfl1.0@10.7" \\
      "L2 at rest=output/joss_bay_refined/L2_rg5e-3_seeded_ui10_pts_cfl1.0@end" \\
      "L3=output/joss_bay_refined/L3_rg5e-3_seeded_ui10_pts_cfl1.0@10.7"
"""

import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import particle_outputs, read_particles  # noqa: E402
from run_summary import onset_time  # noqa: E402


def parse_run(text):
    if "=" not in text or "@" not in text:
        sys.exit(f"'{text}': expected LABEL=DIR@T (T seconds after the "
                 "onset, or 'end')")
    label, rest = text.split("=", 1)
    directory, when = rest.rsplit("@", 1)
    if when != "end":
        try:
            when = float(when)
        except ValueError:
            sys.exit(f"'{text}': T must be a number of seconds or 'end'")
    return label, directory, when


def band_energies(p, speed, edges):
    """Kinetic energy of the points in each band of x (edges ascending), and
    of the fully damaged ones among them: [(name, energy, damaged)]."""
    names = ([f"x < {edges[0]:g} m"]
             + [f"{a:g} <= x < {b:g} m" for a, b in zip(edges, edges[1:])]
             + [f"{edges[-1]:g} m <= x"])
    energy = [0.] * (len(edges) + 1)
    damaged = [0.] * (len(edges) + 1)
    for x, m, v, d in zip(p["x"], p["mass"], speed, p["damage"]):
        band = sum(1 for e in edges if x >= e)
        e = 0.5 * m * v * v
        energy[band] += e
        if d >= 0.99:
            damaged[band] += e
    return list(zip(names, energy, damaged))


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR@T")
    parser.add_argument("--output", required=True, help="PNG to write")
    parser.add_argument("--xlim", type=float, nargs=2, default=None)
    parser.add_argument("--ylim", type=float, nargs=2, default=None)
    parser.add_argument("--speed-max", type=float, default=2.0,
                        help="top of the speed colour scale, m/s")
    parser.add_argument("--fast", type=float, default=0.5,
                        help="speed counted as moving, m/s")
    parser.add_argument("--marker-size", type=float, default=1.5,
                        help="marker area in units of a point's own area")
    parser.add_argument("--dpi", type=int, default=100)
    parser.add_argument("--bands", default=None, metavar="X1,X2,...",
                        help="also print where the kinetic energy is: its "
                             "share in the bands of x between these edges "
                             "(m), and on fully damaged points (d >= 0.99)")
    args = parser.parse_args()
    edges = []
    if args.bands:
        try:
            edges = sorted(float(x) for x in args.bands.split(","))
        except ValueError:
            sys.exit(f"--bands '{args.bands}': expected numbers separated "
                     "by commas")

    runs = [parse_run(r) for r in args.runs]
    band_rows = []
    fig, axes = plt.subplots(len(runs), 2, figsize=(14, 4.2 * len(runs)),
                             squeeze=False)
    print("| run | output | t | after the onset | kinetic energy | "
          f"points faster than {args.fast} m/s (of all) |")
    print("|---|---|---|---|---|---|")
    for row, (label, directory, when) in enumerate(runs):
        onset = onset_time(directory)
        records = particle_outputs(directory)
        if when == "end":
            t, pvtu = records[-1]
        else:
            t, pvtu = min(records, key=lambda r: abs(r[0] - onset - when))
        p = read_particles(pvtu)
        speed = [math.hypot(a, b)
                 for a, b in zip(p["velocity_0"], p["velocity_1"])]
        kinetic = sum(0.5 * m * s * s for m, s in zip(p["mass"], speed))
        n_fast = sum(1 for s in speed if s > args.fast)
        print(f"| {label} | {os.path.basename(pvtu)} | {t:.2f} s | "
              f"{t - onset:.2f} s | {kinetic:.3g} J | "
              f"{n_fast} ({len(speed)}) |")
        if edges:
            band_rows.append((label, band_energies(p, speed, edges), kinetic))
        title = f"{label}: t = {t:.2f} s, {t - onset:.2f} s after the onset"
        panels = [(p["damage"], 1.0, "viridis", "damage"),
                  (speed, args.speed_max, "magma", "speed, m/s")]
        for col, (values, top, cmap, name) in enumerate(panels):
            ax = axes[row][col]
            ax.set_aspect("equal")
            if args.xlim:
                ax.set_xlim(*args.xlim)
            if args.ylim:
                ax.set_ylim(*args.ylim)
            # Each point a square of its reference area (times
            # --marker-size, 1.5 so that squares overlap instead of leaving
            # raster seams), so that coarse and fine runs look alike;
            # dilated debris shows its gaps.
            box = ax.get_window_extent()
            x0, x1 = args.xlim if args.xlim else (min(p["x"]), max(p["x"]))
            y0, y1 = args.ylim if args.ylim else (min(p["y"]), max(p["y"]))
            # A row or column of points spans nothing in one direction:
            # the other one sets the scale.
            spans = [(box.width, x1 - x0), (box.height, y1 - y0)]
            scales = [w / s for w, s in spans if s > 0] or [box.width]
            points_per_m = 72. / fig.dpi * min(scales)
            sizes = [args.marker_size * (points_per_m * math.sqrt(v)) ** 2
                     for v in p["reference_volume"]]
            drawn = ax.scatter(p["x"], p["y"], c=values, s=sizes, marker="s",
                               vmin=0,
                               vmax=top, cmap=cmap, linewidths=0)
            fig.colorbar(drawn, ax=ax, label=name, shrink=0.8)
            ax.set_title(f"{title} ({name})", fontsize=9)
            ax.set_xlabel("x (m)")
            ax.set_ylabel("y (m)")
    if edges:
        print()
        print("| run | band | kinetic energy | share | of it on fully damaged "
              "points (d >= 0.99) |")
        print("|---|---|---|---|---|")
        for label, bands, kinetic in band_rows:
            for name, energy, damaged in bands:
                share = 100. * energy / kinetic if kinetic > 0 else 0.
                print(f"| {label} | {name} | {energy:.3g} J | {share:.1f} % | "
                      f"{damaged:.3g} J |")
    fig.tight_layout()
    fig.savefig(args.output, dpi=args.dpi)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
