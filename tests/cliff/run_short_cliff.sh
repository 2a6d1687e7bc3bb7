#!/usr/bin/env bash
# ctest: run the short cliff and check it. Arguments: scarp, source dir, run
# dir, mpiexec, mpi flags (from scarp_add_script_test).
set -euo pipefail
scarp="$1"; src="$2"; run="$3"
mkdir -p "$run" && cd "$run"
rm -rf short_cliff_output
"$scarp" "$src/tests/cliff/short_cliff.prm" > short_cliff.log 2>&1 || { tail -20 short_cliff.log; exit 1; }
/usr/bin/python3 "$src/tests/cliff/check_short_cliff.py" "$run/short_cliff_output"
