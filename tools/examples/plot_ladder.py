#!/usr/bin/env python3
"""Run-out ratio against aspect ratio from column_ladder.csv, with the 2D
scaling law of Lube et al. (2005): (L_f - L0)/L0 = 1.2 a (a < 1.8),
1.9 a^(2/3) (a > 2.8).

    plot_ladder.py column_ladder.csv OUT.png [extra.csv ...]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

rows = list(csv.DictReader(open(sys.argv[1])))
a = [float(r["a"]) for r in rows]
r = [float(r["runout_ratio"]) for r in rows]
fig, ax = plt.subplots(figsize=(5.5, 4))
ax.loglog(a, r, "bo-", label="scarp (cells L0/20, rough floor)")
xs = [0.3 + 0.01 * i for i in range(150)]
ax.loglog([x for x in xs if x < 1.8], [1.2 * x for x in xs if x < 1.8], "k--",
          label="Lube et al. 2005: 1.2 a (a < 1.8)")
ax.loglog([x for x in xs if x > 2.8], [1.9 * x ** (2 / 3) for x in xs if x > 2.8], "k:",
          label="Lube et al. 2005: 1.9 a^(2/3) (a > 2.8)")
ax.set_xlabel("aspect ratio a = H0 / L0")
ax.set_ylabel("(L_f - L0) / L0")
ax.legend(fontsize=8)
ax.grid(alpha=0.3, which="both")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=150)
