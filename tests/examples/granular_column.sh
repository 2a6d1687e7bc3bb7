#!/usr/bin/env bash
# Quick test of the granular column collapse example
# (prm/examples/granular_column_collapse.prm, doc/examples.md) at cells of
# 10 mm: runs it to rest and checks the deposit. Arguments: scarp, source
# dir, run dir, mpiexec, mpi flags.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
"$scarp" "$src/tests/examples/granular_column_h10.prm" > run.log 2>&1 || {
  echo "FAIL: the run failed"; tail -5 run.log; exit 1; }
/usr/bin/python3 "$src/tools/examples/column_profile.py" granular_column_h10 > profile.txt || exit 1
cat profile.txt
/usr/bin/python3 - profile.txt <<'PY'
import math, sys
v = {k: float(x) for k, x in (l.split(" = ") for l in open(sys.argv[1]) if " = " in l)}
phi = 19.8
failures = []
# 1. A cohesionless Mohr-Coulomb slope at rest cannot stand steeper than phi
#    (limit equilibrium of an infinite slope, exact). The measured angle is
#    a line through bin tops 10 mm wide: 0.5 deg of slack for that.
if not v["surface_angle_deg"] <= phi + 0.5:
    failures.append("deposit surface %.2f deg steeper than phi = %.1f deg" % (v["surface_angle_deg"], phi))
# 2. Hence the run-out is at least that of the steepest deposit that holds
#    the column's area (no volume change: psi = 0): a plateau at H0 and a
#    slope at phi, (L_f - L0)/L0 >= H0 / (2 L0 tan phi) = 0.694.
bound = v["H0"] / (2 * v["L0"] * math.tan(math.radians(phi)))
if not v["runout_ratio"] >= bound - 1e-9:
    failures.append("run-out ratio %.3f below the static bound %.3f" % (v["runout_ratio"], bound))
# 3. The number doc/examples.md gives for this resolution, (L_f - L0)/L0 =
#    1.00, to one bin of the run-out measure (10 mm = 0.05 L0): the run-out
#    is a count of occupied bins. (The 2D scaling law of Lube et al. 2005
#    says 1.2 a = 0.6; scarp's run-out is longer, doc/examples.md.)
if not abs(v["runout_ratio"] - 1.00) <= 0.05 + 1e-9:
    failures.append("run-out ratio %.3f, doc/examples.md: 1.00 +- 0.05" % v["runout_ratio"])
# 4. The top of the column behind the failure line does not move: H_f = H0
#    to half a point spacing.
if not abs(v["H_f"] - v["H0"]) <= 0.0025:
    failures.append("final height %.4f m, expected H0 = %.4f m" % (v["H_f"], v["H0"]))
for f in failures:
    print("FAIL: " + f)
print("granular column: %s" % ("all checks passed" if not failures else "%d failures" % len(failures)))
sys.exit(1 if failures else 0)
PY
