#!/usr/bin/env bash
# bench/cosim_instructions.sh: the RTL's co-simulation cost at two or more git revisions, from one run (docs/hardware.md,
# "Co-simulation speed"). For each revision: rtl/ of that revision (`git archive`; "worktree" = the files as they
# are) Verilated as bench_cosim's fastest model (LANES 4, SAW 12, MAW 13, --noassert, -O3 --x-assign fast
# --x-initial fast) around bench/cosim_instructions.cpp, with the parameters after an "@" (NAME=VALUE, comma
# separated: "worktree@Depth=5" is the working tree's RTL at pipeline depth 5), then
#   - instructions per device cycle: callgrind's count for 12 jobs minus that for 4 (the set-up cancels), divided
#     by the cycles between them: repeatable on any x86-64 machine, whatever its load;
#   - Mcycles/s: the median over REPEATS runs of 64 jobs (4096 points each, COUNT) by wall time;
# each with its ratio to the first revision. Every revision must give the same hits (it is the same device) and, at
# the same parameters, the same cycles (a deeper pipeline adds its depth to the first job's latency); the script
# stops if they differ.
#
# Needs verilator, valgrind, g++ (Debian packages). Usage: bash bench/cosim_instructions.sh REV[@NAME=V,...] [...]
#   e.g. bash bench/cosim_instructions.sh d4cede9 worktree worktree@Depth=5
set -euo pipefail
REPEATS="${REPEATS:-5}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
(($# >= 1)) || { echo "usage: bash bench/cosim_instructions.sh REV [REV...]" >&2; exit 2; }
for tool in verilator valgrind g++ git; do
  command -v "$tool" >/dev/null || { echo "cosim_instructions.sh: $tool not found" >&2; exit 1; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

ir_of() {  # BINARY JOBS: "cycles instructions"
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$1" "$2" 2>"$tmp/cg.err" >"$tmp/cg.txt"
  echo "$(awk '{print $2}' "$tmp/cg.txt") $(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.err")"
}

rows=()
for spec in "$@"; do
  rev="${spec%%@*}"
  params=()
  if [[ "$spec" == *@* ]]; then
    IFS=',' read -r -a kv <<<"${spec#*@}"
    for p in "${kv[@]}"; do params+=("-G$p"); done
  fi
  dir="$tmp/r$((${#rows[@]}))"
  mkdir -p "$dir"
  if [[ "$rev" == worktree ]]; then
    cp -r "$root/rtl" "$dir/rtl"
    subject="the working tree"
  else
    git -C "$root" archive "$rev" rtl | tar -x -C "$dir"
    subject="$(git -C "$root" log -1 --format='%h %cs' "$rev")"
  fi
  verilator --cc --exe --build -j 2 -O3 --x-assign fast --x-initial fast --noassert -GLANES=4 -GSAW=12 -GMAW=13 \
    "${params[@]}" \
    --top-module voxcd_device -I"$dir/rtl" -F "$dir/rtl/voxcd.f" "$root/bench/cosim_instructions.cpp" \
    -Mdir "$dir/obj" -CFLAGS "-O3 -std=c++17" -MAKEFLAGS "OPT_FAST=-O3 OPT_SLOW=-O1 OPT_GLOBAL=-O3" >"$dir/build.log" 2>&1 ||
    { echo "cosim_instructions.sh: $spec does not build ($dir/build.log):" >&2; tail -20 "$dir/build.log" >&2; exit 1; }
  bin="$dir/obj/Vvoxcd_device"
  read -r c4 i4 <<<"$(ir_of "$bin" 4)"
  read -r c12 i12 <<<"$(ir_of "$bin" 12)"
  rates=()
  for ((k = 0; k < REPEATS; k++)); do
    read -r _ cycles _ hits _ secs <<<"$("$bin" 64)"
    rates+=("$(awk -v c="$cycles" -v s="$secs" 'BEGIN { printf "%.4f", c / s / 1e6 }')")
  done
  median="$(printf '%s\n' "${rates[@]}" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }')"
  ipc="$(awk -v a="$i4" -v b="$i12" -v c="$c4" -v d="$c12" 'BEGIN { printf "%.0f", (b - a) / (d - c) }')"
  rows+=("$spec|$subject|$ipc|$median|$cycles|$hits")
done

first_ipc="" first_rate="" first_hits=""
declare -A cycles_at  # cycles by parameters
echo "| revision | RTL of | device cycles | instructions per cycle (callgrind) | ratio | Mcycles/s (wall, median of $REPEATS) | ratio |"
echo "|---|---|--:|--:|--:|--:|--:|"
for row in "${rows[@]}"; do
  IFS='|' read -r spec subject ipc rate cycles hits <<<"$row"
  at="${spec#*@}"
  [[ "$spec" == *@* ]] || at="(defaults)"
  if [[ -z "$first_ipc" ]]; then
    first_ipc=$ipc first_rate=$rate first_hits=$hits
  elif [[ "$hits" != "$first_hits" ]]; then
    echo "cosim_instructions.sh: $spec gives $hits hits, the first row $first_hits" >&2
    exit 1
  fi
  if [[ -n "${cycles_at[$at]:-}" && "${cycles_at[$at]}" != "$cycles" ]]; then
    echo "cosim_instructions.sh: $spec gives $cycles cycles, another row of the same parameters ${cycles_at[$at]}" >&2
    exit 1
  fi
  cycles_at[$at]=$cycles
  awk -v r="$spec" -v s="$subject" -v c="$cycles" -v i="$ipc" -v f="$first_ipc" -v m="$rate" -v g="$first_rate" \
    'BEGIN { printf "| %s | %s | %d | %d | %.2f | %.2f | %.2f |\n", r, s, c, i, f / i, m, m / g }'
done
echo
echo "LANES 4 (SAW 12, MAW 13, --noassert), 64 jobs of 4096 points on a 64^3 voxmap, COUNT, $first_hits hits in every row; ratios are speed-ups over the first row (fewer instructions, more cycles per second). $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $(nproc) hardware threads."
