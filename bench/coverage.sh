#!/usr/bin/env bash
# bench/coverage.sh: the full coverage campaign of rtl/ (docs/verification.md, "Coverage"). In its own build
# directory (default build-cov) with every coverage model and toggle coverage (-DVOXCD_RTL_COVERAGE_FULL=ON), into one coverage directory:
#   1. the AXI tests on the AXI tops' coverage models (test_axi_cov);
#   2. bench/coverage/lanes4.json: every kind of device at LANES 4 (each depth, distance, banks, sparse, brick lanes),
#      6 seeds of 400 jobs, random back-pressure 0.3, cycles compared;
#   3. bench/coverage/lanes.json: LANES 1, 2 and 8; bench/coverage/widths.json: narrow and wide widths at LANES 2;
#   4. LANES 4 and the widths at LANES 2 again, other seeds, aimed at the stimulus bins still empty (--aim-at-holes);
#   5. every configuration of 2 and 3 once more, aimed at the tops of the fields (tags, memories, point counts).
# Prints the merged report and writes it to docs/results/coverage.txt. Usage: bash bench/coverage.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-cov}
export CCACHE_BASEDIR="$PWD"
start=$SECONDS
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_RTL_COVERAGE_FULL=ON -UVOXCD_RTL_COVERAGE_MODELS -UVOXCD_RTL_COVERAGE_FULL_MODELS >/dev/null
cmake --build "$build" -j2 --target voxcd voxcd_rtl_cov_backend test_axi_cov
echo "coverage: built in $((SECONDS - start)) s" >&2
dir="$build/coverage"
rm -rf "$dir"
mkdir -p "$dir"
VOXCD_COVERAGE_DIR="$dir" "$build/test_axi_cov" --gtest_brief=1
"$build/voxcd" regress --campaign bench/coverage/lanes4.json --coverage "$dir" >"$dir/lanes4.txt"
"$build/voxcd" regress --campaign bench/coverage/lanes.json --coverage "$dir" >"$dir/lanes.txt"
"$build/voxcd" regress --campaign bench/coverage/widths.json --coverage "$dir" >"$dir/widths.txt"
"$build/voxcd" regress --seeds 101-103 --configs "default;SB 8 WB 8;BL 3;BANKS 2 BL 3;SB 8 WB 8 BANKS 2 BL 3;BL 3 TX 1" \
  --lanes 4 --backends rtl --jobs-per-shard 200 --cycles --stall 0.3 --coverage "$dir" --aim-at-holes \
  >"$dir/aimed.txt"
"$build/voxcd" regress --seeds 101-103 --configs "PW 32 MW 32 TW 64 TAGW 32;SB 4 WB 8;SB 16 WB 8" --lanes 2 \
  --backends rtl --jobs-per-shard 200 --cycles --stall 0.3 --coverage "$dir" --aim-at-holes >"$dir/aimed2.txt"
# The top of every field the generator keeps small: tags in the upper half, the last map and shell block at the top of
# their memories, a job of every shell word (its hit and point counts at their largest), on every configuration.
top=job.tag.top,job.map.top,job.shell.top,job.points.max
"$build/voxcd" regress --seeds 201-202 --configs "$(/usr/bin/python3 -c 'import json; print(";".join(json.load(open("bench/coverage/lanes4.json"))["configs"]))')" \
  --lanes 4 --backends rtl --jobs-per-shard 60 --cycles --stall 0.3 --coverage "$dir" --aim "$top" >"$dir/top4.txt"
"$build/voxcd" regress --seeds 201-202 --configs "$(/usr/bin/python3 -c 'import json; print(";".join(json.load(open("bench/coverage/widths.json"))["configs"]))')" \
  --lanes 2 --backends rtl --jobs-per-shard 60 --cycles --stall 0.3 --coverage "$dir" --aim "$top" >"$dir/top2.txt"
mkdir -p docs/results
{
  echo "# bash bench/coverage.sh ($(date -u +%Y-%m-%d), $((SECONDS - start)) s on $(nproc) cores)"
  grep -h "^campaign:\|^shards:\|^failures:\|^aiming" "$dir/lanes4.txt" "$dir/lanes.txt" "$dir/widths.txt" "$dir/aimed.txt" "$dir/aimed2.txt" \
    "$dir/top4.txt" "$dir/top2.txt" || true
  cat "$dir/summary.txt"
} | tee docs/results/coverage.txt
echo "coverage: done in $((SECONDS - start)) s" >&2
