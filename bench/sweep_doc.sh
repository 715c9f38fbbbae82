#!/usr/bin/env bash
# bench/sweep_doc.sh: regenerates the worked example of docs/sweep.md by running voxcd sweep on
# tests/scenes/small.json over three ranks (mpirun --oversubscribe; about a minute on two cores).
# Usage: bash bench/sweep_doc.sh [BUILD_DIR]   (default build/)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
voxcd="$build/voxcd"
cd "$root"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
args=(sweep tests/scenes/small.json --lanes 1,2 --voxel-scale 1,2 --distance-bits 0,8 --accuracy 0.02,0.005
      --frames 100 --sample-frames 4)
{
  echo '```'
  echo "\$ mpirun --oversubscribe -np 3 build/voxcd ${args[*]} | sed 's/ranks 3, .*;/ranks 3, (time);/'"
  mpirun --oversubscribe -np 3 "$voxcd" "${args[@]}" | sed 's/ranks 3, .*;/ranks 3, (time);/'
  echo '```'
} >"$tmp/example.md"
bash bench/splice.sh docs/sweep.md sweep-example "$tmp/example.md"
