#!/usr/bin/env bash
# Installs exactly the Debian 12 packages scarp needs, skipping those already
# present (safe to run again). Run as root (or with sudo available).
set -euo pipefail

packages=(
  libdeal.ii-dev      # deal.II 9.4 with MPI, p4est, Trilinos, Boost
  cmake g++ make      # the build
  openmpi-bin         # mpirun for parallel runs and the 2-rank tests
  python3-matplotlib  # the pictures of the main job and the studies
  python3-numpy
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_dependencies: all packages present."
  exit 0
fi

echo "install_dependencies: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq "${missing[@]}"
