#!/usr/bin/env bash
# tools/compare_failure_surfaces.py, tools/dilation_classes.py,
# tools/summarise_runs.py, tools/probe_points.py and
# tools/plot_damage_history.py (the tables of the convergence study in
# doc/joss_bay.md and doc/joss_bay/*.md) on hand-made inputs of known
# values. Every expected number is an exact sum or a square root of the
# values below, printed to its digits (none lies on a rounding boundary):
#
# compare_failure_surfaces.py, strips of 0.5 m, snapshots
#   cliff_failure_particles.csv (x, y, damage, x0, y0, volume):
#   run f (the finest, last): damaged (d = 1) points at x0 = 2.0 and 3.0 in
#   strip 0 (y0 = 0.25; the one at 3.0 moved 0.5 m), 2.5 in strip 1, 1.0 in
#   strip 2 (y0 = 1.25, the top: kept, since (2 + 0.5) 0.5 is not above
#   it), each of volume 0.5, and an undamaged point (volume 1): x_f = 2.00,
#   2.50, 1.00; failed area (moved > 0.1 m) 0.5; d >= 0.99 area 2.0.
#   run c: damaged points at 2.3 (strip 0, volume 0.2) and 2.1 (strip 1,
#   volume 0.3, moved 0.2 m), a point of damage 0.95 at 0.5 (strip 2,
#   volume 1, moved 0.05 m: not failed), an undamaged one at the top:
#   x_f = 2.30, 2.10, - ; RMS to f over strips 0 and 1
#   sqrt((0.3^2 + 0.4^2) / 2) = 0.354; with --threshold 0.9 strip 2 holds
#   0.50 and the RMS over three strips is sqrt(0.5 / 3) = 0.408; failed
#   area 0.3; d >= 0.99 area 0.5 (0.9: 1.5).
#   f's summary.json: onset 4.25 s, collapse from 0.2 s, mass scaling ends
#   at 4.28 s (4.08 s after the start), 100 points, 40 cells, finest cell
#   0.06 m, 1234 steps, 90 s (1.5 min); c has none ("-" throughout, not
#   "uniform"). Without --output
#   no figure is drawn; with it, a PNG.
# dilation_classes.py: outputs at t = 1 s (every F = I) and 2 s: points of
#   det F 1, 10 (exactly: not above 10), 20, 200 and 2000, with masses 1,
#   5, 2, 3, 4 and V0 0.5, 0.1, 0.25, 0.1, 0.01, so areas now V0 det F
#   0.5, 1, 5, 20, 20: all 5, 15 kg, 46.5 m^2; above 10: 3, 9, 45.0; above
#   100: 2, 7, 40.0; above 1000: 1, 4, 20.0. --time 1.2 takes the first
#   output: all 5, 15, area 0.96 (the sum of V0, printed 1.0), none
#   above 10.
# summarise_runs.py: steps 100, t = 12.346 s, wall 150 s, onset 4.25 s,
#   angle 42.33, run-out 7.68, areas 61.114 (41.843), retreat 4.1666; the
#   peak kinetic energy of the last stage (5e5 J; the gravity stage's 1e6
#   does not count); transfer and plastic dissipation 195 000 and
#   3 742 000 J at the last row. A run that stopped at its failure: "-"
#   for the debris columns.
# probe_points.py: two outputs (t = 0.5 and 1.5 s) of three points whose
#   reference positions are (0, 0), (1, 0) and (0, 2) and whose damage is
#   0.1, 0.2, 0.3 at the first and 0.4, 0.5, 0.6 at the second; the second
#   output holds them in another order and moved 5 m: the probe at
#   (0.9, 0.2) follows the point of reference (1, 0) (damage 0.2, then 0.5),
#   the one at (0.1, 1.5) that of (0, 2); --every 2 keeps the first output
#   only; a field the output lacks is refused with the fields it has.
# plot_damage_history.py: statistics rows at t = 0..5 s, stage 0 then 1
#   from t = 2 s (so the time counts from t = 1 s, the last row before it),
#   damaged volume 0.5 until then, then 0.504, 0.6, 1.0 (grown by 0, 0.004,
#   0.1, 0.5 from the first row of stage 1, at 1, 2, 3, 4 s since the
#   start), largest speed above 0.1 m/s first at t = 4 s: at 1.5 s since
#   the start 0.00, at 2.5 s 0.10, none at 9 s; grown beyond 0.01 from
#   3.00 s; onset 3.00 s; a run never faster than 0.1 m/s has its onset
#   after its last row ("> 4.00").
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"

/usr/bin/python3 - "$src" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(sys.argv[1], "tests", "cliff"))
from synthetic_particles import write_run

def snapshot(name, rows):
    os.makedirs(name, exist_ok=True)
    with open(f"{name}/cliff_failure_particles.csv", "w") as f:
        f.write("x,y,damage,x0,y0,volume\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")

#          x    y     d     x0   y0    volume
snapshot("f", [(2.0, 0.25, 1, 2.0, 0.25, 0.5), (3.5, 0.25, 1, 3.0, 0.25, 0.5),
               (2.5, 0.75, 1, 2.5, 0.75, 0.5), (1.0, 1.25, 1, 1.0, 1.25, 0.5),
               (0.0, 0.25, 0, 0.0, 0.25, 1.0)])
snapshot("c", [(2.3, 0.25, 1, 2.3, 0.25, 0.2), (2.3, 0.75, 1, 2.1, 0.75, 0.3),
               (0.55, 1.25, 0.95, 0.5, 1.25, 1.0), (0.0, 1.25, 0, 0.0, 1.25, 1.0)])
with open("f/summary.json", "w") as f:
    json.dump({"cliff": {"failure_onset_s": 4.25},
               "stages": {"collapse": {"start_time": 0.2,
                                       "mass_scaling_end_time": 4.28}},
               "material_points": 100, "cells": 40,
               "refinement": {"finest_cell": 0.06}, "steps": 1234,
               "wall_time": 90.0}, f)

def point(f, mass, v0):
    return {"x": 0.0, "y": 0.0, "F_00": f[0], "F_01": f[1], "F_10": f[2],
            "F_11": f[3], "mass": mass, "reference_volume": v0}

masses = [1, 5, 2, 3, 4]
volumes = [0.5, 0.1, 0.25, 0.1, 0.01]
stretched = [(1, 0, 0, 1), (2, 0, 0, 5), (4, 0, 0, 5), (10, 0, 0, 20),
             (40, 0, 0, 50)]
rest = [point((1, 0, 0, 1), m, v) for m, v in zip(masses, volumes)]
now = [point(f, m, v) for f, m, v in zip(stretched, masses, volumes)]
write_run("dil", [(1.0, [rest[:2], rest[2:]]), (2.0, [now[:3], now[3:]])])

def run(name, cliff):
    os.makedirs(name, exist_ok=True)
    with open(f"{name}/summary.json", "w") as f:
        json.dump({"steps": 100, "time": 12.346, "wall_time": 150.0,
                   "cliff": cliff}, f)
    with open(f"{name}/statistics.csv", "w") as f:
        f.write("step,stage,kinetic_energy,transfer_dissipation,"
                "plastic_dissipation\n")
        f.write("10,gravity,1e6,0,0\n50,collapse,5e5,1000,2000\n"
                "100,collapse,20,195000,3742000\n")

run("rest", {"failure_onset_s": 4.25, "debris_angle_deg": 42.33,
             "run_out_m": 7.68, "failed_area_m2": 61.114,
             "failed_reference_area_m2": 41.843, "scarp_retreat_m": 4.1666})
run("onset", {"failure_onset_s": 4.25})

def probe(x0, y0, d, shift):
    return {"x": x0 + shift, "y": y0, "reference_position_0": x0,
            "reference_position_1": y0, "reference_position_2": 0.0,
            "damage": d}

first = [probe(0, 0, 0.1, 0), probe(1, 0, 0.2, 0), probe(0, 2, 0.3, 0)]
second = [probe(0, 2, 0.6, 5), probe(0, 0, 0.4, 5), probe(1, 0, 0.5, 5)]
write_run("probe", [(0.5, [first[:1], first[1:]]), (1.5, [second[:2], second[2:]])])

for name, speeds in (("creep", (0, 0, 0, 0.05, 0.2, 1)),
                     ("slow", (0, 0, 0, 0.05, 0.05, 0.1))):
    os.makedirs(name, exist_ok=True)
    with open(f"{name}/statistics.csv", "w") as f:
        f.write("time,stage,damaged_volume,max_speed\n")
        for t, stage, v, u in zip(range(6), (0, 0, 1, 1, 1, 1),
                                  (0.5, 0.5, 0.5, 0.504, 0.6, 1.0), speeds):
            f.write(f"{t},{stage},{v},{u}\n")
PY

fail() { echo "FAIL: $1"; exit 1; }
expect() { # output, fixed string, what
  echo "$1" | grep -qF -- "$2" || fail "$3: expected '$2'"
}

out=$(/usr/bin/python3 "$src/tools/compare_failure_surfaces.py" \
        "C=c" "F=f" --heights 0.25 0.75 1.25)
echo "$out"
expect "$out" "| 0.25 | 2.30 | 2.00 |" "strip 0"
expect "$out" "| 0.75 | 2.10 | 2.50 |" "strip 1"
expect "$out" "| 1.25 | - | 1.00 |" "strip 2, none damaged in C"
expect "$out" "| failed area [m^2] | 0.3 | 0.5 |" "failed area"
expect "$out" "| d >= 0.99 area [m^2] | 0.5 | 2.0 |" "damaged area"
expect "$out" "| RMS distance to F [m] | 0.35 | 0.00 |" "RMS over two strips"
expect "$out" "| failure onset [s] | - | 4.25 |" "onset"
expect "$out" "| mass scaling ends [s after the collapse starts] | - | 4.08 |" "mass scaling"
expect "$out" "| material points (end), cells | - | 100, 40 |" "size"
expect "$out" "| finest cell [m] | - | 0.06 |" "finest cell"
expect "$out" "| wall time [min] | - | 1.5 |" "wall time"
echo "$out" | grep -q "^wrote" && fail "a figure without --output"
ls ./*.png > /dev/null 2>&1 && fail "a PNG written without --output"
out=$(/usr/bin/python3 "$src/tools/compare_failure_surfaces.py" --threshold 0.9 \
        --output surfaces.png "C=c" "F=f" --heights 0.25 0.75 1.25)
echo "$out"
expect "$out" "| 1.25 | 0.50 | 1.00 |" "--threshold 0.9, strip 2"
expect "$out" "| RMS distance to F [m] | 0.41 | 0.00 |" "--threshold 0.9, RMS over three strips"
expect "$out" "| d >= 0.9 area [m^2] | 1.5 | 2.0 |" "--threshold 0.9, damaged area"
head -c 8 surfaces.png | grep -q PNG || fail "no PNG written"

out=$(/usr/bin/python3 "$src/tools/dilation_classes.py" --thresholds 10,100,1000 "D=dil")
echo "$out"
expect "$out" "| D | 2.00 s | (all) | 5 | 15.0 | 46.5 |" "all points"
expect "$out" "| D | 2.00 s | 10 | 3 | 9.0 | 45.0 |" "above 10 (10 itself not)"
expect "$out" "| D | 2.00 s | 100 | 2 | 7.0 | 40.0 |" "above 100"
expect "$out" "| D | 2.00 s | 1000 | 1 | 4.0 | 20.0 |" "above 1000"
out=$(/usr/bin/python3 "$src/tools/dilation_classes.py" --time 1.2 --thresholds 10 "D=dil")
echo "$out"
expect "$out" "| D | 1.00 s | (all) | 5 | 15.0 | 1.0 |" "--time 1.2: the first output"
expect "$out" "| D | 1.00 s | 10 | 0 | 0.0 | 0.0 |" "--time 1.2: none stretched"

out=$(/usr/bin/python3 "$src/tools/summarise_runs.py" "R=rest" "O=onset")
echo "$out"
expect "$out" "| R | 100 | 12.35 | 2.5 | 4.250 | 42.3 | 7.68 | 61.11 (41.84) | 4.17 | 5e+05 | 0.195 | 3.742 |" "a run to rest"
expect "$out" "| O | 100 | 12.35 | 2.5 | 4.250 | - | - | - | - | 5e+05 | 0.195 | 3.742 |" "a run stopped at its failure"
if /usr/bin/python3 "$src/tools/summarise_runs.py" "N=none" > none.out 2>&1; then
  fail "a run without summary.json was accepted"
fi
grep -q "summary.json" none.out || { cat none.out; fail "message for a missing summary"; }
out=$(/usr/bin/python3 "$src/tools/probe_points.py" probe --at 0.9,0.2 0.1,1.5 --fields damage)
echo "$out"
expect "$out" "| 0.500 | 1.00, 0.00 | 0.2 |" "probe 1, first output"
expect "$out" "| 0.500 | 0.00, 2.00 | 0.3 |" "probe 2, first output"
expect "$out" "| 1.500 | 1.00, 0.00 | 0.5 |" "probe 1 follows its point"
expect "$out" "| 1.500 | 0.00, 2.00 | 0.6 |" "probe 2 follows its point"
out=$(/usr/bin/python3 "$src/tools/probe_points.py" probe --at 0.9,0.2 --fields damage --every 2)
[ "$(echo "$out" | grep -c '^| [0-9]')" = 1 ] || fail "--every 2: one output expected"
if /usr/bin/python3 "$src/tools/probe_points.py" probe --at 0,0 --fields kappa > nofield.out 2>&1; then
  fail "a missing field was accepted"
fi
grep -q "has no field kappa (it has: damage" nofield.out || { cat nofield.out; fail "missing field message"; }

out=$(/usr/bin/python3 "$src/tools/plot_damage_history.py" --output history.png \
        "C=creep" "S=slow" --times 1.5 2.5 9)
echo "$out"
expect "$out" "| 1.5 | 0.00 | 0.00 |" "grown at 1.5 s"
expect "$out" "| 2.5 | 0.10 | 0.10 |" "grown at 2.5 s"
expect "$out" "| 9 | - | - |" "after the last row"
expect "$out" "| damage grown > 0.01 m^3/m from [s] | 3.00 | 3.00 |" "growth start"
expect "$out" "| failure onset [s] | 3.00 | > 4.00 |" "onset"
head -c 8 history.png | grep -q PNG || fail "no damage history PNG"
echo "ok"
