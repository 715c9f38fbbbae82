#!/usr/bin/env bash
# bench/against_cpu.sh: docs/hardware.md "Against the CPU", the block between <!-- bench:against_cpu:begin --> and
# <!-- bench:against_cpu:end -->. For every lane count and depth: `voxcd simulate --json` on its built-in scene
# (lookups, device cycles, the clock and its source), build/bench_against_cpu on the room and the tori (device cycles
# of the timing model) and the cpu backend's own lookups per second on the same jobs, one core and every core; then
# bench/against_cpu.py makes the table with the area of host/device/timing.tsv and the energy of
# host/sizing/energy.tsv (when it exists).
# Usage: bash bench/against_cpu.sh [--quick] [--lanes 4,8,16,32,64] [--depths 0,4] [--build DIR] [--out FILE]
#   --quick: a smoke run of about a minute (50 frames, 200 room poses, 10 torus poses) instead of the default
#            (1000 frames, 20,000 room poses, 1,000 torus poses: about a minute on 2 cores);
#   --out FILE: write the block to FILE instead of splicing it into docs/hardware.md.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
python=/usr/bin/python3
build=build lanes=4,8,16,32,64 depths=0,4 quick=0 out=""
command="bash bench/against_cpu.sh"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1; command+=" --quick"; shift ;;
    --lanes) lanes="$2"; command+=" --lanes $2"; shift 2 ;;
    --depths) depths="$2"; command+=" --depths $2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "usage: bash bench/against_cpu.sh [--quick] [--lanes L,...] [--depths D,...] [--build DIR] [--out FILE]" >&2
       exit 2 ;;
  esac
done
if [ "$quick" = 1 ]; then frames=50 room=200 tori=10; else frames=1000 room=20000 tori=1000; fi
for bin in voxcd bench_against_cpu; do
  [ -x "$build/$bin" ] || { echo "against_cpu.sh: build $build/$bin first (cmake --build $build --target $bin)" >&2; exit 2; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

machine() {  # "AMD EPYC, 2 cores (/proc/cpuinfo)"
  local model cores
  model="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
  cores="$(grep -c '^processor' /proc/cpuinfo)"
  echo "${model:-unknown processor}, $cores cores (/proc/cpuinfo)"
}
revision() {  # "abc1234", with "+ uncommitted changes" when the tree differs from it
  local r
  r="$(git rev-parse --short HEAD)"
  [ -z "$(git status --porcelain --untracked-files=no)" ] || r+=" + uncommitted changes"
  echo "$r"
}
simulate_all() {  # one line per configuration: {"lanes": L, "depth": D, "simulate": {...}}
  local l d
  for l in ${lanes//,/ }; do
    for d in ${depths//,/ }; do
      echo "{\"lanes\": $l, \"depth\": $d, \"simulate\": $("$build/voxcd" simulate --objects 1024 --frames "$frames" \
        --config "LANES $l DEPTH $d" --json --no-progress)}"
      echo "against_cpu.sh: simulate LANES $l DEPTH $d done" >&2
    done
  done
}

start=$(date +%s)
load="$(cut -d' ' -f1 /proc/loadavg)"
rev="$(revision)"
simulate_all >"$tmp/simulate.jsonl"
"$build/bench_against_cpu" --lanes "$lanes" --depths "$depths" --frames "$frames" --room-poses "$room" \
  --torus-poses "$tori" --repeats 5 | tee "$tmp/bench.jsonl" >&2
"$python" bench/against_cpu.py table --simulate "$tmp/simulate.jsonl" --bench "$tmp/bench.jsonl" \
  --timing host/device/timing.tsv --energy host/sizing/energy.tsv --command "$command" \
  --seconds $(($(date +%s) - start)) --revision "$rev" --machine "$(machine)" --load "$load" >"$tmp/block.md"
if [ -n "$out" ]; then
  cp "$tmp/block.md" "$out"
  echo "wrote $out"
else
  bash bench/splice.sh docs/hardware.md against_cpu "$tmp/block.md"
fi
cat "$tmp/block.md"
