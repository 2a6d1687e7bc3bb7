#!/usr/bin/env bash
# Draws the pictures of a finished run next to its outputs: energies, and for
# cliff scenes the particles coloured by damage (start, failure, after
# failure, end) and the final surface profile over the initial one.
set -euo pipefail
out="$1"
py=/usr/bin/python3   # Debian's python3 with python3-matplotlib
here="$(dirname "$0")"
"$py" "$here/plot_statistics.py" "$out"
# Cliff scenes: particles by damage at each snapshot the run wrote, and the
# final profile when the debris was run to rest.
snaps=()
for tag in start failure after_failure end; do
  [ -f "$out/cliff_${tag}_particles.csv" ] && snaps+=("$out/cliff_${tag}_particles.csv")
done
profile=()
[ -f "$out/cliff_profile.csv" ] && profile=(--profile "$out/cliff_profile.csv")
if [ ${#snaps[@]} -gt 0 ] || [ ${#profile[@]} -gt 0 ]; then
  "$py" "$here/plot_cliff.py" "${profile[@]}" --particles "${snaps[@]}" \
        --output-dir "$out"
fi
echo "pictures in $out/"
