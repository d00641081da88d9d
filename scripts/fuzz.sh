#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang-14, ASan + UBSan, build-fuzz/) and runs each for
# the given time from its seeds (fuzz/corpus/<target>); prints executions and coverage.
#
#   scripts/fuzz.sh [seconds per target, default 60] [target ...]
#
# Targets: body_spec scene sid_reader results_reader mesh_arrays (default: all). The growing
# corpus is kept in build-fuzz/corpus/<target>, crashing inputs in build-fuzz/artifacts/<target>/,
# each run's log in build-fuzz/logs/<target>.log. -malloc_limit_mb: HDF5 asks malloc for what a
# damaged size field claims (scripts/clang-env.sh); libFuzzer would call any malloc above
# -rss_limit_mb an out-of-memory crash. FLEXMBS_JOBS sets build parallelism (default: nproc);
# FLEXMBS_FUZZ_RUNS=N stops each target after N executions (the time still bounds it).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-60}
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(body_spec scene sid_reader results_reader mesh_arrays)
jobs=${FLEXMBS_JOBS:-$(nproc)}
runs=${FLEXMBS_FUZZ_RUNS:-}

# The libraries get coverage instrumentation (fuzzer-no-link); the targets link libFuzzer.
source scripts/clang-env.sh
configure_clang_tree build-fuzz "-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
  -DFLEXMBS_BUILD_TESTS=OFF -DFLEXMBS_BUILD_FUZZ=ON
cmake --build build-fuzz -j"$jobs" --target "${targets[@]/#/fuzz_}"
export_sanitizer_options "$root"

# HDF5 leaks on most damaged files (scripts/lsan.supp): a leak check after each of them would
# take 90 % of the HDF5 readers' time. Their runs go without, and their corpora are then replayed
# with leak checks on.
declare -A no_leak_check=([sid_reader]=1 [results_reader]=1)

status=0
summary=()
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/artifacts/$t" build-fuzz/logs
  log=build-fuzz/logs/$t.log
  echo "== fuzz_$t for ${seconds} s"
  leaks=1
  [[ -z ${no_leak_check[$t]:-} ]] || leaks=0
  if ! "build-fuzz/bin/fuzz_$t" -max_total_time="$seconds" ${runs:+-runs="$runs"} -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1048576 -print_final_stats=1 \
      -detect_leaks=$leaks -artifact_prefix="build-fuzz/artifacts/$t/" "build-fuzz/corpus/$t" "fuzz/corpus/$t" > "$log" 2>&1; then
    status=1
    tail -n 40 "$log"
  fi
  if [[ $leaks == 0 ]] && ! "build-fuzz/bin/fuzz_$t" -runs=0 -malloc_limit_mb=1048576 -artifact_prefix="build-fuzz/artifacts/$t/" \
      "build-fuzz/corpus/$t" > "build-fuzz/logs/$t.leaks.log" 2>&1; then
    status=1
    tail -n 40 "build-fuzz/logs/$t.leaks.log"
  fi
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  final=$(grep -E '^#[0-9]+' "$log" | tail -n 1 | grep -oE 'cov: [0-9]+ ft: [0-9]+' || true)
  crashes=$(find "build-fuzz/artifacts/$t" -type f | wc -l)
  summary+=("$(printf '%-12s executions %-10s %-22s artifacts %s' "$t" "${executed:-?}" "${final:-cov: ? ft: ?}" "$crashes")")
done
printf '%s\n' "== summary (${seconds} s per target)" "${summary[@]}"
exit "$status"
