#!/usr/bin/env bash
# Installs the Debian 12 packages a set-up command needs, and only those:
#   scripts/install-deps.sh main     the lean program of the main job (generate, info, render...)
#   scripts/install-deps.sh python   that, and the Python module (pybind11, NumPy)
#   scripts/install-deps.sh [test]   everything: the viewer and benchmarks, the test suites, their
#                                    independent checks, Slurm, Blender (the default)
# Idempotent: does nothing when every package is already installed. Uses sudo when not root.
set -euo pipefail

group="${1:-test}"
main=(
  cmake g++ make pkg-config
  libtbb-dev libopenvdb-dev libboost-iostreams-dev libblosc-dev zlib1g-dev
  libopenexr-dev libglm-dev libepoxy-dev libegl-dev libgl-dev libgl1-mesa-dri libpng-dev
  libcli11-dev nlohmann-json3-dev
)
python=(pybind11-dev python3-dev python3-numpy)
test=(
  git python3 libglfw3-dev libimgui-dev
  libgtest-dev libgmock-dev libkissfft-dev libnoise-dev glslang-tools
  libopenvdb-tools python3-openvdb openexr python3-pytest python3-hypothesis blender
  xvfb xauth xdotool
  munge slurmctld slurmd slurm-client
)
case "$group" in
  main) packages=("${main[@]}") ;;
  python) packages=("${main[@]}" "${python[@]}") ;;
  test) packages=("${main[@]}" "${python[@]}" "${test[@]}") ;;
  *) echo "install-deps.sh: unknown group '$group' (main, python or test)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "installing: ${missing[*]}" >&2
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
