#!/usr/bin/env bash
# ctest: the chunked particle VTU writer against deal.II's Particles::DataOut
# on 1 and 2 ranks (particle_vtu_writer.cc writes both). Arguments: scarp,
# source dir, run dir, mpiexec, mpi flags, the writer test executable.
set -euo pipefail
src="$2"; run="$3"; mpiexec="$4"; flags="${5//;/ }"; exe="$6"
mkdir -p "$run" && cd "$run"
for np in 1 2; do
  rm -rf "np$np" && mkdir "np$np" && cd "np$np"
  # shellcheck disable=SC2086
  "$mpiexec" $flags -np "$np" "$exe" > log 2>&1 || { cat log; exit 1; }
  /usr/bin/python3 "$src/tests/postprocess/check_particle_vtu.py" \
    "$src/tools" reference chunked "$np"
  cd ..
done
