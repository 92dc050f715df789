#!/usr/bin/env bash
# Installs the Debian 12 packages skinspec needs (only those missing), then configures and builds the
# Release build in build/. Safe to re-run: nothing is reinstalled and the build is incremental.
# Run as root or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config
  libopenimageio-dev openimageio-tools libopencolorio-dev opencolorio-tools
  libglm-dev libtbb-dev libpcg-cpp-dev catch2 libplplot-dev plplot-driver-cairo fonts-dejavu-core libnlopt-cxx-dev libhwy-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libfmt-dev libfftw3-dev libeigen3-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-venv
  libpugixml-dev libopenmpi-dev openmpi-bin libjemalloc-dev
  clang libclang-rt-14-dev
  ccache
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -gt 0 ]; then
  sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  echo "setup: installing ${missing[*]}"
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

mkdir -p build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build/configure.log 2>&1 || { cat build/configure.log; exit 1; }
cmake --build build -j "$(nproc)"
