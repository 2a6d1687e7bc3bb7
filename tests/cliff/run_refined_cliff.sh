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

# The same run cut by <Maximum steps> 5 steps after the onset (an error
# inside the collapse stage): its summary must still carry the onset and
# the stage in progress.
onset_step=$(sed -n 's/^Cliff: failure onset at t = .* (step \([0-9]*\))$/\1/p' refined_cliff.log)
[ -n "$onset_step" ] || { echo "FAIL: no onset line in refined_cliff.log"; exit 1; }
rm -rf refined_cliff_cut
cat > refined_cliff_cut.prm <<END
include $src/tests/cliff/refined_cliff.prm
set Output directory = refined_cliff_cut
subsection Time
  set Maximum steps = $((onset_step + 5))
end
END
if "$scarp" refined_cliff_cut.prm > refined_cliff_cut.log 2>&1; then
  echo "FAIL: the run cut by Maximum steps exited with status 0"; exit 1
fi
/usr/bin/python3 "$src/tests/cliff/check_refined_cliff.py" \
  --cut "$run/refined_cliff_cut" "$run/refined_cliff_output"
