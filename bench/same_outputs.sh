#!/usr/bin/env bash
# The tool's outputs of this tree against those of an earlier revision, both built here in the same run (without the
# device models), compared by bench/output_diff.sh: simulate's state hashes and summaries, object files byte for byte,
# contacts, size reports, a sweep and conformance vectors, timings blanked. A change that must not change an output
# (a restructuring) shows "identical".
#   bash bench/same_outputs.sh REV [MESH]     REV: a commit, e.g. the one before the change; MESH: a mesh to add
# Builds build-same/before (REV's source in build-same/src) and build-same/after; exits 1 when an output differs.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/same_outputs.sh REV [MESH]}
work=$PWD/build-same
export CCACHE_BASEDIR=$PWD SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
mkdir -p "$work"
build() {  # build SRC DIR: the tool of SRC in DIR
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_DEVICE_MODELS=OFF -DVOXCD_TESTS=OFF \
        -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF >/dev/null
  cmake --build "$2" -j2 --target voxcd >/dev/null
}
[ -d "$work/src" ] && git worktree remove --force "$work/src"
git worktree add --detach "$work/src" "$rev" >/dev/null
build "$work/src" "$work/before"
build "$PWD" "$work/after"
echo "before: $rev ($(git rev-parse --short "$rev")), after: $(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo ' with changes')"
rm -rf "$work/outputs"
MESH=${2:-} bash bench/output_diff.sh "$work/before/voxcd" "$work/after/voxcd" "$work/outputs"
