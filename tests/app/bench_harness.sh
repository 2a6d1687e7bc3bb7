#!/usr/bin/env bash
# bench/run_bench.py, the benchmark harness of doc/performance.md, on its
# smallest elastic column (size 5: 100 cells of 2x2 points, 400 points; the
# harness fixes the steps at 204), Q1 and GIMP, on 1 and 2 ranks, once
# each. Nothing here is timed or compared with a speed: the test checks that
# the harness runs the scenes it names and reports for each the figures it
# promises, with the counts they must have: 400 points, 204 steps,
# 400 x 204 = 81 600 point-steps, positive wall time and speed, memory
# (where GNU time is installed), a
# figure for every phase and part of the step (the exchange within P2G and
# the grid update), the imbalance of the ranks' compute (1 on one rank, in
# [1, 2) on two), and a 2-rank efficiency line per scene.
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$src"
/usr/bin/python3 bench/run_bench.py --scarp "$scarp" --suite column --sizes 5 \
  --repeat 1 --ranks 1,2 --work "$run/work" --csv "$run/bench.csv" > "$run/bench.log" 2>&1 \
  || { cat "$run/bench.log"; exit 1; }
cat "$run/bench.log"
/usr/bin/python3 - "$run/bench.csv" "$run/bench.log" <<'PY'
import csv, os, sys
rows = list(csv.DictReader(open(sys.argv[1])))
log = open(sys.argv[2]).read()
seen = sorted((r["scene"], int(r["ranks"])) for r in rows)
want = sorted((s, n) for s in ("column_Q1_400", "column_GIMP_400") for n in (1, 2))
assert seen == want, f"runs {seen}, expected {want}"
phases = [k for k in rows[0] if k.startswith("ns ")]
# 6 phases of the run, 5 parts of the step and the exchange in two of them
assert len(phases) == 12, phases
for r in rows:
    what = f'{r["scene"]} on {r["ranks"]} rank(s)'
    assert int(r["points"]) == 400, (what, r["points"])
    assert int(r["steps"]) == 204, (what, r["steps"])
    assert float(r["point_steps"]) == 400 * 204, (what, r["point_steps"])
    for key in ("wall_s", "Mps_per_core", "ns MPM step", "ns P2G", "ns G2P",
                "ns constitutive update"):
        assert float(r[key]) > 0, (what, key, r[key])
    # Peak memory comes from GNU time (Debian package time); without it the
    # harness reports nan.
    if os.path.exists("/usr/bin/time"):
        assert float(r["max_rss_MB"]) > 0 and float(r["bytes_per_point"]) > 0, what
    for key in phases:
        assert float(r[key]) >= 0, (what, key, r[key])
    # The exchange is counted in P2G and the grid update.
    assert float(r["ns exchange"]) <= float(r["ns P2G"]) + float(r["ns grid update"]), what
    # The slowest rank's compute over the mean: 1 on one rank, at least 1
    # on two (the mean of two is at most their largest).
    imbalance = float(r["imbalance"])
    if int(r["ranks"]) == 1:
        assert imbalance == 1.0, (what, imbalance)
    else:
        assert 1.0 <= imbalance < 2.0, (what, imbalance)
for scene in ("column_Q1_400", "column_GIMP_400"):
    assert any(line.startswith(scene) and "np 2:" in line
               for line in log.splitlines()), f"no 2-rank efficiency for {scene}"
print("ok: 4 runs, 400 points, 204 steps, every figure present")
PY
