#!/usr/bin/env bash
# Record a perf profile of each MPI rank into its own file (Open MPI):
#   mpirun -np 2 tools/perf_each_rank.sh build/scarp scene.prm
# writes perf_rank0.data, perf_rank1.data, ... in the working directory
# (PERF_PREFIX=dir/name changes "perf_rank"); read them with
#   perf report -i perf_rank0.data --no-children
set -euo pipefail
exec perf record -q -o "${PERF_PREFIX:-perf_rank}${OMPI_COMM_WORLD_RANK:-0}.data" "$@"
