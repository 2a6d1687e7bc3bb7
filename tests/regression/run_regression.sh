#!/usr/bin/env bash
# ctest: run one regression scene and compare its summary.json and
# statistics.csv with the expected files in tests/regression/expected/SCENE/
# (compare.py says how). Arguments (from scarp_add_script_test): scarp,
# source dir, run dir, mpiexec, mpi flags, then SCENE RANKS TOLERANCE.
set -euo pipefail
scarp="$1"; src="$2"; run="$3"; mpiexec="$4"; flags="${5//;/ }"
scene="$6"; ranks="$7"; tolerance="$8"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
if [ "$ranks" -gt 1 ]; then
  $mpiexec $flags -np "$ranks" "$scarp" "$src/tests/regression/$scene.prm" \
    > "$scene.log" 2>&1 || { tail -20 "$scene.log"; exit 1; }
else
  "$scarp" "$src/tests/regression/$scene.prm" > "$scene.log" 2>&1 \
    || { tail -20 "$scene.log"; exit 1; }
fi
# The scene writes to its Output directory (named after the scene),
# relative to the working directory.
/usr/bin/python3 "$src/tests/regression/compare.py" "$run/$scene" \
  "$src/tests/regression/expected/$scene" --tolerance "$tolerance"
