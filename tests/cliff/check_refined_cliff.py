#!/usr/bin/python3
"""Checks of the refined cliff collapse (ctest cliff_refined_collapse).

The scene: refined_cliff.prm (Joss Bay as its authors set it up, GIMP on a
mesh that refines where it fails). On its output directory:

1. The run stopped after the failure (the cliff failed: onset >= 0).
2. The mesh refined and points split (summary.json "refinement").
3. Mass is conserved: the same mass in every statistics row to 1e-12
   (splitting divides masses exactly; sums change order only).
4. A failure path of fully damaged points (d >= 0.99) joins the bottom of
   the pre-damage band of the tension crack to the wave-cut notch, in the
   reference configuration, 0.5 s after the onset. Points are neighbours
   when closer than 1.5 times the larger of their spacings (sqrt of their
   volume: split points are closer together than the others).
"""
import csv
import json
import math
import sys
from collections import deque

failures = []


def check(ok, what):
    print(("  ok:   " if ok else "  FAIL: ") + what)
    if not ok:
        failures.append(what)


if sys.argv[1] == "--cut":
    # 5. A run cut by an error inside the collapse stage (<Maximum steps>
    #    just after the onset) reports in its summary.json the onset of the
    #    full run (the same steps: equal to round-off) and the collapse
    #    stage as in progress.
    cut = json.load(open(f"{sys.argv[2]}/summary.json"))
    full = json.load(open(f"{sys.argv[3]}/summary.json"))
    check(cut["ended"].startswith("error"), f"cut run ended: {cut['ended']}")
    onset_cut = cut.get("cliff", {}).get("failure_onset_s", float("nan"))
    onset_full = full["cliff"]["failure_onset_s"]
    check(abs(onset_cut - onset_full) <= 1e-12 * max(1.0, onset_full),
          f"cut run reports the onset {onset_cut} (full run {onset_full})")
    stage = cut["stages"].get("collapse", {})
    check(stage.get("end_reason") == "in progress",
          f"collapse stage reported in progress ({stage})")
    sys.exit(1 if failures else 0)

out = sys.argv[1]

summary = json.load(open(f"{out}/summary.json"))
check(summary["ended"].startswith("stopped after failure"),
      f"run stopped after the failure ({summary['ended']})")
onset = summary["cliff"]["failure_onset_s"]
check(onset >= 0, f"the cliff failed: onset {onset:.3f} s")
refinement = summary["refinement"]
check(refinement["passes"] > 0 and refinement["points_split"] > 0,
      f"the mesh refined ({refinement['passes']} passes) and "
      f"{refinement['points_split']} points split")

rows = list(csv.DictReader(open(f"{out}/statistics.csv")))
m0 = float(rows[0]["mass"])
worst = max(abs(float(r["mass"]) - m0) for r in rows) / m0
check(worst < 1e-12, f"mass constant to 1e-12 (worst {worst:.1e})")
points = [int(float(r["material_points"])) for r in rows]
check(points[-1] > points[0], f"points {points[0]} -> {points[-1]}")

# The crack: the lowest point of the pre-damaged band at the start.
start = list(csv.DictReader(open(f"{out}/cliff_start_particles.csv")))
band = [(float(p["x0"]), float(p["y0"])) for p in start
        if float(p["damage"]) > 0.5]
crack_bottom = min(band, key=lambda q: q[1])
notch_root = (31 - 0.5, 0.25)

after = list(csv.DictReader(open(f"{out}/cliff_after_failure_particles.csv")))
damaged = [(float(p["x0"]), float(p["y0"]), math.sqrt(float(p["volume"])))
           for p in after if float(p["damage"]) >= 0.99]
bucket = 1.0
cells = {}
for k, (x, y, _) in enumerate(damaged):
    cells.setdefault((int(x // bucket), int(y // bucket)), []).append(k)


def neighbours(k):
    x, y, s = damaged[k]
    i, j = int(x // bucket), int(y // bucket)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            for m in cells.get((i + di, j + dj), []):
                if math.dist(damaged[m][:2], (x, y)) <= 1.5 * max(s, damaged[m][2]):
                    yield m


def closest(target):
    return min(range(len(damaged)),
               key=lambda k: math.dist(damaged[k][:2], target))


first, goal = closest(crack_bottom), closest(notch_root)
check(math.dist(damaged[first][:2], crack_bottom) < 1.5,
      f"damage at the crack tip {crack_bottom} ({damaged[first][:2]})")
check(math.dist(damaged[goal][:2], notch_root) < 1.5,
      f"damage at the notch ({damaged[goal][:2]})")
seen = {first}
queue = deque([first])
while queue:
    k = queue.popleft()
    for m in neighbours(k):
        if m not in seen:
            seen.add(m)
            queue.append(m)
check(goal in seen,
      f"a path of fully damaged points joins crack tip and notch "
      f"({len(seen)} points reached of {len(damaged)} damaged)")
sys.exit(1 if failures else 0)
