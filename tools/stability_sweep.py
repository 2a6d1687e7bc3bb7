#!/usr/bin/env python3
"""Stability sweep for scarp (verification.md 13-15).

Runs short scenes over the CFL number, the stiffness (E x 1e-3 .. 1e6),
Poisson's ratio (to 0.499), the residual stiffness of fully damaged chalk
(to 1e-9), the speed (to a large fraction of c_p) and tiny nodal masses
(a block edge eps*h past a node), for the method variants, and records
whether scarp completed or stopped (its exit status and the first line of
its message: energy growth, NaN, J <= 0, a point faster than a cell per
step, a point leaving the mesh). Also the relative displacement error
against the exact solution where there is one, and the largest speed.

Outputs in --out: sweep.csv, sweep.md (one table per sweep), cfl_map.png
and cfl_nocross_map.png (completed/stopped per variant and CFL) and
poisson_locking.png. Tables and plots include the rows of other sweeps
(rows of sweeps not run now are kept from an earlier sweep.csv).

  python3 tools/stability_sweep.py --scarp build-study/scarp --out study/stability
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

ALL_VARIANTS = [(s, t, m) for s in ("Q1", "GIMP")
                for t in ("PIC", "FLIP", "APIC") for m in ("USL", "MUSL")]
FEW_VARIANTS = [("Q1", "FLIP", "MUSL"), ("Q1", "FLIP", "USL"),
                ("Q1", "APIC", "MUSL"), ("GIMP", "FLIP", "MUSL")]
# With --fbar: the same with Transfer/Volumetric averaging = F-bar, in the
# cfl, stiffness and poisson sweeps.
FBAR_VARIANTS = [v + ("F-bar",) for v in FEW_VARIANTS]
ORDER = ["/".join(v) for v in ALL_VARIANTS + FBAR_VARIANTS]


def vname(v):
    return "/".join(v)


def tail(shape, transfer, scheme, cfl, outdir, stats=10, averaging="none"):
    return (f"subsection Transfer\n  set Shape functions = {shape}\n"
            f"  set Velocity transfer = {transfer}\n"
            f"  set Volumetric averaging = {averaging}\n"
            f"  set Update scheme = {scheme}\nend\n"
            f"subsection Time\n  set CFL number = {cfl}\nend\n"
            f"set Output directory = {outdir}\n"
            "subsection Output\n  set Interval = 0\n"
            f"  set Statistics interval = {stats}\n"
            "  set Write mesh = false\nend\n")


def material(model, E, nu, rho, extra=""):
    return (f"subsection Material material\n  set Model = {model}\n"
            f"  set Density = {rho}\n  subsection Elasticity\n"
            f"    set Young's modulus = {E!r}\n"
            f"    set Poisson's ratio = {nu}\n  end\n{extra}end\n")


def mesh(lower, upper, h, faces):
    names = ["Left", "Right", "Bottom", "Top"]
    s = (f"subsection Mesh\n  set Lower corner = {lower[0]}, {lower[1]}\n"
         f"  set Upper corner = {upper[0]}, {upper[1]}\n"
         f"  set Cell size = {h}\n  subsection Boundary conditions\n")
    for n, f in zip(names, faces):
        s += f"    set {n} = {f}\n"
    return s + "  end\nend\n"


def header(bodies="body", stages="run", regions=""):
    s = (f"set Dimension = 2\nset Materials = material\nset Bodies = "
         f"{bodies}\nset Stages = {stages}\n")
    if regions:
        s += f"set Pre-damaged regions = {regions}\n"
    return s


def box_body(corners, ppc=2, velocity="0; 0", displacement=None):
    s = ("subsection Body body\n  set Material = material\n"
         f"  set Particles per cell = {ppc}\n  set Shape = box\n"
         f"  set Box corners = {', '.join(map(str, corners))}\n"
         f"  subsection Initial velocity\n    set Function expression = "
         f"{velocity}\n  end\n")
    if displacement:
        s += ("  subsection Initial displacement\n    set Enabled = true\n"
              f"    set Function expression = {displacement}\n  end\n")
    return s + "end\n"


def stage(end, extra=""):
    return f"subsection Stage run\n  set End time = {end!r}\n{extra}end\n"


def reference(expr):
    return ("subsection Reference solution\n  set Enabled = true\n"
            f"  set Function expression = {expr}\nend\n")


def gravity(g):
    return f"subsection Physics\n  set Gravity = 0, {-g}\nend\n"


# --------------------------------------------------------------------------
def bar_scene(v0=0.1, h=0.5):
    L, E = 25.0, 100.0
    b = math.pi / (2 * L)
    w = b * 10
    return (header() + mesh((0, 0), (30, 1), h,
                            ["fixed", "free", "slip", "slip"]) +
            material("linear elastic", 100, 0, 1) +
            box_body((0, 0, L, 1), velocity=f"{v0}*sin({b!r}*x); 0") +
            gravity(0) + stage(10) +
            reference(f"{v0 / w!r}*sin({w!r}*t)*sin({b!r}*x); 0"))


def column_scene(E=743.0, nu=0.3, h=0.1, scale_time=1.0):
    H, rho, g = 1.0, 1.0, 1.0
    M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    return (header() + mesh((0, 0), (0.2, 1.2), h,
                            ["slip", "slip", "fixed", "free"]) +
            material("linear elastic", E, nu, rho) +
            box_body((0, 0, 0.2, H)) + gravity(g) +
            stage(2 * scale_time,
                  "  set Damping type = local\n  set Damping = 0.7\n") +
            reference(f"0; -({rho * g / M!r})*({H}*y-y*y/2)"))


def translation_scene(fraction, h=0.25):
    E, rho = 100.0, 1.0
    c = math.sqrt(E / rho)
    v = fraction * c
    t_end = 5.0 / v
    return (header() + mesh((0, 0), (8, 1.5), h,
                            ["free", "free", "free", "free"]) +
            material("linear elastic", E, 0.3, rho) +
            box_body((0.5, 0.25, 1.5, 1.25), velocity=f"{v!r}; 0") +
            gravity(0) + stage(t_end) +
            reference(f"{v!r}*t; 0"))


def tiny_mass_scene(eps, h=0.25, ppc=2):
    # A block resting on the floor under gravity, shifted rigidly (F = I)
    # so that its rightmost points sit eps*h past the node x = 2: the node
    # x = 2 + h then gets a weight ~ eps of a point mass.
    shift = h / (2 * ppc) + eps * h
    return (header() + mesh((0, 0), (3, 2), h,
                            ["free", "free", "fixed", "free"]) +
            material("linear elastic", 1e4, 0.3, 1) +
            box_body((0.5, 0, 2.0, 1), ppc=ppc,
                     displacement=f"{shift!r}; 0") +
            gravity(10) + stage(0.5))


def residual_scene(ratio, h=1.0):
    chalk = ("  set Model = chalk\n")
    extra = ("  subsection Damage\n"
             f"    set Residual tensile ratio = {ratio!r}\n"
             f"    set Residual shear ratio = {max(ratio, 1e-12)!r}\n"
             f"    set Residual compressive ratio = {max(ratio, 1e-12)!r}\n"
             "    set Length scale = 2\n  end\n")
    return (header(regions="all") + mesh((0, 0), (40, 20), h,
                                         ["slip", "slip", "fixed", "free"]) +
            "subsection Material material\n" + chalk +
            "  set Density = 1700\n  subsection Elasticity\n"
            "    set Young's modulus = 1e9\n    set Poisson's ratio = 0.24\n"
            "  end\n" + extra + "end\n" +
            box_body((0, 0, 10, 10)) +
            "subsection Pre-damaged region all\n  set Shape = box\n"
            "  set Box corners = -1, -1, 50, 50\nend\n" +
            gravity(9.81) +
            stage(1.0, "  set Plasticity = true\n  set Damage = true\n"))


# --------------------------------------------------------------------------
def classify(text):
    t = text.lower()
    for key, label in (("energy grew", "energy growth"),
                       ("not finite", "NaN"), ("nan", "NaN"),
                       ("j <= 0", "J<=0"), ("distortion", "J<=0"),
                       ("more than a cell", "too fast"),
                       ("leaves the background", "left mesh"),
                       ("maximum steps", "max steps"),
                       ("is refused", "refused")):
        if key in t:
            return label
    return "error"


def run(args, sweep, value, variant, scene, cfl=0.5, stats=10):
    tag = f"{sweep}_{value}_{'_'.join(variant)}_cfl{cfl}"
    outdir = os.path.abspath(os.path.join(args.out, "runs", tag))
    os.makedirs(outdir, exist_ok=True)
    prm = os.path.join(outdir, "scene.prm")
    with open(prm, "w") as f:
        f.write(scene + tail(*variant[:3], cfl, outdir, stats,
                             variant[3] if len(variant) > 3 else "none"))
    start = time.time()
    proc = subprocess.run([args.scarp, prm], capture_output=True, text=True)
    row = {"sweep": sweep, "value": value, "variant": vname(variant),
           "cfl": cfl, "exit": proc.returncode,
           "status": "stable" if proc.returncode == 0 else "stopped",
           "reason": "", "message": "", "relative_error": "",
           "max_speed": "", "steps": "", "wall_time": time.time() - start}
    if proc.returncode != 0:
        msg = " ".join(l.strip() for l in (proc.stderr + proc.stdout)
                       .splitlines() if "step" in l.lower() or
                       "error" in l.lower() or "cause" in l.lower())
        row["message"] = msg[-400:]
        row["reason"] = classify(msg)
    sfile = os.path.join(outdir, "summary.json")
    if os.path.exists(sfile):
        s = json.load(open(sfile))
        row["steps"] = int(s.get("steps", 0))
        ref = s.get("reference_error")
        if ref and ref.get("norm_max", 0) > 0:
            row["relative_error"] = ref["max"] / ref["norm_max"]
            if sweep in ("stiffness", "poisson"):
                row["relative_error"] = ref["final"] / ref["norm_max"]
    stat = os.path.join(outdir, "statistics.csv")
    if os.path.exists(stat):
        with open(stat) as f:
            speeds = [float(r["max_speed"]) for r in csv.DictReader(f)
                      if r["max_speed"] not in ("", "nan")]
        if speeds:
            row["max_speed"] = max(speeds)
    return row


def jobs_for(sweeps, fbar=False):
    jobs = []
    extra = FBAR_VARIANTS if fbar else []
    if "cfl" in sweeps:
        for v in ALL_VARIANTS + extra:
            for c in (0.5, 0.9, 1.0, 1.1, 1.3, 1.6, 2.0):
                jobs.append(("cfl", c, v, bar_scene(), c, 10))
    if "cfl_nocross" in sweeps:
        for v in ALL_VARIANTS:
            for c in (0.5, 0.9, 1.0, 1.1, 1.3, 1.6, 2.0):
                jobs.append(("cfl_nocross", c, v, bar_scene(v0=0.001), c,
                             10))
    if "stiffness" in sweeps:
        for v in FEW_VARIANTS + extra:
            for s in (1e-3, 1e-2, 1e-1, 1, 1e2, 1e4, 1e6):
                jobs.append(("stiffness", s, v,
                             column_scene(E=743.0 * s,
                                          scale_time=1 / math.sqrt(s)),
                             0.5, 100))
    if "poisson" in sweeps:
        for v in FEW_VARIANTS + extra:
            for nu in (0.3, 0.45, 0.49, 0.495, 0.499):
                jobs.append(("poisson", nu, v,
                             column_scene(nu=nu, h=0.05), 0.5, 500))
    if "speed" in sweeps:
        for v in ALL_VARIANTS:
            for f in (0.01, 0.1, 0.3, 0.5, 0.9):
                jobs.append(("speed", f, v, translation_scene(f), 0.5, 5))
    if "tiny_mass" in sweeps:
        for v in ALL_VARIANTS:
            for e in (1e-6, 1e-4, 1e-2, 0.1, 0.45):
                jobs.append(("tiny_mass", e, v, tiny_mass_scene(e), 0.5, 5))
    if "residual" in sweeps:
        for v in FEW_VARIANTS:
            for r in (1e-3, 1e-6, 1e-9):
                jobs.append(("residual", r, v, residual_scene(r), 0.5, 10))
    return jobs


def report(args, rows):
    keys = ["sweep", "value", "variant", "cfl", "exit", "status", "reason",
            "relative_error", "max_speed", "steps", "wall_time", "message"]
    with open(os.path.join(args.out, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in keys})
    titles = {
        "cfl": "CFL number (vibrating bar, v0 = 0.1, h = 0.5, one period)",
        "cfl_nocross": "CFL number (vibrating bar, v0 = 0.001: no point "
                       "crosses a cell face; h = 0.5, one period)",
        "stiffness": "E x factor (column under gravity, t_end and so the "
                     "step count scaled with 1/sqrt(factor)); error: final "
                     "displacement vs the small-strain solution",
        "poisson": "Poisson's ratio (column, h = 0.05): final displacement "
                   "error vs -(rho g/M)(HY - Y^2/2)",
        "speed": "speed / c (stress-free block translating 5 m = 20 "
                 "cells): max displacement error vs v t",
        "tiny_mass": "eps (block on the floor under gravity, right points "
                     "eps*h past a node): largest point speed",
        "residual": "residual ratio (fully damaged chalk block 10 m under "
                    "gravity, 1 s): largest point speed",
    }
    md = ["# Stability sweep\n", "Generated by `" + " ".join(sys.argv) +
          "`. A cell: `ok` (the run completed) or the reason scarp stopped "
          "(energy growth beyond 10 %, NaN, J<=0, too fast = a point moved "
          "more than a cell in a step, left mesh); then the relative error "
          "or the largest speed.\n"]
    for sweep, title in titles.items():
        srows = [r for r in rows if r["sweep"] == sweep]
        if not srows:
            continue
        values = sorted({r["value"] for r in srows})
        md.append(f"\n## {sweep}: {title}\n")
        md.append("| variant | " + " | ".join(f"{v:g}" for v in values) +
                  " |")
        md.append("|---" * (len(values) + 1) + "|")
        for v in sorted({r["variant"] for r in srows},
                        key=ORDER.index):
            cells = []
            for val in values:
                r = next((r for r in srows if r["variant"] == v and
                          r["value"] == val), None)
                if r is None:
                    cells.append("")
                    continue
                c = "ok" if r["status"] == "stable" else r["reason"]
                if sweep in ("tiny_mass", "residual") and r["max_speed"] != "":
                    c += f" {r['max_speed']:.3g}"
                elif r["relative_error"] != "":
                    c += f" {r['relative_error']:.2g}"
                cells.append(c)
            md.append(f"| {v} | " + " | ".join(cells) + " |")
    with open(os.path.join(args.out, "sweep.md"), "w") as f:
        f.write("\n".join(md) + "\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    for sweep in ("cfl", "cfl_nocross"):
        cfl_map(args, plt, [r for r in rows if r["sweep"] == sweep],
                sweep)
    prows = [r for r in rows if r["sweep"] == "poisson" and
             r["relative_error"] != ""]
    if prows:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for v in sorted({r["variant"] for r in prows}):
            vr = sorted((r for r in prows if r["variant"] == v),
                        key=lambda r: r["value"])
            ax.semilogy([1 - 2 * r["value"] for r in vr],
                        [r["relative_error"] for r in vr], "o-", label=v)
        ax.set_xscale("log")
        ax.set_xlabel("1 - 2 nu")
        ax.set_ylabel("relative displacement error (column, h = 0.05)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "poisson_locking.png"), dpi=110)
        plt.close(fig)


def cfl_map(args, plt, crows, sweep):
    if not crows:
        return
    variants = [v for v in ORDER if any(r["variant"] == v for r in crows)]
    cfls = sorted({r["cfl"] for r in crows})
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, v in enumerate(variants):
        for j, c in enumerate(cfls):
            r = next((r for r in crows if r["variant"] == v and
                      r["cfl"] == c), None)
            if r is None:
                continue
            ok = r["status"] == "stable"
            ax.scatter(j, i, marker="o" if ok else "x", s=60,
                       color="tab:green" if ok else "tab:red")
    ax.set_xticks(range(len(cfls)))
    ax.set_xticklabels([f"{c:g}" for c in cfls])
    ax.set_yticks(range(len(variants)))
    ax.set_yticklabels(variants, fontsize=8)
    ax.set_xlabel("CFL number")
    ax.set_title(f"{sweep}: completed (o) / stopped by scarp (x)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, f"{sweep}_map.png"), dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--scarp", default="build/scarp")
    ap.add_argument("--out", default="study/stability")
    ap.add_argument("--sweeps",
                    default="cfl,stiffness,poisson,speed,tiny_mass,residual")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--fbar", action="store_true",
                    help="add the F-bar variants to the cfl, stiffness and "
                         "poisson sweeps")
    args = ap.parse_args()
    args.scarp = os.path.abspath(args.scarp)
    os.makedirs(args.out, exist_ok=True)
    jobs = jobs_for(args.sweeps.split(","), args.fbar)
    rows = []
    t0 = time.time()
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for k, r in enumerate(pool.map(lambda j: run(args, *j), jobs)):
            rows.append(r)
            print(f"[{k + 1}/{len(jobs)} {time.time() - t0:5.0f} s] "
                  f"{r['sweep']} {r['value']} {r['variant']} cfl={r['cfl']}:"
                  f" {r['status']} {r['reason']} err={r['relative_error']} "
                  f"vmax={r['max_speed']}", flush=True)
    # Keep the rows of the other sweeps from an earlier invocation.
    old = os.path.join(args.out, "sweep.csv")
    if os.path.exists(old):
        done = {r["sweep"] for r in rows}
        with open(old) as f:
            for r in csv.DictReader(f):
                if r["sweep"] in done:
                    continue
                for k in ("value", "cfl", "wall_time"):
                    r[k] = float(r[k])
                for k in ("relative_error", "max_speed"):
                    r[k] = float(r[k]) if r[k] else ""
                rows.append(r)
    report(args, rows)
    print(f"done in {time.time() - t0:.0f} s: {args.out}/sweep.md")


if __name__ == "__main__":
    main()
