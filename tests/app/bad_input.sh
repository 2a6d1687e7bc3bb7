#!/usr/bin/env bash
# Bad input stops scarp with a message naming the cause and exit status 1;
# files written before the failure stay intact.
set -uo pipefail
# Arguments (from scarp_add_script_test): scarp, source dir, run dir,
# mpiexec, mpi flags.
scarp="$1"; src="$2"; run="$3"; mpiexec="${4:-}"; flags="${5:-}"; flags="${flags//;/ }"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
base="$src/prm/examples/vibrating_bar.prm"
failures=0

# Messages about the scene file itself are one readable line
# "scarp: error: FILE:LINE: what", in the words of the scene file: the entry
# with its subsection path, the value and what is accepted, never deal.II's
# exception names, source locations or stack traces.
internal='Exc|deal\.II|\.cc|\.h:|ExceptionBase|Stacktrace|An error occurred|^-----|Line <'

# expect_line NAME LINE PRM-TEXT: the run must fail with exit 1, and its
# output (blank lines aside) must be exactly "scarp: error: LINE".
expect_line() {
  local name="$1" line="scarp: error: $2"
  printf '%s\n' "$3" > "$name.prm"
  "$scarp" "$name.prm" > "$name.log" 2>&1
  check_line "$name" $? "$line"
}

# check_line NAME STATUS LINE: NAME.log holds only LINE, and STATUS is 1.
check_line() {
  local name="$1" status="$2" line="$3"
  if [ "$status" -eq 1 ] && [ "$(grep -v '^$' "$name.log")" = "$line" ] \
     && ! grep -Eq -- "$internal" "$name.log"; then
    echo "  ok:   $name (exit $status): $line"
  else
    echo "  FAIL: $name: exit $status; expected 1 and only the line"
    echo "        $line"
    echo "        output:"
    sed 's/^/        /' "$name.log" | head -20
    failures=$((failures + 1))
  fi
}

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

expect_line unknown_entry "unknown_entry.prm:2: unknown entry <Pink elephants>." \
"include $base
set Pink elephants = 3"

expect_line unknown_nested_entry \
  "unknown_nested_entry.prm:4: unknown entry <Mesh/Boundary conditions/Botom>." \
"include $base
subsection Mesh
  subsection Boundary conditions
    set Botom = slip   # mistyped
  end
end"

expect_line malformed_value \
  "malformed_value.prm:3: invalid value <fast> for <Mesh/Cell size>; accepted: a number >= 0." \
"include $base
subsection Mesh
  set Cell size = fast
end"

expect_line bad_selection \
  "bad_selection.prm:4: invalid value <sideways> for <Transfer/Update scheme>; accepted: one of USL, MUSL." \
"include $base
subsection Transfer
  # a comment line
  set Update scheme = sideways
end"

expect_line malformed_list_entry \
  "malformed_list_entry.prm:1: invalid value <2, 3> for <Dimension>; accepted: an integer from 2 to 3." \
"set Dimension = 2, 3
include $base"

expect_line unknown_subsection "unknown_subsection.prm:3: unknown subsection <Mesh/Refinment>." \
"include $base
subsection Mesh
  subsection Refinment
    set Adaptive refinement = false
  end
end"

expect_line unknown_material_subsection \
  "unknown_material_subsection.prm:2: unknown subsection <Material bar materal>." \
"include $base
subsection Material bar materal
end"

# The 'end' of Boundary conditions closes Mesh: Mesh is the one left open.
expect_line missing_end "missing_end.prm:2: subsection <Mesh> is not closed: an 'end' line is missing." \
"include $base
subsection Mesh
  set Cell size = 0.5
  subsection Boundary conditions
    set Left = fixed
end"

expect_line extra_end "extra_end.prm:3: an 'end' line without an open subsection." \
"include $base
set Output directory = out
end"

mkdir -p a_directory.prm
"$scarp" a_directory.prm > unreadable_directory.log 2>&1
check_line unreadable_directory $? \
  "scarp: error: a_directory.prm: cannot read the file (it is a directory)."

"$scarp" does_not_exist.prm > unreadable_missing.log 2>&1
check_line unreadable_missing $? \
  "scarp: error: does_not_exist.prm: cannot read the file (no such file)."

expect_line unreadable_include \
  "unreadable_include.prm:2: cannot read the included file <no_such_common.prm> (no such file)." \
"set Dimension = 2
include no_such_common.prm"

# On 2 ranks every rank stops, one prints.
if [ -n "$mpiexec" ]; then
  printf 'include %s\nsubsection Mesh\n  set Cell size = fast\nend\n' "$base" > mpi_malformed.prm
  $mpiexec $flags -np 2 "$scarp" mpi_malformed.prm > mpi_output.log 2>&1
  status=$?
  # mpiexec adds its own report of the failed ranks: leave it out.
  grep '^scarp' mpi_output.log > mpi_malformed.log
  grep -q '^scarp' mpi_output.log || cat mpi_output.log > mpi_malformed.log
  check_line mpi_malformed "$status" \
    "scarp: error: mpi_malformed.prm:3: invalid value <fast> for <Mesh/Cell size>; accepted: a number >= 0."
fi

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

# The deposit rest criterion measures a cliff's deposit: a scene without a
# cliff body refuses it rather than never ending on it.
expect_line deposit_rest_without_cliff \
  "Stage vibrate: <End on deposit at rest> measures the deposit of a cliff, but this scene has no body with <Shape> = cliff (2D); use <End on kinetic energy>." \
"include $base
subsection Stage vibrate
  set End on deposit at rest = true
end"

expect_line deposit_check_interval_zero \
  "Stage vibrate: <Deposit check interval> must be positive with <End on deposit at rest>." \
"include $base
subsection Stage vibrate
  set End on deposit at rest = true
  set Deposit check interval = 0
end"

# A material's own check (not a pattern): one line naming the material,
# the entry and the value, without deal.II's exception dump.
expect_line removal_stretch_below_one \
  "Material chalk: 'Remove points stretched beyond' must be 0 (never) or > 1, got 0.5." \
"include $src/prm/joss_bay.prm
subsection Material chalk
  subsection Damage
    set Remove points stretched beyond = 0.5
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
"$scarp" nested/a/top.prm > nested_include.log 2>&1
check_line nested_include $? \
  "scarp: error: nested/b/leaf.prm:2: unknown entry <Pink elephants>."

printf '# a cycle\ninclude cycle.prm\n' > cycle.prm
"$scarp" cycle.prm > include_cycle.log 2>&1
check_line include_cycle $? \
  "scarp: error: cycle.prm:2: the file <cycle.prm> includes itself (an include cycle)."

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
