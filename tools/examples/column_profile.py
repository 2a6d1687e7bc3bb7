#!/usr/bin/env python3
"""Run-out, final height and profile of a granular column collapse.

    column_profile.py RUN_DIR [--l0 L0] [--h0 H0] [--bin B] [--plot FILE.png]

Reads the first and last particle outputs of RUN_DIR. The run-out L_f is
the right end of the deposit: the right edge of the last bin (width B, one
cell by default: 2 points) of a contiguous run of occupied bins from the
wall, so that single points thrown ahead of the front do not count. H_f is
the highest point. Prints L0, H0, a = H0/L0, L_f, (L_f - L0)/L0, H_f and
H_f/L0 as `name = value` lines, and where the mass lies: the
centroid of the points' reference volumes along x and the x below which 95
and 99 % of them lie (tools/deposit_measures.py); with --plot, draws the initial outline and
the final points coloured by their displacement (the static wedge and the
failure line show as the region that did not move).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from read_particles import first_output, last_output, read_particles  # noqa: E402
from deposit_measures import mass_centroid_x, mass_quantile_x  # noqa: E402


def runout(xs, bin_width):
    occupied = set(int(math.floor(x / bin_width)) for x in xs)
    k = 0
    while k in occupied:
        k += 1
    return k * bin_width


def surface_angle(xs, ys, bin_width, h_top):
    """Angle [deg] of the deposit's free surface: a least-squares line
    through the tops of the bins (width bin_width) whose top lies between
    20 % and 80 % of the deposit height."""
    tops = {}
    for x, y in zip(xs, ys):
        k = int(math.floor(x / bin_width))
        tops[k] = max(tops.get(k, 0.0), y)
    pts = [((k + 0.5) * bin_width, y) for k, y in tops.items()
           if 0.2 * h_top <= y <= 0.8 * h_top]
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return math.degrees(math.atan(-sxy / sxx))


def failure_line_angle(p1, threshold, l0, h0):
    """Angle [deg] from the horizontal of the line that separates, in the
    initial column, the points that moved less than @p threshold from those
    that moved more: for each row of points (initial y in 10 % to 90 % of
    H0) the first initial x from the wall whose point moved, fitted by a
    least-squares line."""
    rows = {}
    for x, y, x0, y0 in zip(p1["x"], p1["y"], p1["reference_position_0"],
                            p1["reference_position_1"]):
        if not (0.1 * h0 <= y0 <= 0.9 * h0):
            continue
        if math.hypot(x - x0, y - y0) > threshold:
            key = round(y0, 9)
            rows[key] = min(rows.get(key, l0), x0)
    pts = [(x0, y0) for y0, x0 in rows.items() if x0 < l0]
    n = len(pts)
    if n < 3:
        return float("nan")
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    syy = sum((p[1] - my) ** 2 for p in pts)
    # x as a function of y: the line can be steep.
    dxdy = sxy / syy
    return math.degrees(math.atan2(1.0, -dxdy)) if dxdy < 0 else 180 - math.degrees(math.atan2(1.0, dxdy))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("--bin", type=float, default=None)
    ap.add_argument("--plot", default=None)
    ap.add_argument("--title", default="")
    ap.add_argument("--phi", type=float, default=None)
    args = ap.parse_args()
    p0 = read_particles(first_output(args.run))
    p1 = read_particles(last_output(args.run))
    l0, h0 = max(p0["x"]), max(p0["y"])
    # Points sit at the centres of their sub-cells: the body's edge is half a
    # point spacing further out.
    xs0 = sorted(set(round(x, 9) for x in p0["x"]))
    spacing = xs0[1] - xs0[0]
    l0 += spacing / 2
    h0 += spacing / 2
    bin_width = args.bin or 2 * spacing
    lf = runout(p1["x"], bin_width)
    hf = max(p1["y"]) + spacing / 2
    a = h0 / l0
    print("L0 = %.6g" % l0)
    print("H0 = %.6g" % h0)
    print("a = %.6g" % a)
    print("L_f = %.6g" % lf)
    print("runout_ratio = %.6g" % ((lf - l0) / l0))
    print("H_f = %.6g" % hf)
    print("H_f_over_L0 = %.6g" % (hf / l0))
    print("points = %d" % len(p1["x"]))
    # The spread of the mass (tools/deposit_measures.py): not moved by thin
    # tongues or single points ahead of the front, unlike L_f.
    v0 = p1["reference_volume"]
    print("x_mass_centroid = %.6g" % mass_centroid_x(p1["x"], v0))
    print("x_mass_95 = %.6g" % mass_quantile_x(p1["x"], v0, 0.95))
    print("x_mass_99 = %.6g" % mass_quantile_x(p1["x"], v0, 0.99))
    print("surface_angle_deg = %.4g" % surface_angle(p1["x"], p1["y"], bin_width, hf))
    print("failure_line_angle_deg = %.4g" % failure_line_angle(p1, 0.01 * h0, l0, h0))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        # Displacement from the reference position when the run wrote it,
        # else matched by point order is not possible: colour by speed.
        u = [math.hypot(x - x0, y - y0) for x, y, x0, y0 in
             zip(p1["x"], p1["y"], p1["reference_position_0"], p1["reference_position_1"])]
        fig, ax = plt.subplots(figsize=(8, 2.8))
        sc = ax.scatter(p1["x"], p1["y"], c=u, s=1.0, cmap="viridis", vmin=0,
                        vmax=max(u), rasterized=True)
        fig.colorbar(sc, ax=ax, label="displacement [m]")
        ax.plot([0, l0, l0], [h0, h0, 0], "k--", lw=1, label="initial column")
        # The points that moved by less than 1 % of H0: the static region.
        still = [i for i, v in enumerate(u) if v < 0.01 * h0]
        ax.scatter([p1["x"][i] for i in still], [p1["y"][i] for i in still],
                   s=1.0, c="0.75", rasterized=True,
                   label="moved < 1 % of H0")
        ax.axvline(lf, color="r", lw=1, label="run-out L_f = %.3f m" % lf)
        # The Rankine active failure line through the toe of the column,
        # at 45 + phi/2 from the horizontal (phi given with --phi).
        if args.phi:
            beta = math.radians(45 + args.phi / 2)
            x_top = l0 - h0 / math.tan(beta)
            ax.plot([l0, x_top], [0, h0], "m-.", lw=1.2,
                    label="Rankine line, 45 + phi/2 = %.1f deg" % (45 + args.phi / 2))
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_xlim(0, max(lf * 1.15, l0 * 1.2))
        ax.set_ylim(0, h0 * 1.1)
        ax.legend(loc="upper right", fontsize=8)
        if args.title:
            ax.set_title(args.title, fontsize=9)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=150)


main()
