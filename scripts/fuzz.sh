#!/usr/bin/env bash
# Runs the libFuzzer harnesses (tests/fuzz, docs/reliability-fuzz.md) for a bounded time each.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: 60 s; every target: params vdb sky view_state exr png)
#
# Installs clang and libclang-rt-14-dev when missing (Debian packages, as install-deps.sh does),
# configures build-fuzz/ with clang, -DNIMBUS_FUZZ=ON and -DNIMBUS_SANITIZE=ON (AddressSanitizer
# and UndefinedBehaviorSanitizer), builds only the harnesses (with base, noise, volume,
# render_core and, for view_state, render_sky, for exr, render_image), and runs each one in libFuzzer's fork mode so that it keeps going after a finding:
#   - seeds: tests/fuzz/corpus/<corpus>/ (read, never written), with the dictionary
#     tests/fuzz/<corpus>.dict (<corpus>: params_json, vdb, sky_json, view_state_json, exr, png); new
#     inputs go to build-fuzz/corpus/<target>/, kept between runs;
#   - findings (crashes, broken contracts, out-of-memory, timeouts): build-fuzz/findings/<target>/,
#     with the log in build-fuzz/findings/<target>.log. Record one in tests/fuzz/findings/<corpus>/
#     (replayed by CTest, Fuzz.*FindingsReplay) and move it to the corpus once fixed.
# Leaks are not looked for: OpenVDB 10 leaks the nodes it had read when a corrupt file makes it
# throw (a one-shot command exits right after), and those reports would hide everything else.
# Limits per input: -rss_limit_mb / -malloc_limit_mb (NIMBUS_FUZZ_MEM_MB, default 2048) and
# -timeout (NIMBUS_FUZZ_TIMEOUT, default 25 s). Environment: NIMBUS_FUZZ_BUILD (build directory),
# NIMBUS_FUZZ_JOBS (build jobs, default 2).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
[ $# -gt 0 ] && shift
targets=("$@")
declare -A seeds=([params]=params_json [vdb]=vdb [sky]=sky_json [view_state]=view_state_json [exr]=exr [png]=png)
all_targets=(params vdb sky view_state exr png)
[ ${#targets[@]} -eq 0 ] && targets=("${all_targets[@]}")
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]]; then
  echo "fuzz.sh: SECONDS_PER_TARGET must be a whole number > 0, got '$seconds'" >&2
  exit 2
fi
for t in "${targets[@]}"; do
  [ -n "$t" ] && [ -n "${seeds[$t]+set}" ] || { echo "fuzz.sh: unknown target '$t' (${all_targets[*]})" >&2; exit 2; }
done

# clang's libFuzzer runtime lives in libclang-rt-14-dev (Debian 12).
packages=(clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "fuzz.sh: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

build=${NIMBUS_FUZZ_BUILD:-$root/build-fuzz}
mem_mb=${NIMBUS_FUZZ_MEM_MB:-2048}
timeout_s=${NIMBUS_FUZZ_TIMEOUT:-25}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNIMBUS_BUILD_TESTS=ON \
  -DNIMBUS_FUZZ=ON -DNIMBUS_SANITIZE=ON "${launcher[@]}" >"$build/configure.log" 2>&1 ||
  { cat "$build/configure.log" >&2; echo "fuzz.sh: configuring $build failed" >&2; exit 1; }
cmake --build "$build" -j"${NIMBUS_FUZZ_JOBS:-2}" --target "${targets[@]/#/nimbus_fuzz_}"

status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  log="$build/findings/$t.log"
  before=$(find "$findings" -type f | wc -l)
  echo "fuzz.sh: $t for $seconds s (log: $log)" >&2
  (
    cd "$build"  # libFuzzer's fork mode keeps its temporary files in the working directory
    ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=0:allocator_may_return_null=0} \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
      "$build/tests/fuzz/nimbus_fuzz_$t" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
      -max_total_time="$seconds" -rss_limit_mb="$mem_mb" -malloc_limit_mb="$mem_mb" -timeout="$timeout_s" \
      -detect_leaks=0 -artifact_prefix="$findings/" -print_final_stats=1 -dict="$root/tests/fuzz/${seeds[$t]}.dict" \
      "$corpus" "$root/tests/fuzz/corpus/${seeds[$t]}"
  ) >"$log" 2>&1 || true
  after=$(find "$findings" -type f | wc -l)
  stats=$(grep -E "^#[0-9]+: cov:" "$log" | tail -1 || true)
  echo "fuzz.sh: $t: ${stats:-no status line, see the log}; new findings: $((after - before)) (in $findings)"
  [ "$after" -gt "$before" ] && status=1
done
exit $status
