#!/usr/bin/env bash
# Installs everything weft needs from Debian 12 packages. Idempotent: when all
# packages are present it only checks them (no apt-get update, no download).
set -euo pipefail

PACKAGES=(
  # toolchain
  g++ cmake make pkg-config ccache git
  # the field's libraries
  libopenvdb-dev libboost-dev libboost-iostreams-dev libtbb-dev
  libopenimageio-dev libopenexr-dev libimath-dev libopencolorio-dev libpng-dev
  libembree-dev libosd-dev
  # mesh files: OBJ/MTL (tinyobjloader), PLY (Assimp)
  libtinyobjloader-dev libassimp-dev
  # small well-kept libraries
  libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  # Mesa (llvmpipe, softpipe) headless through EGL: hwsim's cross-checks
  libegl-mesa0 libgl1-mesa-dri libegl-dev libopengl-dev libgl-dev
  # tools: vdb_render/vdb_print, oiiotool/iinfo, ociocheck; python for scripts
  libopenvdb-tools openimageio-tools opencolorio-tools
  python3 python3-openimageio python3-numpy python3-matplotlib
  # the weft Python module (python/): pybind11 against Debian's python3
  pybind11-dev python3-dev
  # a single-node Slurm cluster for the farm tests (scripts/slurm-local.sh)
  slurmctld slurmd slurm-client munge
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or with sudo) to install them" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
