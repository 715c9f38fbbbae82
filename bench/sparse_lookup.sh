#!/usr/bin/env bash
# bench/sparse_lookup.sh: docs/device-speed.md's table of sparse against dense maps and shells (bench/bench_sparse_lookup.cpp), with
# callgrind's instructions per lookup beside the times of the in-cache cases: the count for 2N jobs less that for N
# (set-up cancels), divided by the points between them; repeatable whatever the machine's load (valgrind runs the
# AVX2 kernels: it does not emulate AVX-512). The times are the median of REPEATS batches of one run of
# bench_sparse_lookup (the out-of-cache maps take a few GB and some seconds to build).
#   bash bench/sparse_lookup.sh [BUILD_DIR] [REPEATS] > /tmp/sparse.md
#   bash bench/splice.sh docs/device-speed.md sparse /tmp/sparse.md
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
repeats="${2:-7}"
bin="$build/bench_sparse_lookup"
[ -x "$bin" ] || { echo "sparse_lookup.sh: build $bin first (cmake --build $build --target bench_sparse_lookup)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "sparse_lookup.sh: valgrind not found (apt-get install valgrind)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

count() {  # CASE JOBS -> "instructions points"
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$bin" --count "$1" "$2" >"$tmp/out" 2>"$tmp/err"
  echo "$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/err") $(awk '{ print $4 }' "$tmp/out")"
}
for kind in 2bit distance; do
  for name in lookup-surface-dense lookup-surface-sparse lookup-box-dense lookup-box-sparse \
              shell-dense-dense shell-sparse-dense shell-dense-sparse shell-sparse-sparse; do
    n=4
    [[ "$name" == lookup-* ]] && n=8
    read -r a pa <<<"$(count "$kind-$name" "$n")"
    read -r b pb <<<"$(count "$kind-$name" "$((2 * n))")"
    awk -v c="$kind-$name" -v a="$a" -v b="$b" -v pa="$pa" -v pb="$pb" \
      'BEGIN { printf "%s %.2f\n", c, (b - a) / (pb - pa) }' >>"$tmp/ir"
  done
done
# The table's first line names this script's command (bench_sparse_lookup's own names a temporary file).
"$bin" --repeats "$repeats" --ir "$tmp/ir" 2>"$tmp/progress" |
  sed "1s|\`build/bench_sparse_lookup --repeats $repeats --ir [^\`]*\`|\`bash bench/sparse_lookup.sh $build $repeats\`|"
