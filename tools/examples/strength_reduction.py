#!/usr/bin/env python3
"""Factor of safety of a slope by strength reduction (doc/examples.md).

    strength_reduction.py SCARP SCENE OUT_DIR [--cell-size H] [--lo 1.0]
        [--hi 2.0] [--tol 0.025] [--factors F1 F2 ...] [--plot FILE.png]

Reruns SCENE (prm/examples/slope_stability.prm: material `soil`, the
reduced strength acting in its last stage) with c / F and
tan(phi) / F and decides for each F whether the slope fails: it fails when
it has not come to rest by the end of the run, i.e. the largest speed of a
point in the last statistics row exceeds --speed (default 1e-3 m/s; a
standing slope is at 1e-6 m/s or less, a failing one still slides at
1e-2 m/s or more, doc/examples.md). The largest displacement after the
reference reset at the end of the gravity stage is printed too. Bisection
between --lo (must stand) and --hi (must fail) until the bracket is --tol
wide; or only the --factors given. Prints one line per run and
`factor_of_safety = ...` (the middle of the final bracket).
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from read_particles import last_output, read_particles  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("scarp")
ap.add_argument("scene")
ap.add_argument("out")
ap.add_argument("--cell-size", type=float, default=None)
ap.add_argument("--lo", type=float, default=1.0)
ap.add_argument("--hi", type=float, default=2.0)
ap.add_argument("--tol", type=float, default=0.025)
ap.add_argument("--factors", type=float, nargs="*", default=None)
ap.add_argument("--speed", type=float, default=1e-3)
ap.add_argument("--plot", default=None)
args = ap.parse_args()

scene = os.path.abspath(args.scene)
text = open(scene).read()
# The full strength, read from the scene.
c0 = float(re.search(r"set Cohesion\s*=\s*([0-9.eE+-]+)", text).group(1))
phi0 = float(re.search(r"set Friction angle\s*=\s*([0-9.eE+-]+)", text).group(1))
os.makedirs(args.out, exist_ok=True)
results = {}


def run(F):
    tag = "F%.4f" % F
    d = os.path.abspath(os.path.join(args.out, tag))
    phi = math.degrees(math.atan(math.tan(math.radians(phi0)) / F))
    prm = os.path.join(args.out, tag + ".prm")
    with open(prm, "w") as f:
        f.write("include %s\nset Output directory = %s\n" % (scene, d))
        if args.cell_size:
            f.write("subsection Mesh\n  set Cell size = %g\nend\n" % args.cell_size)
        f.write("subsection Material soil\n  subsection Mohr-Coulomb\n"
                "    set Cohesion = %.10g\n    set Friction angle = %.10g\n  end\nend\n"
                % (c0 / F, phi))
    with open(os.path.join(args.out, tag + ".log"), "w") as log:
        status = subprocess.call([args.scarp, prm], stdout=log, stderr=subprocess.STDOUT)
    if status != 0:
        raise SystemExit("scarp failed for F = %g (see %s.log)" % (F, tag))
    p = read_particles(last_output(d))
    u = max(math.hypot(x - x0, y - y0) for x, y, x0, y0 in
            zip(p["x"], p["y"], p["reference_position_0"], p["reference_position_1"]))
    s = json.load(open(os.path.join(d, "summary.json")))
    with open(os.path.join(d, "statistics.csv")) as f:
        speed = float(list(csv.DictReader(f))[-1]["max_speed"])
    failed = speed > args.speed
    results[F] = (u, failed, d, speed)
    print("F = %.4f: c = %.1f Pa, phi = %.3f deg, largest displacement %.4g m, "
          "final largest speed %.3g m/s: %s (%d steps, %.1f s)"
          % (F, c0 / F, phi, u, speed, "fails" if failed else "stands", s["steps"],
             s["wall_time"]), flush=True)
    return failed


if args.factors:
    for F in args.factors:
        run(F)
else:
    lo, hi = args.lo, args.hi
    if run(lo):
        raise SystemExit("the slope fails already at F = %g" % lo)
    if not run(hi):
        raise SystemExit("the slope still stands at F = %g" % hi)
    while hi - lo > args.tol + 1e-12:
        mid = 0.5 * (lo + hi)
        if run(mid):
            hi = mid
        else:
            lo = mid
    print("bracket = %.4f %.4f" % (lo, hi))
    print("factor_of_safety = %.4f" % (0.5 * (lo + hi)))

if args.plot:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fs = sorted(results)
    failing = [F for F in fs if results[F][1]]
    standing = [F for F in fs if not results[F][1]]
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.6), gridspec_kw={"width_ratios": [1, 1.6]})
    ax = axes[0]
    ax.semilogy(fs, [results[F][3] for F in fs], "ko")
    ax.axhline(args.speed, color="r", ls="--", label="failure criterion: %.2g m/s" % args.speed)
    ax.axvline(1.4, color="b", ls=":", label="Griffiths & Lane 1999: 1.4")
    ax.set_xlabel("strength reduction factor F")
    ax.set_ylabel("largest speed at the end [m/s]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    ax = axes[1]
    F = min(failing) if failing else max(fs)
    p = read_particles(last_output(results[F][2]))
    u = [math.hypot(x - x0, y - y0) for x, y, x0, y0 in
         zip(p["x"], p["y"], p["reference_position_0"], p["reference_position_1"])]
    sc = ax.scatter(p["x"], p["y"], c=u, s=2, cmap="viridis", rasterized=True)
    fig.colorbar(sc, ax=ax, label="displacement [m]")
    ax.set_aspect("equal")
    ax.set_title("F = %.3f (first failing): displacement in the strength stage" % F, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=150)
