#!/usr/bin/env bash
# A still's speed against its grain: a view state (VIEW, by default README command 1's,
# samples/views/first-picture.json) at 1280x720, for each multiple-scattering method (the light volume, the octaves, single
# scattering), rendered one frame without and with the grain filter and as the mean of 4 and 16
# jittered frames, each against that method's converged picture (the mean of CONVERGED jittered
# frames, unfiltered: from 32 frames on the filter is off). Prints one Markdown row per method and
# setting: whole-process seconds (median of RUNS, the settings alternated) and the relative RMSE.
# A converged picture already in OUT_DIR is taken as it is (another binary's rows against the same
# anchor).
#   usage: [VIEW=state.json] [METHODS="light-volume octaves single"] scripts/still_grain.sh OUT_DIR NIMBUS_BINARY [RUNS=3] [CONVERGED=64]
set -euo pipefail
out=$1
bin=$2
runs=${3:-3}
converged=${4:-64}
mkdir -p "$out"
here=$(cd "$(dirname "$0")/.." && pwd)
declare -A optics=(
  [light-volume]='{}'
  [octaves]='{"ms_method": "octaves"}'
  [single]='{"ms_method": "octaves", "multiple": 0}'
)
settings=("--no-grain-filter" "" "--spp 4" "--spp 16")
names=("1 frame, unfiltered" "1 frame, filtered (the default)" "mean of 4" "mean of 16")
for method in ${METHODS:-light-volume octaves single}; do
  state="$out/$method.json"
  /usr/bin/python3 - "${VIEW:-$here/samples/views/first-picture.json}" "$state" "${optics[$method]}" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s.setdefault("optics", {}).update(json.loads(sys.argv[3]))
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
  ref="$out/$method-converged.exr"
  [ -f "$ref" ] || "$bin" render --view-state "$state" --res 1280x720 --spp "$converged" -o "$ref" > /dev/null 2>&1
  declare -A times=()
  for run in $(seq "$runs"); do
    for i in "${!settings[@]}"; do
      start=$(date +%s.%N)
      "$bin" render --view-state "$state" --res 1280x720 ${settings[$i]} -o "$out/$method-$i.exr" > /dev/null 2>&1
      times[$i]="${times[$i]:-} $(awk -v a="$(date +%s.%N)" -v b="$start" 'BEGIN {print a - b}')"
    done
  done
  for i in "${!settings[@]}"; do
    median=$(tr ' ' '\n' <<< "${times[$i]}" | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
    err=$("$bin" compare "$out/$method-$i.exr" "$ref" | grep -o "rel_rmse [0-9.e-]*" | cut -d' ' -f2)
    printf "| %s | %s | %.1f s | %.2f %% |\n" "$method" "${names[$i]}" "$median" "$(awk -v e="$err" 'BEGIN {print 100 * e}')"
  done
  unset times
done
