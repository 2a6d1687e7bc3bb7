#!/usr/bin/env bash
# The ladder of aspect ratios of the granular column collapse
# (doc/examples.md): columns of width L0 = 0.1 m and height a L0 for
# a = 0.5, 1, 3, 4 (either side of the transition 1.8 < a < 2.8), the material, floor and numerics of
# prm/examples/granular_column_collapse.prm at cells of L0/20, each run to
# rest; prints a table of the run-out ratio (L_f - L0)/L0 against the 2D
# scaling law of Lube et al. (2005) and writes column_ladder.csv.
#
#   bash tools/examples/column_ladder.sh build/scarp output/column_ladder [a ...]
set -euo pipefail
scarp="$(realpath "$1")"; out="$2"; shift 2
ratios=("$@")
[ $# -eq 0 ] && ratios=(0.5 1 3 4)
here="$(cd "$(dirname "$0")" && pwd)"
base="$(realpath "$here/../../prm/examples/granular_column_collapse.prm")"
py=/usr/bin/python3
mkdir -p "$out"
out="$(realpath "$out")"
echo "a,L0,H0,L_f,runout_ratio,law,H_f_over_L0,surface_angle_deg,steps,wall_time_s" > "$out/column_ladder.csv"
for a in "${ratios[@]}"; do
  h0=$($py -c "print(0.1 * $a)")
  # Room for twice the run-out of the scaling law, and a little above.
  width=$($py -c "import math; a=$a; r=1.2*a if a<1.8 else 1.9*a**(2/3); print(round(0.1*(1+2.2*r)+0.1, 1))")
  height=$($py -c "print(round(0.1 * $a + 0.025, 3))")
  dir="$out/a$a"
  cat > "$out/a$a.prm" <<PRM
include $base
set Output directory = $dir
subsection Mesh
  set Upper corner = $width, $height
end
subsection Body column
  set Box corners = 0, 0, 0.1, $h0
  subsection Initial stress
    set Function constants  = rho=2650, g=9.81, H=$h0, K0=0.661
  end
end
subsection Output
  set Interval = 0.1
end
PRM
  "$scarp" "$out/a$a.prm" > "$out/a$a.log" 2>&1
  $py "$here/column_profile.py" "$dir" --phi 19.8 --plot "$dir/profile.png" \
      --title "a = $a" > "$dir/profile.txt"
  $py - "$dir" "$a" >> "$out/column_ladder.csv" <<'PY'
import json, sys
d, a = sys.argv[1], float(sys.argv[2])
v = dict(l.split(" = ") for l in open(d + "/profile.txt").read().split("\n") if " = " in l)
s = json.load(open(d + "/summary.json"))
law = 1.2 * a if a < 1.8 else 1.9 * a ** (2 / 3)
wall = s.get("wall_time", s.get("wall_time_s", ""))
if isinstance(wall, dict):
    wall = wall.get("total", "")
print(",".join(str(x) for x in [a, v["L0"], v["H0"], v["L_f"], v["runout_ratio"], law,
                                v["H_f_over_L0"], v["surface_angle_deg"], s.get("steps", ""), wall]))
PY
  tail -1 "$out/column_ladder.csv"
done
