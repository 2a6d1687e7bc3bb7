#!/usr/bin/env bash
# Quick test of F-bar against volumetric locking (doc/examples.md, section
# 3; doc/stability.md): the undrained Prandtl footing (phi = psi = 0,
# isochoric plastic flow) at cells of 0.1 m, pushed to 0.9 % of B, with
# Transfer/Volumetric averaging = F-bar (argument fbar: no locking) or none
# (argument none: it locks). Arguments: scarp, source dir, run dir,
# mpiexec, mpi flags, fbar | none.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"; variant="$6"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
scene=prandtl_footing_undrained_h10
[ "$variant" = fbar ] && scene=prandtl_footing_undrained_fbar_h10
"$scarp" "$src/tests/examples/$scene.prm" > run.log 2>&1 || {
  echo "FAIL: $scene failed"; tail -5 run.log; exit 1; }
/usr/bin/python3 "$src/tools/examples/footing_load.py" $scene --velocity 0.02 \
  --phi 0 --cell-size 0.1 > load.txt || { echo "FAIL: footing_load.py"; exit 1; }
/usr/bin/python3 - "$variant" $scene <<'PY'
import csv, math, sys
variant, scene = sys.argv[1], sys.argv[2]
c, half_width, v, B = 10e3, 0.5, 0.02, 1.0
q_u = (math.pi + 2) * c                   # 51.4 kPa
values = dict(l.split(" = ") for l in open("load.txt").read().splitlines())
rows = list(csv.DictReader(open(scene + "/statistics.csv")))[1:]
# The plateau window of doc/examples.md, 0.4 % to 0.9 % of B.
q = [float(r["reaction_y"]) / half_width for r in rows
     if 0.004 <= v * float(r["time"]) / B <= 0.009]
mean = sum(q) / len(q)
ratio, rise = mean / q_u, (q[-1] - q[0]) / mean
spread = float(values["pressure_spread_in_cell_under_footing_median"])
print("%s: q/q_u = %.4f over 0.4-0.9 %% of B (%d rows), rise over the window "
      "%+.4f, pressure spread within a cell under the footing %.4g Pa"
      % (variant, ratio, len(q), rise, spread))
# Measured (doc/examples.md): F-bar 1.089, falling by 1 % over the window,
# spread 0.7 mPa (the float precision of the VTU stress: one pressure per
# cell); none 1.326, rising by 7 %, spread 78 kPa.
if variant == "fbar":
    # F-bar's excess is the discretisation error of 5 cells under the half
    # footing: it falls to 1.030 at cells of 0.05 m; the footing's last
    # node at x = B/2 drags half a cell beyond the footing (up to h/B =
    # 10 % here). The band 1 +- 0.12 holds it with 3 % to spare and
    # excludes the locked value (1.33) by far; a plateau: the load changes
    # by less than 3 % over the window.
    ok = abs(ratio - 1) <= 0.12 and abs(rise) < 0.03 and spread < 100
else:
    # Without F-bar it locks: above the band, still rising, pressures
    # scattered within cells (this half would notice an F-bar that is always
    # on, or locking that went away for another reason).
    ok = ratio > 1.2 and rise > 0.05 and spread > 20e3
print("prandtl footing undrained (%s): %s"
      % (variant, "all checks passed" if ok else "FAIL"))
sys.exit(0 if ok else 1)
PY
