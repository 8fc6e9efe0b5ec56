#!/usr/bin/env bash
# Installs the Debian 12 packages nimbus builds, tests and benchmarks with. Idempotent: does
# nothing when every package is already installed. Uses sudo when not run as root.
set -euo pipefail

packages=(
  cmake g++ make pkg-config git python3
  libtbb-dev libopenvdb-dev libboost-iostreams-dev libblosc-dev zlib1g-dev
  libopenexr-dev libglm-dev libglfw3-dev libepoxy-dev libegl-dev glslang-tools libgl1-mesa-dri
  libgtest-dev libgmock-dev libcli11-dev nlohmann-json3-dev libkissfft-dev
  libnoise-dev
  libopenvdb-tools python3-openvdb
  libpng-dev openexr
  libimgui-dev xvfb xauth xdotool
  munge slurmctld slurmd slurm-client
)

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
