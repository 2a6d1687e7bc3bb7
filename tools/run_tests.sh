#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the quick test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_dependencies.sh
bash tools/build.sh
cd build
ctest -L quick --output-on-failure -j "$(nproc)"
