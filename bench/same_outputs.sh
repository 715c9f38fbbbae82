#!/usr/bin/env bash
# The tool's outputs of this tree against those of an earlier revision, built in the same run: state hashes of
# simulate runs, object files, conformance vectors, contacts and size reports. A refactoring that changes no output on
# purpose shows "same" on every row. Timings are left out (JSON keys about time and rates; text lines are compared
# only where they carry no time: state hashes).
#   bash bench/same_outputs.sh REV [MESH...]     REV: a commit (e.g. the one before a change); MESH: extra meshes
# Writes build-same/{before,after}/ and prints one row per output; exits 1 when any differs.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/same_outputs.sh REV [MESH...]}
shift
meshes=("$@")
work=$PWD/build-same
export CCACHE_BASEDIR=$PWD SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
mkdir -p "$work"

build() {  # build SRC DIR: the tool of SRC in DIR, without the device models
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOXCD_DEVICE_MODELS=OFF -DVOXCD_TESTS=OFF \
        -DVOXCD_BENCH=OFF -DVOXCD_PYTHON=OFF >/dev/null
  cmake --build "$2" -j2 --target voxcd >/dev/null
}
if [ ! -d "$work/src-$rev" ]; then
  git worktree add --detach "$work/src-$rev" "$rev" >/dev/null
fi
build "$work/src-$rev" "$work/build-before"
build "$PWD" "$work/build-after"

# A JSON document without what depends on the machine: keys that hold times, rates, threads or paths.
normalise_json() {
  /usr/bin/python3 -c '
import json, re, sys
DROP = re.compile(r"(second|time|_ms$|_us$|rate|per_s|wall|elapsed|threads|path|file|version|hardware)", re.I)
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if not DROP.search(k)}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
print(json.dumps(clean(json.load(sys.stdin)), indent=1, sort_keys=True))'
}

run_all() {  # run_all TOOL OUT
  local v=$1 out=$2
  rm -rf "$out" && mkdir -p "$out"
  "$v" simulate --frames 20 --no-progress | grep "state hash" >"$out/simulate_builtin.txt"
  "$v" simulate --frames 5 --objects 64 --seed 3 --no-progress | grep "state hash" >"$out/simulate_64.txt"
  "$v" simulate --frames 4 --objects 48 --distance-bits 8 --no-progress | grep "state hash" >"$out/simulate_distance.txt"
  "$v" simulate tests/scenes/small.json --frames 6 --no-progress | grep "state hash" >"$out/simulate_small.txt"
  for s in torus stellated sphere; do
    "$v" voxelize "$s" --resolution 24 --storage dense -o "$out/$s.vxo" >/dev/null
    "$v" voxelize "$s" --resolution 24 --storage sparse -o "$out/$s.sparse.vxo" >/dev/null
    "$v" voxelize "$s" --resolution 20 --distance-bits 8 -o "$out/$s.d8.vxo" >/dev/null
  done
  local i=0
  for m in "${meshes[@]}"; do
    i=$((i + 1))
    "$v" voxelize "$m" --resolution 32 -o "$out/mesh$i.vxo" >/dev/null
  done
  "$v" conform --generate --seed 5 --jobs 200 -o "$out/vectors.vec" >/dev/null
  "$v" pair torus stellated --random 40 --seed 2 --both --json | normalise_json >"$out/pair_random.json"
  "$v" pair "$out/torus.d8.vxo" "$out/sphere.d8.vxo" --pose 0.3,0.2,0.1,10,20,30 --margin 0.05 --both --json |
    normalise_json >"$out/pair_distance.json"
  "$v" size tests/scenes/small.json --json | normalise_json >"$out/size_small.json"
}
run_all "$work/build-before/voxcd" "$work/before"
run_all "$work/build-after/voxcd" "$work/after"

status=0
printf '%-28s %s\n' output "before ($rev) vs after ($(git rev-parse --short HEAD)$(git diff --quiet || echo +changes))"
for f in $(cd "$work/after" && ls); do
  if cmp -s "$work/before/$f" "$work/after/$f"; then
    printf '%-28s same (%s bytes)\n' "$f" "$(stat -c %s "$work/after/$f")"
  else
    printf '%-28s DIFFERENT: diff %s %s\n' "$f" "$work/before/$f" "$work/after/$f"
    status=1
  fi
done
exit $status
