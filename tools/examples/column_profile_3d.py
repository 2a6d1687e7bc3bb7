#!/usr/bin/env python3
"""Run-out of the 3D column collapse (prm/examples/column_collapse_3d.prm).

    column_profile_3d.py RUN_DIR [--plot FILE.png]

The quarter column stands in the corner x, z >= 0 (y up). Along a ray from
the axis at angle theta in the x-z plane (0: along x, 90: along z, 45: the
diagonal), the run-out is the end of the contiguous deposit: the points
within one point spacing of the ray, binned by their distance along it in
bins of two spacings, the last occupied bin of the run from the axis.
Prints L0 (the half width), H0, the run-outs along x, z and the diagonal
(from the axis, the diagonal one divided by sqrt 2 to compare with the
column's corner), (L_f - L0)/L0 along x and z, and H_f.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from read_particles import first_output, last_output, read_particles  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("--plot", default=None)
args = ap.parse_args()
p0 = read_particles(first_output(args.run))
p1 = read_particles(last_output(args.run))
xs0 = sorted(set(round(x, 9) for x in p0["x"]))
sp = xs0[1] - xs0[0]
l0 = max(p0["x"]) + sp / 2
h0 = max(p0["y"]) + sp / 2


def runout(theta_deg):
    t = math.radians(theta_deg)
    ex, ez = math.cos(t), math.sin(t)
    occupied = set()
    for x, z in zip(p1["x"], p1["z"]):
        along = x * ex + z * ez
        across = abs(-x * ez + z * ex)
        if across <= sp and along >= 0:
            occupied.add(int(along // (2 * sp)))
    k = 0
    while k in occupied:
        k += 1
    return k * 2 * sp


rx, rz, rd = runout(0), runout(90), runout(45)
print("L0 = %.6g" % l0)
print("H0 = %.6g" % h0)
print("L_f_x = %.6g" % rx)
print("L_f_z = %.6g" % rz)
print("L_f_diagonal = %.6g" % rd)
print("runout_ratio_x = %.6g" % ((rx - l0) / l0))
print("runout_ratio_z = %.6g" % ((rz - l0) / l0))
print("runout_ratio_diagonal = %.6g" % ((rd - math.sqrt(2) * l0) / (math.sqrt(2) * l0)))
print("H_f = %.6g" % (max(p1["y"]) + sp / 2))
print("points = %d" % len(p1["x"]))
if args.plot:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    order = sorted(range(len(p1["y"])), key=lambda i: p1["y"][i])
    sc = axes[0].scatter([p1["x"][i] for i in order], [p1["z"][i] for i in order],
                         c=[p1["y"][i] for i in order], s=1, cmap="viridis", rasterized=True)
    fig.colorbar(sc, ax=axes[0], label="height y [m]")
    axes[0].plot([0, l0, l0], [l0, l0, 0], "k--", lw=1, label="initial column")
    axes[0].set_aspect("equal")
    axes[0].set_xlabel("x [m]")
    axes[0].set_ylabel("z [m]")
    axes[0].set_title("deposit seen from above (quarter)", fontsize=9)
    axes[0].legend(fontsize=8)
    sel = [i for i in range(len(p1["x"])) if p1["z"][i] <= sp]
    axes[1].scatter([p1["x"][i] for i in sel], [p1["y"][i] for i in sel], s=2, c="b",
                    label="3D, symmetry plane z = 0")
    axes[1].plot([0, l0, l0], [h0, h0, 0], "k--", lw=1, label="initial column")
    axes[1].set_aspect("equal")
    axes[1].set_xlabel("x [m]")
    axes[1].set_ylabel("y [m]")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=150)
