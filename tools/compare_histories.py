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

Example:
  compare_histories.py "L2=output/joss_bay_refined/L2_rg1e-2_seeded_ui10" \\
      "L3=output/joss_bay_refined/L3_rg1e-2_seeded_ui10@4.53"
"""

import argparse
import bisect
import csv
import json
import os


def onset_time(directory):
    """Absolute time of the failure onset from summary.json."""
    summary = json.load(open(os.path.join(directory, "summary.json")))
    after = summary["cliff"]["failure_onset_s"]
    stages = summary["stages"]
    names = list(stages)
    start = stages[names[names.index("collapse") - 1]]["end_time"] \
        if "collapse" in names and names.index("collapse") > 0 else 0.0
    return start + after


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--times", default="0.25,0.5,1,1.5,2,3,4,5",
                        help="times after the onset [s], comma-separated")
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR[@ONSET]")
    args = parser.parse_args()
    times = [float(t) for t in args.times.split(",")]

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
