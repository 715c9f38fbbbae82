#!/usr/bin/env bash
# bench/kernel_revisions.sh: the cpu backend's lookup kernels (ref/fast) at two or more git revisions, measured in one
# run on this machine (docs/device-speed.md). For each revision: its ref/ (`git archive`; "worktree" = the files as
# they are) compiled with bench/bench_kernel.cpp of the working tree into one program (-O3, the flags
# ref/CMakeLists.txt gives fast/fast.cpp), then
#   - ns per point per core: medians of ROUNDS rounds, each running every revision's program in turn (so that the
#     machine's load falls on all alike), each program taking the median of its own repeats;
#   - instructions per point: callgrind's count for 2 jobs' worth of points minus that for 1 (set-up cancels),
#     divided by the points between them: repeatable whatever the load (valgrind runs the AVX2 kernels, never the
#     AVX-512 ones: it does not emulate AVX-512);
# each with its ratio to the first revision. Every revision must count the same hits; the script stops if not.
#
# Needs g++, valgrind, git. Usage: bash bench/kernel_revisions.sh REV [REV...]   e.g. 8bfb371 worktree
# CASES (default the four lookup cases) picks bench_kernel's cases, e.g. CASES="2bit-in-cache 2bit-small-jobs".
set -euo pipefail
ROUNDS="${ROUNDS:-5}"
read -r -a cases <<<"${CASES:-2bit-in-cache 2bit-out-of-cache distance-in-cache distance-out-of-cache}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
(($# >= 1)) || { echo "usage: bash bench/kernel_revisions.sh REV [REV...]" >&2; exit 2; }
for tool in valgrind g++ git; do
  command -v "$tool" >/dev/null || { echo "kernel_revisions.sh: $tool not found" >&2; exit 1; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

bins=()
for rev in "$@"; do
  dir="$tmp/r${#bins[@]}"
  mkdir -p "$dir/include/voxcd"
  if [[ "$rev" == worktree ]]; then
    cp -r "$root/ref" "$dir/ref"
  else
    git -C "$root" archive "$rev" ref | tar -x -C "$dir"
  fi
  ln -s "$dir/ref" "$dir/include/voxcd/ref"
  objs=()
  # ref/sparse.cpp from the revision that brought sparse maps (pipeline.cpp reads their layout) on.
  sparse=()
  [[ -f "$dir/ref/sparse.cpp" ]] && sparse=("$dir/ref/sparse.cpp")
  for src in "$dir"/ref/{config,types,fixed,pipeline,float_model,timing,banks}.cpp "${sparse[@]}" "$dir"/ref/fast/*.cpp; do
    extra=()
    [[ "$(basename "$src")" == fast.cpp ]] && extra=(-fno-trapping-math -ffp-contract=fast)
    obj="$dir/$(basename "$(dirname "$src")")_$(basename "$src" .cpp).o"
    g++ -O3 -DNDEBUG -std=c++17 "${extra[@]}" -I"$dir/include" -c "$src" -o "$obj" 2>>"$dir/build.log" ||
      { echo "kernel_revisions.sh: $rev does not build ($dir/build.log):" >&2; tail -20 "$dir/build.log" >&2; exit 1; }
    objs+=("$obj")
  done
  g++ -O3 -DNDEBUG -std=c++17 -I"$dir/include" -I"$root" "$root/bench/bench_kernel.cpp" "${objs[@]}" -o "$dir/bench_kernel" \
    -pthread 2>>"$dir/build.log" || { echo "kernel_revisions.sh: $rev does not link ($dir/build.log)" >&2; exit 1; }
  bins+=("$dir/bench_kernel")
done

# Timing: ROUNDS rounds over every revision; lines "case threads ns hits" into r<i>.times.
for ((round = 0; round < ROUNDS; round++)); do
  for i in "${!bins[@]}"; do "${bins[$i]}" --repeats 5 >>"$tmp/r$i.times"; done
done
# Instructions per point (one thread): callgrind of N and 2N jobs.
ir_of() {  # BINARY CASE JOBS
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$1" --count "$2" "$3" 2>"$tmp/cg.err" >/dev/null
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.err"
}
declare -A jobs=([2bit-in-cache]=64 [2bit-out-of-cache]=2 [distance-in-cache]=64 [distance-out-of-cache]=2
                 [2bit-small-jobs]=2048 [distance-small-jobs]=2048)
declare -A points=([2bit-in-cache]=4096 [2bit-out-of-cache]=65536 [distance-in-cache]=4096 [distance-out-of-cache]=65536
                   [2bit-small-jobs]=24 [distance-small-jobs]=24)
for i in "${!bins[@]}"; do
  for c in "${cases[@]}"; do
    a="$(ir_of "${bins[$i]}" "$c" "${jobs[$c]}")"
    b="$(ir_of "${bins[$i]}" "$c" "$((2 * ${jobs[$c]}))")"
    echo "$c $(awk -v a="$a" -v b="$b" -v n="$((${jobs[$c]} * ${points[$c]}))" 'BEGIN { printf "%.2f", (b - a) / n }')" \
      >>"$tmp/r$i.ir"
  done
done

median_of() {  # FILE CASE THREADS -> median ns, hits
  awk -v c="$2" -v t="$3" '$1 == c && $2 == t { print $3, $4 }' "$1" | sort -g |
    awk '{ a[NR] = $1; h[NR] = $2 } END { m = (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2; print m, h[1] }'
}
echo "| case | threads | revision | ns per point per core (median of $ROUNDS rounds) | speed-up | instructions per point (callgrind, AVX2 kernels) | fewer |"
echo "|---|--:|---|--:|--:|--:|--:|"
for c in "${cases[@]}"; do
  for t in 1 2; do
    first_ns="" first_ir="" first_hits=""
    for i in "${!bins[@]}"; do
      read -r ns hits <<<"$(median_of "$tmp/r$i.times" "$c" "$t")"
      ir="$(awk -v c="$c" '$1 == c { print $2 }' "$tmp/r$i.ir")"
      if [[ -z "$first_ns" ]]; then
        first_ns=$ns first_ir=$ir first_hits=$hits
      elif [[ "$hits" != "$first_hits" ]]; then
        echo "kernel_revisions.sh: ${*:$((i + 1)):1} counts $hits hits in $c, the first revision $first_hits" >&2
        exit 1
      fi
      rev="${*:$((i + 1)):1}"
      irs="-" fewer="-"
      if [[ "$t" == 1 ]]; then irs="$ir" fewer="$(awk -v a="$first_ir" -v b="$ir" 'BEGIN { printf "%.2f", a / b }')"; fi
      awk -v c="$c" -v t="$t" -v r="$rev" -v n="$ns" -v f="$first_ns" -v i="$irs" -v w="$fewer" \
        'BEGIN { printf "| %s | %s | %s | %.3f | %.2f | %s | %s |\n", c, t, r, n, f / n, i, w }'
    done
  done
done
echo
echo "COUNT jobs (in cache: 256 of 4096 points on a 32^3 voxmap; out of cache: 16 of 65536 on 1024 x 1024 x 64; small jobs: 16384 of 24 points on the 32^3 voxmap, with their cycles), the same hits at every revision; speed-ups and instruction ratios against the first revision. $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $(nproc) hardware threads."
