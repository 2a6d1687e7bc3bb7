#!/usr/bin/python3
"""Compare the damage history of runs at different resolutions.

Reads statistics.csv of each run directory (columns time, stage,
damaged_volume = sum of d V0 over the points [m^3 per m of cliff],
max_speed) and draws the damaged volume against the time since the start of
the first stage with damage (the stage column changes there), less its
value there (the pre-damaged crack), with the
failure onset (the first row whose max_speed exceeds --failure-speed) marked.
Prints the damaged volume at a few times and each run's onset.

Usage:
  plot_damage_history.py --output doc/figures/joss_bay/damage_history.png \\
      LABEL=DIR [LABEL=DIR ...]
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(directory, failure_speed):
    name = f"{directory}/statistics.csv"
    try:
        rows = list(csv.DictReader(open(name, newline="")))
    except OSError as e:
        sys.exit(f"{name}: {e.strerror}")
    stages = [r["stage"] for r in rows]
    start_stage = stages[-1]
    first = next(k for k, r in enumerate(rows) if r["stage"] == start_stage)
    t0 = float(rows[first - 1]["time"]) if first > 0 else 0.0
    t = [float(r["time"]) - t0 for r in rows[first:]]
    # Minus the value at the start: the pre-damaged crack (one cell wide,
    # so its volume halves with h) is not part of the creep.
    v0 = float(rows[first]["damaged_volume"])
    v = [float(r["damaged_volume"]) - v0 for r in rows[first:]]
    onset = next((float(r["time"]) - t0 for r in rows[first:]
                  if float(r["max_speed"]) > failure_speed), None)
    return t, v, onset


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", metavar="LABEL=DIR")
    parser.add_argument("--failure-speed", type=float, default=0.1)
    parser.add_argument("--times", type=float, nargs="+",
                        default=[0.5, 1, 2, 3, 4])
    parser.add_argument("--output", required=True)
    args = parser.parse_args()

    fig, (ax, zoom) = plt.subplots(1, 2, figsize=(10, 4))
    print("| t since collapse start [s] | "
          + " | ".join(r.partition("=")[0] for r in args.runs) + " |")
    print("|" + "---|" * (len(args.runs) + 1))
    data = []
    for item in args.runs:
        label, _, directory = item.partition("=")
        t, v, onset = read(directory, args.failure_speed)
        data.append((label, t, v, onset))
        line, = ax.plot(t, v, label=label)
        zoom.plot(t, v, label=label, color=line.get_color())
        if onset is not None:
            ax.axvline(onset, ls=":", color=line.get_color())
    for time in args.times:
        cells = []
        for _, t, v, _ in data:
            k = next((k for k, x in enumerate(t) if x >= time), None)
            cells.append(f"{v[k]:.2f}" if k is not None else "-")
        print(f"| {time:g} | " + " | ".join(cells) + " |")
    print("| damage grown > 0.01 m^3/m from [s] | " + " | ".join(
        next((f"{x:.2f}" for x, y in zip(d[1], d[2]) if y > 0.01), "-")
        for d in data) + " |")
    print("| failure onset [s] | " + " | ".join(
        f"{d[3]:.2f}" if d[3] is not None else f"> {d[1][-1]:.2f}"
        for d in data) + " |")
    ax.set_xlabel("time since the start of the collapse stage [s]")
    ax.set_ylabel("damage grown, sum d V0 - crack [m^3/m]")
    ax.set_title("damage creep before failure (dotted: failure onset)",
                 fontsize=9)
    ax.legend(fontsize=8)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    # The right panel: up to the end of the shortest run.
    t_end = min(d[1][-1] for d in data)
    v_end = max((y for d in data for x, y in zip(d[1], d[2]) if x <= t_end),
                default=1.0)
    zoom.set_xlim(0, t_end)
    zoom.set_ylim(0, 1.05 * v_end if v_end > 0 else 1.0)
    zoom.set_xlabel("time since the start of the collapse stage [s]")
    zoom.set_title(f"up to the end of the shortest run ({t_end:.2f} s)",
                   fontsize=9)
    zoom.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=150)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
