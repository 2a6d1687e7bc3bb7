#!/usr/bin/env bash
# tools/compare_histories.py --deposit: the deposit of cliff_history.csv at
# times after the onset, its bulking, and the least-squares rates of scarp
# retreat and of the failed area before it moved. On a hand-made history
# (onset at t = 2 s from summary.json: collapse from 0.5 s, onset 1.5 s
# after it; a row every 0.5 s; retreat 1 + 0.5 s m, failed area before it
# moved 10 + 4 s m^2, failed area 1.5 times that, s the time after the
# onset) the rates are 0.500 m/s and 4.00 m^2/s (straight lines: exact to
# the printed digits) and the bulking 1.50; rows before the window must not
# enter the fit (a jump of 100 m before it would show), and a run given its
# onset after "@" reads the same.
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run/a"; cd "$run"

printf '{"stages": {"gravity": {"end_time": 0.5}, "collapse": {"start_time": 0.5}}, "cliff": {"failure_onset_s": 1.5}}\n' > a/summary.json
awk 'BEGIN {
  print "time,kinetic_energy,max_speed,debris_angle,run_out,debris_toe,failed_area,failed_reference_area,n_failed_particles,scarp_position,scarp_retreat";
  for (i = 0; i <= 30; ++i) { t = 0.5 * i; s = t - 2;
    if (s < 0) { printf "%g,0,0,nan,0,31,0,0,0,nan,nan\n", t; continue }
    r = (s < 1) ? 100 : 1 + 0.5 * s; a = 10 + 4 * s;
    printf "%g,1,1,30,%g,40,%g,%g,10,20,%g\n", t, 2 + s, 1.5 * a, a, r } }' \
  > a/cliff_history.csv

out=$(/usr/bin/python3 "$src/tools/compare_histories.py" --deposit \
        --times 2,4 --rates 2,12 "A=a" "B=a@2")
echo "$out"
for label in A B; do
  echo "$out" | grep -q "^$label: from 2 to 12 s after the onset (21 rows): scarp retreat 0.500 m/s, failed area before it moved 4.00 m^2/s" \
    || { echo "FAIL: rates of $label"; exit 1; }
done
# 4 s after the onset: retreat 3, run-out 6, area 39 (26), bulking 1.50.
echo "$out" | grep -q "^| 4 s | 3.00, 6.00, 39.0 (26.0), 1.50 \[4.00 s\] | 3.00, 6.00, 39.0 (26.0), 1.50 \[4.00 s\] |" \
  || { echo "FAIL: deposit 4 s after the onset"; exit 1; }

# A history with the failed mass's columns (runs since 2026-12-07): the
# cell adds centroid, 95 and 99 % (here 30 + s, 33 + s, 34 + s).
mkdir -p c && cp a/summary.json c/
awk 'BEGIN {
  print "time,kinetic_energy,max_speed,debris_angle,run_out,debris_toe,failed_area,failed_reference_area,n_failed_particles,scarp_position,scarp_retreat,failed_mass_centroid,failed_mass_x95,failed_mass_x99,mass_run_out";
  for (i = 0; i <= 30; ++i) { t = 0.5 * i; s = t - 2;
    if (s < 0) { printf "%g,0,0,nan,0,31,0,0,0,nan,nan,nan,nan,nan,nan\n", t; continue }
    a = 10 + 4 * s;
    printf "%g,1,1,30,%g,40,%g,%g,10,20,%g,%g,%g,%g,%g\n", t, 2 + s, 1.5 * a, a, 1 + 0.5 * s, 30 + s, 33 + s, 34 + s, 3 + s } }' \
  > c/cliff_history.csv
out=$(/usr/bin/python3 "$src/tools/compare_histories.py" --deposit \
        --times 4 "A=a" "C=c")
echo "$out"
echo "$out" | grep -q "^| 4 s | 3.00, 6.00, 39.0 (26.0), 1.50 \[4.00 s\] | 3.00, 6.00, 39.0 (26.0), 1.50; 34.00, 37.00, 38.00 \[4.00 s\] |" \
  || { echo "FAIL: the failed mass 4 s after the onset"; exit 1; }
echo "ok"
