#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, ASan and UBSan into build-fuzz/ and runs each for EXECS executions
# (default 10^6), one after the other, each from its seed corpus and its regressions:
#   bash tests/fuzz/run.sh [EXECS] [TARGET...]        targets: mesh mesh_obj vectors object_file scene scene_file recording
# Inputs a run finds interesting go to <build>/corpus/<target>/; a crash, leak, timeout or out-of-memory input
# goes to <build>/findings/<target>/ (copy it to tests/fuzz/regressions/<target>/ once fixed). Prints, per
# target: executions, seconds, findings. Exit status 1 when any target found something. FUZZ_SECONDS=N stops each
# target after N seconds even if it has not reached EXECS (the count it reached is printed).
# FUZZ_SANITIZERS=leak,undefined builds into build-fuzz-leak-undefined/ with LeakSanitizer and UBSan but without
# ASan's allocator: the slow targets (mesh_obj, mesh, scene) run many times faster; replay what it found under
# ASan with `build-fuzz/fuzz_<target> -runs=0 <build>/corpus/<target>` (docs/robustness.md, Fuzzing).
set -euo pipefail
cd "$(dirname "$0")/../.."
execs="${1:-1000000}"
[ $# -gt 0 ] && shift
targets=("$@")
((${#targets[@]})) || targets=(mesh mesh_obj vectors object_file scene scene_file recording)

command -v clang++ >/dev/null || { echo "run.sh needs clang++: apt-get install -y clang libclang-rt-14-dev" >&2; exit 2; }
sanitizers="${FUZZ_SANITIZERS:-address,undefined}"
bdir=build-fuzz
[ "$sanitizers" = address,undefined ] || bdir=build-fuzz-${sanitizers//,/-}
cmake -S . -B "$bdir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
      -DVOXCD_FUZZ=ON -DVOXCD_FUZZ_SANITIZERS="$sanitizers" -DVOXCD_DEVICE_MODELS=OFF -DVOXCD_WERROR=OFF >/dev/null
cmake --build "$bdir" -j2 --target "${targets[@]/#/fuzz_}"

export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
summary=()
for t in "${targets[@]}"; do
  corpus=$bdir/corpus/$t
  found=$bdir/findings/$t
  mkdir -p "$corpus" "$found"
  log=$bdir/fuzz_$t.log
  start=$(date +%s%N)
  rc=0
  # -timeout: seconds per input before it counts as a hang; -rss_limit_mb: memory before it counts as one.
  "$bdir/fuzz_$t" -runs="$execs" -max_total_time="${FUZZ_SECONDS:-0}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$found/" "$corpus" "tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t" >"$log" 2>&1 || rc=$?
  secs=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  done_execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  findings=$(find "$found" -type f | wc -l)
  if [ "$rc" != 0 ]; then
    status=1
    echo "fuzz_$t stopped (exit $rc); the end of $log:" >&2
    tail -n 30 "$log" >&2
  fi
  summary+=("$(printf '%-12s %12s %9.1f %9s' "$t" "${done_execs:-?}" "$secs" "$findings")")
done
printf '%-12s %12s %9s %9s\n' target executions seconds findings
printf '%s\n' "${summary[@]}"
exit $status
