#!/usr/bin/env bash
# bench/simulate_revisions.sh: `voxcd simulate --objects N` at two or more git revisions, measured in one run on this
# machine (docs/simulate.md, "Frame rates across revisions"). Each argument is a git revision (its `voxcd` built in a
# temporary directory: `git archive`, CMake with VOXCD_DEVICE_MODELS=OFF, target voxcd; ccache makes a second run
# quick) or the path of a built `voxcd` (e.g. build/voxcd for the working tree). Then, for N = 256, 4096, 65536 and
# 10^6 (NS overrides) on 1 and 2 threads:
#   - frames per second: medians of ROUNDS rounds, each running every revision in turn (the machine's load falls on
#     all alike), each run a scene of N objects with every other option at its default;
#   - the state hash of every run, which must be the same at every revision and thread count (the script stops if not);
#   - with CALLGRIND=1, instructions per frame at N = 256 and 4096 on one thread: callgrind's count of
#     Simulation::step over 2F frames minus that over F frames, divided by F (repeatable whatever the load).
# Prints a Markdown table. Needs cmake, ninja, g++, git (and valgrind with CALLGRIND=1).
# Usage: bash bench/simulate_revisions.sh REV|VOXCD [REV|VOXCD...]   e.g. 8bfb371 build/voxcd
set -euo pipefail
ROUNDS="${ROUNDS:-3}"
NS="${NS:-256 4096 65536 1000000}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
(($# >= 1)) || { echo "usage: bash bench/simulate_revisions.sh REV|VOXCD [REV|VOXCD...]" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

frames_for() {  # N -> frames of one timed run
  case "$1" in 256) echo 2000 ;; 4096) echo 200 ;; 65536) echo 20 ;; *) echo 3 ;; esac
}

bins=() names=()
for arg in "$@"; do
  if [[ -x "$arg" && ! -d "$arg" ]]; then
    bins+=("$(cd "$(dirname "$arg")" && pwd)/$(basename "$arg")")
    names+=("$arg")
    continue
  fi
  dir="$tmp/r${#bins[@]}"
  mkdir -p "$dir/src"
  git -C "$root" archive "$arg" | tar -x -C "$dir/src"
  cmake -S "$dir/src" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_DEVICE_MODELS=OFF >"$dir/cmake.log" 2>&1 ||
    { echo "simulate_revisions.sh: $arg does not configure ($dir/cmake.log)" >&2; tail -20 "$dir/cmake.log" >&2; exit 1; }
  cmake --build "$dir/build" -j 2 --target voxcd >"$dir/build.log" 2>&1 ||
    { echo "simulate_revisions.sh: $arg does not build:" >&2; tail -20 "$dir/build.log" >&2; exit 1; }
  bins+=("$dir/build/voxcd")
  names+=("$(git -C "$root" log -1 --format='%h' "$arg")")
done

run() {  # BIN N THREADS FRAMES -> "rate hash"
  "$1" simulate --objects "$2" --threads "$3" --frames "$4" --no-progress --json |
    python3 -c 'import json, sys; d = json.load(sys.stdin); print(d["frame_rate_hz"], d["state_hash"])'
}

for ((round = 0; round < ROUNDS; round++)); do
  for n in $NS; do
    for t in 1 2; do
      for i in "${!bins[@]}"; do
        echo "$n $t $(run "${bins[$i]}" "$n" "$t" "$(frames_for "$n")")" >>"$tmp/r$i.rates"
      done
    done
  done
done

ir_per_frame() {  # BIN N FRAMES -> instructions per frame
  local a b
  a="$(valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" --toggle-collect='voxcd::Simulation::step*' \
       "$1" simulate --objects "$2" --threads 1 --frames "$3" --no-progress 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p')"
  b="$(valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" --toggle-collect='voxcd::Simulation::step*' \
       "$1" simulate --objects "$2" --threads 1 --frames "$((2 * $3))" --no-progress 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p')"
  awk -v a="$a" -v b="$b" -v f="$3" 'BEGIN { printf "%.0f", (b - a) / f }'
}

median_of() {  # FILE N THREADS -> median rate, then the hash
  awk -v n="$2" -v t="$3" '$1 == n && $2 == t { print $3, $4 }' "$1" | sort -g |
    awk '{ a[NR] = $1; h[NR] = $2 } END { m = (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2; print m, h[1] }'
}

echo "| objects | revision | 1 thread (Hz) | 2 threads (Hz) | 2 threads / 1 | 1 thread / first revision's | 2 threads / first revision's | instructions per frame, 1 thread (callgrind) | state hash |"
echo "|--:|---|--:|--:|--:|--:|--:|--:|---|"
for n in $NS; do
  first1="" first2="" hash0=""
  for i in "${!bins[@]}"; do
    read -r r1 h1 <<<"$(median_of "$tmp/r$i.rates" "$n" 1)"
    read -r r2 h2 <<<"$(median_of "$tmp/r$i.rates" "$n" 2)"
    for h in $(awk -v n="$n" '$1 == n { print $4 }' "$tmp/r$i.rates"); do
      [[ -z "$hash0" ]] && hash0="$h"
      [[ "$h" == "$hash0" ]] || { echo "simulate_revisions.sh: ${names[$i]} gives state hash $h at N = $n, the first run $hash0" >&2; exit 1; }
    done
    [[ -z "$first1" ]] && first1="$r1" first2="$r2"
    ir="-"
    if [[ "${CALLGRIND:-0}" == 1 && ( "$n" == 256 || "$n" == 4096 ) ]]; then
      ir="$(ir_per_frame "${bins[$i]}" "$n" "$([[ $n == 256 ]] && echo 100 || echo 10)")"
    fi
    awk -v n="$n" -v r="${names[$i]}" -v a="$r1" -v b="$r2" -v fa="$first1" -v fb="$first2" -v ir="$ir" -v h="$h1" \
      'BEGIN { printf "| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s |\n", n, r, a, b, b / a, a / fa, b / fb, ir, h }'
  done
done
echo
echo "\`voxcd simulate --objects N\` with every other option at its default (grid, cpu backend, ALL contacts), frames per second as the tool reports them (medians of $ROUNDS rounds; frames a run: 2000 at 256, 200 at 4096, 20 at 65,536, 3 at 10^6), the same state hash at every revision and thread count. $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $(nproc) hardware threads; load average $(cut -d' ' -f1 /proc/loadavg) at the end."
