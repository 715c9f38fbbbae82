#!/usr/bin/env bash
# bench/output_diff.sh: the tool's outputs before and after a change that must not change them (a restructuring):
# simulate (the built-in scene, 20 frames; 5 frames of 64 objects; sap at 300; ccd on a distance device; a scene
# file), voxelize (built-in shapes and tests/scenes/tetra.obj, dense, sparse and with a distance field; MESH too when
# given, e.g. an FCL mesh), pair contacts (random poses, a pose, distance, sparse), size (tests/scenes, text and
# JSON), a small sweep and generated conformance vectors (2-bit and sparse). Timings are blanked before the outputs are compared; the object files byte for byte.
# Exits 1 on any difference, naming the outputs that differ.
# Usage: MESH=file.obj bash bench/output_diff.sh VOXCD_BEFORE VOXCD_AFTER [WORKDIR]
set -uo pipefail
(($# >= 2)) || { echo "usage: MESH=file.obj bash bench/output_diff.sh VOXCD_BEFORE VOXCD_AFTER [WORKDIR]" >&2; exit 2; }
scenes="$(cd "$(dirname "$0")/../tests/scenes" && pwd)"
work="${3:-$(mktemp -d)}"
before="$(realpath "$1")" after="$(realpath "$2")"

outputs() {  # outputs VOXCD DIR
  local v=$1 o=$2
  mkdir -p "$o" && cd "$o" || exit 2
  run() { local n=$1; shift; "$v" "$@" >"$n.out" 2>"$n.err"; echo "rc $?" >>"$n.out"; }
  run sim20 simulate --frames 20
  run sim5x64 simulate --frames 5 --objects 64
  run sim_sap simulate --frames 4 --objects 300 --broadphase sap --seed 7
  run sim_ccd simulate --frames 4 --objects 64 --distance-bits 8 --ccd
  run sim_scene simulate "$scenes/mixed.json" --frames 4
  for s in polytope36 torus sphere; do run "vox_$s" voxelize $s --resolution 32 -o $s.vox --json; done
  run vox_tetra voxelize "$scenes/tetra.obj" --resolution 24 -o tetra.vox --json
  run vox_tetra_sparse voxelize "$scenes/tetra.obj" --resolution 64 --storage sparse -o tetra_sparse.vox --json
  run vox_dist voxelize torus --resolution 32 --distance-bits 8 -o torus_d8.vox --json
  if [[ -n "${MESH:-}" ]]; then
    run vox_mesh voxelize "$MESH" --resolution 48 -o mesh.vox --json
    run vox_mesh_sparse voxelize "$MESH" --resolution 96 --storage sparse -o mesh_sparse.vox
    run pair_sparse pair mesh_sparse.vox mesh_sparse.vox --random 10 --json
  fi
  run pair_rand pair polytope36 torus --random 50 --json
  run pair_pose pair torus.vox polytope36.vox --pose 0.3,0.1,0.2,10,20,30 --json
  run pair_dist pair torus sphere --distance-bits 8 --random 20 --json
  for f in paper small mixed; do run "size_$f" size "$scenes/$f.json"; run "sizej_$f" size "$scenes/$f.json" --json; done
  run sweep sweep "$scenes/small.json" --lanes 1,2 --frames 4 --sample-frames 2 --json
  run vectors conform --generate --seed 5 --jobs 200 -o vectors.vec
  run vectors_sparse conform --generate --seed 6 --jobs 100 --config "LANES 4 BL 3" -o vectors_sparse.vec
}

# Timings (seconds, rates, per-stage times) differ from run to run: blanked.
norm() {
  sed -E 's/("[a-z_]*(seconds|_s|_us|_ms|rate|hz|_hz)": )[-0-9.eE+]+/\1T/g; /^(frame rate|time per stage|wall time|host time)/d
          s/[0-9.]+ (us|ms|s) per/T per/g' "$1"
}

(outputs "$before" "$work/before")
(outputs "$after" "$work/after")
status=0
for f in "$work"/before/*.out "$work"/before/*.err; do
  n="$(basename "$f")"
  if ! diff -q <(norm "$f") <(norm "$work/after/$n") >/dev/null; then
    echo "DIFF $n"; diff <(norm "$f") <(norm "$work/after/$n") | head -6 | cut -c1-300; status=1
  fi
done
for f in "$work"/before/*.vox "$work"/before/*.vec; do cmp "$f" "$work/after/$(basename "$f")" || status=1; done
echo "$(ls "$work"/before/*.out | wc -l) outputs, $(ls "$work"/before/*.vox | wc -l) object files," \
     "$(ls "$work"/before/*.vec | wc -l) vector files ($work):" \
     "$([[ $status == 0 ]] && echo identical || echo DIFFERENT)"
exit $status
