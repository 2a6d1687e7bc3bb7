#!/usr/bin/env bash
# The main job: installs the dependencies, builds, runs the Joss Bay cliff
# collapse (prm/joss_bay.prm) on all cores and draws its pictures.
# Usage: tools/run_main_job.sh [scene.prm]   (default prm/joss_bay.prm)
set -euo pipefail
cd "$(dirname "$0")/.."
scene="${1:-prm/joss_bay.prm}"
bash tools/install_dependencies.sh
bash tools/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ranks=$(nproc)
mpirun --oversubscribe -np "$ranks" build/scarp "$scene" | tee main_job.log
outdir=$(sed -n 's/^ *set *Output directory *= *//p' "$scene" | tail -1)
bash tools/plot_run.sh "$outdir"
