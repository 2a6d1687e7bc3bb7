#!/usr/bin/env bash
# tools/plot_point_curves.py (doc/materials.md) on two stress paths whose
# numbers are known by construction: a tension path whose loading
# component (sigma_xx) peaks at 5 MPa beside a smaller sigma_yy, and a
# compression path (strain < 0) in sigma_yy down to -10 MPa, which the tool
# reports with compression positive. The printed peak, component and
# energies must be those of the rows (the tool prints them with 6
# significant digits, so the comparison allows 1e-5 relative), and each
# PNG must exist and be a PNG.
# Arguments (scarp_add_script_test): scarp, source dir, run dir, ...
set -euo pipefail
src="$2"; run="$3"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
/usr/bin/python3 - <<'PY'
import csv
cols = ["strain", "sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "damage",
        "damage_dissipation", "plastic_dissipation", "external_work"]
def write(name, rows):
    with open(name, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        w.writerows(rows)
# Tension: linear to 5 MPa at strain 0.005, linear softening to 0 at 0.01.
rows = []
for i in range(11):
    e = 0.001 * i
    s = 1e9 * e if e <= 0.005 else 1e9 * (0.01 - e)
    d = 0.0 if e <= 0.005 else (e - 0.005) / 0.005
    rows.append([e, s, 0.3 * s, 0.3 * s, 0.0, d,
                 1234.5 * d, 0.0, 0.5 * 1e9 * 0.005 * e])
write("tension.csv", rows)
# Compression: linear in sigma_yy to -10 MPa at strain -0.01, plastic.
rows = []
for i in range(11):
    e = -0.001 * i
    rows.append([e, 0.2e9 * e, 1e9 * e, 0.2e9 * e, 0.0, 0.0,
                 0.0, 250.0 * i, 5e4 * i])
write("compression.csv", rows)
PY
/usr/bin/python3 "$src/tools/plot_point_curves.py" --output-dir plots \
  tension.csv compression.csv > printed.txt
cat printed.txt
/usr/bin/python3 - <<'PY'
import re, sys
want = {
    "tension": ("sigma_xx", 5000.0, 1234.5, 0.0, 0.5 * 1e9 * 0.005 * 0.01),
    "compression": ("sigma_yy", 10000.0, 0.0, 2500.0, 5e5),
}
lines = open("printed.txt").read().splitlines()
ok = True
for name, (comp, peak, dd, pd, work) in want.items():
    line = [l for l in lines if l.startswith(f"plots/{name}.png:")]
    if len(line) != 1:
        print(f"FAIL: no line for {name}"); ok = False; continue
    m = re.search(r"peak (\S+) (\S+) kPa, damage dissipation (\S+) J/m\^3, "
                  r"plastic dissipation (\S+) J/m\^3, external work (\S+)",
                  line[0])
    got = (m.group(1),) + tuple(float(m.group(i)) for i in range(2, 6))
    for label, g, w in zip(("component", "peak", "damage dissipation",
                            "plastic dissipation", "external work"),
                           got, (comp, peak, dd, pd, work)):
        good = g == w if label == "component" else \
            abs(g - w) <= 1e-5 * max(abs(w), 1.0)
        if not good:
            print(f"FAIL: {name} {label} {g}, expected {w}"); ok = False
    with open(f"plots/{name}.png", "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            print(f"FAIL: plots/{name}.png is not a PNG"); ok = False
sys.exit(0 if ok else 1)
PY
echo "ok: peaks, components and energies as constructed, two PNGs"
