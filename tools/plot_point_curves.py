#!/usr/bin/env python3
"""Plot stress-strain curves written by scarp_point_driver.

For every CSV given, writes <output-dir>/<name>.png with the main stress
component against the path strain (compression paths are drawn with
compression positive) and the damage on a second axis, and prints the peak
stress and the dissipated energies.

Usage: python3 tools/plot_point_curves.py [--output-dir DIR] file.csv ...
Needs python3-matplotlib (Debian package).
"""

import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--output-dir", default=".")
    args = parser.parse_args()
    os.makedirs(args.output_dir, exist_ok=True)

    for path in args.csv:
        data = read(path)
        name = os.path.splitext(os.path.basename(path))[0]
        # The component that carries the load: largest excursion.
        comps = ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy"]
        comp = max(comps, key=lambda c: max(abs(v - data[c][0])
                                            for v in data[c]))
        strain = data["strain"]
        sign = -1.0 if strain[-1] < 0.0 else 1.0
        x = [sign * e for e in strain]
        y = [sign * s / 1e3 for s in data[comp]]

        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(x, y, color="tab:blue", label=comp)
        ax.set_xlabel(("-" if sign < 0 else "") +
                      ("shear gamma" if comp == "sigma_xy"
                       else "log strain") + " [-]")
        ax.set_ylabel(("-" if sign < 0 else "") + comp + " [kPa]",
                      color="tab:blue")
        ax.grid(True, alpha=0.3)
        if max(data["damage"]) > 0.0:
            ax2 = ax.twinx()
            ax2.plot(x, data["damage"], color="tab:red", ls="--")
            ax2.set_ylabel("damage d [-]", color="tab:red")
            ax2.set_ylim(0.0, 1.05)
        title = (f"{name}: peak {max(y):.4g} kPa, dissipated "
                 f"{data['damage_dissipation'][-1]:.3g} (damage) + "
                 f"{data['plastic_dissipation'][-1]:.3g} (plastic) J/m^3")
        ax.set_title(title, fontsize=8)
        fig.tight_layout()
        out = os.path.join(args.output_dir, name + ".png")
        fig.savefig(out, dpi=120)
        plt.close(fig)
        print(f"{out}: peak {comp} {max(y):.6g} kPa, damage dissipation "
              f"{data['damage_dissipation'][-1]:.6g} J/m^3, plastic "
              f"dissipation {data['plastic_dissipation'][-1]:.6g} J/m^3, "
              f"external work {data['external_work'][-1]:.6g} J/m^3")


if __name__ == "__main__":
    main()
