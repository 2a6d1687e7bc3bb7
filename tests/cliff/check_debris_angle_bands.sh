#!/usr/bin/env bash
# tools/debris_angle_bands.py refits the debris angle over other bands of
# the pile height. On a hand-made straight 45 deg flank (bins every 0.5 m,
# summit 8 m high at x = 10 m, toe at x = 18 m) every band gives 45.0 deg
# (a line through exact points: any band fits it exactly, to the printed
# 0.1 deg); a profile whose written angle the 0.1-0.9 band does not
# reproduce makes the tool fail (exit status 1).
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run/ok" "$run/bad"; cd "$run"

profile() { # dir written_angle
  {
    printf '# pile_summit = 10\n# debris_toe = 18\n# pile_height = 8\n'
    printf '# debris_angle = %s\nx,y_initial,y_final\n' "$2"
    awk 'BEGIN { for (i = 0; i <= 40; ++i) { x = 0.5 * i;
                 y = x < 10 ? 8 : (x > 18 ? 0 : 18 - x);
                 printf "%g,8,%g\n", x, y } }'
  } > "$1/cliff_profile.csv"
}
profile ok 45
profile bad 40

out=$(/usr/bin/python3 "$src/tools/debris_angle_bands.py" "flank=ok")
echo "$out"
n=$(echo "$out" | grep -o "45.0 deg" | wc -l)
[ "$n" = 5 ] || { echo "FAIL: expected 45.0 deg in all 5 bands, got $n"; exit 1; }

if /usr/bin/python3 "$src/tools/debris_angle_bands.py" "bad=bad" > bad.out 2>&1; then
  echo "FAIL: a written angle of 40 deg against a 45 deg flank was accepted"
  exit 1
fi
grep -q "the run wrote 40" bad.out || { echo "FAIL: no message"; cat bad.out; exit 1; }
echo "ok"
