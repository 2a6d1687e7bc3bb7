#!/usr/bin/env bash
# The main job: installs the dependencies, builds, runs the Joss Bay cliff
# collapse (prm/joss_bay.prm: the converged setting, to 0.5 s after the
# failure onset, 3 to 14 min on 2 cores by machine, 17 min sharing them
# with another run) on all cores and draws its pictures.
# Usage: tools/run_main_job.sh [scene.prm]   (default prm/joss_bay.prm)
set -euo pipefail
cd "$(dirname "$0")/.."
scene="${1:-prm/joss_bay.prm}"
bash tools/install_dependencies.sh
bash tools/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ranks=$(nproc)
mpirun --oversubscribe -np "$ranks" build/scarp "$scene" | tee main_job.log
# The run names its output directory on its last line ("... Output in DIR/").
outdir=$(sed -n 's/.*Output in \(.*\)$/\1/p' main_job.log | tail -1)
bash tools/plot_run.sh "$outdir"
