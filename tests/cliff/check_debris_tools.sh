#!/usr/bin/env bash
# tools/debris_bulking.py, tools/plot_snapshots.py and
# tools/debris_separation.py (the table and figure
# tools of doc/joss_bay.md) on hand-made particle outputs of known values
# (tests/cliff/synthetic_particles.py writes them as scarp does, two pieces
# per output as from two ranks). The expected numbers are exact sums of the
# values below, printed to their digits (none lies on a rounding boundary):
#
# debris_bulking.py, last output: 4 points at rest (F = I, V0 = 1), 2 moved
#   1 m with F = diag(2, 1) (det F = 2, V0 = 0.25 each), 1 moved 1.41 m with
#   F = [[1.3, 0.3], [0.1, 1]] (det F = 1.27, V0 = 1): area before 5.5, now
#   6.27, bulking 1.140, largest det F 2.00, the area gained in det F > 1.5
#   0.5 of 0.77 (65 %); with --moved 0.5 only the 3 moved points: 1.5,
#   2.27, 1.513, 65 %; --time 0.1 takes the first output (F = I): 1.000.
#   Where the mass lies (tools/deposit_measures.py): the V0-weighted
#   centroid along x of the last output is 9.75 / 5.5 = 1.773 m (2.500 m
#   for the moved points); the quantiles are checked on five unit volumes
#   at x = 0..4: the 60 % point is x = 2 (exactly 3 of 5 held there), the
#   61 % point x = 3, the 95 % point x = 4.
# plot_snapshots.py: onset at t = 2 s (collapse from 0.5 s, onset 1.5 s
#   after it; for run b from the end of the stage before, as summaries
#   without stage start times give it); outputs at t = 1, 2.9, 3.2, 4 s;
#   "@1" takes the output nearest t = 3 (2.9 s, 0.90 s after the onset),
#   "@end" the last; the kinetic energy of masses 2 and 1 at speeds 5 and
#   0.4 m/s is 25.08 J at 2.9 s and 6.33 J at 4 s (one point faster than
#   0.5 m/s); the points lie in one row (no extent in y); a run without a
#   failure onset is refused. With --bands 0.5 the energy at 2.9 s splits
#   into 25 J at x = 0 (99.7 %, undamaged) and 0.08 J at x = 1 (0.3 %, all
#   of it on the fully damaged point).
# debris_separation.py: finest cell h = 1, onset t = 2 s, one output at
#   t = 3 s. Points (x; damage; speed; mass; J): A (0; 1; 0; 1; 1),
#   B (0.5; 1; 0; 1; 2), C (5; 1; 1 m/s; 2; 4, from (1, 2)), D (6.5; 0.5;
#   0.2; 1; 1), E (10; 1; 0.6; 1; 1, from (3, 4)). Fully damaged A B C E,
#   moving C E; nearest other point over h: 0.5, 0.5, 1.5 (D), 3.5 (D,
#   beyond the buckets' reach of 2 h). J median 1.5, 90 % 3.4 (numpy's
#   linear percentile of 1 1 2 4); nn/h median 1.0, 90 % 2.9; loose (beyond one
#   cell) C E: 50 % of the fully damaged, 100 % of the moving; kinetic
#   energy 1 + 0.02 + 0.18 = 1.2 J, 1.18 of it on C E (98.3 %). Loose
#   moving C E: from x 1, 3 (10/50/90 %: 1.2/2.0/2.8), y 2, 4
#   (2.2/3.0/3.8), at x 5, 10 (5.5/7.5/9.5), y 0; J 4, 1 (median 2.5,
#   90 % 3.7); speed 1, 0.6 (0.8, 0.96). No output 3 s after the onset; a
#   run without a finest cell refused.
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"

/usr/bin/python3 - "$src" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(sys.argv[1], "tests", "cliff"))
from synthetic_particles import write_run

def point(x, y, x0, y0, v0, f=(1, 0, 0, 1), vel=(0, 0), mass=1.0, d=0.0):
    return {"x": x, "y": y, "reference_position_0": x0,
            "reference_position_1": y0, "reference_position_2": 0.0,
            "reference_volume": v0, "F_00": f[0], "F_01": f[1],
            "F_10": f[2], "F_11": f[3], "velocity_0": vel[0],
            "velocity_1": vel[1], "velocity_2": 0.0, "mass": mass,
            "damage": d}

rest = [point(i, 0, i, 0, 1.0) for i in range(4)]
start = [point(0, 1, 0, 1, 0.25), point(1, 1, 1, 1, 0.25),
         point(2, 1, 2, 1, 1.0)]
moved = [point(1, 1, 0, 1, 0.25, (2, 0, 0, 1), d=1),
         point(2, 1, 1, 1, 0.25, (2, 0, 0, 1), d=1),
         point(3, 2, 2, 1, 1.0, (1.3, 0.3, 0.1, 1), d=0.5)]
write_run("col", [(0.0, [rest, start]), (1.0, [rest[:2], rest[2:] + moved])])
with open("col/summary.json", "w") as f:
    json.dump({"stages": {"collapse": {"end_reason": "kinetic energy settled"}}}, f)

def snapshot(speed_scale):
    return [[point(0, 0, 0, 0, 1.0, vel=(3 * speed_scale, 4 * speed_scale), mass=2)],
            [point(1, 0, 1, 0, 1.0, vel=(0, 0.4), d=1)]]
outputs = [(t, snapshot(s)) for t, s in ((1.0, 0), (2.9, 1), (3.2, 2), (4.0, 0.5))]
for name in "abc":
    write_run(name, outputs)
gravity = {"start_time": 0, "end_time": 0.5}
summaries = {
    "a": {"stages": {"gravity": gravity, "collapse": {"start_time": 0.5}},
          "cliff": {"failure_onset_s": 1.5}},
    "b": {"stages": {"gravity": {"end_time": 0.5}, "collapse": {}},
          "cliff": {"failure_onset_s": 1.5}},
    "c": {"stages": {"gravity": gravity, "collapse": {"start_time": 0.5}},
          "cliff": {}}}
for name, s in summaries.items():
    with open(f"{name}/summary.json", "w") as f:
        json.dump(s, f)

sep = [[point(0, 0, 0, 0, 1.0, d=1), point(0.5, 0, 0.5, 0, 1.0, (2, 0, 0, 1), d=1),
        point(5, 0, 1, 2, 1.0, (4, 0, 0, 1), vel=(1, 0), mass=2, d=1)],
       [point(6.5, 0, 6.5, 0, 1.0, vel=(0, 0.2), d=0.5),
        point(10, 0, 3, 4, 1.0, vel=(0, 0.6), d=1)]]
for name in ("sep", "sep_no_cell"):
    write_run(name, [(3.0, sep)])
    s = dict(summaries["a"])
    if name == "sep":
        s["refinement"] = {"finest_cell": 1.0}
    with open(f"{name}/summary.json", "w") as f:
        json.dump(s, f)
PY

fail() { echo "FAIL: $1"; exit 1; }
expect() { # output, fixed string, what
  echo "$1" | grep -qF -- "$2" || fail "$3: expected '$2'"
}

out=$(/usr/bin/python3 "$src/tools/debris_bulking.py" --output bulking.png col)
echo "$out"
expect "$out" "| col | 1.00 s | kinetic energy settled | 7 | 5.500, 6.270 | 1.140 | 2.00 | 65 % | 3.00, 2.00 |" "all points"
expect "$out" "| 3.00, 2.00 | 1.773, 3.00, 3.00 |" "all points: mass centroid"
head -c 8 bulking.png | grep -q PNG || fail "no PNG written"
q=$(/usr/bin/python3 -c "
import sys; sys.path.insert(0, '$src/tools')
from deposit_measures import mass_centroid_x, mass_quantile_x
xs, v = [4, 0, 3, 1, 2], [1.0] * 5
print(mass_centroid_x(xs, v), *(mass_quantile_x(xs, v, f) for f in (0.6, 0.61, 0.95)))")
[ "$q" = "2.0 2 3 4" ] || fail "mass centroid and quantiles of five unit volumes: got '$q'"
out=$(/usr/bin/python3 "$src/tools/debris_bulking.py" --moved 0.5 col)
echo "$out"
expect "$out" "| col | 1.00 s | kinetic energy settled | 3 | 1.500, 2.270 | 1.513 | 2.00 | 65 % |" "--moved 0.5"
expect "$out" "| 3.00, 2.00 | 2.500, 3.00, 3.00 |" "--moved 0.5: mass centroid"
out=$(/usr/bin/python3 "$src/tools/debris_bulking.py" --time 0.1 col)
echo "$out"
expect "$out" "| col | 0.00 s | kinetic energy settled | 7 | 5.500, 5.500 | 1.000 | 1.00 | 0 % |" "--time 0.1"

out=$(/usr/bin/python3 "$src/tools/plot_snapshots.py" --output snapshots.png \
        "A=a@1" "B=b@end")
echo "$out"
expect "$out" "| A | particles_00001.pvtu | 2.90 s | 0.90 s | 25.1 J | 1 (2) |" "A@1"
expect "$out" "| B | particles_00003.pvtu | 4.00 s | 2.00 s | 6.33 J | 1 (2) |" "B@end"
head -c 8 snapshots.png | grep -q PNG || fail "no PNG written"
out=$(/usr/bin/python3 "$src/tools/plot_snapshots.py" --output bands.png \
        --bands 0.5 "A=a@1")
echo "$out"
expect "$out" "| A | x < 0.5 m | 25 J | 99.7 % | 0 J |" "--bands, first band"
expect "$out" "| A | 0.5 m <= x | 0.08 J | 0.3 % | 0.08 J |" "--bands, last band"
if /usr/bin/python3 "$src/tools/plot_snapshots.py" --output bad.png \
     --bands 0.5,x "A=a@1" > bad.out 2>&1; then
  fail "--bands with a non-number was accepted"
fi
grep -q "expected numbers" bad.out || { cat bad.out; fail "--bands message"; }
if /usr/bin/python3 "$src/tools/plot_snapshots.py" --output c.png "C=c@1" > c.out 2>&1; then
  fail "a run without a failure onset was accepted"
fi
grep -q "no failure onset" c.out || { cat c.out; fail "message"; }
[ ! -e c.png ] || fail "c.png written for a refused run"

out=$(/usr/bin/python3 "$src/tools/debris_separation.py" --after-onset 1,3 "S=sep")
echo "$out"
expect "$out" "| S | 1.0 s (1.00 s) | 1 | 4 (2) | 1.50, 3.40 | 1.00, 2.90 | 50.0 %, 100.0 % | 98.3 % (1.2 J) |" "separation table"
expect "$out" "| S | 3.0 s | no output within 0.3 s |" "no output 3 s after the onset"
expect "$out" "| S | 1.0 s | 2 | 1.2/2.0/2.8; 2.2/3.0/3.8 | 5.5/7.5/9.5; 0.0/0.0/0.0 | 2.5/3.7 | 0.8/1.0 |" "loose moving points"
if /usr/bin/python3 "$src/tools/debris_separation.py" "S=sep_no_cell" > nc.out 2>&1; then
  fail "a run without a finest cell was accepted"
fi
grep -q "no refinement/finest_cell" nc.out || { cat nc.out; fail "finest cell message"; }
echo "ok"
