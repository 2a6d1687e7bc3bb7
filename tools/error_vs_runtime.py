#!/usr/bin/env python3
"""Error against run time for every method variant of scarp.

Writes scene files for the verification problems (vibrating bar at small and
large amplitude, column under its own weight, axis-aligned manufactured
solution; /work/shared/design/verification.md 5-7), runs build/scarp over a
ladder of cell sizes (and of particle densities) for every variant
(shape functions Q1/GIMP x velocity transfer PIC/FLIP/APIC x scheme
USL/MUSL), and reads the error that scarp itself measures against the exact
displacement (subsection Reference solution -> summary.json
reference_error), the wall time, the points and the steps.

Outputs in --out: runs.csv, table.md (errors, fitted convergence order per
variant, cheapest variant for a target accuracy), error_vs_time_<problem>.png
and error_vs_h_<problem>.png (log-log, one curve per variant).

Standard library only; the plots need matplotlib (/usr/bin/python3 with
python3-matplotlib) and are skipped without it.

  python3 tools/error_vs_runtime.py --scarp build-study/scarp --out study/err
  python3 tools/error_vs_runtime.py --quick ...   (2 resolutions, a minute)
"""
import argparse
import csv
import itertools
import json
import math
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

SHAPES = ["Q1", "GIMP"]
TRANSFERS = ["PIC", "FLIP", "APIC"]
SCHEMES = ["USL", "MUSL"]


def variant_name(shape, transfer, scheme):
    return f"{shape}/{transfer}/{scheme}"


def transfer_text(shape, transfer, scheme):
    return (f"subsection Transfer\n  set Shape functions = {shape}\n"
            f"  set Velocity transfer = {transfer}\n"
            f"  set Update scheme = {scheme}\nend\n")


def common_text(outdir, stats_interval):
    return (f"set Output directory = {outdir}\n"
            "subsection Output\n  set Interval = 0\n"
            f"  set Statistics interval = {stats_interval}\n"
            "  set Write mesh = false\nend\n")


# ---------------------------------------------------------------------------
# Problems: each returns the scene text for (h, ppc); "measure" says which
# reference_error entry of summary.json is the error of the run.

def vibrating_bar(v0):
    L, E, rho = 25.0, 100.0, 1.0
    beta = math.pi / (2 * L)
    omega = beta * math.sqrt(E / rho)

    def scene(h, ppc):
        # Bar height: one cell at least, so that the lattice is regular.
        H = max(1.0, h)
        return f"""set Dimension = 2
set Materials = bar material
set Bodies = bar
set Stages = vibrate
subsection Mesh
  set Lower corner = 0, 0
  set Upper corner = {L + 5}, {H}
  set Cell size = {h}
  subsection Boundary conditions
    set Left = fixed
    set Right = free
    set Bottom = slip
    set Top = slip
  end
end
subsection Material bar material
  set Model = linear elastic
  set Density = {rho}
  subsection Elasticity
    set Young's modulus = {E}
    set Poisson's ratio = 0
  end
end
subsection Body bar
  set Material = bar material
  set Particles per cell = {ppc}
  set Shape = box
  set Box corners = 0, 0, {L}, {H}
  subsection Initial velocity
    set Function constants = v0={v0}, L={L}
    set Function expression = v0*sin(pi*x/(2*L)); 0
  end
end
subsection Physics
  set Gravity = 0, 0
end
subsection Time
  set CFL number = 0.5
end
subsection Stage vibrate
  set End time = 10
end
subsection Reference solution
  set Enabled = true
  set Function constants = v0={v0}, b={beta!r}, w={omega!r}
  set Function expression = v0/w*sin(w*t)*sin(b*x); 0
end
"""
    return scene


def column():
    # The column of tests/core (verification 6): H = 1, rho = g = 1,
    # E = 743, nu = 0.3, gravity loaded with local damping 0.7 until t = 2.
    H, w, rho, g, E, nu = 1.0, 0.2, 1.0, 1.0, 743.0, 0.3
    M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))

    def scene(h, ppc):
        return f"""set Dimension = 2
set Materials = material
set Bodies = column
set Stages = load
subsection Mesh
  set Lower corner = 0, 0
  set Upper corner = {w}, 1.2
  set Cell size = {h}
  subsection Boundary conditions
    set Left = slip
    set Right = slip
    set Bottom = fixed
    set Top = free
  end
end
subsection Material material
  set Model = linear elastic
  set Density = {rho}
  subsection Elasticity
    set Young's modulus = {E}
    set Poisson's ratio = {nu}
  end
end
subsection Body column
  set Material = material
  set Particles per cell = {ppc}
  set Shape = box
  set Box corners = 0, 0, {w}, {H}
end
subsection Physics
  set Gravity = 0, {-g}
end
subsection Time
  set CFL number = 0.5
end
subsection Stage load
  set End time = 2
  set Damping type = local
  set Damping = 0.7
end
subsection Reference solution
  set Enabled = true
  set Function constants = r={rho}, g={g}, M={M!r}, H={H}
  set Function expression = 0; -(r*g/M)*(H*y-y*y/2)
end
"""
    return scene


def manufactured():
    # Wallstedt & Guilkey (2008), verification 7: unit square, neo-Hookean,
    # E = 1e4, nu = 0.3, rho0 = 1, c = 100, A = 0.05, t_end = 0.02.
    E, nu, rho, A = 1e4, 0.3, 1.0, 0.05
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    c = math.sqrt(E / rho)
    const = f"A={A}, c={c!r}, mu={mu!r}, lam={lam!r}, r={rho}"
    ux = "A*sin(pi*x)*sin(c*pi*t)"
    uy = "A*sin(pi*y)*sin(c*pi*t+2*pi/3)"
    fxx = "(1+A*pi*cos(pi*x)*sin(c*pi*t))"
    fyy = "(1+A*pi*cos(pi*y)*sin(c*pi*t+2*pi/3))"
    lnj = f"log({fxx}*{fyy})"
    bx = (f"pi^2*{ux}*(mu/r-c^2-(lam*({lnj}-1)-mu)/(r*{fxx}^2))")
    by = (f"pi^2*{uy}*(mu/r-c^2-(lam*({lnj}-1)-mu)/(r*{fyy}^2))")

    def scene(h, ppc):
        return f"""set Dimension = 2
set Materials = material
set Bodies = square
set Stages = run
subsection Mesh
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Cell size = {h}
  subsection Boundary conditions
    set Left = slip
    set Right = slip
    set Bottom = slip
    set Top = slip
  end
end
subsection Material material
  set Model = neo-Hookean
  set Density = {rho}
  subsection Elasticity
    set Young's modulus = {E}
    set Poisson's ratio = {nu}
  end
end
subsection Body square
  set Material = material
  set Particles per cell = {ppc}
  set Shape = box
  set Box corners = 0, 0, 1, 1
  subsection Initial velocity
    set Function constants = {const}
    set Function expression = A*sin(pi*x)*c*pi; A*sin(pi*y)*c*pi*cos(2*pi/3)
  end
  subsection Initial displacement
    set Enabled = true
    set Function constants = {const}
    set Function expression = 0; A*sin(pi*y)*sin(2*pi/3)
  end
end
subsection Physics
  set Gravity = 0, 0
  subsection Body force
    set Enabled = true
    set Function constants = {const}
    set Function expression = {bx}; {by}
  end
end
subsection Time
  set CFL number = 0.5
end
subsection Stage run
  set End time = 0.02
end
# The work of the body force is not part of the energy balance: the
# energy-growth check cannot judge this run.
subsection Stability
  set Energy growth tolerance = 1e30
end
subsection Reference solution
  set Enabled = true
  set Function constants = {const}
  set Function expression = {ux}; {uy}
end
"""
    return scene


# name: (scene builder, error measure, h ladder, quick h ladder, ppc ladder
#        at the middle h, statistics interval)
PROBLEMS = {
    "bar_small": (vibrating_bar(0.001), "max", [1.0, 0.5, 0.25, 0.125],
                  [0.5, 0.25], 5),
    "bar_large": (vibrating_bar(0.5), "max", [1.0, 0.5, 0.25, 0.125],
                  [0.5, 0.25], 5),
    "column": (column(), "final", [0.1, 0.05, 0.025],
               [0.1, 0.05], 50),
    "mms": (manufactured(), "max", [1 / 8, 1 / 16, 1 / 32, 1 / 64],
            [1 / 8, 1 / 16], 2),
}


def run_one(args, problem, shape, transfer, scheme, h, ppc):
    scene_builder, measure, _, _, stats = PROBLEMS[problem]
    tag = f"{problem}_{shape}_{transfer}_{scheme}_h{h:.6g}_ppc{ppc}"
    outdir = os.path.abspath(os.path.join(args.out, "runs", tag))
    os.makedirs(outdir, exist_ok=True)
    prm = os.path.join(outdir, "scene.prm")
    with open(prm, "w") as f:
        f.write(scene_builder(h, ppc))
        f.write(transfer_text(shape, transfer, scheme))
        f.write(common_text(outdir, stats))
    start = time.time()
    proc = subprocess.run([args.scarp, prm], capture_output=True, text=True)
    elapsed = time.time() - start
    row = {"problem": problem, "shape": shape, "transfer": transfer,
           "scheme": scheme, "variant": variant_name(shape, transfer, scheme),
           "h": h, "ppc": ppc, "status": "ok" if proc.returncode == 0
           else "failed", "error": "", "relative_error": "",
           "wall_time": elapsed, "points": "", "steps": "", "message": ""}
    summary_file = os.path.join(outdir, "summary.json")
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            s = json.load(f)
        row["wall_time"] = s.get("wall_time", elapsed)
        row["points"] = int(s.get("material_points", 0))
        row["steps"] = int(s.get("steps", 0))
        ref = s.get("reference_error")
        if ref and proc.returncode == 0:
            row["error"] = ref[measure]
            norm = ref["norm_max"]
            row["relative_error"] = ref[measure] / norm if norm > 0 else ""
    if proc.returncode != 0:
        lines = (proc.stderr + proc.stdout).strip().splitlines()
        row["message"] = " ".join(
            l for l in lines if "step" in l or "rror" in l)[-300:]
    return row


def fit_slope(xs, ys):
    """Least-squares slope of log y against log x."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys)
           if x and y and x > 0 and y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    return sxy / sxx if sxx > 0 else float("nan")


def time_to_reach(rows, target):
    """Wall time a variant needs to reach error <= target: log-log
    interpolation along its h ladder; None if it never does."""
    pts = sorted((r["wall_time"], r["error"]) for r in rows)
    best = None
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 <= target:
            return t0
        if e1 <= target < e0:
            a = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    if pts and pts[-1][1] <= target:
        best = pts[-1][0]
    return best


def write_outputs(args, rows):
    keys = ["problem", "variant", "shape", "transfer", "scheme", "h", "ppc",
            "status", "error", "relative_error", "wall_time", "points",
            "steps", "message"]
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in keys})

    md = ["# Error against run time\n",
          "Generated by `" + " ".join(sys.argv) + "`.\n",
          "Error: volume-weighted L2 norm of the point displacement error "
          "against the exact solution (max over time; column: at the end), "
          "divided by the largest norm of the exact displacement. Order: "
          "least-squares slope of log(error) against log(h) over the h "
          "ladder at 2 points per cell; time slope: against log(wall time). "
          "`fail` marks a run that stopped (see runs.csv).\n"]
    recommendations = {}
    for problem in PROBLEMS:
        prows = [r for r in rows if r["problem"] == problem]
        if not prows:
            continue
        hs = sorted({r["h"] for r in prows if r["ppc"] == 2}, reverse=True)
        md.append(f"\n## {problem}\n")
        md.append("| variant | " + " | ".join(f"h={h:.4g}" for h in hs) +
                  " | order | time slope | wall time finest [s] |")
        md.append("|---" * (len(hs) + 4) + "|")
        ladders = {}
        for shape, transfer, scheme in itertools.product(SHAPES, TRANSFERS,
                                                         SCHEMES):
            v = variant_name(shape, transfer, scheme)
            vr = sorted((r for r in prows
                         if r["variant"] == v and r["ppc"] == 2),
                        key=lambda r: -r["h"])
            if not vr:
                continue
            cells = []
            for h in hs:
                r = next((r for r in vr if r["h"] == h), None)
                if r is None:
                    cells.append("")
                elif r["status"] != "ok" or r["relative_error"] == "":
                    cells.append("fail")
                else:
                    cells.append(f"{r['relative_error']:.3e}")
            ok = [r for r in vr if r["status"] == "ok" and r["error"] != ""]
            order = fit_slope([r["h"] for r in ok],
                              [r["relative_error"] for r in ok])
            tslope = fit_slope([r["wall_time"] for r in ok],
                               [r["relative_error"] for r in ok])
            ladders[v] = [{"wall_time": r["wall_time"],
                           "error": r["relative_error"]} for r in ok]
            finest = vr[-1]["wall_time"] if vr else float("nan")
            md.append(f"| {v} | " + " | ".join(cells) +
                      f" | {order:.2f} | {tslope:.2f} | {finest:.2f} |")
        # Particle-density ladder.
        pp = sorted({r["ppc"] for r in prows})
        if len(pp) > 1:
            hmid = sorted({r["h"] for r in prows if r["ppc"] != 2})
            md.append(f"\nParticles per cell at h = "
                      f"{', '.join(f'{h:.4g}' for h in hmid)}:\n")
            md.append("| variant | " + " | ".join(f"ppc={p}" for p in pp) +
                      " |")
            md.append("|---" * (len(pp) + 1) + "|")
            for v in sorted({r["variant"] for r in prows
                             if r["ppc"] != 2}):
                cells = []
                for p in pp:
                    r = next((r for r in prows if r["variant"] == v and
                              r["ppc"] == p and r["h"] in hmid), None)
                    if r is None:
                        cells.append("")
                    elif r["status"] != "ok" or r["relative_error"] == "":
                        cells.append("fail")
                    else:
                        cells.append(f"{r['relative_error']:.3e} "
                                     f"({r['wall_time']:.2f} s)")
                md.append(f"| {v} | " + " | ".join(cells) + " |")
        # Cheapest variant for a target accuracy: the error the present
        # default (Q1/FLIP/MUSL) reaches on its finest grid.
        default = ladders.get("Q1/FLIP/MUSL")
        if default:
            target = min(p["error"] for p in default)
            times = {}
            for v, lad in ladders.items():
                t = time_to_reach(lad, target)
                if t is not None:
                    times[v] = t
            if times:
                best = min(times, key=times.get)
                recommendations[problem] = (best, target, times[best],
                                            times.get("Q1/FLIP/MUSL"))
                md.append(
                    f"\nTarget: relative error {target:.3e} (Q1/FLIP/MUSL, "
                    f"finest grid). Cheapest: **{best}** in {times[best]:.2f}"
                    f" s (Q1/FLIP/MUSL: {times.get('Q1/FLIP/MUSL', 0):.2f} "
                    "s). Time to reach it, per variant: " +
                    ", ".join(f"{v} {t:.2f} s" for v, t in
                              sorted(times.items(), key=lambda x: x[1])) +
                    ".")
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(args.out, "recommendation.json"), "w") as f:
        json.dump(recommendations, f, indent=1)

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no plots")
        return
    colours = {"PIC": "tab:blue", "FLIP": "tab:orange", "APIC": "tab:green"}
    for problem in PROBLEMS:
        prows = [r for r in rows if r["problem"] == problem and r["ppc"] == 2
                 and r["status"] == "ok" and r["relative_error"] != ""]
        if not prows:
            continue
        for xkey, fname, xlabel in (("wall_time", "error_vs_time",
                                     "wall time [s]"),
                                    ("h", "error_vs_h", "cell size h")):
            fig, ax = plt.subplots(figsize=(7, 5))
            for shape, transfer, scheme in itertools.product(
                    SHAPES, TRANSFERS, SCHEMES):
                v = variant_name(shape, transfer, scheme)
                vr = sorted((r for r in prows if r["variant"] == v),
                            key=lambda r: r[xkey])
                if not vr:
                    continue
                ax.loglog([r[xkey] for r in vr],
                          [r["relative_error"] for r in vr],
                          color=colours[transfer],
                          linestyle="-" if scheme == "MUSL" else "--",
                          marker="o" if shape == "Q1" else "s",
                          markerfacecolor="none" if shape == "Q1" else None,
                          label=v)
            ax.set_xlabel(xlabel)
            ax.set_ylabel("relative L2 displacement error")
            ax.set_title(problem)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7, ncol=2)
            fig.tight_layout()
            fig.savefig(os.path.join(args.out, f"{fname}_{problem}.png"),
                        dpi=110)
            plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--scarp", default="build/scarp")
    ap.add_argument("--out", default="study/error_vs_runtime")
    ap.add_argument("--problems", default=",".join(PROBLEMS))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--quick", action="store_true",
                    help="two resolutions, no particle-density ladder")
    ap.add_argument("--plot-only", action="store_true",
                    help="re-read runs.csv and redo table and plots")
    args = ap.parse_args()
    args.scarp = os.path.abspath(args.scarp)
    os.makedirs(args.out, exist_ok=True)
    problems = args.problems.split(",")

    if args.plot_only:
        rows = []
        with open(os.path.join(args.out, "runs.csv")) as f:
            for r in csv.DictReader(f):
                for k in ("h", "wall_time"):
                    r[k] = float(r[k])
                r["ppc"] = int(r["ppc"])
                for k in ("error", "relative_error"):
                    r[k] = float(r[k]) if r[k] else ""
                rows.append(r)
        write_outputs(args, rows)
        return

    jobs = []
    for problem in problems:
        _, _, ladder, quick_ladder, _ = PROBLEMS[problem]
        hs = quick_ladder if args.quick else ladder
        for shape, transfer, scheme in itertools.product(SHAPES, TRANSFERS,
                                                         SCHEMES):
            for h in hs:
                jobs.append((problem, shape, transfer, scheme, h, 2))
            if not args.quick and transfer == "FLIP" and scheme == "MUSL":
                # Particle density ladder at the second h of the ladder.
                for ppc in (1, 3, 4):
                    jobs.append((problem, shape, transfer, scheme, hs[1],
                                 ppc))
    # Longest first keeps both workers busy to the end.
    jobs.sort(key=lambda j: j[4])
    rows = []
    t0 = time.time()
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for k, row in enumerate(pool.map(lambda j: run_one(args, *j), jobs)):
            rows.append(row)
            print(f"[{k + 1}/{len(jobs)} {time.time() - t0:6.0f} s] "
                  f"{row['problem']} {row['variant']} h={row['h']:.4g} "
                  f"ppc={row['ppc']}: {row['status']} "
                  f"err={row['relative_error']} "
                  f"wall={row['wall_time']:.2f}", flush=True)
    write_outputs(args, rows)
    print(f"done in {time.time() - t0:.0f} s: {args.out}/table.md")


if __name__ == "__main__":
    main()
