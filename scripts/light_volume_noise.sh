#!/usr/bin/env bash
# The light volume's photon noise in the picture: each cloud rendered with the slicer (no jitter,
# so the volume is all that changes) at the default photons with seeds 1-3, against the same view
# with 2^24 photons (the converged volume of the same model), by the binaries given (e.g. the code
# before a change and after it). Prints one row per binary and cloud: the relative RMSE of each
# seed against the converged picture, and the volume's build time.
#   usage: scripts/light_volume_noise.sh OUT_DIR NEW_BINARY [OLD_BINARY ...]
set -euo pipefail
out=$1; shift
new=$1
mkdir -p "$out"
declare -A view=(
  [cumulus-mediocris]="--eye 1500,-6500,400 --look-at 0,0,900"
  [cumulus-congestus]="--eye 1200,-5000,2000 --look-at 0,0,2500"
  [stratus]="--eye 0,-1200,-575 --look-at 0,0,425"
)
common="--scene none --res 320x180 --no-jitter --sun-elevation 35 --sun-azimuth 135"
for cloud in cumulus-mediocris cumulus-congestus stratus; do
  [ -f "$out/$cloud.vdb" ] || "$new" generate --preset "$cloud" -o "$out/$cloud.vdb" > /dev/null
  [ -f "$out/$cloud-converged.exr" ] || "$new" render "$out/$cloud.vdb" $common ${view[$cloud]} --ms-photons 16777216 --ms-seed 99 -o "$out/$cloud-converged.exr" > /dev/null 2>&1
  for bin in "$@"; do
    tag=$(basename "$bin")
    row="| $cloud | $tag |"
    for seed in 1 2 3; do
      line=$("$bin" render "$out/$cloud.vdb" $common ${view[$cloud]} --ms-seed $seed -o "$out/$cloud-$tag-$seed.exr" 2>&1)
      ms=$(grep -o "built in [0-9]* ms" <<< "$line" | grep -o "[0-9]*")
      err=$("$new" compare "$out/$cloud-converged.exr" "$out/$cloud-$tag-$seed.exr" | grep -o "rel_rmse [0-9.e-]*" | cut -d' ' -f2)
      row="$row $err ($ms ms) |"
    done
    echo "$row"
  done
done
