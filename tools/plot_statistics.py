#!/usr/bin/python3
"""Plot the energy history of a scarp run from its statistics.csv.

Usage: plot_statistics.py OUTPUT_DIR [--output FILE]

Writes OUTPUT_DIR/energies.png (unless --output is given): kinetic, strain,
change of gravitational energy, internal work, damping, plastic and damage
dissipation, and the energy balance residual, all against time.
Uses the Debian package python3-matplotlib, hence /usr/bin/python3.
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", help="output directory of a run")
    parser.add_argument("--output", help="PNG file to write")
    args = parser.parse_args()
    with open(os.path.join(args.directory, "statistics.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit("statistics.csv has no rows")
    col = {k: [float(r[k]) for r in rows] for k in rows[0]}
    t = col["time"]
    g0 = col["gravitational_energy"][0]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    series = [
        ("kinetic_energy", "kinetic", None),
        ("strain_energy", "strain", None),
        ("internal_work", "internal work", None),
        ("damping_dissipation", "damping", None),
        ("boundary_dissipation", "boundary (friction)", None),
        ("transfer_dissipation", "transfer (PIC share)", None),
        ("plastic_dissipation", "plastic dissipation", None),
        ("damage_dissipation", "damage dissipation", None),
        ("energy_residual", "balance residual", None),
    ]
    ax.plot(t, [g0 - g for g in col["gravitational_energy"]],
            label="gravitational energy released", color="k", lw=1.5)
    for key, label, _ in series:
        if key in col:  # statistics of older runs lack the transfer column
            ax.plot(t, col[key], label=label, lw=1)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J per m thickness in 2D]")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_title(os.path.basename(os.path.normpath(args.directory)))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    out = args.output or os.path.join(args.directory, "energies.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
