#!/usr/bin/python3
"""How far apart the fully damaged points of a cliff run lie
(doc/joss_bay/weak_damping.md, section "Why level 3's mantle does not stop").

    /usr/bin/python3 tools/debris_separation.py [--after-onset 5.5,11]
        [--speed 0.5] [--damage 0.99] LABEL=RUN_DIR ...

For each run and each time after its failure onset (the particle output
nearest to it), of the points with damage >= --damage:

* N: their number, and how many move faster than --speed;
* J: det F of their deformation gradient (the area they take now over the
  area they came from): median, 90th percentile;
* nn/h: the distance from each to its nearest other point (any point,
  damaged or not) over the run's finest cell h (summary.json): median,
  90th percentile, and the share beyond one cell; of the moving ones the
  same share, and the share of the kinetic energy of all points that they
  carry.

and a second table of the loose moving points (fully damaged, faster than
--speed, nearest neighbour beyond one cell): where they came from
(reference position, 10/50/90 % percentiles of x and y), where they are
(the same of the current position), their J (median, 90 %) and speed
(median, 90 %).

A point whose nearest neighbour is more than a cell away shares no cell
with another point: it is loose, and the grid pushes on it only where its
shape functions overlap those of points one cell or more away.

Needs Debian's python3-numpy; reads the .vtu files with
tools/read_particles.py.
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_particles import particle_outputs, read_particles  # noqa: E402
from run_summary import onset_time  # noqa: E402


def finest_cell(directory):
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    h = summary.get("refinement", {}).get("finest_cell")
    if h is None:
        sys.exit("%s/summary.json: no refinement/finest_cell" % directory)
    return h


def nearest_other(x, reach):
    """Distance from each point of x (n x 2) to its nearest other point
    (inf for a single point): the points in square buckets of side
    @p reach, each compared with the 3 x 3 buckets around its own, and the
    few with none within reach with every point."""
    keys = np.floor(x / reach).astype(np.int64)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.ravel()
    order = np.argsort(inverse, kind="stable")
    starts = np.searchsorted(inverse[order], np.arange(len(unique) + 1))
    bucket = {tuple(k): order[starts[i]:starts[i + 1]]
              for i, k in enumerate(unique)}
    nearest = np.full(len(x), np.inf)
    for (i, j), members in bucket.items():
        near = [bucket[(i + a, j + b)] for a in (-1, 0, 1) for b in (-1, 0, 1)
                if (i + a, j + b) in bucket]
        candidates = np.concatenate(near)
        dist = np.hypot(x[members, 0][:, None] - x[candidates, 0][None, :],
                        x[members, 1][:, None] - x[candidates, 1][None, :])
        dist[members[:, None] == candidates[None, :]] = np.inf
        nearest[members] = dist.min(axis=1)
    for k in np.flatnonzero(nearest > reach):
        dist = np.hypot(x[:, 0] - x[k, 0], x[:, 1] - x[k, 1])
        dist[k] = np.inf
        nearest[k] = dist.min()
    return nearest


def measure(p, h, damage_min, speed_min):
    x = np.column_stack([p["x"], p["y"]])
    d = np.asarray(p["damage"])
    v2 = np.asarray(p["velocity_0"]) ** 2 + np.asarray(p["velocity_1"]) ** 2
    m = np.asarray(p["mass"])
    J = (np.asarray(p["F_00"]) * np.asarray(p["F_11"]) -
         np.asarray(p["F_01"]) * np.asarray(p["F_10"]))
    nn = nearest_other(x, 2 * h) / h
    ke = 0.5 * m * v2
    full = d >= damage_min
    moving = full & (v2 > speed_min ** 2)
    loose = nn > 1.0
    lm = moving & loose
    x0 = np.column_stack([p["reference_position_0"],
                          p["reference_position_1"]])

    def pct(a, q=(10, 50, 90)):
        return "/".join("%.1f" % v for v in np.percentile(a, q)) \
            if len(a) else "-"
    origin = {
        "n": int(lm.sum()),
        "from_x": pct(x0[lm, 0]), "from_y": pct(x0[lm, 1]),
        "at_x": pct(x[lm, 0]), "at_y": pct(x[lm, 1]),
        "J": pct(J[lm], (50, 90)), "speed": pct(np.sqrt(v2[lm]), (50, 90)),
    }
    return origin, {
        "N": int(full.sum()),
        "moving": int(moving.sum()),
        "J50": float(np.median(J[full])),
        "J90": float(np.percentile(J[full], 90)),
        "nn50": float(np.median(nn[full])),
        "nn90": float(np.percentile(nn[full], 90)),
        "loose": float(loose[full].mean()),
        "loose_moving": float(loose[moving].mean()) if moving.any() else 0.,
        "ke_loose": float(ke[moving & loose].sum() / max(ke.sum(), 1e-300)),
        "ke": float(ke.sum()),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="LABEL=RUN_DIR")
    ap.add_argument("--after-onset", default="5.5,11",
                    help="times after the failure onset [s], comma-separated")
    ap.add_argument("--speed", type=float, default=0.5,
                    help="moving: faster than this [m/s]")
    ap.add_argument("--damage", type=float, default=0.99,
                    help="fully damaged: damage at least this")
    args = ap.parse_args()
    times = [float(t) for t in args.after_onset.split(",")]
    origins = []
    print("| run | after onset (output at) | h [m] | N (moving) | J median, "
          "90 % | nn/h median, 90 % | beyond one cell: all, moving | "
          "their share of the kinetic energy (of) |")
    print("|---|---|---|---|---|---|---|---|")
    for run in args.runs:
        label, _, directory = run.rpartition("=")
        label = label or directory
        onset = onset_time(directory)
        h = finest_cell(directory)
        outputs = particle_outputs(directory)
        for t in times:
            time, pvtu = min(outputs, key=lambda o: abs(o[0] - onset - t))
            if abs(time - onset - t) > 0.3:
                print("| %s | %.1f s | no output within 0.3 s |||||||"
                      % (label, t))
                continue
            o, r = measure(read_particles(pvtu), h, args.damage, args.speed)
            origins.append((label, t, o))
            print("| %s | %.1f s (%.2f s) | %.3g | %d (%d) | %.2f, %.2f | "
                  "%.2f, %.2f | %.1f %%, %.1f %% | %.1f %% (%.3g J) |" % (
                      label, t, time - onset, h, r["N"], r["moving"],
                      r["J50"], r["J90"], r["nn50"], r["nn90"],
                      100 * r["loose"], 100 * r["loose_moving"],
                      100 * r["ke_loose"], r["ke"]))
    print("\nThe loose moving points (10/50/90 % percentiles; J and speed: "
          "median/90 %)\n")
    print("| run | after onset | loose moving points | came from x; y [m] | "
          "are at x; y [m] | J | speed [m/s] |")
    print("|---|---|---|---|---|---|---|")
    for label, t, o in origins:
        print("| %s | %.1f s | %d | %s; %s | %s; %s | %s | %s |" % (
            label, t, o["n"], o["from_x"], o["from_y"], o["at_x"], o["at_y"],
            o["J"], o["speed"]))


if __name__ == "__main__":
    main()
