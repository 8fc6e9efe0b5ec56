#!/usr/bin/env bash
# The Python module: installs its packages (install-deps.sh python), builds it in build-python
# for Debian's python3 and installs the package nimbus into that python's site-packages
# (/usr/local/lib/python3.11/dist-packages, which Debian's Blender reads too). Idempotent: a
# second run rebuilds nothing and installs the same files. Uses sudo when not root.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh python
cmake -S . -B build-python -DCMAKE_BUILD_TYPE=Release -DNIMBUS_VIEWER_AND_BENCH=OFF -DNIMBUS_BUILD_PYTHON=ON >/dev/null
cmake --build build-python -j2 --target nimbus_python
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo cmake --install build-python --component python
