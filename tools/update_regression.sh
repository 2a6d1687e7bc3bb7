#!/usr/bin/env bash
# Regenerate the expected files of the regression tests (tests/regression/,
# doc/testing.md): run each scene on one rank with BUILD_DIR/scarp and store
# its summary.json and statistics.csv (without wall times) under
# tests/regression/expected/SCENE/.
#
#   tools/update_regression.sh [BUILD_DIR] [SCENE ...]
#
# BUILD_DIR defaults to build/; without SCENE names every scene
# tests/regression/*.prm is run. Do this only when a change moves the
# results on purpose, check the diff of the expected files (git diff
# tests/regression/expected) and say in the commit why the numbers moved.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
shift || true
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  for f in "$root"/tests/regression/*.prm; do scenes+=("$(basename "$f" .prm)"); done
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  echo "$scene:"
  (cd "$work" && "$build/scarp" "$root/tests/regression/$scene.prm" > "$scene.log" 2>&1) \
    || { tail -20 "$work/$scene.log"; exit 1; }
  /usr/bin/python3 "$root/tests/regression/compare.py" "$work/$scene" \
    "$root/tests/regression/expected/$scene" --update
done
