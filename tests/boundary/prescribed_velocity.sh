#!/usr/bin/env bash
# A prescribed velocity on part of a boundary face: the reaction on a rigid
# plate pushed into an elastic layer against the closed form (1 rank, or on
# 2 ranks with RANKS 2), and the refusals of regions and velocities that
# cannot be applied. Arguments: scarp, source dir, run dir, mpiexec, mpi
# flags, then the number of ranks and the dimension (2 or 3).
set -uo pipefail
scarp="$1"; src="$2"; run="$3"; mpiexec="${4:-}"; flags="${5:-}"; flags="${flags//;/ }"
ranks="${6:-1}"; dim="${7:-2}"
here="$src/tests/boundary"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
failures=0

scene=plate_compression; thickness=""
[ "$dim" -eq 3 ] && { scene=plate_compression_3d; thickness=0.2; }
if [ "$ranks" -gt 1 ]; then
  $mpiexec $flags -np "$ranks" "$scarp" "$here/$scene.prm" > plate.log 2>&1
else
  "$scarp" "$here/$scene.prm" > plate.log 2>&1
fi
if [ $? -ne 0 ]; then
  echo "FAIL: the plate run failed"; tail -5 plate.log; exit 1
fi
/usr/bin/python3 "$here/check_plate_compression.py" $scene $thickness || failures=$((failures + 1))

# expect NAME LINE LINES...: the scene with the lines appended must stop
# before any step with exit status 1 and exactly the message LINE.
expect() {
  local name="$1" line="scarp: error: $2"; shift 2
  { cat "$here/plate_compression.prm"; printf '%s\n' "$@"; } > "$name.prm"
  "$scarp" "$name.prm" > "$name.log" 2>&1
  local status=$?
  if [ "$status" -eq 1 ] && [ "$(grep -v '^$' "$name.log")" = "$line" ]; then
    echo "  ok:   $name: $line"
  else
    echo "  FAIL: $name: exit $status, expected 1 and only the line"
    echo "        $line"; sed 's/^/        /' "$name.log" | head -10
    failures=$((failures + 1))
  fi
}
if [ "$ranks" -eq 1 ] && [ "$dim" -eq 2 ]; then
  pv="subsection Mesh
subsection Boundary conditions
subsection Prescribed velocity"
  expect off_face \
    "Mesh/Boundary conditions/Prescribed velocity: <Region> spans 0.5 to 0.9 in direction 1, so it does not lie on the Top face (at 1); the box must contain it." \
    "$pv" "set Region = 0.2, 0.5, 0.6, 0.9" "end" "end" "end"
  expect no_node \
    "Mesh/Boundary conditions/Prescribed velocity: <Region> holds no node of the Top face; make it reach at least one mesh node." \
    "$pv" "set Region = 0.42, 1, 0.48, 1" "end" "end" "end"
  expect slip_contradiction \
    "Mesh/Boundary conditions/Prescribed velocity: the region reaches the Left face, which is slip (no normal velocity), but <Velocity> prescribes 0.001 in direction 0 there; make the region end before that face or change its condition." \
    "$pv" "set Components = all" "set Velocity = 0.001, -0.01" "set Region = 0, 1, 0.5, 1" "end" "end" "end"
  expect normal_with_tangential \
    "Mesh/Boundary conditions/Prescribed velocity: <Components> = normal prescribes only the velocity normal to the Top face, but <Velocity> has 0.001000 in direction 0 (tangential); set it to 0 or use <Components> = all." \
    "$pv" "set Velocity = 0.001, -0.01" "end" "end" "end"
fi
[ "$failures" -eq 0 ] && echo "prescribed velocity: all checks passed"
exit $((failures > 0))
