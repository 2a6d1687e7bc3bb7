#!/usr/bin/env bash
# Quick test of the 3D column collapse example (prm/examples/
# column_collapse_3d.prm, doc/examples.md) at cells of 20 mm on 2 ranks.
# Arguments: scarp, source dir, run dir, mpiexec, mpi flags.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"; mpiexec="${4:-}"; flags="${5:-}"; flags="${flags//;/ }"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
$mpiexec $flags -np 2 "$scarp" "$src/tests/examples/column_collapse_3d_h20.prm" > run.log 2>&1 || {
  echo "FAIL: the run failed"; tail -5 run.log; exit 1; }
/usr/bin/python3 "$src/tools/examples/column_profile_3d.py" column_collapse_3d_h20 > profile.txt || exit 1
cat profile.txt
/usr/bin/python3 - profile.txt <<'PY'
import sys
v = {k: float(x) for k, x in (l.split(" = ") for l in open(sys.argv[1]) if " = " in l)}
bin_ = 0.04  # two point spacings at 20 mm cells: the resolution of a run-out
failures = []
# The quarter column is symmetric under x <-> z (both symmetry planes slip,
# both far faces free): the run-outs along x and z agree to a bin.
if abs(v["L_f_x"] - v["L_f_z"]) > bin_ + 1e-9:
    failures.append("run-out along x %.3f m and along z %.3f m differ" % (v["L_f_x"], v["L_f_z"]))
# The number doc/examples.md gives at these cells, (L_f - L0)/L0 = 1.4
# along x, to one bin (0.04 m = 0.4 L0 is the width of a bin of the
# measure, which counts occupied bins of two point spacings).
if abs(v["runout_ratio_x"] - 1.4) > 0.4 + 1e-9:
    failures.append("run-out ratio along x %.3f, doc/examples.md: 1.4 +- 0.4" % v["runout_ratio_x"])
# The column has collapsed: its top came down (2D plane strain at a = 1:
# H_f / H0 = 0.76), and no point rose above H0.
if not (v["H_f"] < 0.95 * v["H0"]):
    failures.append("the column did not collapse: H_f = %.4f m" % v["H_f"])
for f in failures:
    print("FAIL: " + f)
print("3D column collapse: %s" % ("all checks passed" if not failures else "%d failures" % len(failures)))
sys.exit(1 if failures else 0)
PY
