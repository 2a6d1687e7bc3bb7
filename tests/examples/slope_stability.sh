#!/usr/bin/env bash
# Quick test of the slope stability example (prm/examples/
# slope_stability.prm, doc/examples.md) at cells of 1 m: the slope must
# stand with its strength divided by 1.26 and fail with it divided by 1.75,
# i.e. its factor of safety lies in [1.26, 1.75] about the published 1.4
# (Griffiths and Lane 1999). Arguments: scarp, source dir, run dir.
#
# Why this band: doc/examples.md finds the factor by bisection at 1 m
# cells (10 across the height): 1.59, and at 0.5 m: 1.445, so the coarse
# mesh overestimates by 13 %; the band is 1.4 - 10 % to 1.4 + 25 %. A
# strength not reduced as asked (c or tan(phi) alone, or not at all), a
# wrong unit weight or a slope that never comes to rest leaves it.
set -uo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
/usr/bin/python3 "$src/tools/examples/strength_reduction.py" "$scarp" \
  "$src/prm/examples/slope_stability.prm" srm --cell-size 1 --factors 1.26 1.75 \
  > srm.txt 2>&1 || { echo "FAIL: the runs failed"; cat srm.txt; exit 1; }
cat srm.txt
if grep -q "F = 1.2600: .*: stands" srm.txt && grep -q "F = 1.7500: .*: fails" srm.txt; then
  echo "slope stability: the factor of safety lies in [1.26, 1.75] (Griffiths and Lane 1999: 1.4)"
else
  echo "FAIL: expected the slope to stand at F = 1.26 and to fail at F = 1.75"; exit 1
fi
