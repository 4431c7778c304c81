#!/usr/bin/env bash
# Installs the Debian packages torte needs, and only those that are missing (idempotent).
# Usage: scripts/install-deps.sh [--bench] [--cycles] [--plots] [--fuzz]   (--bench adds Embree for
# bench/embree-compare, --cycles Blender and Python image reading for make bench-cycles, --plots Python image
# reading and matplotlib for the RMSE scripts in scripts/, --fuzz clang's libFuzzer and sanitizer runtimes for
# make fuzz)
set -euo pipefail
packages=(cmake clang g++ make pkg-config ninja-build libhwy-dev libtbb-dev libopenimageio-dev liblua5.4-dev
          libbenchmark-dev catch2 zlib1g-dev liblz4-dev libxxhash-dev libopencolorio-dev
          openimageio-tools openmpi-bin libopenmpi-dev libcli11-dev libopenexr-dev libpng-dev
          libtinygltf-dev nlohmann-json3-dev libstb-dev time)  # tiny_gltf.h needs nlohmann/json and stb to build; OIIO's CMake config checks that /usr/bin/iconvert etc. exist; time: GNU time for scripts/gallery.sh
for arg in "$@"; do
  case "$arg" in
    --bench) packages+=(libembree-dev) ;;
    --cycles) packages+=(blender python3-numpy python3-openimageio) ;;  # make bench-cycles: Cycles and region means
    --plots) packages+=(python3-numpy python3-openimageio python3-matplotlib) ;;  # scripts/integrator-rmse.sh
    --fuzz) packages+=(libclang-rt-14-dev) ;;  # make fuzz: libFuzzer and the sanitizer runtimes
    *) echo "install-deps: unknown option $arg" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then missing+=("$p"); fi
done
if ((${#missing[@]} == 0)); then exit 0; fi
echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 update -qq
"${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}"
