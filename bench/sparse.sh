#!/usr/bin/env bash
# bench/sparse.sh: every measurement of sparse voxmaps and shells in one run, each table regenerated in its document
# and each sparse/dense ratio measured by one program against the other form in the same process (docs/sparse.md):
#   1. memory: bytes of voxmap + shell, sparse against dense and against OpenVDB's bool grid, at 128 to 1,020 voxels
#      across and at 4,096, and `voxcd voxelize --resolution 4096` (bench/sparse_memory.sh -> docs/voxelize.md);
#   2. lookups: cpu backend ns per lookup, sparse against dense, in and out of cache, 2-bit and distance, with
#      callgrind's instructions per lookup (bench/sparse_lookup.sh -> docs/device-speed.md);
#   3. contact error: sparse distance fields with refined bricks against exact geometry on the whole differential
#      corpus (build/bench_differential -> docs/results.md, "Against exact geometry on every kind of model");
#   4. the RTL: points per cycle of sparse maps and shells on the Verilated models at every depth
#      (bench/sparse_rtl.sh -> docs/hardware.md; the second read port's cost in yosys is bench/sparse_cost.sh's, run on
#      its own).
# Usage: bash bench/sparse.sh [BUILD] [--skip rtl]   (BUILD: a Release or RelWithDebInfo build with the benchmarks and
# the device models, default build). About 40 minutes on 2 cores; each step prints its time to standard error.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
skip=""
while [ $# -gt 0 ]; do
  case "$1" in
    --skip) skip="$2"; shift 2 ;;
    *) build="$1"; shift ;;
  esac
done
start=$SECONDS
step() {  # label command...
  local t=$SECONDS
  echo "sparse.sh: $1" >&2
  shift
  "$@"
  echo "sparse.sh: took $((SECONDS - t)) s" >&2
}
cmake --build "$build" -j2 --target voxcd bench_sparse_memory bench_sparse_lookup bench_differential >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

step "memory (bench/sparse_memory.sh)" bash bench/sparse_memory.sh "$build"
step "lookups (bench/sparse_lookup.sh)" bash -c "bash bench/sparse_lookup.sh '$build' 9 > '$tmp/lookup.md'"
bash bench/splice.sh docs/device-speed.md sparse "$tmp/lookup.md" >/dev/null
differential() {
  "$build/bench_differential" --poses 150 --resolution 32 --seed 1 --out "$tmp/differential.md" >/dev/null
}
step "contact error (bench_differential --poses 150)" differential
bash bench/splice.sh docs/results.md results-differential "$tmp/differential.md" >/dev/null
if [ "$skip" != rtl ]; then
  step "RTL throughput (bench/sparse_rtl.sh)" env BUILD="$build" bash bench/sparse_rtl.sh
fi
echo "sparse.sh: docs/voxelize.md, docs/device-speed.md, docs/results.md$([ "$skip" = rtl ] || echo ", docs/hardware.md")" \
     "regenerated in $((SECONDS - start)) s" >&2
