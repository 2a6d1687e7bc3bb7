#!/usr/bin/env bash
# doc/parameters.md is what the executable declares: the reference that
# tools/make_parameter_reference.py writes from `scarp --print-parameters
# json` must equal the committed file, so that every documented entry
# exists, with its default and accepted values, and none is missing. A
# change of a parameter without regenerating the page fails here (the diff
# says which entries differ; regenerate with the command the page names).
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
scarp="$1"; src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
/usr/bin/python3 "$src/tools/make_parameter_reference.py" "$scarp" > parameters.md
if ! diff -u "$src/doc/parameters.md" parameters.md > parameters.diff; then
  head -40 parameters.diff
  echo "FAIL: doc/parameters.md differs from what $scarp declares; run"
  echo "  tools/make_parameter_reference.py build/scarp > doc/parameters.md"
  exit 1
fi
# The check itself can fail: a page with one default changed is caught.
sed 's/^| `CFL number` | `[^`]*`/| `CFL number` | `0.123`/' "$src/doc/parameters.md" > changed.md
cmp -s changed.md "$src/doc/parameters.md" && { echo "FAIL: the page has no CFL number entry to change"; exit 1; }
diff -q changed.md parameters.md > /dev/null && { echo "FAIL: a changed default was not seen"; exit 1; }
echo "ok: $(grep -c '^| `' parameters.md) entries as declared"
