#!/usr/bin/env python3
"""The bulking of a deposit: its area now over its area before it moved.

Reads the last particle output of each run directory (or the one nearest
--time) and prints, for all points of the run: their area before they
moved (the sum of the reference volumes V0, per unit thickness in 2D),
their area now (the sum of V0 det F), the ratio of the two (the bulking),
the largest det F, the extent of the deposit (largest x and y of a point),
where its mass lies (the centroid of V0 along x, and the x left of which
95 and 99 % of V0 lie: tools/deposit_measures.py; unlike the largest x
they do not grow with a thin front that a finer run resolves) and how the
run ended (summary.json).

--moved D takes only the points displaced more than D metres (a cliff's
failed mass, as its diagnostics count it with D = 0.5). The table also
gives the share of the area gained (sum of V0 (det F - 1)) held by points
with det F > 1.5.

--output PNG draws the deposits one above the other, each point coloured
by its det F (the area it gained), on the axes --xlim, --ylim.

Used for the fully damaged chalk column (prm/joss_bay/debris_column/,
doc/joss_bay/weak_damping.md, "The debris of fully damaged chalk").

Example:
  debris_bulking.py output/debris_column/h0.24 output/debris_column/h0.12
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import particle_outputs, read_particles  # noqa: E402
from deposit_measures import mass_centroid_x, mass_quantile_x  # noqa: E402
from run_summary import read_summary  # noqa: E402


def pick_output(directory, time):
    records = particle_outputs(directory)
    if time is None:
        return records[-1]
    return min(records, key=lambda r: abs(r[0] - time))


def measure(pvtu, moved):
    p = read_particles(pvtu)
    if moved is not None:
        keep = [i for i in range(len(p["x"])) if math.hypot(
            p["x"][i] - p["reference_position_0"][i],
            p["y"][i] - p["reference_position_1"][i]) > moved]
        p = {k: [v[i] for i in keep] for k, v in p.items()}
        if not keep:
            sys.exit(f"{pvtu}: no point moved more than {moved} m")
    if "F_00" not in p:
        sys.exit(f"{pvtu}: no deformation gradient (F_00 ...) in the output")
    if "F_22" in p:
        sys.exit(f"{pvtu}: 3D output; this tool reads 2D runs")
    js = [p["F_00"][i] * p["F_11"][i] - p["F_01"][i] * p["F_10"][i]
          for i in range(len(p["x"]))]
    before = now = gained_inflated = 0.
    largest_j = 0.
    for j, v0 in zip(js, p["reference_volume"]):
        before += v0
        now += v0 * j
        largest_j = max(largest_j, j)
        if j > 1.5:
            gained_inflated += v0 * (j - 1)
    gained = now - before
    return {"points": len(p["x"]), "before": before, "now": now,
            "inflated_share": gained_inflated / gained if gained > 0 else 0,
            "largest_j": largest_j, "x_max": max(p["x"]),
            "y_max": max(p["y"]),
            "x_centroid": mass_centroid_x(p["x"], p["reference_volume"]),
            "x_95": mass_quantile_x(p["x"], p["reference_volume"], 0.95),
            "x_99": mass_quantile_x(p["x"], p["reference_volume"], 0.99),
            "x": p["x"], "y": p["y"], "j": js,
            "v0": p["reference_volume"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="DIR")
    parser.add_argument("--time", type=float, default=None,
                        help="the output nearest this time instead of the "
                        "last")
    parser.add_argument("--moved", type=float, default=None, metavar="D",
                        help="only the points displaced more than D m")
    parser.add_argument("--output", default=None, metavar="PNG",
                        help="draw the deposits, coloured by det F")
    parser.add_argument("--xlim", type=float, nargs=2, default=(0, 7))
    parser.add_argument("--ylim", type=float, nargs=2, default=(0, 3))
    args = parser.parse_args()
    drawn = []
    print("| run | output at t | ended | points | area before, now [m^2] | "
          "bulking | largest det F | area gained in det F > 1.5 | "
          "deposit to x, top y [m] | mass centroid x, 95 and 99 % of the "
          "mass left of x [m] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for directory in args.runs:
        t, pvtu = pick_output(directory, args.time)
        m = measure(pvtu, args.moved)
        ended = "?"
        # A run still under way has no summary: its outputs are measured all
        # the same.
        summary = read_summary(directory, required=False)
        stages = (summary or {}).get("stages", {})
        if stages:
            ended = list(stages.values())[-1].get("end_reason", "?")
        print(f"| {directory} | {t:.2f} s | {ended} | {m['points']} | "
              f"{m['before']:.3f}, {m['now']:.3f} | "
              f"{m['now'] / m['before']:.3f} | {m['largest_j']:.2f} | "
              f"{100 * m['inflated_share']:.0f} % | "
              f"{m['x_max']:.2f}, {m['y_max']:.2f} | "
              f"{m['x_centroid']:.3f}, {m['x_95']:.2f}, {m['x_99']:.2f} |")
        drawn.append((directory, t, m))
    if args.output:
        draw(drawn, args)


def draw(drawn, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(drawn), 1, squeeze=False,
                             figsize=(10, 2.8 * len(drawn)))
    for ax, (directory, t, m) in zip(axes[:, 0], drawn):
        ax.set_xlim(*args.xlim)
        ax.set_ylim(*args.ylim)
        ax.set_aspect("equal")
        # Each point a square of its reference area (1.5 times, so that
        # neighbours overlap instead of leaving raster seams).
        box = ax.get_window_extent()
        points_per_m = 72. / fig.dpi * min(
            box.width / (args.xlim[1] - args.xlim[0]),
            box.height / (args.ylim[1] - args.ylim[0]))
        sizes = [1.5 * (points_per_m * math.sqrt(v)) ** 2 for v in m["v0"]]
        shown = ax.scatter(m["x"], m["y"], c=m["j"], s=sizes, marker="s",
                           linewidths=0, vmin=0.9, vmax=1.5, cmap="coolwarm")
        fig.colorbar(shown, ax=ax, label="det F")
        ax.set_title(f"{directory}, t = {t:.2f} s: bulking "
                     f"{m['now'] / m['before']:.3f}", fontsize=9)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
