#!/usr/bin/env bash
# The N = 256 frame rate of the paper's scene, measured again and again over a stretch of time: on a shared machine
# the speed of a core changes from one minute to the next, and one median of a few seconds says only what that
# minute was like. Each round is `bench_simulate --counts 256 --prunings grid,tree,sap --voxel 1 --repeats 7
# --frames 1000` pinned to one core; the rounds are spread INTERVAL seconds apart.
#   bash bench/rate_over_time.sh [ROUNDS] [INTERVAL] [CORE]        (defaults 12, 150, 0)
# Prints one row per round (start time, the three broadphases' median frame rates in Hz) and, over the rounds, the
# median, lowest and highest rate of `grid` (the default) and how many rounds reached 10 kHz.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds="${1:-12}"
interval="${2:-150}"
core="${3:-0}"
bin=build/bench_simulate
[ -x "$bin" ] || { echo "rate_over_time.sh: build $bin first (cmake --build build --target bench_simulate)" >&2; exit 2; }
echo "| round | start (UTC) | grid (Hz) | tree (Hz) | sap (Hz) |"
echo "|---:|---|---:|---:|---:|"
grid=()
for ((r = 1; r <= rounds; ++r)); do
  start=$(date -u +%H:%M:%S)
  row=$(taskset -c "$core" "$bin" --counts 256 --prunings grid,tree,sap --voxel 1 --repeats 7 --frames 1000 2>/dev/null |
        awk -F'|' '$2 ~ /^ *256 *$/ { gsub(/ /, "", $3); gsub(/ /, "", $4); gsub(/ /, "", $5); print $3, $4, $5 }')
  read -r g t s <<<"$row"
  echo "| $r | $start | $g | $t | $s |"
  grid+=("$g")
  ((r < rounds)) && sleep "$interval"
done
printf '%s\n' "${grid[@]}" | sort -n | awk -v n="$rounds" '
  { v[NR] = $1; if ($1 >= 10000) hit++ }
  END {
    med = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    printf "\ngrid over %d rounds: median %.0f Hz, lowest %.0f, highest %.0f; %d of %d rounds at or above 10 kHz.\n",
           NR, med, v[1], v[NR], hit + 0, NR
  }'
echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) hardware threads; core $core."
