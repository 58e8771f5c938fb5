#!/usr/bin/env bash
# setup.sh — installs what is missing (Debian 12 packages only), then configures and builds
# fenestra in build/. Idempotent: a second run installs nothing and rebuilds only what changed.
# Run as root (or with sudo available). Used by both README commands and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libglm-dev libopenexr-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libgtest-dev libcli11-dev
  libembree-dev   # only the yardstick of `fenestra bench`
  libopenmpi-dev openmpi-bin openssh-client   # mpirun fenestra render (openssh: Open MPI's launcher wants it)
  python3 python3-matplotlib python3-numpy   # scripts/compare.py's charts
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
