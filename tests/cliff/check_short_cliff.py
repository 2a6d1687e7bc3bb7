#!/usr/bin/python3
"""Checks of the short cliff collapse (issue 4 test), on its output files.

1. The run completed and the cliff failed (a point moved faster than the
   failure speed: summary.json cliff.failure_onset_s >= 0).
2. A failure path of fully damaged points (d >= 0.99) connects the bottom of
   the tension crack to the wave-cut notch, in the reference configuration
   (neighbours closer than 1.5 point spacings).
3. The block seaward of the crack moved (mean displacement > 1 m) while the
   cliff behind it stayed (mean displacement < 0.1 m).
4. Mass is conserved: no point was lost (same mass in every statistics row,
   to round-off: 1e-12 relative).
"""
import csv
import json
import math
import sys
from collections import deque

out = sys.argv[1]
failures = []


def check(ok, what):
    print(("  ok:   " if ok else "  FAIL: ") + what)
    if not ok:
        failures.append(what)


summary = json.load(open(f"{out}/summary.json"))
check(summary["ended"] == "completed", f"run completed ({summary['ended']})")
onset = summary["cliff"]["failure_onset_s"]
check(onset >= 0, f"the cliff failed: onset {onset:.3f} s after damage started")

points = list(csv.DictReader(open(f"{out}/cliff_end_particles.csv")))
spacing = 0.25       # 2 points per 0.5 m cell
crest_x = 31 - 15.5 / math.tan(math.radians(78))
crack_x = crest_x - 2.2
crack_bottom = (crack_x, 15.5 - 5)
notch_root = (31 - 0.5, 0.25)

damaged = [(float(p["x0"]), float(p["y0"])) for p in points
           if float(p["damage"]) >= 0.99]
cell = {}
for k, (x, y) in enumerate(damaged):
    cell.setdefault((int(x // spacing), int(y // spacing)), []).append(k)


def near(k, radius):
    x, y = damaged[k]
    i, j = int(x // spacing), int(y // spacing)
    for di in (-2, -1, 0, 1, 2):
        for dj in (-2, -1, 0, 1, 2):
            for m in cell.get((i + di, j + dj), []):
                if math.dist(damaged[m], damaged[k]) <= radius:
                    yield m


def closest(target):
    return min(range(len(damaged)), key=lambda k: math.dist(damaged[k], target))


start, goal = closest(crack_bottom), closest(notch_root)
check(math.dist(damaged[start], crack_bottom) < 2 * spacing,
      f"damage at the crack tip ({damaged[start]})")
check(math.dist(damaged[goal], notch_root) < 3 * spacing,
      f"damage at the notch ({damaged[goal]})")
seen = {start}
queue = deque([start])
while queue:
    k = queue.popleft()
    for m in near(k, 1.5 * spacing):
        if m not in seen:
            seen.add(m)
            queue.append(m)
check(goal in seen,
      f"a path of fully damaged points joins crack tip and notch "
      f"({len(seen)} points reached of {len(damaged)} damaged)")

moved_block, moved_back = [], []
for p in points:
    x0, y0 = float(p["x0"]), float(p["y0"])
    d = math.hypot(float(p["x"]) - x0, float(p["y"]) - y0)
    if x0 > crack_x + 1 and y0 > 3:
        moved_block.append(d)
    elif x0 < crack_x - 5:
        moved_back.append(d)
mean_block = sum(moved_block) / len(moved_block)
mean_back = sum(moved_back) / len(moved_back)
check(mean_block > 1.0, f"the block moved: mean displacement {mean_block:.2f} m")
check(mean_back < 0.1, f"the cliff behind stayed: mean displacement {mean_back:.4f} m")

rows = list(csv.DictReader(open(f"{out}/statistics.csv")))
m0 = float(rows[0]["mass"])
worst = max(abs(float(r["mass"]) - m0) / m0 for r in rows)
check(worst < 1e-12, f"mass conserved (largest relative change {worst:.1e})")
sys.exit(1 if failures else 0)
