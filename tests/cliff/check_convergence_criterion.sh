#!/usr/bin/env bash
# tools/compare_profiles.py judges three levels by the study's convergence
# criterion (doc/joss_bay.md): each quantity changes from level 2 to 3 by
# less than half its change from level 1 to 2, and levels 2 and 3 agree
# within 1.5 deg, 0.5 m, 0.5 m and 10 % (angle, run-out, retreat, onset).
# Hand-made run directories (summary.json, cliff_profile.csv) whose
# verdicts follow from the numbers by hand, at and beside each threshold.
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
fails=0

level() { # dir angle run_out area retreat onset [reference_area [centroid mass_run_out]]
  mkdir -p "$1"
  local reference=""
  [ $# -ge 7 ] && reference=", \"failed_reference_area_m2\": $7"
  [ $# -ge 9 ] && reference="$reference, \"failed_mass_centroid_x_m\": $8, \"mass_run_out_m\": $9"
  cat > "$1/summary.json" <<JSON
{"cliff": {"debris_angle_deg": $2, "run_out_m": $3, "failed_area_m2": $4,
           "scarp_retreat_m": $5, "failure_onset_s": $6$reference}}
JSON
  printf 'x,y_initial,y_final\n0,15,15\n10,15,14\n20,0,0\n' > "$1/cliff_profile.csv"
  printf 'x,y,damage,x0,y0,volume\n1,1,0,1,1,1\n12,2,1,9,9,1\n' \
    > "$1/cliff_end_particles.csv"
}

# verdict NAME QUANTITY EXPECTED: the line of QUANTITY in the criterion
# table says EXPECTED ("converged" or "not converged").
verdict() {
  local line
  line=$(grep -F "| $2 |" "$1.out" | tail -1 || true)
  case "$line" in
    *"| $3 |") echo "  ok:   $1: $2 $3" ;;
    *) echo "  FAIL: $1: $2: expected $3, got: $line"; fails=$((fails + 1)) ;;
  esac
}

# verdict_all NAME EXPECTED OVERALL: every quantity EXPECTED, and the
# summary line "all quantities converged: OVERALL".
verdict_all() {
  local q
  for q in "debris angle [deg]" "run-out [m]" "failed area [m^2]" \
           "failed area before it moved [m^2]" \
           "scarp retreat [m]" "failure onset [s]"; do
    verdict "$1" "$q" "$2"
  done
  grep -q "all quantities converged: $3" "$1.out" \
    && echo "  ok:   $1: all quantities converged: $3" \
    || { echo "  FAIL: $1: no 'all quantities converged: $3'"; fails=$((fails + 1)); }
}

judge() { # name: compares name/1, name/2, name/3
  /usr/bin/python3 "$src/tools/compare_profiles.py" --output "$1.png" \
    --particles-output "$1_particles.png" --xlim 0 20 \
    "L1=$1/1" "L2=$1/2" "L3=$1/3" > "$1.out"
  # Both pictures are written (their content is for the eye).
  for f in "$1.png" "$1_particles.png"; do
    [ -s "$f" ] || { echo "  FAIL: $f not written"; fails=$((fails + 1)); }
  done
}

# Converged: every second change below half the first and within its
# tolerance (angle 4 -> 1.4 deg, run-out 1 -> 0.4 m, area 10 -> 4 m^2,
# retreat -2 -> -0.45 m, onset -5.4 -> -0.3 s = 7.5 % of 4 s; area before
# it moved 6 -> 2.9 m^2).
level conv/1 40 5 50 6 9.7 40
level conv/2 44 6 60 4 4.3 46
level conv/3 45.4 6.4 64 3.55 4.0 48.9
judge conv
verdict_all conv converged True

# Not converged, one reason each: the angle's second change is more than
# half its first (2 -> 1.2 deg, within 1.5); the run-out halves but is
# beyond 0.5 m (2 -> 0.6 m); the retreat does not change from 1 to 2 and
# then does (0 -> 0.1 m); the onset halves but is beyond 10 % (10 -> 0.5 s
# of 4.5 s = 11 %); the area increases its change (4 -> 5 m^2), the area
# before it moved halves it exactly (2 -> 1 m^2, not under half).
level not/1 40 5 50 4 15 40
level not/2 42 7 54 4 5 42
level not/3 43.2 7.6 59 4.1 4.5 43
judge not
verdict_all not "not converged" False

# No change at all on either refinement counts as converged.
level same/1 40 5 50 4 5 40
level same/2 40 5 50 4 5 40
level same/3 40 5 50 4 5 40
judge same
verdict same "run-out [m]" converged
verdict same "failed area before it moved [m^2]" converged

# Summaries of older runs without the area before the points moved: that
# quantity is left out and the others decide (here: all converged).
level old/1 40 5 50 6 9.7
level old/2 44 6 60 4 4.3
level old/3 45.4 6.4 64 3.55 4.0
judge old
grep -q "| failed area before it moved \[m^2\] | | | | | not in every run |" old.out \
  && echo "  ok:   old: area before it moved not in every run" \
  || { echo "  FAIL: old: no 'not in every run' line"; fails=$((fails + 1)); }
grep -q "all quantities converged: True" old.out \
  && echo "  ok:   old: all quantities converged: True" \
  || { echo "  FAIL: old: expected all converged"; fails=$((fails + 1)); }

# The mass measures judged beside the profile's: the profile's run-out
# fails (4 -> 4 m, a thin tongue running on), the mass centroid converges
# (1 -> 0.3 m, within 0.5), the run-out of 99 % of the mass does not
# (1 -> 0.6 m: more than half, and beyond 0.5 m).
level mass/1 40 5 50 6 9.7 40 30 6
level mass/2 44 9 60 4 4.3 46 31 7
level mass/3 45.4 13 64 3.55 4.0 48.9 31.3 7.6
judge mass
verdict mass "run-out [m]" "not converged"
verdict mass "failed mass centroid x [m]" converged
verdict mass "run-out of 99 % of the failed mass [m]" "not converged"
verdict mass "scarp retreat [m]" converged

[ "$fails" = 0 ] || { echo "$fails check(s) failed"; exit 1; }
