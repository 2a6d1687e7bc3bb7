#!/usr/bin/python3
"""Compare the failure surfaces of cliff runs at different resolutions.

Reads one cliff snapshot (x, y, damage, x0, y0, volume) of each run
directory — cliff_failure_particles.csv, written at the failure onset, by
default; --snapshot after_failure for the one written <Snapshot after
failure> seconds later — and, in the reference configuration:

* the failure surface x_f(y0): for each horizontal strip of height --strip,
  the smallest x0 of the damaged points (d >= --threshold, 0.99 by default;
  --criterion damage, the default: the band the block detaches along,
  pre-damaged crack included), or of the points that moved more than --moved metres
  (--criterion moved: the block seaward of it has detached; the cliff behind
  it moves elastically, by millimetres);
* the failed area: the volume of the points that moved more than --moved;
* the fully damaged area: the volume of the points with damage >= 0.99.

Prints a Markdown table (x_f at a few heights, failed and damaged areas, and
the RMS distance of each surface to the finest run's over the strips both
have, and from each run's summary.json its onset, size and cost) and, with
--output, draws the surfaces over the finest run's damage in one PNG.

Usage:
  compare_failure_surfaces.py [--output doc/figures/joss_bay/failure_surfaces.png] \\
      LABEL=DIR [LABEL=DIR ...]     (finest resolution last)
"""
import argparse
import csv
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_points(directory, snapshot):
    name = f"{directory}/cliff_{snapshot}_particles.csv"
    try:
        with open(name, newline="") as f:
            rows = list(csv.DictReader(line for line in f
                                       if not line.startswith("#")))
    except OSError as e:
        sys.exit(f"{name}: {e.strerror}; did the cliff fail (and, for "
                 "after_failure, was <Snapshot after failure> >= 0)?")
    return [{k: float(v) for k, v in r.items()} for r in rows]


def failure_surface(points, criterion, threshold, moved, strip, y_max):
    surface = {}
    for p in points:
        if criterion == "moved":
            if math.hypot(p["x"] - p["x0"], p["y"] - p["y0"]) <= moved:
                continue
        elif p["damage"] < threshold:
            continue
        k = int(p["y0"] // strip)
        if (k + 0.5) * strip > y_max:
            continue
        surface[k] = min(surface.get(k, math.inf), p["x0"])
    return surface


def summary_rows(items):
    """Rows from each run's summary.json: onset, cost, size."""
    summaries = []
    for item in items:
        directory = item.partition("=")[2]
        try:
            with open(f"{directory}/summary.json") as f:
                summaries.append(json.load(f))
        except (OSError, ValueError):
            summaries.append({})

    def row(name, get):
        cells = []
        for s in summaries:
            if not s:
                cells.append("-")  # no summary.json: nothing to say
                continue
            try:
                cells.append(get(s))
            except (KeyError, TypeError, ZeroDivisionError):
                cells.append("-")
        print(f"| {name} | " + " | ".join(cells) + " |")

    def collapse(s):
        return s["stages"]["collapse"]

    row("failure onset [s]",
        lambda s: f"{s['cliff']['failure_onset_s']:.2f}")
    row("mass scaling ends [s after the collapse starts]",
        lambda s: f"{collapse(s)['mass_scaling_end_time'] - collapse(s)['start_time']:.2f}"
        if collapse(s).get("mass_scaling_end_time", -1) >= 0 else "none")
    row("material points (end), cells",
        lambda s: f"{int(s['material_points'])}, {int(s['cells'])}")
    row("finest cell [m]",
        lambda s: f"{s['refinement']['finest_cell']:g}"
        if "refinement" in s else "uniform")
    row("steps", lambda s: f"{int(s['steps'])}")
    row("wall time [min]", lambda s: f"{s['wall_time'] / 60:.1f}")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    parser.add_argument("--snapshot", choices=["failure", "after_failure"],
                        default="failure",
                        help="which snapshot to compare (see above)")
    parser.add_argument("--criterion", choices=["damage", "moved"],
                        default="damage",
                        help="what marks a failed point (see above)")
    parser.add_argument("--threshold", type=float, default=0.99,
                        help="damage that marks a failed point")
    parser.add_argument("--moved", type=float, default=0.1,
                        help="displacement that marks a failed point [m]")
    parser.add_argument("--strip", type=float, default=0.5,
                        help="height of the strips [m]")
    parser.add_argument("--heights", type=float, nargs="+",
                        default=[1, 3, 5, 7, 9, 11, 13, 15],
                        help="heights of the table rows [m]")
    parser.add_argument("--output", default=None,
                        help="PNG to write (none: the table only)")
    args = parser.parse_args()

    runs = []
    for item in args.runs:
        label, _, directory = item.partition("=")
        if not directory:
            sys.exit(f"expected LABEL=DIR, got {item}")
        points = read_points(directory, args.snapshot)
        y_max = max(p["y0"] for p in points)
        runs.append((label, points,
                     failure_surface(points, args.criterion, args.threshold,
                                     args.moved, args.strip, y_max)))

    finest = runs[-1][2]
    header = "| y0 [m] | " + " | ".join(r[0] for r in runs) + " |"
    print(header)
    print("|" + "---|" * (len(runs) + 1))
    for y in args.heights:
        k = int(y // args.strip)
        cells = [f"{r[2][k]:.2f}" if k in r[2] else "-" for r in runs]
        print(f"| {y:g} | " + " | ".join(cells) + " |")
    failed = [sum(p["volume"] for p in r[1]
                  if math.hypot(p["x"] - p["x0"], p["y"] - p["y0"]) > args.moved)
              for r in runs]
    damaged = [sum(p["volume"] for p in r[1] if p["damage"] >= args.threshold)
               for r in runs]
    print("| failed area [m^2] | " + " | ".join(f"{a:.1f}" for a in failed) + " |")
    print(f"| d >= {args.threshold} area [m^2] | " + " | ".join(f"{a:.1f}" for a in damaged)
          + " |")
    rms = []
    for r in runs:
        common = sorted(set(r[2]) & set(finest))
        rms.append(math.sqrt(sum((r[2][k] - finest[k]) ** 2 for k in common)
                             / max(len(common), 1)))
    print(f"| RMS distance to {runs[-1][0]} [m] | "
          + " | ".join(f"{v:.2f}" for v in rms) + " |")
    summary_rows(args.runs)
    if args.output:
        draw(runs, args)


def draw(runs, args):
    """The surfaces over the finest run's damage."""
    fig, ax = plt.subplots(figsize=(8, 5))
    pts = runs[-1][1]
    sc = ax.scatter([p["x0"] for p in pts], [p["y0"] for p in pts],
                    c=[p["damage"] for p in pts], s=0.3, cmap="Greys",
                    vmin=0, vmax=1, rasterized=True)
    fig.colorbar(sc, ax=ax, label=f"damage ({runs[-1][0]})", shrink=0.7)
    for (label, _, surface), style in zip(runs, ["-", "--", "-.", ":"] * 3):
        # One point per strip; strips without a failed point leave a gap.
        ks = range(min(surface), max(surface) + 1) if surface else []
        ax.plot([surface.get(k, math.nan) for k in ks],
                [(k + 0.5) * args.strip for k in ks], style, marker=".",
                lw=1.6, label=f"failure surface, {label}")
    ax.set_xlabel("x0 [m] (reference configuration)")
    ax.set_ylabel("y0 [m]")
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(15, 33)
    ax.legend(loc="lower left", fontsize=7)
    what = (f"d >= {args.threshold}" if args.criterion == "damage"
            else f"moved > {args.moved} m")
    ax.set_title(f"failure surface (most landward point with {what}), "
                 f"snapshot '{args.snapshot}'", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=150)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
