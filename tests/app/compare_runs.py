#!/usr/bin/env python3
"""Compare two output directories of the same scene (tests/app/checkpoint.sh):
an uninterrupted run A and a run B that was stopped and resumed.

    compare_runs.py A B TOLERANCE

* statistics.csv: the same columns and the same number of rows (a resumed
  run neither loses nor repeats rows), every value but the wall time within
  TOLERANCE times its column's largest magnitude, at least 1e-3 of its
  group's (energies, momenta, angular momenta: tests/regression/compare.py);
* cliff_history.csv, if A has it: likewise;
* particles.pvd (and mesh.pvd): the same records, times within TOLERANCE;
* summary.json: every number but wall times, speeds, rank counts and the
  non-local list counters within TOLERANCE (energies: times the largest
  energy; others: times their own size), every string equal.
Prints the largest differences; exit status 1 when one is beyond.
"""
import csv
import json
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

# The regression comparison's column groups and floor: a column that is zero
# up to round-off (the horizontal momentum of a symmetric column) is
# measured at FLOOR times the largest value of its group, not at its own
# 1e-14, whose digits are noise in two runs that round differently.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "regression"))
from compare import FLOOR, column_group  # noqa: E402

a_dir, b_dir, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
failures = []
largest = []  # (relative difference, where)


def note(difference, where):
    largest.append((difference, where))
    if not difference <= tolerance:
        failures.append(f"{where}: relative difference {difference:.3e}")


def table(name, skip=("wall_time",)):
    """A CSV of rows in time (statistics.csv, cliff_history.csv): A's rows
    in B, every value within the tolerance of its column's largest
    magnitude; a value without a number (nan) must be so in both."""
    path_a = os.path.join(a_dir, name)
    if name != "statistics.csv" and not os.path.exists(path_a):
        return
    if not os.path.exists(os.path.join(b_dir, name)):
        failures.append(f"{name}: missing")
        return
    a = list(csv.reader(open(path_a)))
    b = list(csv.reader(open(os.path.join(b_dir, name))))
    if a[0] != b[0]:
        failures.append(f"{name}: other columns")
        return
    if len(a) != len(b):
        failures.append(f"{name}: {len(b) - 1} rows, expected "
                        f"{len(a) - 1} (rows lost or repeated)")
        return
    columns = a[0]
    group_largest = {}
    for c, column in enumerate(columns):
        largest_c = max((abs(float(r[c])) for r in a[1:]
                         if not math.isnan(float(r[c]))), default=0.0)
        g = column_group(column)
        group_largest[g] = max(group_largest.get(g, 0.0), largest_c)
    for c, column in enumerate(columns):
        if column in skip:
            continue
        values = [(float(ra[c]), float(rb[c]), ra[0])
                  for ra, rb in zip(a[1:], b[1:])]
        if any(math.isnan(x) != math.isnan(y) for x, y, _ in values):
            failures.append(f"{name} {column}: nan in one run only")
            continue
        values = [v for v in values if not math.isnan(v[0])]
        scale = max([abs(x) for x, _, _ in values] +
                    [FLOOR * group_largest[column_group(column)]])
        worst, where = 0.0, ""
        for x, y, key in values:
            d = abs(x - y) / max(scale, 1e-300)
            if d > worst:
                worst, where = d, f"{name} {column} at {columns[0]} {key}"
        note(worst, where or f"{name} {column}")


def pvd(name):
    path_a = os.path.join(a_dir, name + ".pvd")
    if not os.path.exists(path_a):
        return
    records = []
    for d in (a_dir, b_dir):
        root = ElementTree.parse(os.path.join(d, name + ".pvd")).getroot()
        records.append([(float(e.get("timestep")), e.get("file"))
                        for e in root.iter("DataSet")])
    ra, rb = records
    if [f for _, f in ra] != [f for _, f in rb]:
        failures.append(f"{name}.pvd: {len(rb)} records, expected "
                        f"{len(ra)} ({[f for _, f in rb]})")
        return
    t_max = max(abs(t) for t, _ in ra)
    note(max(abs(x - y) for (x, _), (y, _) in zip(ra, rb)) /
         max(t_max, 1e-300), f"{name}.pvd times")


skipped = {"wall_time", "particle_steps_per_second", "wall_time_per_phase",
           "mpm_step_parts", "mpm_step_parts_over_ranks",
           "mpi_ranks", "nonlocal_lists", "load_rebalances"}


def summary(a, b, path, scale=None):
    for key, value in a.items():
        where = f"{path}/{key}"
        if key in skipped:
            continue
        if key not in b:
            failures.append(f"summary.json: {where} missing")
            continue
        other = b[key]
        if isinstance(value, dict):
            group = None
            if key == "energies":
                group = max(abs(v) for v in value.values()
                            if isinstance(v, (int, float)))
            summary(value, other, where, group)
        elif isinstance(value, str):
            if value != other:
                failures.append(f"summary.json: {where} = <{other}>, "
                                f"expected <{value}>")
        elif value is None or other is None:
            if value != other:
                failures.append(f"summary.json: {where} {other} vs {value}")
        else:
            s = scale if scale else max(abs(value), abs(other))
            note(abs(value - other) / max(s, 1e-300), f"summary.json {where}")


table("statistics.csv")
table("cliff_history.csv")
pvd("particles")
pvd("mesh")
summary(json.load(open(os.path.join(a_dir, "summary.json"))),
        json.load(open(os.path.join(b_dir, "summary.json"))), "")
largest.sort(reverse=True)
print(f"  {b_dir} against {a_dir} (tolerance {tolerance:g}); largest "
      "differences:")
for d, where in largest[:3]:
    print(f"    {d:.3e}  {where}")
if failures:
    for f in failures:
        print("  FAIL: " + f)
    sys.exit(1)
print(f"  ok:   {b_dir} equals {a_dir}")
