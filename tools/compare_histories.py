#!/usr/bin/env python3
"""Compare runs at the same times after their failure onsets.

Reads statistics.csv of each run directory and prints, at the given times
after each run's failure onset, its kinetic energy, largest point speed and
damaged volume (the row at or just after that time), so that a run still
under way can be set beside a finished one of another level.

The onset is taken from summary.json ("cliff": "failure_onset_s", after
the start of the collapse stage, whose start is the end of the stage
before); a run still under way has no summary.json yet: give the onset time
t (from its log line "Cliff: failure onset at t = ...") after an "@".

With --deposit it reads cliff_history.csv instead (a row per particle
output) and prints the deposit: scarp retreat, run-out, failed area, the
same points' area before they moved, and the ratio of the two (the
bulking of the failed mass), and, where the history has them (runs since
2026-12-07), the centroid of the failed mass and the x left of which 95
and 99 % of it lie; --rates A,B adds the least-squares rates of
scarp retreat and of the failed area before it moved (the pace of the
progressive failure) over A to B seconds after the onset.

Example:
  compare_histories.py "L2=output/joss_bay_refined/L2_rg1e-2_seeded_ui10" \\
      "L3=output/joss_bay_refined/L3_rg1e-2_seeded_ui10@4.53"
  compare_histories.py --deposit --times 2,6,10 --rates 3,10 "L2=..." "L3=..."
"""

import argparse
import bisect
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_summary import onset_time  # noqa: E402


# Where the failed mass lies (cliff diagnostics, doc/scenes.md); histories
# written before these columns existed lack them.
MASS_COLUMNS = ("failed_mass_centroid", "failed_mass_x95", "failed_mass_x99")


def slope(xs, ys):
    """Least-squares slope of ys over xs."""
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return (sum((x - mx) * (y - my) for x, y in zip(xs, ys)) /
            sum((x - mx) ** 2 for x in xs))


def compare_deposits(args, times):
    """The deposit columns of cliff_history.csv at the times after each
    run's onset (the row nearest to it; rows come every particle
    output)."""
    runs = []
    for item in args.runs:
        label, rest = item.rsplit("=", 1)
        directory, _, given = rest.partition("@")
        onset = float(given) if given else onset_time(directory)
        rows = [r for r in csv.DictReader(open(os.path.join(
            directory, "cliff_history.csv"))) if r["scarp_retreat"] != "nan"]
        data = [(float(r["time"]) - onset, float(r["scarp_retreat"]),
                 float(r["run_out"]), float(r["failed_area"]),
                 float(r["failed_reference_area"]),
                 tuple(float(r.get(k) or "nan") for k in MASS_COLUMNS))
                for r in rows]
        runs.append((label, onset, data))
    print("| time after the onset | " + " | ".join(
        f"{label}: scarp retreat [m], run-out [m], failed area (before it "
        "moved) [m^2], bulking[; failed mass centroid, 95, 99 % x [m]]"
        for label, _, _ in runs) + " |")
    print("|---" * (len(runs) + 1) + "|")
    for dt in times:
        cells = []
        for _, _, data in runs:
            if not data or dt > data[-1][0] + 0.25:
                cells.append("(not reached)")
                continue
            t, retreat, run_out, area, before, mass = min(
                data, key=lambda d: abs(d[0] - dt))
            masses = ("" if any(math.isnan(m) for m in mass) else
                      "; " + ", ".join(f"{m:.2f}" for m in mass))
            cells.append(f"{retreat:.2f}, {run_out:.2f}, {area:.1f} "
                         f"({before:.1f}), {area / before:.2f}{masses} "
                         f"[{t:.2f} s]")
        print(f"| {dt:g} s | " + " | ".join(cells) + " |")
    if args.rates:
        a, b = (float(x) for x in args.rates.split(","))
        for label, _, data in runs:
            window = [d for d in data if a <= d[0] <= b]
            if len(window) < 2:
                print(f"{label}: fewer than 2 rows from {a:g} to {b:g} s")
                continue
            ts = [d[0] for d in window]
            print(f"{label}: from {a:g} to {b:g} s after the onset "
                  f"({len(window)} rows): scarp retreat "
                  f"{slope(ts, [d[1] for d in window]):.3f} m/s, failed "
                  "area before it moved "
                  f"{slope(ts, [d[4] for d in window]):.2f} m^2/s")
    for label, onset, data in runs:
        print(f"{label}: onset at t = {onset:.3f} s, last row "
              f"{data[-1][0]:.2f} s after it")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--times", default="0.25,0.5,1,1.5,2,3,4,5",
                        help="times after the onset [s], comma-separated")
    parser.add_argument("--deposit", action="store_true",
                        help="the deposit of cliff_history.csv instead")
    parser.add_argument("--rates", default=None, metavar="A,B",
                        help="with --deposit: rates over A to B s after "
                        "the onset")
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR[@ONSET]")
    args = parser.parse_args()
    times = [float(t) for t in args.times.split(",")]
    if args.deposit:
        compare_deposits(args, times)
        return

    runs = []
    for item in args.runs:
        label, rest = item.rsplit("=", 1)  # labels may hold "="
        directory, _, given = rest.partition("@")
        onset = float(given) if given else onset_time(directory)
        rows = list(csv.DictReader(open(os.path.join(directory,
                                                     "statistics.csv"))))
        data = [(float(r["time"]), float(r["kinetic_energy"]),
                 float(r["max_speed"]), float(r["damaged_volume"]))
                for r in rows]
        runs.append((label, onset, data, [row[0] for row in data]))

    print("| time after the onset | " + " | ".join(
        f"{label}: E_kin [J], max speed [m/s], damaged volume [m^2]"
        for label, _, _, _ in runs) + " |")
    print("|---" * (len(runs) + 1) + "|")
    for dt in times:
        cells = []
        for _, onset, data, row_times in runs:
            i = bisect.bisect_left(row_times, onset + dt)
            if i >= len(data):
                cells.append("(not reached)")
                continue
            _, e, v, dv = data[i]
            cells.append(f"{e:.3g}, {v:.2f}, {dv:.1f}")
        print(f"| {dt:g} s | " + " | ".join(cells) + " |")
    for label, onset, data, _ in runs:
        last = data[-1][0] - onset
        print(f"{label}: onset at t = {onset:.3f} s, last row "
              f"{last:.2f} s after it")


if __name__ == "__main__":
    main()
