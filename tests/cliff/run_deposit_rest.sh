#!/usr/bin/env bash
# ctest: the deposit rest criterion (Stage/End on deposit at rest) on the
# short cliff. Arguments: scarp, source dir, run dir (scarp_add_script_test).
set -euo pipefail
scarp="$1"; src="$2"; run="$3"
mkdir -p "$run" && cd "$run"
rm -rf deposit_rest_output resumed_output
"$scarp" "$src/tests/cliff/deposit_rest.prm" > deposit_rest.log 2>&1 || { tail -20 deposit_rest.log; exit 1; }

# The stage ended on the criterion, and the history (a row at every check:
# same interval, the checks fall on its multiples) shows it did so at the
# first check that closed a quiet period of 0.3 s: from the row that opened
# the period to the last row, the toe and the scarp stayed within 0.05 m and
# the failed areas within 1 % of the opening row; the row before the
# opening one had nothing failed or differed by more (else the period would
# have begun earlier); no earlier stretch of 0.3 s was quiet (else the run
# would have ended there). The tolerances are the scene's: the check repeats
# the criterion on the printed history (10 significant digits).
/usr/bin/python3 - deposit_rest_output <<'PY'
import csv, json, math, sys
out = sys.argv[1]
summary = json.load(open(f"{out}/summary.json"))
stage = summary["stages"]["collapse"]
rows = [{k: float(v) for k, v in r.items()}
        for r in csv.DictReader(open(f"{out}/cliff_history.csv"))]
onset = summary["cliff"]["failure_onset_s"] + summary["stages"]["gravity"]["end_time"]
tol, rel, settle = 0.05, 0.01, 0.3

def near(a, b, t):
    return (math.isnan(a) and math.isnan(b)) or abs(a - b) <= t

def quiet(ref, r):
    return (r["failed_reference_area"] > 0 and ref["failed_reference_area"] > 0
            and near(r["debris_toe"], ref["debris_toe"], tol)
            and near(r["scarp_position"], ref["scarp_position"], tol)
            and near(r["failed_area"], ref["failed_area"], rel * ref["failed_area"])
            and near(r["failed_reference_area"], ref["failed_reference_area"],
                     rel * ref["failed_reference_area"]))

# Replay the criterion on the rows after the onset.
checks = [r for r in rows if r["time"] >= onset - 0.05 - 1e-9]
ref, end = None, None
for r in checks:
    if r["time"] < onset:
        continue
    if ref is None or not quiet(ref, r):
        ref = r if r["failed_reference_area"] > 0 else None
    elif r["time"] - ref["time"] >= settle * (1 - 1e-12):
        end = r
        break
last = rows[-1]
ok = (stage["end_reason"] == "deposit at rest"
      and end is not None
      and abs(end["time"] - last["time"]) <= 1e-9 * last["time"]
      and abs(stage["end_time"] - last["time"]) <= 1e-9 * last["time"]
      and last["time"] < 10)
print(f"  ended '{stage['end_reason']}' at t = {stage['end_time']:.4f} s "
      f"(onset at t = {onset:.4f} s); replayed on the history: quiet from "
      f"t = {ref['time'] if ref else float('nan'):.4f} s, ends at "
      f"t = {end['time'] if end else float('nan'):.4f} s; "
      f"run-out {last['run_out']} m, scarp retreat {last['scarp_retreat']:.3f} m, "
      f"failed area {last['failed_area']:.2f} m^2")
sys.exit(0 if ok else 1)
PY

# The quiet period survives a checkpoint: the last checkpoint (every 0.1 s,
# so inside the 0.3 s period) resumed ends the stage at the same step with
# the same results: on one rank to 1e-12 of each column's largest value, the
# bound of the checkpoint tests (tests/app/checkpoint.sh). A resumed run
# that forgot the period would open a new one and end 0.3 s later.
cp -r deposit_rest_output resumed_output
cat > resumed.prm <<PRM
include $src/tests/cliff/deposit_rest.prm
set Output directory = resumed_output
PRM
"$scarp" --resume resumed_output resumed.prm > resumed.log 2>&1 || { tail -20 resumed.log; exit 1; }
grep "Resumed from" resumed.log
/usr/bin/python3 - deposit_rest_output resumed_output <<'PY'
import json, sys
a, b = (json.load(open(f"{d}/summary.json")) for d in sys.argv[1:])
sa, sb = a["stages"]["collapse"], b["stages"]["collapse"]
print(f"  full run: {a['steps']} steps to t = {sa['end_time']}; resumed: "
      f"{b['steps']} steps to t = {sb['end_time']} ({sb['end_reason']})")
sys.exit(0 if (a["steps"] == b["steps"] and sb["end_reason"] == "deposit at rest") else 1)
PY
/usr/bin/python3 "$src/tests/app/compare_runs.py" deposit_rest_output resumed_output 1e-12

# Like the end time, the deposit entries may differ between a run and its
# resumption (the L3 run of doc/joss_bay.md took the criterion on half way):
# the same checkpoint resumed without the criterion and with the end time
# at the check that ended the full run is accepted, and ends at its step on
# the end time.
rm -rf plain_output
cp -r deposit_rest_output plain_output
# The stage ended at the first step past a check time (a multiple of
# 0.05 s); an end time there stops at the same step.
end=$(/usr/bin/python3 -c "import json; t = json.load(open('deposit_rest_output/summary.json'))['stages']['collapse']['end_time']; print(round(t / 0.05) * 0.05)")
cat > plain.prm <<PRM
include $src/tests/cliff/deposit_rest.prm
set Output directory = plain_output
subsection Stage collapse
  set End time               = $end
  set End on deposit at rest = false
  set Deposit settle time    = 2
end
PRM
"$scarp" --resume plain_output plain.prm > plain.log 2>&1 || { tail -20 plain.log; exit 1; }
/usr/bin/python3 - deposit_rest_output plain_output <<'PY'
import json, sys
a, b = (json.load(open(f"{d}/summary.json")) for d in sys.argv[1:])
sb = b["stages"]["collapse"]
print(f"  resumed without the criterion: {b['steps']} steps ({sb['end_reason']}), "
      f"the full run {a['steps']}")
sys.exit(0 if (a["steps"] == b["steps"] and sb["end_reason"] == "end time") else 1)
PY
