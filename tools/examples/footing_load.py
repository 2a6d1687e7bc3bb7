#!/usr/bin/env python3
"""Load-settlement curve of the strip footing example against Prandtl.

    footing_load.py RUN_DIR [--half-width 0.5] [--velocity 0.05] [--c 10e3]
                    [--phi 20] [--plot-load FILE.png] [--plot-pressure FILE.png]
                    [--compare RUN_DIR LABEL] [--label LABEL]

q = reaction_y / (B/2) (the half footing of the symmetric model), settlement
v t. Prints Prandtl's q_u = c N_c, the largest q, the limit load q_lim (the
mean q over settlements from --window S0 S1 times B, by default 0.4 % to
0.9 %: the plateau of the example), the last q, q_lim / q_u, and the
median spread of the pressure within a cell under the footing and far from
it, and the median difference between a cell's mean pressure and its
neighbours' under the footing (locking, checkerboard), as `name = value`
lines. --plot-pressure draws the mean pressure
p = -(s_xx + s_yy + s_zz)/3 at the points of the last output (a
checkerboard of p from cell to cell would be volumetric locking).
--compare adds the load curve of another run (e.g. without F-bar) to
--plot-load, and the pressure of its last output as a second panel of
--plot-pressure; --label names this run in the legends.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from read_particles import last_output, read_particles  # noqa: E402


def prandtl(c, phi_deg):
    t = math.tan(math.radians(phi_deg))
    if t == 0:
        return c * (math.pi + 2), math.pi + 2, 1.0
    nq = math.exp(math.pi * t) * math.tan(math.radians(45 + phi_deg / 2)) ** 2
    nc = (nq - 1) / t
    return c * nc, nc, nq


ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("--half-width", type=float, default=0.5)
ap.add_argument("--velocity", type=float, default=0.05)
ap.add_argument("--c", type=float, default=10e3)
ap.add_argument("--phi", type=float, default=20.0)
ap.add_argument("--window", type=float, nargs=2, default=[0.004, 0.009])
ap.add_argument("--cell-size", type=float, default=0.05)
ap.add_argument("--plot-load", default=None)
ap.add_argument("--plot-pressure", default=None)
ap.add_argument("--compare", nargs=2, default=None, metavar=("RUN", "LABEL"))
ap.add_argument("--label", default="scarp")
args = ap.parse_args()

qu, nc, nq = prandtl(args.c, args.phi)
rows = list(csv.DictReader(open(os.path.join(args.run, "statistics.csv"))))
t = [float(r["time"]) for r in rows[1:]]
q = [float(r["reaction_y"]) / args.half_width for r in rows[1:]]
s = [args.velocity * x for x in t]
B = 2 * args.half_width
window = [x for x, d in zip(q, s) if args.window[0] <= d / B <= args.window[1]]
q_lim = sum(window) / len(window)
print("N_q = %.4f" % nq)
print("N_c = %.4f" % nc)
print("q_u_prandtl = %.6g" % qu)
print("q_max = %.6g" % max(q))
print("q_lim = %.6g" % q_lim)
print("q_end = %.6g" % q[-1])
print("q_lim_over_q_u = %.4f" % (q_lim / qu))
print("settlement_end = %.4g" % s[-1])

# Volumetric locking shows as pressures that differ from point to point
# within a cell: the spread (max - min) of p over the points of each cell
# (--cell-size), under the footing (cell centres at x < 1.2 B/2 and within
# 1.2 B of the top) and far from it (x > 4 B/2), at the last output.
pts = read_particles(last_output(args.run))
top = max(pts["y"])
cells = {}
for x, y, a, b, c_ in zip(pts["x"], pts["y"], pts["stress_xx"], pts["stress_yy"], pts["stress_zz"]):
    cells.setdefault((int(x // args.cell_size), int(y // args.cell_size)), []).append(-(a + b + c_) / 3)
under, far, p_under = [], [], []
for (i, j), ps in cells.items():
    if len(ps) < 3:
        continue
    if (i + 0.5) * args.cell_size < 1.2 * args.half_width and top - (j + 0.5) * args.cell_size < 1.2 * B:
        under.append(max(ps) - min(ps))
        p_under.append(sum(ps) / len(ps))
    elif (i + 0.5) * args.cell_size > 4 * args.half_width:
        far.append(max(ps) - min(ps))
# One pressure per cell can still alternate from cell to cell (the
# checkerboard of constant-pressure cells): the cell mean minus the mean of
# its four neighbours' means, under the footing. A smooth field gives a
# fraction of the pressure's change over a cell.
mean = {k: sum(ps) / len(ps) for k, ps in cells.items() if len(ps) >= 3}
jump = []
for (i, j), pm in mean.items():
    nb = [mean.get(k) for k in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1))]
    if None in nb:
        continue
    if (i + 0.5) * args.cell_size < 1.2 * args.half_width and top - (j + 0.5) * args.cell_size < 1.2 * B:
        jump.append(abs(pm - sum(nb) / 4))
under.sort(); far.sort(); p_under.sort(); jump.sort()
print("pressure_spread_in_cell_under_footing_median = %.6g" % under[len(under) // 2])
print("pressure_under_footing_median = %.6g" % p_under[len(p_under) // 2])
print("pressure_spread_in_cell_far_median = %.6g" % far[len(far) // 2])
print("pressure_cell_to_neighbours_under_footing_median = %.6g" % jump[len(jump) // 2])

if args.plot_load or args.plot_pressure:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
if args.plot_load:
    fig, ax = plt.subplots(figsize=(5.5, 3.5))
    ax.plot([x / B for x in s], [x / args.c for x in q], "b-", label=args.label)
    if args.compare:
        other = list(csv.DictReader(open(os.path.join(args.compare[0], "statistics.csv"))))[1:]
        q_other = [float(r["reaction_y"]) / args.half_width for r in other]
        ax.plot([args.velocity * float(r["time"]) / B for r in other],
                [x / args.c for x in q_other], "r-", lw=0.8, label=args.compare[1])
        q = q + q_other
    ax.axhline(nc, color="k", ls="--", label="Prandtl N_c = %.2f" % nc)
    ax.set_xlabel("settlement / B")
    ax.set_ylabel("q / c")
    ax.set_ylim(0, 1.25 * max(nc, max(q) / args.c))
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.plot_load, dpi=150)
if args.plot_pressure:
    runs = [(args.run, args.label)] + ([tuple(args.compare)] if args.compare else [])
    panels = []
    for run, label in runs:
        p = read_particles(last_output(run))
        pr = [-(a + b + c) / 3 / 1e3 for a, b, c in zip(p["stress_xx"], p["stress_yy"], p["stress_zz"])]
        # The region around the footing: 4 B/2 wide, 3 B/2 deep.
        top = max(p["y"])
        keep = [i for i in range(len(pr)) if p["x"][i] <= 4 * args.half_width
                and p["y"][i] >= top - 3 * args.half_width]
        panels.append((p, pr, keep, top, label))
    # The colour scale: the 99th percentile of |p| over the panels (a few
    # points at the footing's edge of a locked run would wash out the rest).
    absp = sorted(abs(pr[i]) for _, pr, keep, _, _ in panels for i in keep)
    vmax = absp[int(0.99 * (len(absp) - 1))]
    fig, axes = plt.subplots(len(panels), 1, figsize=(7, 4.2 * len(panels)), squeeze=False)
    for ax, (p, pr, keep, top, label) in zip(axes[:, 0], panels):
        sc = ax.scatter([p["x"][i] for i in keep], [p["y"][i] for i in keep],
                        c=[pr[i] for i in keep], s=4, cmap="RdBu_r", rasterized=True,
                        vmin=-vmax, vmax=vmax)
        fig.colorbar(sc, ax=ax, label="mean pressure p [kPa]", extend="both")
        ax.plot([0, args.half_width], [top] * 2, "k-", lw=3)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        if len(panels) > 1:
            ax.set_title(label)
    fig.tight_layout()
    fig.savefig(args.plot_pressure, dpi=150)
