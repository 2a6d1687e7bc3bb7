#!/usr/bin/env bash
# Load balancing during a run: a block that slides from the left half of the
# box into the right half carries its points from one rank's cells to the
# other's. With <Check interval> = 20 the 2-rank run must repartition at
# least once and still give the physics of the 1-rank run: the same energies
# and momenta in statistics.csv (to 1e-9 relative: repartitioning only
# reorders the sums) and no point lost. It also checks the timing of the
# parts of the MPM step in summary.json.
# Arguments (from scarp_add_script_test): scarp, source dir, run dir,
# mpiexec, mpi flags.
set -euo pipefail
scarp="$1"; src="$2"; run="$3"; mpiexec="$4"; flags="${5//;/ }"
rm -rf "$run"; mkdir -p "$run"; cd "$run"
cat > slide.prm <<'PRM'
set Dimension = 2
set Materials = rock
set Bodies    = block
set Stages    = slide
set Output directory = OUT
subsection Mesh
  set Lower corner = 0, 0
  set Upper corner = 16, 4
  set Cell size    = 0.5
  subsection Boundary conditions
    set Bottom = slip
  end
end
subsection Material rock
  set Model   = linear elastic
  set Density = 1000
  subsection Elasticity
    set Young's modulus = 1e6
    set Poisson's ratio = 0.25
  end
end
subsection Body block
  set Material = rock
  set Particles per cell = 2
  set Shape = box
  set Box corners = 0.5, 0, 4.5, 2
  subsection Initial velocity
    set Function expression = 4; 0
  end
end
subsection Physics
  set Gravity = 0, -9.81
end
subsection Stage slide
  set End time = 2.5
end
subsection Output
  set Interval = 0
  set Statistics interval = 50
end
subsection Load balancing
  set Check interval = 20
end
PRM
sed 's/OUT/one/' slide.prm > one.prm
sed 's/OUT/two/' slide.prm > two.prm
"$scarp" one.prm > one.log 2>&1 || { tail -5 one.log; exit 1; }
$mpiexec $flags -np 2 "$scarp" two.prm > two.log 2>&1 || { tail -5 two.log; exit 1; }
/usr/bin/python3 - <<'PY'
import csv, json, sys
one = list(csv.DictReader(open("one/statistics.csv")))
two = list(csv.DictReader(open("two/statistics.csv")))
s2 = json.load(open("two/summary.json"))
fails = 0
def check(ok, what):
    global fails
    print(("  ok:   " if ok else "  FAIL: ") + what)
    fails += not ok
check(len(one) == len(two), f"same number of statistics rows ({len(one)}, {len(two)})")
check(s2["load_rebalances"] >= 1, f"2 ranks repartitioned {s2['load_rebalances']:.0f} time(s)")
worst, where = 0.0, ""
for a, b in zip(one, two):
    for key in ("kinetic_energy", "strain_energy", "gravitational_energy",
                "momentum_x", "momentum_y", "mass", "material_points"):
        x, y = float(a[key]), float(b[key])
        scale = max(abs(x), abs(float(one[0]["kinetic_energy"])) * 1e-6, 1e-300)
        if abs(x - y) / scale > worst:
            worst, where = abs(x - y) / scale, f"{key} at step {a['step']}"
check(worst < 1e-9, f"1 vs 2 ranks: largest relative difference {worst:.2e} ({where})")
check(one[-1]["material_points"] == two[-1]["material_points"] == one[0]["material_points"],
      "no point lost")
x_end = float(one[-1]["momentum_x"]) / float(one[-1]["mass"])
check(abs(x_end - 4) < 1e-6 * 4, f"block still slides at 4 m/s (mean {x_end:.9f})")
# The parts of the MPM step (summary.json, mpm_step_parts) are timed inside
# its phase, one after the other: each >= 0, and on each run their sum is
# at most the phase's wall time, and on one rank covers most of it (what is
# left out is the reduction of the step report and the timer calls). Time
# counted twice breaks the upper bound, most of the step untimed the lower.
# The exchange is the part of P2G and the grid update spent in the ghost
# rounds, counted in those two as well.
five = ["shape functions", "P2G", "grid update", "G2P", "constitutive update"]
for name in ("one", "two"):
    s = json.load(open(f"{name}/summary.json"))
    parts = dict(s.get("mpm_step_parts", {}))
    exchange = parts.pop("exchange", -1.0)
    step = s["wall_time_per_phase"]["MPM step"]
    total = sum(parts.values())
    check(sorted(parts) == sorted(five) and min(parts.values()) >= 0,
          f"{name}: the five parts of the MPM step, none negative")
    check(0 <= exchange <= parts["P2G"] + parts["grid update"],
          f"{name}: exchange {exchange:.4f} s within P2G and the grid update")
    # Over the ranks: min <= avg <= max for every part, rank 0's own value
    # among them, the ranks named those of the run, and compute = the five
    # parts less the exchange (on one rank exactly rank 0's).
    over = s.get("mpm_step_parts_over_ranks", {})
    ranks = s["mpi_ranks"]
    check(sorted(over) == sorted(five + ["exchange", "compute"]),
          f"{name}: every part over the ranks ({sorted(over)})")
    mine = dict(parts, exchange=exchange, compute=total - exchange)
    for part, m in over.items():
        eps = 1e-9 * max(1.0, abs(m["max"]))
        check(m["min"] - eps <= m["avg"] <= m["max"] + eps
              and m["min"] - eps <= mine[part] <= m["max"] + eps
              and 0 <= m["min_rank"] < ranks and 0 <= m["max_rank"] < ranks,
              f"{name}: {part} over the ranks {m}, rank 0's {mine[part]}")
        if ranks == 1:
            check(abs(m["avg"] - mine[part]) <= eps,
                  f"{name}: {part} on one rank is rank 0's")
    # On 2 ranks the rank that writes the summary may hold few points and
    # wait for the other in the reduction: only the upper bound there.
    lower = 0.5 * step if name == "one" else 0.0
    check(lower <= total <= step * 1.0001,
          f"{name}: parts sum to {total:.4f} s of the MPM step's {step:.4f} s")
sys.exit(1 if fails else 0)
PY
