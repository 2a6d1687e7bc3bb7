#!/usr/bin/python3
"""Plot a cliff collapse: surface profiles and particles coloured by damage.

Reads the files written by scarp::postprocess::CliffDiagnostics:

* a profile CSV (write_profile_csv): optional "# name = value" lines with the
  diagnostics, then the columns x,y_initial,y_final (one row per bin);
* particle CSV snapshots (write_particles_csv, or any CSV with a header that
  has the columns x, y and damage).

and writes PNG files:

* <prefix>profile.png: the final free surface over the initial one, with the
  debris toe, the fit range of the debris angle and the scarp marked when the
  profile CSV carries the diagnostics;
* <prefix><snapshot name>.png for every particle CSV: the particles coloured
  by damage (0 to 1), with the profiles drawn over them when given.

Uses the Debian package python3-matplotlib, hence /usr/bin/python3.

Examples:
  plot_cliff.py --profile output/profile.csv
  plot_cliff.py --profile output/profile.csv \\
                --particles output/particles-*.csv --output-dir figures
"""

import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402


def read_profile(filename):
    """Return (columns, diagnostics) of a profile CSV."""
    diagnostics = {}
    rows = []
    with open(filename, newline="") as f:
        for line in f:
            if line.startswith("#"):
                name, _, value = line[1:].partition("=")
                try:
                    diagnostics[name.strip()] = float(value)
                except ValueError:
                    pass
            elif line.strip():
                rows.append(line)
    reader = csv.DictReader(rows)
    missing = {"x", "y_initial", "y_final"} - set(reader.fieldnames or [])
    if missing:
        sys.exit(f"{filename}: missing column(s) {', '.join(sorted(missing))}; "
                 "expected x,y_initial,y_final")
    columns = {"x": [], "y_initial": [], "y_final": []}
    for row in reader:
        for key in columns:
            columns[key].append(float(row[key]))
    return columns, diagnostics


def read_particles(filename):
    """Return the x, y and damage columns of a particle CSV."""
    with open(filename, newline="") as f:
        reader = csv.DictReader(line for line in f if not line.startswith("#"))
        missing = {"x", "y", "damage"} - set(reader.fieldnames or [])
        if missing:
            sys.exit(f"{filename}: missing column(s) "
                     f"{', '.join(sorted(missing))}; expected x,y,damage")
        x, y, damage = [], [], []
        for row in reader:
            x.append(float(row["x"]))
            y.append(float(row["y"]))
            damage.append(float(row["damage"]))
    return x, y, damage


def finite(diagnostics, name):
    value = diagnostics.get(name)
    return value is not None and math.isfinite(value)


def draw_profiles(ax, columns, diagnostics, annotate):
    ax.plot(columns["x"], columns["y_initial"], "--", color="0.4",
            lw=1.2, label="initial surface", drawstyle="steps-mid")
    ax.plot(columns["x"], columns["y_final"], "-", color="k",
            lw=1.4, label="final surface", drawstyle="steps-mid")
    if not annotate:
        return
    if finite(diagnostics, "fit_x_begin") and finite(diagnostics, "fit_x_end"):
        ax.axvspan(diagnostics["fit_x_begin"], diagnostics["fit_x_end"],
                   color="tab:orange", alpha=0.15, label="debris angle fit")
    for name, style, label in (("initial_toe", ":", "initial toe"),
                               ("debris_toe", "-.", "debris toe"),
                               ("scarp_position", "-", "scarp")):
        if finite(diagnostics, name):
            ax.axvline(diagnostics[name], ls=style, lw=0.9, color="tab:blue"
                       if name != "scarp_position" else "tab:red",
                       label=label)


def summary(diagnostics):
    parts = []
    for name, text, unit in (("debris_angle", "debris angle", " deg"),
                             ("run_out", "run-out", " m"),
                             ("failed_area", "failed area", " m^2"),
                             ("scarp_retreat", "scarp retreat", " m")):
        if finite(diagnostics, name):
            parts.append(f"{text} {diagnostics[name]:.3g}{unit}")
    return ", ".join(parts)


def finish(fig, ax, args, title, filename):
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal", adjustable="box")
    if args.xlim:
        ax.set_xlim(*args.xlim)
    if args.ylim:
        ax.set_ylim(*args.ylim)
    if title:
        ax.set_title(title, fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    fig.savefig(filename, dpi=args.dpi)
    plt.close(fig)
    print(f"wrote {filename}")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--profile", metavar="CSV",
                        help="profile CSV with columns x,y_initial,y_final")
    parser.add_argument("--particles", metavar="CSV", nargs="+", default=[],
                        help="particle CSV snapshots with columns x,y,damage")
    parser.add_argument("--output-dir", default=".", metavar="DIR",
                        help="directory for the PNG files (default: .)")
    parser.add_argument("--prefix", default="",
                        help="prefix of the PNG file names")
    parser.add_argument("--dpi", type=int, default=150,
                        help="resolution of the PNG files (default: 150)")
    parser.add_argument("--xlim", type=float, nargs=2, metavar=("XMIN", "XMAX"),
                        help="x range of the plots")
    parser.add_argument("--ylim", type=float, nargs=2, metavar=("YMIN", "YMAX"),
                        help="y range of the plots")
    parser.add_argument("--marker-size", type=float, default=1.0,
                        help="particle marker size in points^2 (default: 1)")
    parser.add_argument("--cmap", default="viridis",
                        help="matplotlib colour map for damage "
                             "(default: viridis)")
    parser.add_argument("--title", default="",
                        help="title prefix of every plot")
    args = parser.parse_args()

    if not args.profile and not args.particles:
        parser.error("give --profile and/or --particles")
    os.makedirs(args.output_dir, exist_ok=True)

    columns, diagnostics = (None, {})
    if args.profile:
        columns, diagnostics = read_profile(args.profile)
        fig, ax = plt.subplots(figsize=(9, 4.5))
        draw_profiles(ax, columns, diagnostics, annotate=True)
        title = " - ".join(t for t in (args.title, summary(diagnostics)) if t)
        finish(fig, ax, args, title,
               os.path.join(args.output_dir, args.prefix + "profile.png"))

    for filename in args.particles:
        x, y, damage = read_particles(filename)
        fig, ax = plt.subplots(figsize=(9, 4.5))
        points = ax.scatter(x, y, c=damage, s=args.marker_size, vmin=0.,
                            vmax=1., cmap=args.cmap, linewidths=0,
                            rasterized=True)
        fig.colorbar(points, ax=ax, label="damage", shrink=0.8)
        if columns is not None:
            draw_profiles(ax, columns, diagnostics, annotate=False)
        stem = os.path.splitext(os.path.basename(filename))[0]
        title = " - ".join(t for t in (args.title, stem) if t)
        finish(fig, ax, args, title,
               os.path.join(args.output_dir, args.prefix + stem + ".png"))


if __name__ == "__main__":
    main()
