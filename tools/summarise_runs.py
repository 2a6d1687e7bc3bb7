#!/usr/bin/python3
"""One Markdown table row per run directory: what a collapse ended with.

From each run's summary.json (steps, end time, wall time, the cliff
diagnostics) and statistics.csv (the peak kinetic energy of the last stage,
the transfer and plastic dissipation at the end):

  tools/summarise_runs.py LABEL=DIR [LABEL=DIR ...]

Columns: steps, end time, wall time, failure onset (after the start of
damage), debris angle, run-out, failed area (before it moved), scarp
retreat, peak kinetic energy, transfer and plastic dissipation. A run that
stopped after its failure has no debris columns ("-").
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_summary import read_summary  # noqa: E402


def cell(value, fmt):
    return "-" if value is None else format(value, fmt)


def main(arguments):
    if not arguments or any("=" not in a for a in arguments):
        sys.exit(__doc__)
    print("| run | steps | end [s] | wall [min] | onset [s] | angle [deg] | "
          "run-out [m] | failed area [m^2] (before it moved) | retreat [m] | "
          "peak E_kin [J] | transfer dissipation [MJ] | plastic [MJ] |")
    print("|---" * 12 + "|")
    for argument in arguments:
        label, directory = argument.rsplit("=", 1)
        summary = read_summary(directory)
        cliff = summary.get("cliff", {})
        with open(f"{directory}/statistics.csv") as f:
            rows = list(csv.DictReader(f))
        last_stage = rows[-1]["stage"]
        peak = max(float(r["kinetic_energy"]) for r in rows
                   if r["stage"] == last_stage)
        area = cliff.get("failed_area_m2")
        before = cliff.get("failed_reference_area_m2")
        area_text = "-" if area is None else (
            f"{area:.2f}" + ("" if before is None else f" ({before:.2f})"))
        print(f"| {label} | {summary['steps']} | {summary['time']:.2f} | "
              f"{summary['wall_time'] / 60:.1f} | "
              f"{cell(cliff.get('failure_onset_s'), '.3f')} | "
              f"{cell(cliff.get('debris_angle_deg'), '.1f')} | "
              f"{cell(cliff.get('run_out_m'), '.2f')} | {area_text} | "
              f"{cell(cliff.get('scarp_retreat_m'), '.2f')} | {peak:.3g} | "
              f"{float(rows[-1]['transfer_dissipation']) / 1e6:.3f} | "
              f"{float(rows[-1]['plastic_dissipation']) / 1e6:.3f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
