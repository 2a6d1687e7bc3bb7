#!/usr/bin/env bash
# Bad input stops scarp with a message naming the cause and exit status 1;
# files written before the failure stay intact.
# Arguments (from scarp_add_script_test): scarp, source dir, run dir.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
base="$src/prm/examples/vibrating_bar.prm"
failures=0

# expect NAME PATTERN PRM-TEXT: the run must fail (exit 1) and print PATTERN.
expect() {
  local name="$1" pattern="$2"
  printf '%s\n' "$3" > "$name.prm"
  "$scarp" "$name.prm" > "$name.log" 2>&1
  local status=$?
  if [ "$status" -eq 1 ] && grep -q -- "$pattern" "$name.log"; then
    echo "  ok:   $name (exit $status): $(grep -m1 -- "$pattern" "$name.log" | cut -c1-150)"
  else
    echo "  FAIL: $name: exit $status, expected 1 and <$pattern>; output:"
    tail -5 "$name.log"
    failures=$((failures + 1))
  fi
}

expect unknown_entry "Pink elephants" "include $base
set Pink elephants = 3"

expect malformed_value "Cell size" "include $base
subsection Mesh
  set Cell size = fast
end"

expect bad_selection "Update scheme" "include $base
subsection Transfer
  set Update scheme = sideways
end"

expect box_not_whole_cells "whole number of cells" "include $base
subsection Mesh
  set Cell size = 0.7
end"

expect body_outside_mesh "outside the background mesh" "include $base
subsection Body bar
  set Box corners = 0, 0, 45, 1
end"

expect body_entirely_outside "no material point inside" "include $base
subsection Body bar
  set Box corners = 100, 100, 101, 101
end"

expect impossible_cliff "Notch depth" "include $src/prm/joss_bay/common.prm
set Output directory = cliff
subsection Body cliff
  subsection Cliff
    set Notch depth = 40
  end
end"

# Includes resolve relative to the including file at any depth, and an
# error names the file and line the user wrote: nested/a/top.prm includes
# ../b/mid.prm, which includes leaf.prm (next to mid.prm, not the working
# directory), whose line 2 is bad.
mkdir -p nested/a nested/b
printf 'include ../b/mid.prm\n' > nested/a/top.prm
printf 'include %s\ninclude leaf.prm\n' "$base" > nested/b/mid.prm
printf '# leaf\nset Pink elephants = 3\n' > nested/b/leaf.prm
"$scarp" nested/a/top.prm > nested.log 2>&1; s=$?
if [ $s -eq 1 ] && grep -q "Line <2> of file <.*nested/b/leaf.prm>" nested.log; then
  echo "  ok:   nested include: $(grep -m1 'Line <2>' nested.log | cut -c1-120)"
else
  echo "  FAIL: nested include ($s)"; tail -5 nested.log; failures=$((failures+1))
fi
printf 'include cycle.prm\n' > cycle.prm
"$scarp" cycle.prm > cycle.log 2>&1; s=$?
if [ $s -eq 1 ] && grep -q "includes itself" cycle.log; then echo "  ok:   include cycle"; else echo "  FAIL: include cycle ($s)"; failures=$((failures+1)); fi

"$scarp" does_not_exist.prm > missing.log 2>&1; s=$?
if [ $s -eq 1 ] && grep -q "cannot read the scene file" missing.log; then echo "  ok:   missing file"; else echo "  FAIL: missing file ($s)"; failures=$((failures+1)); fi

# An unstable time step: the run stops at the step it happens, with the
# cause, and keeps what it wrote before.
expect unstable_cfl "CFL number" "include $base
set Output directory = unstable
subsection Time
  set CFL number = 3
end
subsection Output
  set Statistics interval = 1
end"
if [ -s unstable/statistics.csv ] && [ "$(wc -l < unstable/statistics.csv)" -gt 2 ] \
   && [ -s unstable/particles_00000.0.vtu ] && grep -q '"ended": "error' unstable/summary.json; then
  echo "  ok:   unstable run kept statistics.csv ($(wc -l < unstable/statistics.csv) lines), the first VTU, and summary.json says it ended in error"
else
  echo "  FAIL: unstable run outputs"; failures=$((failures + 1))
fi

expect nan_velocity "NaN" "include $base
set Output directory = nan
subsection Body bar
  subsection Initial velocity
    set Function expression = sqrt(-1); 0
  end
end"

echo "$failures failure(s)"
[ "$failures" -eq 0 ]
