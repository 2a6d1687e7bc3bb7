#!/usr/bin/python3
"""Compare a run's summary.json and statistics.csv with stored expected files.

    compare.py OUTPUT_DIR EXPECTED_DIR --tolerance T
    compare.py OUTPUT_DIR EXPECTED_DIR --update      (tools/update_regression.sh)

The regression tests of scarp (tests/regression/, doc/testing.md), in the
spirit of the `.output` files of deal.II and ASPECT: a change that moves the
results of a scene beyond round-off shows up as a failed test with the
quantities that moved and by how much.

What is compared, and how (T: the tolerance, chosen per scene in
tests/regression/CMakeLists.txt with the reason for its size):

* summary.json: every number and string, recursively, except what depends on
  the machine or the partition (wall times, speeds, rank counts, repartition
  and neighbour-list counts). Strings (how the run ended) and counts
  (steps, material points, cells) must be equal; a number x must be within
  |x - e| <= T * max(|e|, floor) of the expected e. The floor is FLOOR times
  the largest final energy for the entries of "energies" (a dissipation or
  a balance residual can be zero up to round-off) and zero elsewhere (other
  sections mix units: the cliff's joules and metres).
* statistics.csv: the same columns and rows; the step and point counts
  exactly (a different step count is a different run), every other value
  within |x - e| <= T * scale. The scale of a column is the largest |e| in
  it (momenta swing through zero: a row's own value is no scale), at least
  FLOOR times the largest value of its group (energies and works, momenta,
  angular momenta): a column that is zero up to round-off, such as the
  horizontal momentum of a symmetric column, is compared at the scale of
  its neighbours, not at its own 1e-14. The time step of the last step is
  not compared: it is the remainder up to the end time, whose digits are
  noise in any run that is not bitwise the same (the time column holds
  what it means).
* --ignore NAME (repeatable) leaves out a summary entry (its dotted path,
  e.g. cliff.run_out_m) or a statistics column that a scene cannot pin down.

FLOOR = 1e-3: a quantity a thousandth of its neighbours carries no
information of its own at round-off level, and a physical change that moves
it moves them too.

Exit status 0 when everything matches, 1 otherwise (a table of the worst
differences is printed either way).
"""
import argparse
import csv
import json
import math
import sys

# Machine- and partition-dependent summary entries: never compared.
VOLATILE = {"wall_time", "wall_time_per_phase", "mpm_step_parts",
            "mpm_step_parts_over_ranks",
            "particle_steps_per_second",
            "mpi_ranks", "load_rebalances", "nonlocal_lists"}
# Columns of statistics.csv that are counts: compared exactly.
EXACT_COLUMNS = {"step", "material_points"}
EXACT_SUMMARY = {"steps", "material_points", "cells", "dimension",
                 "points_removed"}


FLOOR = 1e-3


def is_volatile_column(name):
    return "wall" in name or name in {"mpi_ranks"}


def column_group(name):
    """Columns measured against a common scale (see FLOOR)."""
    if name.startswith("angular_momentum"):
        return "angular momentum"
    if name.startswith("momentum"):
        return "momentum"
    if any(word in name for word in ("energy", "work", "dissipation",
                                     "residual")):
        return "energy"
    return name


class Report:
    def __init__(self):
        self.failures = []
        self.worst = []          # (relative difference, where)

    def number(self, where, value, expected, scale, tolerance):
        if not (math.isfinite(value) and math.isfinite(expected)):
            ok = (value == expected) or (math.isnan(value) and
                                         math.isnan(expected))
            diff = 0.0 if ok else math.inf
        else:
            diff = abs(value - expected) / scale if scale > 0 else \
                abs(value - expected)
            ok = diff <= tolerance
        self.worst.append((diff, where, value, expected))
        if not ok:
            self.failures.append(
                f"{where}: {value!r}, expected {expected!r} "
                f"(difference {diff:.3e} of the scale {scale:.3e}, "
                f"tolerance {tolerance:.1e})")

    def exact(self, where, value, expected):
        if value != expected:
            self.failures.append(f"{where}: {value!r}, expected {expected!r}"
                                 " (must be equal)")


def largest_number(node):
    if isinstance(node, bool):
        return 0.0
    if isinstance(node, (int, float)):
        return abs(node) if math.isfinite(node) else 0.0
    if isinstance(node, dict):
        return max([largest_number(v) for v in node.values()] + [0.0])
    if isinstance(node, list):
        return max([largest_number(v) for v in node] + [0.0])
    return 0.0


def compare_json(report, path, value, expected, tolerance, section_scale,
                 ignore=()):
    if path in ignore:
        return
    if isinstance(expected, dict):
        if not isinstance(value, dict):
            report.failures.append(f"{path}: not an object in the run")
            return
        scale = FLOOR * largest_number(expected) \
            if path == "energies" else 0.0
        for key in expected:
            if key in VOLATILE:
                continue
            where = f"{path}.{key}" if path else key
            if key not in value:
                report.failures.append(f"{where}: missing in the run")
                continue
            if key in EXACT_SUMMARY:
                report.exact(where, value[key], expected[key])
            else:
                compare_json(report, where, value[key], expected[key],
                             tolerance, scale, ignore)
        for key in value:
            if key not in expected and key not in VOLATILE:
                where = f"{path}.{key}" if path else key
                report.failures.append(
                    f"{where}: in the run but not in the expected file "
                    "(regenerate with tools/update_regression.sh if it is "
                    "new on purpose)")
    elif isinstance(expected, list):
        if not isinstance(value, list) or len(value) != len(expected):
            report.failures.append(f"{path}: list of another length")
            return
        for k, (v, e) in enumerate(zip(value, expected)):
            compare_json(report, f"{path}[{k}]", v, e, tolerance,
                         section_scale, ignore)
    elif isinstance(expected, bool) or isinstance(expected, str) or \
            expected is None:
        report.exact(path, value, expected)
    else:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            report.failures.append(f"{path}: {value!r} is not a number")
            return
        report.number(path, float(value), float(expected),
                      max(abs(expected), section_scale), tolerance)


def read_csv(name):
    """The header and rows of a statistics file, volatile columns left out."""
    with open(name) as f:
        rows = list(csv.reader(f))
    keep = [c for c, n in enumerate(rows[0]) if not is_volatile_column(n)]
    return ([rows[0][c] for c in keep],
            [[float(row[c]) for c in keep] for row in rows[1:]])


def without_volatile(node):
    if isinstance(node, dict):
        return {k: without_volatile(v) for k, v in node.items()
                if k not in VOLATILE}
    if isinstance(node, list):
        return [without_volatile(v) for v in node]
    return node


def update(output, expected_dir):
    """Store the run's files as the expected ones, without what is never
    compared (so that a regeneration's diff shows only what moved)."""
    import os
    os.makedirs(expected_dir, exist_ok=True)
    with open(f"{output}/summary.json") as f:
        summary = without_volatile(json.load(f))
    with open(f"{expected_dir}/summary.json", "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    with open(f"{output}/statistics.csv") as f:
        rows = list(csv.reader(f))
    keep = [c for c, n in enumerate(rows[0]) if not is_volatile_column(n)]
    with open(f"{expected_dir}/statistics.csv", "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        for row in rows:
            writer.writerow([row[c] for c in keep])
    print(f"  wrote {expected_dir}/summary.json and statistics.csv "
          f"({len(rows) - 1} rows)")


def compare_csv(report, output, expected_dir, tolerance, ignore=()):
    names, rows = read_csv(f"{output}/statistics.csv")
    expected_names, expected_rows = read_csv(
        f"{expected_dir}/statistics.csv")
    if names != expected_names:
        report.failures.append(
            f"statistics.csv: columns {names}, expected {expected_names}")
        return
    if len(rows) != len(expected_rows):
        report.failures.append(
            f"statistics.csv: {len(rows)} rows, expected {len(expected_rows)}")
        return
    largest = [max([abs(r[c]) for r in expected_rows] + [0.0])
               for c in range(len(names))]
    group_largest = {}
    for c, name in enumerate(names):
        group = column_group(name)
        group_largest[group] = max(group_largest.get(group, 0.0), largest[c])
    for c, name in enumerate(names):
        if name in ignore:
            continue
        scale = max(largest[c], FLOOR * group_largest[column_group(name)],
                    1e-300)
        for row, expected in zip(rows, expected_rows):
            where = f"statistics.csv {name} at step {expected[0]:.0f}"
            if name == "dt" and expected[0] == expected_rows[-1][0]:
                continue
            if name in EXACT_COLUMNS:
                report.exact(where, row[c], expected[c])
            else:
                report.number(where, row[c], expected[c], scale, tolerance)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the run's output directory")
    parser.add_argument("expected", help="directory of the expected files")
    parser.add_argument("--tolerance", type=float,
                        help="relative tolerance (see the module doc)")
    parser.add_argument("--ignore", action="append", default=[],
                        help="a summary entry (dotted path) or statistics "
                        "column not to compare")
    parser.add_argument("--update", action="store_true",
                        help="store the run's files as the expected ones")
    args = parser.parse_args()
    if args.update:
        update(args.output, args.expected)
        return 0
    if args.tolerance is None:
        parser.error("--tolerance is required")

    report = Report()
    with open(f"{args.output}/summary.json") as f:
        summary = json.load(f)
    with open(f"{args.expected}/summary.json") as f:
        expected = json.load(f)
    compare_json(report, "", summary, expected, args.tolerance, 0.0,
                 set(args.ignore))
    compare_csv(report, args.output, args.expected, args.tolerance,
                set(args.ignore))

    report.worst.sort(key=lambda w: -w[0])
    print(f"  {len(report.worst)} numbers compared with tolerance "
          f"{args.tolerance:.1e}; largest scaled differences:")
    for diff, where, value, expected in report.worst[:5]:
        print(f"    {diff:.3e}  {where}: {value:.17g} (expected {expected:.17g})")
    for failure in report.failures:
        print("  FAIL: " + failure)
    if report.failures:
        print(f"  {len(report.failures)} difference(s) beyond the tolerance;"
              " if the change is intended, regenerate the expected files"
              " with tools/update_regression.sh and say why in the commit.")
        return 1
    print("  ok: the run matches the expected files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
