#!/usr/bin/env bash
# Campaign throughput of `voxcd regress`: one campaign (seeds 1-24, the default and a distance configuration, lanes
# 1,2,4, backends ref,cpu, 200 jobs per shard, cycles compared: 288 shards) run on 1 rank (no mpirun), 2 ranks and
# 3 ranks (mpirun --oversubscribe: on a 2-core machine the third rank shares a core), each REPEATS times; prints the
# median run of each: shards/s, lookups/s and the payload bytes sent between ranks per shard.
#   bash bench/regress.sh [BUILD_DIR] [REPEATS] [BACKENDS]        (defaults build, 3, ref,cpu)
# docs/regress.md, "Throughput", holds its output.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
repeats="${2:-3}"
backends="${3:-ref,cpu}"
voxcd="$build/voxcd"
[ -x "$voxcd" ] || { echo "regress.sh: build $voxcd first (cmake --build $build --target voxcd)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
campaign=(--seeds 1-24 --configs "default;SB 8 WB 8" --lanes 1,2,4 --backends "$backends" --jobs-per-shard 200
          --cycles --json)
echo "campaign: voxcd regress ${campaign[*]} ($(nproc) cores)"
echo
echo "| ranks | shards | lookups | seconds | shards/s | lookups/s | bytes sent per shard |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for np in 1 2 3; do
  runs=()
  for ((r = 0; r < repeats; ++r)); do
    if [ "$np" = 1 ]; then
      out=$("$voxcd" regress "${campaign[@]}")
    else
      out=$(mpirun --oversubscribe -np "$np" "$voxcd" regress "${campaign[@]}")
    fi
    runs+=("$out")
  done
  # The median run by seconds (the machine is shared: one run may be slowed by others).
  best=$(python3 -c '
import json, sys
rs = [json.loads(t) for t in sys.argv[1:]]
if any(r["failures"] or not r["complete"] for r in rs): sys.exit("regress.sh: the campaign failed")
r = sorted(rs, key=lambda r: r["seconds"])[len(rs) // 2]
print("%d %d %d %.3f %d" % (r["ranks"], r["shards_done"], r["lookups"], r["seconds"], r["bytes_between_ranks"]))' "${runs[@]}")
  read -r ranks shards lookups seconds bytes <<<"$best"
  label="$ranks"
  [ "$np" = 3 ] && label="3 (oversubscribed)"
  python3 -c 'import sys
ranks, shards, lookups, s, b = sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6])
print("| %s | %d | %d | %.2f | %.1f | %.3g | %s |" % (sys.argv[1], shards, lookups, s, shards / s, lookups / s,
      "-" if ranks == "1" else "%.0f" % (b / shards)))' "$label" "$ranks" "$shards" "$lookups" "$seconds" "$bytes"
done
