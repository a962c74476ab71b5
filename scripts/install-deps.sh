#!/usr/bin/env bash
# Installs the Debian packages lamina builds and runs with, if any is missing.
# Safe to run repeatedly: does nothing when everything is present.
set -euo pipefail
PKGS=(cmake g++ make pkg-config ninja-build
      libeigen3-dev libfftw3-dev libhdf5-dev libgmsh-dev gmsh
      libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgtest-dev
      libsuitesparse-dev libboost-graph-dev time openmpi-bin libopenmpi-dev libfftw3-mpi-dev
      clang libclang-rt-14-dev libomp-dev llvm
      libexpat1-dev zlib1g-dev libtiff-dev libssl-dev
      python3 python3-numpy python3-matplotlib python3-h5py universal-ctags
      python3-dev pybind11-dev python3-pytest python3-setuptools python3-wheel python3-pip python3-venv)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "lamina: installing missing Debian packages: ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
