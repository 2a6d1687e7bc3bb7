#!/usr/bin/env bash
# Draws the pictures of a finished run next to its outputs: energies, and for
# cliff scenes the particles coloured by damage (start, failure, end) and the
# final surface profile over the initial one.
set -euo pipefail
out="$1"
py=/usr/bin/python3   # Debian's python3 with python3-matplotlib
here="$(dirname "$0")"
"$py" "$here/plot_statistics.py" "$out"
if [ -f "$out/cliff_profile.csv" ]; then
  snaps=()
  for tag in start failure end; do
    [ -f "$out/cliff_${tag}_particles.csv" ] && snaps+=("$out/cliff_${tag}_particles.csv")
  done
  "$py" "$here/plot_cliff.py" --profile "$out/cliff_profile.csv" \
        --particles "${snaps[@]}" --output-dir "$out"
fi
echo "pictures in $out/"
