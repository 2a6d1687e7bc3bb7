#!/usr/bin/env bash
# ctest cliff_refined_collapse: run the refined cliff and check it.
# Arguments: scarp, source dir, run dir, mpiexec, mpi flags (from
# scarp_add_script_test).
set -euo pipefail
scarp="$1"; src="$2"; run="$3"
mkdir -p "$run" && cd "$run"
rm -rf refined_cliff_output
"$scarp" "$src/tests/cliff/refined_cliff.prm" > refined_cliff.log 2>&1 || { tail -20 refined_cliff.log; exit 1; }
/usr/bin/python3 "$src/tests/cliff/check_refined_cliff.py" "$run/refined_cliff_output"
