#!/usr/bin/env bash
# Quick test of Prandtl's strip footing example (prm/examples/
# prandtl_footing.prm, doc/examples.md) at cells of 0.1 m: the limit load
# from the reaction on the prescribed-velocity footing against Prandtl's
# closed form. Arguments: scarp, source dir, run dir, mpiexec, mpi flags.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
"$scarp" "$src/tests/examples/prandtl_footing_h10.prm" > run.log 2>&1 || {
  echo "FAIL: the run failed"; tail -5 run.log; exit 1; }
/usr/bin/python3 - prandtl_footing_h10/statistics.csv <<'PY'
import csv, math, sys
c, phi, half_width, v = 10e3, 20.0, 0.5, 0.02
t = math.tan(math.radians(phi))
nq = math.exp(math.pi * t) * math.tan(math.radians(45 + phi / 2)) ** 2
nc = (nq - 1) / t                       # 14.835
rows = list(csv.DictReader(open(sys.argv[1])))
# The limit load: the mean footing pressure over settlements of 0.5 % to
# 1 % of B (the test's run ends there; past the peak of the elastic-plastic
# transition, the pressure oscillates by +-2 % about its mean).
q = [float(r["reaction_y"]) / half_width for r in rows[1:]
     if 0.005 <= v * float(r["time"]) / (2 * half_width) <= 0.010]
ratio = sum(q) / len(q) / (c * nc)
print("N_c = %.4f, limit load q/c = %.3f over %d rows, q / (c N_c) = %.4f"
      % (nc, sum(q) / len(q) / c, len(q), ratio))
# Tolerance 25 %, from what the example measures (doc/examples.md): at
# cells of 0.1 m (5 under the half footing) q/(c N_c) = 1.20 over this
# window and 1.19 on the plateau (0.4 to 0.9 % of B); at 0.05 m 1.10 on the
# plateau, so the error halves with h and extrapolates to 1.01. Part of it is the footing's edge: the last prescribed node at
# x = B/2 carries half a cell beyond it (up to h/B = 10 % here). A
# reaction off by a factor (the whole footing instead of half, the damping
# force counted, a missing dt) or a strength parameter not honoured
# (c off by 30 %) leaves the band.
ok = abs(ratio - 1) <= 0.25
# The smooth footing: no tangential reaction.
ok = ok and all(float(r["reaction_x"]) == 0.0 for r in rows)
print("prandtl footing: " + ("all checks passed" if ok else "FAIL"))
sys.exit(0 if ok else 1)
PY
