#!/usr/bin/env bash
# The viewer's frame on a GPU machine (the `device` tool's, when one is lent): builds the nimbus
# program (Release, viewer and benches) unless BUILD_DIR already holds one, then measures at
# 1920x1080 what a demanding user sees: the device's rates (`nimbus bench gl`), and the orbit,
# the time-lapse and the sun drag with each pass's GPU time (GL_TIME_ELAPSED queries on a GPU) and
# fragments (`nimbus bench view`). The target: 60 fps at full quality. Prints Markdown tables,
# and copies them to OUT_DIR (the device tool's $OUT) when given.
#   usage: [BUILD_DIR=build-gpu] [SIZES=1920x1080] [FRAMES=60] scripts/gpu_view_bench.sh [OUT_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$here/build-gpu}
sizes=${SIZES:-1920x1080}
frames=${FRAMES:-60}
out=${1:-}
if [ ! -x "$build/nimbus" ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DNIMBUS_BUILD_TESTS=OFF -DNIMBUS_VIEWER_AND_BENCH=ON > /dev/null
  cmake --build "$build" --target nimbus -j "$(nproc)"
fi
log=$(mktemp)
{
  echo "# $(date -u +%FT%TZ) $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || echo "(no nvidia-smi)"
  "$build/nimbus" bench gl --sizes "$sizes"
  "$build/nimbus" bench view --sizes "$sizes" --frames "$frames" --still-samples 0 --error-every 3 \
    --paths 'orbit|orbit, temporal|time-lapse|time-lapse, temporal|sun drag'
} 2>&1 | tee "$log"
if [ -n "$out" ]; then
  mkdir -p "$out"
  cp "$log" "$out/gpu_view_bench.md"
fi
rm -f "$log"
